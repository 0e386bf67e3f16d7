"""Robustness fuzz: many random scenes and shots, every invariant checked on each.

Run: ``python bench/fuzz.py --shots 100000`` (the long run; CI runs a small sample through
``tests/test_properties.py``). Prints the violation count and writes
``results/fuzz.md``. Scenes mix: random layouts of 2-16 balls (some touching), 9- and 15-ball
breaks with jittered aim, random speeds from 1e-6 to 15 m/s, random masses and restitutions,
jaw tables (half of them; random jaw restitution including 0), capture-circle and
pocketless tables. Shots aim at a pocket one time in four, so jaws are hit often.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from pool_env import Table, simulate
from pool_env.sim.layouts import break_scene
from pool_env.testing.invariants import check_shot
from pool_env.testing.scenes_random import random_layout


def random_case(rng: np.random.Generator) -> tuple[Table, np.ndarray, np.ndarray, np.ndarray]:
    """One random table, layout, initial velocities and masses."""
    e_cushion = float(rng.choice([1.0, 0.7, rng.uniform(0, 1)]))
    table = Table(
        e_ball=float(rng.choice([1.0, 0.95, rng.uniform(0, 1), 0.0])),
        e_cushion=e_cushion,
        pockets=str(rng.choice(["jaws", "jaws", "circles", "none"])),
        e_jaw=float(rng.choice([e_cushion, rng.uniform(0, 1), 0.0])),
    )
    kind = rng.integers(4)
    if kind == 0:
        pos = break_scene(table, str(rng.choice(["nine", "eight"])))
        # Pockets may cover the rack region on odd tables; these are standard tables.
    else:
        n = int(rng.integers(2, 17))
        pos = random_layout(table, n, rng, min_gap=float(rng.choice([0.0, 1e-3, 0.05])))
        if kind == 1 and n > 1:  # push ball 1 to touch ball 0 exactly, in a random direction
            phi = rng.uniform(0, 2 * np.pi)
            cand = pos[0] + 2 * table.ball_radius * np.array([np.cos(phi), np.sin(phi)])
            trial = pos.copy()
            trial[1] = cand
            try:
                simulate(table, trial, np.zeros_like(trial), record=False)
                pos = trial
            except ValueError:
                pass
    n = pos.shape[0]
    vel = np.zeros((n, 2))
    movers = [0] if rng.random() < 0.8 else list(range(n))
    for i in movers:
        # Mostly playing speeds, and a tail down to 1e-6 m/s.
        speed = float(rng.uniform(0.1, 15) if rng.random() < 0.8 else 10 ** rng.uniform(-6, -1))
        phi = rng.uniform(0, 2 * np.pi) if kind else rng.normal(0, 0.01)
        if kind and table.n_pockets and rng.random() < 0.25:  # at a pocket's mouth, jittered
            target = table.pockets[int(rng.integers(table.n_pockets)), :2]
            aim = target - pos[i] + rng.normal(0.0, 0.03, 2)
            phi = float(np.arctan2(aim[1], aim[0]))
        vel[i] = speed * np.array([np.cos(phi), np.sin(phi)])
    masses = rng.uniform(0.1, 0.3, n) if rng.random() < 0.3 else np.full(n, table.ball_mass)
    return table, pos, vel, masses


def main() -> None:
    """Run the fuzz and write ``results/fuzz.md``."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--shots", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--samples", type=int, default=400, help="G samples between events")
    parser.add_argument("--out", type=Path, default=Path("results/fuzz.md"))
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    started = time.time()
    failures: list[str] = []
    long_shots: list[str] = []
    events = []
    for shot in range(args.shots):
        table, pos, vel, masses = random_case(rng)
        result = simulate(table, pos, vel, masses)
        events.append(result.n_events)
        problems = check_shot(table, result, masses, samples=args.samples)
        if result.hit_event_cap:
            # T is about termination: a shot that needs more than the default cap (an
            # elastic table full of fast balls can) must end within ten times as many.
            longer = simulate(table, pos, vel, masses, max_events=10 * result.n_events)
            long_shots.append(f"shot {shot}: {longer.n_events} events over {longer.duration:.0f} s")
            problems = [p for p in problems if not p.startswith("T:")]
            problems += check_shot(table, longer, masses, samples=args.samples)
        if shot % 10 == 0:
            again = simulate(table, pos, vel, masses)
            if not np.array_equal(again.positions, result.positions) or not np.array_equal(
                again.event_times, result.event_times
            ):
                problems.append("D: rerun differs")
        if problems:
            failures.append(f"shot {shot}: {problems[:3]}")
            print(failures[-1], flush=True)
        if (shot + 1) % 10000 == 0:
            print(
                f"{shot + 1} shots, {len(failures)} with violations, {time.time() - started:.0f} s",
                flush=True,
            )
    ev = np.array(events)
    report = [
        "# Fuzz: invariants over random scenes and shots",
        "",
        f"Command: `python bench/fuzz.py --shots {args.shots} --seed {args.seed}`",
        "",
        f"- shots: {args.shots}; shots with any violation (G, P, E, T, D): {len(failures)}",
        f"- events per shot: median {np.median(ev):.0f}, p99 {np.percentile(ev, 99):.0f}, "
        f"max {ev.max()}",
        f"- wall time: {time.time() - started:.0f} s",
        "- shots needing more than the default cap of 10,000 events (checked again, with",
        f"  every invariant, under a cap ten times higher): {len(long_shots)}",
        *[f"  - {s}" for s in long_shots],
        "",
    ]
    report += [f"- {f}" for f in failures[:50]]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text("\n".join(report) + "\n")
    print("\n".join(report))


if __name__ == "__main__":
    main()
