"""Touching racks: break statistics with today's sequential rule and with tiny gaps.

Run::

    python -m bench.rack_gap                # 2000 breaks per gap -> results/rack_gap.md
    python -m bench.rack_gap --breaks 40    # smoke run (prints, writes nothing)

A frozen rack has every ball touching its neighbours, so one cue-ball impact starts many
contacts at one instant; conservation and restitution do not fix the outcome of three or
more bodies in contact (Mueller and Poeschel, "Three balls problem revisited", 2010), and
each simulator picks a rule. This package resolves them as a chain of pairwise impacts in
a fixed order at the same instant (``pool_env.sim.kernels.loop``); a rack with a gap
between neighbours resolves every impact at its own instant, in the order the physics
gives. The bench plays the same seeded 9-ball breaks on ``Table(model="spin")`` (jaw
pockets) with the rack touching (gap 0: today's rule) and with gaps of 1e-6, 1e-5 and 1e-4
m, and reports per gap: balls potted per break, breaks potting at least one, the cue ball
scratched, the cue ball's distance from its start, the events per break, and how often a
break pots a different set of balls than the touching rack.

Breaks: the cue ball on the head string's half, 0.1-0.4 m off the long axis; a centre-ball
stroke (the tip at ``(0, N(0, 0.05))``) at 7-11 m/s aimed at the 1-ball with N(0, 0.3
degrees) of error.
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

from pool_env import Table, shoot
from pool_env.sim.layouts import break_scene

ROOT = Path(__file__).resolve().parents[1]
GAPS = (0.0, 1e-6, 1e-5, 1e-4)  # m between rack neighbours


def breaks(table: Table, n: int, seed: int = 31) -> list[tuple[np.ndarray, float, float, float]]:
    """``n`` seeded breaks: (cue ball position, aim, speed, vertical tip)."""
    rng = np.random.default_rng(seed)
    rack = break_scene(table, "nine")
    out = []
    for _ in range(n):
        cue = np.array(
            [table.length / 4, table.width / 2 + rng.choice((-1, 1)) * rng.uniform(0.1, 0.4)]
        )
        aim = rack[1] - cue
        angle = math.atan2(aim[1], aim[0]) + math.radians(rng.normal(0.0, 0.3))
        out.append((cue, angle, float(rng.uniform(7.0, 11.0)), float(rng.normal(0.0, 0.05))))
    return out


def play(table: Table, gap: float, shots: list) -> dict[str, np.ndarray]:
    """Each break on a rack with ``gap``: potted counts, scratches, cue travel, events, sets."""
    rack = break_scene(table, "nine", gap=gap)
    made, scratch, travel, events, capped, sets = [], [], [], [], [], []
    for cue, angle, speed, b in shots:
        pos = rack.copy()
        pos[0] = cue
        res = shoot(table, pos, angle, speed, 0, tip=(0.0, b), record=False)
        pocketed = res.pocketed
        made.append(int((pocketed[1:] >= 0).sum()))
        scratch.append(bool(pocketed[0] >= 0))
        travel.append(float(np.hypot(*(res.positions[0] - cue))))
        events.append(int(res.n_events))
        capped.append(bool(res.hit_event_cap))
        sets.append(frozenset(np.flatnonzero(pocketed[1:] >= 0).tolist()))
    return {
        "made": np.array(made),
        "scratch": np.array(scratch),
        "travel": np.array(travel),
        "events": np.array(events),
        "capped": np.array(capped),
        "sets": np.array(sets, dtype=object),
    }


def _mean_ci(x: np.ndarray) -> str:
    """Mean with a 95% normal interval."""
    half = 1.96 * x.std(ddof=1) / math.sqrt(len(x)) if len(x) > 1 else 0.0
    return f"{x.mean():.3f} +- {half:.3f}"


def main() -> None:
    """Entry point."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--breaks", type=int, default=2000)
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "rack_gap.md")
    args = ap.parse_args()
    table = Table(model="spin")
    shots = breaks(table, args.breaks)
    t0 = time.perf_counter()
    runs = {gap: play(table, gap, shots) for gap in GAPS}
    base = runs[0.0]["sets"]
    lines = [
        "| rack gap | balls potted per break | breaks potting >= 1 | cue ball scratched "
        "| cue ball's final distance (m) | events per break (median) | other potted set "
        "than touching |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for gap, r in runs.items():
        differ = np.mean([a != b for a, b in zip(r["sets"], base, strict=True)])
        lines.append(
            f"| {'touching (today)' if gap == 0 else f'{gap:.0e} m'} | {_mean_ci(r['made'])} | "
            f"{_mean_ci((r['made'] > 0).astype(float))} | {_mean_ci(r['scratch'].astype(float))} "
            f"| {_mean_ci(r['travel'])} | {np.median(r['events']):.0f} | {differ:.2f} |"
        )
    capped = sum(int(r["capped"].sum()) for r in runs.values())
    seconds = time.perf_counter() - t0
    note = f"{args.breaks} breaks per gap, {seconds:.0f} s; event cap hit {capped} times"
    print("\n".join([*lines, note]))
    if args.breaks >= 2000:
        header = (
            "# Touching racks: break statistics by rack gap\n\n"
            f"`python -m bench.rack_gap` ({time.strftime('%Y-%m-%d', time.gmtime())}); the "
            "set-up is the script's docstring. Intervals: 95% normal intervals of the mean.\n\n"
        )
        args.out.write_text(header + "\n".join([*lines, "", note]) + "\n")
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
