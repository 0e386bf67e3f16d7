"""Three-cushion innings: the search player's average (points per inning), and a baseline's.

``python -m agents.evaluation.three_cushion`` plays innings on the raw simulator
(``Table.preset("carom")``, white's cue ball) from fixed seeds: from the UMB break position
(the cue ball must meet the red first on the break shot) and from random three-ball
layouts, at FastFiz x0, x1 and x5. An inning goes on while points are made (capped at
``--max-shots``). Each shot is played as the env plays it: the player's shot plus the
noise's draws (:func:`agents.baselines.carom.noisy_rows`), then recorded, and the point
judged from the event log (:func:`agents.baselines.carom.point_of_events`), not from the
rows the player searched.

It reports points per inning (the "average" players are ranked by) with its 95% interval,
the point rate per shot (clustered by inning), seconds per shot, and the same for random
shots (the trivial baseline), and writes a markdown file with its command.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from agents.baselines.carom import noisy_rows, point_of_events
from agents.baselines.three_cushion_search import CaromPlan, ThreeCushionSearch
from agents.evaluation.metrics import Estimate, mean_ci, ratio_ci
from pool_env import Table, shoot
from pool_env.game.checks import default_tip_limit
from pool_env.game.noise import fastfiz_sigmas

__all__ = ["InningLog", "break_layout", "play_inning", "random_layout", "summarize"]

#: The UMB break: the red on the top spot, the yellow on the head spot, the white on the
#: head string 0.1825 m to the side of it (pooltool 0.6's three-cushion rack).
BREAK_OFFSET = 0.1825
#: The red: the ball the cue ball must meet first on the break.
RED = 2
#: A random layout's balls keep this much clearance (m) from each other and the cushions.
CLEARANCE = 0.002

#: A player: ``(positions, cue, first_ball) -> (angle, speed, tip a, tip b)``.
Player = Callable[[NDArray[np.float64], int, int | None], tuple[float, float, float, float]]


def break_layout(table: Table) -> NDArray[np.float64]:
    """``(3, 2)`` white, yellow, red at the UMB break (the long axis is x)."""
    length, width = table.length, table.width
    return np.array(
        [
            [length / 4.0, width / 2.0 + BREAK_OFFSET],
            [length / 4.0, width / 2.0],
            [3.0 * length / 4.0, width / 2.0],
        ]
    )


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
    """One inning: its points, shots and the player's seconds per shot."""

    points: int = 0
    shots: int = 0
    capped: bool = False
    seconds: list[float] = field(default_factory=list)


def play_inning(
    table: Table,
    positions: NDArray[np.float64],
    player: Player,
    sigmas: Sequence[float],
    rng: np.random.Generator,
    max_shots: int,
    first_ball: int | None = None,
) -> InningLog:
    """Play one inning with white's cue ball: shots while they score, at most ``max_shots``.

    Args:
        table: The carom table.
        positions: ``(3, 2)`` the layout.
        player: The player.
        sigmas: The execution noise ``(angle, speed, tip)`` (zeros: none).
        rng: The noise's generator.
        max_shots: The cap on an inning's shots.
        first_ball: The ball the first shot must meet first (the break's red), or ``None``.
    """
    log = InningLog()
    pos = positions.copy()
    limit = default_tip_limit(table)
    for _ in range(max_shots):
        start = time.perf_counter()
        angle, speed, a, b = player(pos, 0, first_ball)
        log.seconds.append(time.perf_counter() - start)
        row = noisy_rows(
            np.array([[angle, speed, a, b, 0.0]]), rng.standard_normal((1, 4)), sigmas, limit
        )[0]
        result = shoot(table, pos, row[0], row[1], cue=0, tip=(row[2], row[3]))
        log.shots += 1
        scored = point_of_events(result.events, 0)
        if first_ball is not None:
            scored &= int(result.first_hit[0]) == first_ball
        if not scored:
            return log
        log.points += 1
        pos = result.positions.copy()
        first_ball = None
    log.capped = True
    return log


def summarize(logs: Sequence[InningLog]) -> dict[str, Estimate | float]:
    """Points per inning, points per shot (clustered by inning), seconds per shot."""
    points = np.array([g.points for g in logs], dtype=np.float64)
    shots = np.array([g.shots for g in logs], dtype=np.float64)
    seconds = np.concatenate([g.seconds for g in logs])
    return {
        "points_per_inning": mean_ci(points),
        "point_rate": ratio_ci(points, shots, bounds=(0.0, 1.0)),
        "seconds_mean": float(seconds.mean()),
        "seconds_max": float(seconds.max()),
        "capped": float(sum(g.capped for g in logs)),
        "innings": float(len(logs)),
        "shots": float(shots.sum()),
    }


