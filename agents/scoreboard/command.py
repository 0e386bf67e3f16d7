"""``python -m agents.scoreboard``: score a policy on a suite, or write the leaderboard page.

Usage::

    python -m agents.scoreboard models/sac_oneball_spin.zip      # the short suite
    python -m agents.scoreboard ghost --suite full --save        # results/scoreboard/ghost.json
    python -m agents.scoreboard my_agents.pool:make_agent --suite short
    python -m agents.scoreboard --leaderboard                    # docs/leaderboard.md

A policy is a player as ``agents.evaluate`` takes it, an SB3 model ``.zip`` with its saved
config, or ``module:attr``, a factory ``env -> agent`` (:mod:`agents.scoreboard.policies`).
The table printed gives each task's id, noise, seeds, episodes, figure with its 95%
interval and the normalized score against the results files of ``--results``
(:mod:`agents.scoreboard.results`). ``--save`` writes the results file; ``--leaderboard``
writes the page from every results file (:mod:`agents.scoreboard.leaderboard`).
"""

from __future__ import annotations

import argparse
import json
import shlex
import sys
import time
from pathlib import Path

from agents.scoreboard.leaderboard import leaderboard_page, score_table
from agents.scoreboard.policies import resolve_policy
from agents.scoreboard.results import (
    RESULTS,
    dump_results,
    load_results,
    merge_results,
    results_path,
    score_policy,
)
from agents.scoreboard.suite import SUITES, suite_tasks

__all__ = ["PAGE", "main"]

#: The leaderboard page ``--leaderboard`` writes.
PAGE = Path("docs/leaderboard.md")


def _parser() -> argparse.ArgumentParser:
    """The command's arguments: a policy to score, or ``--leaderboard``."""
    parser = argparse.ArgumentParser(
        prog="python -m agents.scoreboard", description=__doc__.split("\n")[0]
    )
    parser.add_argument(
        "policy",
        nargs="?",
        help="a player (random, ghost, models/search_player.yaml, ...), an SB3 model .zip, "
        "or module:attr (a factory: env -> agent with predict)",
    )
    parser.add_argument("--suite", default="short", help=f"one of {', '.join(SUITES)}")
    parser.add_argument(
        "--tasks", nargs="+", default=None, metavar="TASK", help="play only these tasks"
    )
    parser.add_argument(
        "--save",
        nargs="?",
        const="",
        default=None,
        metavar="PATH",
        help="write the results file (default: RESULTS/<player>.json, <player>.<suite>.json "
        "off the full suite)",
    )
    parser.add_argument(
        "--results",
        default=str(RESULTS),
        help="the results files the normalized score and the page read (default: %(default)s)",
    )
    parser.add_argument(
        "--leaderboard",
        nargs="?",
        const=str(PAGE),
        default=None,
        metavar="PAGE",
        help=f"write the leaderboard page from the results files (default: {PAGE})",
    )
    return parser


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = _parser()
    args = parser.parse_args(argv)
    folder = Path(args.results)
    if (args.policy is None) == (args.leaderboard is None):
        parser.error("give a policy to score, or --leaderboard (not both)")
    try:
        files = load_results(folder) if folder.is_dir() else {}
    except ValueError as err:
        parser.error(str(err))
    if args.leaderboard is not None:
        page = Path(args.leaderboard)
        page.write_text(leaderboard_page(files, page))
        print(f"wrote {page} from {len(files)} results files of {folder}")
        return 0
    try:
        suite_tasks(args.suite)  # an unknown suite, before a policy is loaded
        policy = resolve_policy(args.policy)
    except ValueError as err:
        parser.error(str(err))
    argv = sys.argv[1:] if argv is None else argv
    command = shlex.join(["python", "-m", "agents.scoreboard", *argv])
    start = time.perf_counter()
    try:
        data = score_policy(
            policy, args.suite, command, args.tasks, lambda line: print(line, flush=True)
        )
    except ValueError as err:  # an unknown task, a factory that breaks the protocol
        parser.error(str(err))
    wall = time.perf_counter() - start
    print(f"\n{policy.spec}, suite {args.suite}, {wall:.0f} s\n")
    print(score_table(data, files))
    if args.save is not None:
        path = Path(args.save) if args.save else results_path(folder, policy.slug, args.suite)
        if args.tasks is not None and path.is_file():  # the other tasks' entries stay
            try:
                data = merge_results(json.loads(path.read_text()), data)
            except ValueError as err:
                parser.error(f"--save {str(path)!r}: {err}")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(dump_results(data))
        print(f"\nwrote {path}")
    return 0
