"""Break-and-run racks: how each agent's racks end, on the same racks, with the time per shot.

Usage::

    python -m agents.evaluation.runouts --agents models/search_player.yaml ghost \
        --racks 100 --seed 949000 --noise fastfiz --out results/search_player_runs/runouts_x1.json

Rack ``k`` is the run-out mode of the id (``end_on_foul``: the player breaks, and the first
miss or foul ends the rack) reset with ``seed + k``, so every agent plays the same racks.
Each rack ends one way (:data:`ENDINGS`): a break scratch (a foul on the break), a dry break
(nothing made: the turn is over), a missed pot, a foul after the break, a run-out (the
money ball made legally), or the shot limit. Beside them: balls made on the break, the wall
time of each decision (the break apart) and the shot-making rate after the break
(:func:`made_after_break`). Rates carry their 95% Wilson intervals; the table is
printed in Markdown and, with ``--out``, written as JSON.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from agents.evaluation.metrics import Z95, Estimate, wilson
from agents.evaluation.noise_flag import noise_kwargs
from agents.evaluation.players import check_agents, check_game_id, make_agent
from agents.learned.envs import make_env
from agents.policy import Policy

#: How a rack can end, in the order of the table's columns.
ENDINGS = ("run-out", "break scratch", "dry break", "missed pot", "foul", "shot limit")


def play_racks(
    agent_name: str,
    env_id: str,
    racks: int,
    seed: int,
    env_kwargs: dict[str, Any],
    build: Callable[[Any], Policy] | None = None,
) -> dict[str, Any]:
    """Play ``racks`` run-out racks with one agent and count how they end.

    ``build`` (``env -> agent``) makes an agent that is no player name (the scoreboard's
    models and factories); ``agent_name`` then only labels it.

    Returns:
        ``endings`` (a count per :data:`ENDINGS`), ``racks``, ``break_made`` (breaks that
        made a ball), ``shots`` (decisions after the break), ``seconds`` (their wall times),
        ``per_rack`` (each rack's ending) and ``break_per_rack`` (whether each break made
        a ball).
    """
    env = make_env(env_id, {**env_kwargs, "end_on_foul": True}, None)
    agent = build(env) if build is not None else make_agent(agent_name, env, seed)
    endings: Counter[str] = Counter()
    per_rack: list[str] = []
    break_per_rack: list[bool] = []
    seconds: list[float] = []
    break_made = 0
    try:
        for k in range(racks):
            obs, info = env.reset(seed=seed + k)
            shot, done, ending = 0, False, "shot limit"
            while not done:
                start = time.perf_counter()
                action = agent.predict(obs, deterministic=True)[0]
                if shot:
                    seconds.append(time.perf_counter() - start)
                obs, _, terminated, truncated, info = env.step(action)
                done = terminated or truncated
                if shot == 0:
                    break_made += int(bool(info["potted"]))
                    break_per_rack.append(bool(info["potted"]))
                if info["winner"] == 0:
                    ending = "run-out"
                elif info["foul"] is not None and terminated:
                    ending = "break scratch" if shot == 0 else "foul"
                elif terminated:
                    ending = "dry break" if shot == 0 else "missed pot"
                shot += 1
            endings[ending] += 1
            per_rack.append(ending)
    finally:
        env.close()
    return {
        "agent": agent_name, "racks": racks, "endings": dict(endings), "break_made": break_made,
        "shots": len(seconds), "seconds": seconds, "per_rack": per_rack,
        "break_per_rack": break_per_rack,
    }  # fmt: skip


def summary_row(result: dict[str, Any]) -> dict[str, Any]:
    """One table row: the rates with their intervals, and the seconds per shot."""
    n = result["racks"]
    rates: dict[str, Estimate] = {e: wilson(result["endings"].get(e, 0), n) for e in ENDINGS}
    secs = np.asarray(result["seconds"]) if result["seconds"] else np.zeros(1)
    return {
        "agent": result["agent"],
        "racks": n,
        **{e: rates[e].as_percent() for e in ENDINGS},
        "ball made on break": wilson(result["break_made"], n).as_percent(),
        "s/shot median": f"{np.median(secs):.3f}",
        "s/shot p95": f"{np.quantile(secs, 0.95):.3f}",
        "shots/rack": f"{result['shots'] / n:.2f}",
        "made after break": made_after_break(result).as_percent(),
    }


def made_after_break(result: dict[str, Any]) -> Estimate:
    """The share of the shots after the break that made a ball and kept the table (or won).

    In run-out mode every shot after the break goes on, wins, or ends the rack by a miss
    or a foul: the shots that ended a rack are the misses.
    """
    ended = sum(result["endings"].get(e, 0) for e in ("missed pot", "foul"))
    return wilson(result["shots"] - ended, result["shots"])


def paired_difference(
    first: list[str | None], second: list[str | None], success: str = "run-out"
) -> tuple[float, float, float]:
    """Success rate of ``first`` minus ``second`` on the same racks, with a 95% interval.

    A rack is a success when its entry is ``success``: a run-out's ending, or a duel's
    winner (``success="agent"`` on :func:`agents.evaluation.duels.play_duels`' ``per_rack``).
    From the discordant racks (one succeeded, the other did not): the paired difference's
    normal interval, much tighter than two independent intervals when the racks matter.
    """
    if len(first) != len(second) or not first:
        raise ValueError("paired racks: two equally long, non-empty lists of endings")
    n = len(first)
    pairs = list(zip(first, second, strict=True))
    wins = sum(a == success and b != success for a, b in pairs)
    losses = sum(a != success and b == success for a, b in pairs)
    diff = (wins - losses) / n
    half = Z95 * math.sqrt(max(wins + losses - (wins - losses) ** 2 / n, 0.0)) / n
    return diff, diff - half, diff + half


def markdown(rows: list[dict[str, Any]]) -> str:
    """The rows as a Markdown table."""
    keys = list(rows[0])
    lines = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    lines += ["| " + " | ".join(str(row[k]) for k in keys) + " |" for row in rows]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--agents", nargs="+", required=True, help="agents, as --agent takes")
    parser.add_argument("--env", default="pool_env/NineBallGame-v2")
    parser.add_argument("--racks", type=int, default=100)
    parser.add_argument("--seed", type=int, default=949000)
    parser.add_argument(
        "--noise", default="fastfiz", help="as agents.evaluate's --noise (none: exact shots)"
    )
    parser.add_argument("--rack-order", default=None, help="the env's rack order (default its own)")
    parser.add_argument("--out", default=None, help="write the results as JSON here")
    args = parser.parse_args(argv)
    if args.racks < 1:
        parser.error("--racks must be >= 1")
    kwargs: dict[str, Any] = noise_kwargs(parser, args.noise)
    if args.rack_order is not None:
        kwargs["rack_order"] = args.rack_order
    check_game_id(parser, args.env, "agents.evaluation.runouts")
    check_agents(parser, args.agents, args.env, {**kwargs, "end_on_foul": True})
    results = []
    for name in args.agents:
        start = time.perf_counter()
        result = play_racks(name, args.env, args.racks, args.seed, kwargs)
        result["wall_seconds"] = time.perf_counter() - start
        results.append(result)
        print(markdown([summary_row(result)]), flush=True)
    print(f"\n{args.env}, {args.racks} racks from seed {args.seed}, noise {args.noise}\n")
    print(markdown([summary_row(r) for r in results]))
    for other in results[1:]:
        diff, low, high = paired_difference(results[0]["per_rack"], other["per_rack"])
        print(
            f"\n{results[0]['agent']} minus {other['agent']}, paired on the same racks: "
            f"{100 * diff:+.1f} points of run-outs [{100 * low:+.1f}, {100 * high:+.1f}]"
        )
    if args.out:
        out = {"env": args.env, "seed": args.seed, "noise": args.noise, "results": results}
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