def search_player(
    table: Table, sigmas: Sequence[float] | None, budget: float, threads: int, seed: int
) -> Player:
    """The search as a :data:`Player` (its plans' diagnostics kept on ``player.plans``)."""
    search = ThreeCushionSearch(
        table,
        noise=None if sigmas is None else tuple(sigmas),
        budget=budget,
        threads=threads,
        seed=seed,
    )
    plans: list[CaromPlan] = []

    def play(
        pos: NDArray[np.float64], cue: int, first_ball: int | None
    ) -> tuple[float, float, float, float]:
        plan = search.plan(pos, cue, first_ball)
        plans.append(plan)
        return plan.angle, plan.speed, plan.tip[0], plan.tip[1]

    play.plans = plans  # type: ignore[attr-defined]
    return play


def random_player(table: Table, seed: int, speed_range: tuple[float, float] = (0.5, 7.0)) -> Player:
    """Uniform shots: any aim, a speed in the range, a tip uniform in the miscue circle."""
    rng = np.random.default_rng(seed)
    limit = default_tip_limit(table)

    def play(
        pos: NDArray[np.float64], cue: int, first_ball: int | None
    ) -> tuple[float, float, float, float]:
        r, t = limit * math.sqrt(rng.uniform()), rng.uniform(0.0, 2.0 * math.pi)
        return (
            rng.uniform(0.0, 2.0 * math.pi),
            rng.uniform(*speed_range),
            r * math.cos(t),
            r * math.sin(t),
        )

    return play


def evaluate(
    table: Table,
    make_player: Callable[[Sequence[float] | None, int], Player],
    multiple: float,
    layout: str,
    innings: int,
    seed: int,
    max_shots: int,
) -> list[InningLog]:
    """``innings`` innings from ``layout`` (``"break"`` or ``"random"``) at FastFiz ``multiple``."""
    sigmas = fastfiz_sigmas(table, multiple)
    player = make_player(sigmas if multiple > 0 else None, seed)
    logs = []
    for k in range(innings):
        rng = np.random.default_rng([seed, k, round(100 * multiple)])
        if layout == "break":
            pos, first = break_layout(table), RED
        else:
            pos, first = random_layout(table, np.random.default_rng([seed, k])), None
        logs.append(play_inning(table, pos, player, sigmas, rng, max_shots, first))
    return logs


def _row(name: str, multiple: float, layout: str, s: dict[str, Estimate | float]) -> str:
    ppi, rate = s["points_per_inning"], s["point_rate"]
    assert isinstance(ppi, Estimate)
    assert isinstance(rate, Estimate)
    return (
        f"| {name} | x{multiple:g} | {layout} | {int(s['innings'])} | {ppi} | {rate.as_percent()} "
        f"| {s['seconds_mean']:.3f} | {s['seconds_max']:.3f} | {int(s['capped'])} |"
    )


def main(argv: Sequence[str] | None = None) -> int:
    """The command line (``--help``)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--innings", type=int, default=100, help="innings per row")
    parser.add_argument(
        "--noise", type=float, nargs="+", default=[0.0, 1.0, 5.0], help="FastFiz multiples"
    )
    parser.add_argument(
        "--layouts", nargs="+", default=["break", "random"], choices=["break", "random"]
    )
    parser.add_argument("--budget", type=float, default=1.0, help="search seconds per shot")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--max-shots", type=int, default=25, help="an inning's cap")
    parser.add_argument(
        "--baseline-innings", type=int, default=200, help="random-shot innings per row"
    )
    parser.add_argument("--out", default=None, help="markdown file to write")
    args = parser.parse_args(argv)
    for name in ("innings", "max_shots", "threads"):
        if getattr(args, name) < 1:
            parser.error(f"--{name.replace('_', '-')} must be >= 1, got {getattr(args, name)}")
    if any(not (math.isfinite(m) and m >= 0) for m in args.noise):
        parser.error(f"--noise multiples must be >= 0, got {args.noise}")
    table = Table.preset("carom")
    load = os.getloadavg()
    lines = [
        "| player | noise | layout | innings | points/inning [95%] | points/shot [95%] "
        "| s/shot mean | s/shot max | capped |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for multiple in args.noise:
        for layout in args.layouts:
            logs = evaluate(
                table,
                lambda sig, seed: search_player(table, sig, args.budget, args.threads, seed),
                multiple,
                layout,
                args.innings,
                args.seed,
                args.max_shots,
            )
            lines.append(_row("search", multiple, layout, summarize(logs)))
            print(lines[-1], flush=True)
            base = evaluate(
                table,
                lambda sig, seed: random_player(table, seed),
                multiple,
                layout,
                args.baseline_innings,
                args.seed,
                args.max_shots,
            )
            lines.append(_row("random shots", multiple, layout, summarize(base)))
            print(lines[-1], flush=True)
    end_load = os.getloadavg()
    command = "python -m agents.evaluation.three_cushion " + " ".join(
        sys.argv[1:] if argv is None else argv
    )
    text = "\n".join(
        [
            "# Three-cushion: the search player's points per inning",
            "",
            f"Command: `{command}` (under `flock /tmp/pool_cpu.lock`).",
            "",
            f"Load average (1, 5, 15 min) at the start {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}, "
            f"at the end {end_load[0]:.2f} {end_load[1]:.2f} {end_load[2]:.2f} (2 cores).",
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
