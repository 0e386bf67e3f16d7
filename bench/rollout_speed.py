"""Rollout speed: shots per second of :func:`pool_env.sim.rollout`, both levels.

Run (under the CPU lock, on a quiet machine)::

    python -m bench.rollout_speed

Two shot sets, on the default table (regulation jaws):

* two-ball: a layout of :func:`bench.simulator_speed.two_ball_shots` (cue and object ball
  anywhere, aimed at the object ball with a random cut), ``S`` candidate shots from it at
  2 m/s, the aim jittered by N(0, 0.02 rad), on the spin level a random tip in
  ``[-0.3, 0.3]^2``;
* 9-ball break: the touching rack of :func:`bench.simulator_speed.break_shots` at 8 m/s,
  the aim jittered by +-5 mrad (and the same tips).

For each: wall time of one ``rollout`` call of ``S`` shots with 1 thread and with every CPU
(medians of repeats after a warm-up), and in the same run the same shots played one by one
through ``shoot(..., record=False)``, the baseline. Writes ``results/rollout_speed.md``.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

import numpy as np

from bench.simulator_speed import break_shots, two_ball_shots
from pool_env import Table, shoot
from pool_env.sim import rollout
from pool_env.sim.batch import available_cpus


def candidate_rows(
    rng: np.random.Generator, angle: float, speed: float, n: int, spin: bool, jitter: float
) -> np.ndarray:
    """``n`` shot rows around one aim: the aim jittered, tips on the spin level."""
    rows = np.zeros((n, 5))
    rows[:, 0] = angle + jitter * rng.standard_normal(n)
    rows[:, 1] = speed
    if spin:
        rows[:, 2:4] = rng.uniform(-0.3, 0.3, (n, 2))
    return rows


def _median_time(f, repeats: int) -> float:
    f()  # warm-up (compiles on a cold cache)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def shot_set(model: str, scene: str, n: int, seed: int) -> tuple[Table, np.ndarray, np.ndarray]:
    """The default table of ``model``, one layout of ``scene`` and ``n`` shot rows from it."""
    table = Table(model=model)
    rng = np.random.default_rng(seed)
    if scene == "two-ball":
        layout, angle, _ = two_ball_shots(table, rng, 1)[0]
        rows = candidate_rows(rng, angle, 2.0, n, model == "spin", 0.02)
    else:
        layout, _, speed = break_shots(table, rng, 1, "nine")[0]
        rows = candidate_rows(rng, 0.0, speed, n, model == "spin", 0.0)
        rows[:, 0] = rng.uniform(-0.005, 0.005, n)
    return table, layout, rows


def measure(model: str, scene: str, n: int, repeats: int, seed: int) -> dict[str, float]:
    """Shots per second of one shot set: rollout on 1 thread, on every CPU, and shoot()."""
    table, layout, rows = shot_set(model, scene, n, seed)
    cpus = available_cpus()
    one = _median_time(lambda: rollout(table, layout, rows, threads=1), repeats)
    every = _median_time(lambda: rollout(table, layout, rows, threads=cpus), repeats)

    def one_by_one() -> None:
        for angle, speed, a, b, e in rows:
            shoot(table, layout, angle, speed, tip=(a, b), elevation=e, record=False)

    single = _median_time(one_by_one, max(1, repeats // 2)) / n
    events = float(np.mean(rollout(table, layout, rows).n_events))
    return {
        "events": events,
        "rollout_1": n / one,
        "rollout_all": n / every,
        "shoot": 1.0 / single,
        "cpus": cpus,
    }


def main() -> None:
    """Measure both levels on both shot sets; print and write the table."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--shots", type=int, default=4096, help="shots per rollout call")
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--out", type=Path, default=Path("results/rollout_speed.md"))
    args = parser.parse_args()
    load_before = os.getloadavg()[0]
    rows = []
    for model in ("roll", "spin"):
        for scene, n in (("two-ball", args.shots), ("9-ball break", max(64, args.shots // 8))):
            r = measure(model, scene, n, args.repeats, args.seed)
            rows.append(
                f"| {model} | {scene} | {n} | {r['events']:.1f} | {r['shoot']:,.0f} | "
                f"{r['rollout_1']:,.0f} | {r['rollout_all']:,.0f} ({r['cpus']}) | "
                f"{r['rollout_all'] / r['shoot']:.1f}x |"
            )
            print(rows[-1], flush=True)
    load_after = os.getloadavg()[0]
    text = "\n".join(
        [
            "# Rollout speed",
            "",
            "`python -m bench.rollout_speed` (see its docstring): shots per second of one "
            "`pool_env.sim.rollout` call of S shots from one layout, on 1 thread and on every "
            "CPU, beside the same shots through `shoot(..., record=False)` one by one, in "
            "the same run. Medians of "
            f"{args.repeats} repeats; load average {load_before:.2f} before, "
            f"{load_after:.2f} after.",
            "",
            "| level | shots | S | events/shot | shoot() /s | rollout 1 thread /s | "
            "rollout all CPUs /s | rollout / shoot |",
            "|---|---|---|---|---|---|---|---|",
            *rows,
            "",
        ]
    )
    args.out.write_text(text)
    print(f"written to {args.out}")


if __name__ == "__main__":
    main()
