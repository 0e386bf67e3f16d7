"""How many root solves a shot makes, against how many find a root and how many are events.

Run: ``python -m bench.prediction_count`` (about a minute; the kernels run interpreted,
``NUMBA_DISABLE_JIT=1``, so that the solvers can be counted). Writes
``results/prediction_count.md``.

The shot sets of :mod:`bench.rollout_speed` (two-ball shots at 2 m/s and 9-ball breaks at
8 m/s on the default table, random tips on the spin level), played one by one through
``shoot``. Counted per shot, by wrapping the solvers where the predictors call them
(:func:`pool_env.testing.solver_counts.install`):

* ``quartic``: ``first_contact`` of :mod:`pool_env.sim.kernels.roots` (a pair of balls, a
  capture circle or a jaw point on a curved path: the bracketed quartic), by caller;
* ``quadratic``: ``equal_accel_contact`` (a pair with
  equal accelerations);
* ``found``: the solves that return a time inside their window (a candidate event);
* ``events``: the shot's events of the kinds these solves predict (ball-ball impacts,
  captures, jaw points).

The gap between solves and events is what a cheaper prediction could still save: a solve
that finds nothing (culling that missed), and a root found and then re-predicted away (an
earlier event changed the ball first).
"""

from __future__ import annotations

import os

os.environ["NUMBA_DISABLE_JIT"] = "1"  # before numba is imported: the solvers as Python

import argparse
import time
from collections import Counter
from pathlib import Path

from bench.rollout_speed import shot_set
from pool_env import shoot
from pool_env.testing import solver_counts

COUNTS: Counter[str] = Counter()


def count(model: str, scene: str, n: int, seed: int) -> dict[str, float]:
    """Per-shot means of the counts over ``n`` shots of one set."""
    table, layout, rows = shot_set(model, scene, n, seed)
    COUNTS.clear()
    events: Counter[str] = Counter()
    for angle, speed, a, b, e in rows:
        result = shoot(table, layout, angle, speed, tip=(a, b), elevation=e)
        events.update(event.kind for event in result.events)
        events["all"] += len(result.events)
    out = {k: v / n for k, v in COUNTS.items()}
    out["events"] = events["all"] / n
    out["predicted events"] = (events["ball"] + events["pocket"] + events["point"]) / n
    return out


def main() -> None:
    """Count both levels on both shot sets; print and write the table."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--shots", type=int, default=40)
    parser.add_argument("--seed", type=int, default=3)
    parser.add_argument("--out", type=Path, default=Path("results/prediction_count.md"))
    args = parser.parse_args()
    solver_counts.install(COUNTS)
    lines = [
        "| level | shots | events/shot | ball, capture and point events/shot | quartic "
        "solves/shot | found a root | quadratic solves/shot | found a root |",
        "|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for model in ("roll", "spin"):
        for scene in ("two-ball", "9-ball break"):
            c = count(model, scene, args.shots, args.seed)
            lines.append(
                f"| {model} | {scene} | {c['events']:.1f} | {c['predicted events']:.1f} | "
                f"{c.get('quartic', 0):.1f} | {c.get('quartic found', 0):.1f} | "
                f"{c.get('quadratic', 0):.1f} | {c.get('quadratic found', 0):.1f} |"
            )
            print(lines[-1], flush=True)
    stamp = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    text = (
        "# Prediction count\n\n"
        f"`python -m bench.prediction_count` ({stamp}; see its docstring): per shot, the "
        "root solves the predictors make, how many find a root inside their window, and "
        f"the events of the kinds they predict; means over {args.shots} shots of each set of "
        "`bench.rollout_speed` (kernels interpreted to count, same arithmetic).\n\n"
        + "\n".join(lines)
        + "\n"
    )
    args.out.write_text(text)
    print(f"written to {args.out}")


if __name__ == "__main__":
    main()
