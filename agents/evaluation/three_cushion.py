"""Three-cushion innings: the search player's average (points per inning), and a baseline's.

``python -m agents.evaluation.three_cushion`` plays innings of ``pool_env/ThreeCushion-v1``
(one inning an episode, white's cue ball; the env's own rules, execution noise and its
100-shot truncation) from fixed seeds: from the UMB starting position (the break, which
must meet the red first) and from random three-ball layouts (``options["positions"]``), at
FastFiz x0, x1 and x5. The env's aim is ``"absolute"`` by default (``--aim``: the id's
own default, ``"cut"``, lets the cue ball go only at the nearest ball, which rules out the
shots that start off a cushion).

It reports points per inning (the "average" players are ranked by) with its 95% interval,
the point rate per shot (clustered by inning), the planner's seconds per shot, the innings
that reached the match target (50: the env ends the inning there, so a row with such
innings gives a floor of the average) or the truncation, and the same for uniformly random
actions (the trivial baseline), and writes a markdown file with its command.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

import pool_env  # noqa: F401  (registers the ids)
from agents.baselines.random_agent import RandomAgent
from agents.baselines.three_cushion_agent import ThreeCushionSearchAgent
from agents.evaluation.metrics import Estimate, mean_ci, ratio_ci
from pool_env import Table

__all__ = ["ENV_ID", "InningLog", "play_innings", "random_layout", "summarize"]

ENV_ID = "pool_env/ThreeCushion-v1"
#: A random layout's balls keep this much clearance (m) from each other and the cushions.
CLEARANCE = 0.002
#: The layouts innings start from.
LAYOUTS = ("break", "random")


def random_layout(table: Table, rng: np.random.Generator) -> NDArray[np.float64]:
    """``(3, 2)`` balls uniform on the bed, apart from each other and the cushions."""
    r = table.ball_radius
    margin = r + CLEARANCE
    while True:
        pos = np.column_stack(
            [
                rng.uniform(margin, table.length - margin, 3),
                rng.uniform(margin, table.width - margin, 3),
            ]
        )
        gaps = [np.hypot(*(pos[i] - pos[j])) for i, j in ((0, 1), (0, 2), (1, 2))]
        if min(gaps) > 2.0 * r + CLEARANCE:
            return pos


@dataclass
class InningLog:
    """One inning: its points, shots, how it ended, seconds per shot.

    ``target``: it ended on a point (the match's target reached: the env ends the inning
    there, so its points are a floor of what the player would have run); ``truncated``: the
    env's 100-shot limit cut it.
    """

    points: int = 0
    shots: int = 0
    target: bool = False
    truncated: bool = False
    seconds: list[float] = field(default_factory=list)


def play_innings(env: gym.Env, agent: Any, layout: str, innings: int, seed: int) -> list[InningLog]:
    """``innings`` episodes of ``env`` played by ``agent`` from ``layout``.

    Args:
        env: A ``ThreeCushion-v1`` env.
        agent: A policy (``predict``).
        layout: ``"break"`` (the env's starting position) or ``"random"``.
        innings: Episodes to play.
        seed: Inning ``k`` resets with seed ``seed * 100_003 + k``; its random layout is
            drawn from ``default_rng([seed, k])``.

    Raises:
        ValueError: On an unknown layout.
    """
    if layout not in LAYOUTS:
        raise ValueError(f"layout must be one of {LAYOUTS}, got {layout!r}")
    table = env.unwrapped.config.table
    logs = []
    for k in range(innings):
        options = None
        if layout == "random":
            options = {"positions": random_layout(table, np.random.default_rng([seed, k]))}
        obs, _ = env.reset(seed=seed * 100_003 + k, options=options)
        log = InningLog()
        while True:
            start = time.perf_counter()
            action, _ = agent.predict(obs)
            log.seconds.append(time.perf_counter() - start)
            obs, _, terminated, truncated, info = env.step(action)
            log.shots += 1
            log.points += int(bool(info["point"]))
            if terminated or truncated:
                log.truncated = bool(truncated) and not terminated
                log.target = bool(terminated) and bool(info["point"])
                break
        logs.append(log)
    return logs


def summarize(logs: Sequence[InningLog]) -> dict[str, Any]:
    """Points per inning, points per shot (clustered by inning), seconds per shot."""
    points = np.array([g.points for g in logs], dtype=np.float64)
    shots = np.array([g.shots for g in logs], dtype=np.float64)
    seconds = np.concatenate([g.seconds for g in logs])
    return {
        "points_per_inning": mean_ci(points),
        "point_rate": ratio_ci(points, shots, bounds=(0.0, 1.0)),
        "seconds_mean": float(seconds.mean()),
        "seconds_max": float(seconds.max()),
        "truncated": sum(g.truncated for g in logs),
        "target": sum(g.target for g in logs),
        "innings": len(logs),
        "best": int(points.max()),
    }


def _row(name: str, multiple: float, layout: str, s: dict[str, Any]) -> str:
    ppi, rate = s["points_per_inning"], s["point_rate"]
    assert isinstance(ppi, Estimate)
    assert isinstance(rate, Estimate)
    return (
        f"| {name} | x{multiple:g} | {layout} | {s['innings']} | {ppi} | {s['best']} "
        f"| {rate.as_percent()} | {s['seconds_mean']:.3f} | {s['seconds_max']:.3f} "
        f"| {s['target']} | {s['truncated']} |"
    )


HEADER = (
    "| player | noise | layout | innings | points/inning [95%] | best | points/shot [95%] "
    "| s/shot mean | s/shot max | at target | truncated |",
    "|---|---|---|---|---|---|---|---|---|---|---|",
)


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--innings", type=int, nargs="+", default=[100], metavar="N",
                        help="search innings per row: one count, or one per --noise")  # fmt: skip
    parser.add_argument("--noise", type=float, nargs="+", default=[0.0, 1.0, 5.0],
                        help="FastFiz multiples")  # fmt: skip
    parser.add_argument("--layouts", nargs="+", default=list(LAYOUTS), choices=LAYOUTS)
    parser.add_argument("--aim", default="absolute", choices=("absolute", "cut", "relative"))
    parser.add_argument("--budget", type=float, default=1.0, help="search seconds per shot")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--baseline-innings", type=int, default=200, help="random-action innings")
    parser.add_argument("--out", default=None, help="markdown file to write")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """The command line (``--help``)."""
    parser = _parser()
    args = parser.parse_args(argv)
    if len(args.innings) not in (1, len(args.noise)) or min(args.innings) < 1:
        parser.error(f"--innings must be one count >= 1 or one per --noise, got {args.innings}")
    if args.baseline_innings < 0:
        parser.error(f"--baseline-innings must be >= 0, got {args.baseline_innings}")
    if any(not (math.isfinite(m) and m >= 0) for m in args.noise):
        parser.error(f"--noise multiples must be >= 0, got {args.noise}")
    counts = args.innings * len(args.noise) if len(args.innings) == 1 else args.innings
    load = os.getloadavg()
    lines = list(HEADER)

    def run(name: str, make: Callable[[gym.Env], Any], multiple: float, n: int) -> None:
        for layout in args.layouts:
            env = gym.make(ENV_ID, noise=("fastfiz", multiple), aim=args.aim)
            logs = play_innings(env, make(env), layout, n, args.seed)
            lines.append(_row(name, multiple, layout, summarize(logs)))
            print(lines[-1], flush=True)
            env.close()

    for multiple, n in zip(args.noise, counts, strict=True):
        run(
            "search",
            lambda env: ThreeCushionSearchAgent(env, args.budget, args.threads, args.seed),
            multiple,
            n,
        )
        if args.baseline_innings:
            run("random actions", lambda env: RandomAgent(env, seed=args.seed), multiple,
                args.baseline_innings)  # fmt: skip
    end = os.getloadavg()
    command = "python -m agents.evaluation.three_cushion " + " ".join(
        sys.argv[1:] if argv is None else argv
    )
    text = "\n".join(
        [
            "# Three-cushion: the search player's points per inning",
            "",
            f"Command: `{command}`, under `flock /tmp/pool_cpu.lock`; aim `{args.aim}`, "
            f"budget {args.budget} s a shot on {args.threads} threads.",
            "",
            f"Load average (1, 5, 15 min) at the start {load[0]:.2f} {load[1]:.2f} "
            f"{load[2]:.2f}, at the end {end[0]:.2f} {end[1]:.2f} {end[2]:.2f} (2 cores).",
            "",
            *lines,
            "",
        ]
    )
    print(text)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
