"""Simulator speed: time per ``shoot()`` call, end to end from Python, and cold starts.

Run: ``python bench/simulator_speed.py`` (about 2 minutes). Prints and writes
``results/simulator_speed.md``. Each suite times ``shoot()`` calls one by one with
``time.perf_counter`` after a warm-up; medians and p95 over all shots of all repeats. Cold
starts time a fresh ``python -c`` from spawn to its first shot done, with an empty and with a
warm numba cache.
"""

from __future__ import annotations

import argparse
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numba
import numpy as np

from pool_env import Table, shoot
from pool_env.sim.batch import simulate_batch
from pool_env.sim.layouts import break_scene
from pool_env.testing.scenes_random import random_layout

# pooltool 0.6.0 on this machine (docs/sources.md, "Other simulators"; not measured here: see
# bench/speed_vs_error.py for a same-run comparison).
POOLTOOL_MS = {"one-ball": 7.0, "two-ball": 7.0, "9-ball break": 80.0, "16-ball break": 150.0}
TARGET_US = {"one-ball": 20.0, "two-ball": 20.0, "9-ball break": 250.0, "16-ball break": 1000.0}

Shot = tuple[np.ndarray, float, float]


def one_ball_shots(table: Table, rng: np.random.Generator, n: int) -> list[Shot]:
    """A lone ball anywhere, any direction, 0.5-8 m/s."""
    return [
        (random_layout(table, 1, rng), rng.uniform(-np.pi, np.pi), rng.uniform(0.5, 8.0))
        for _ in range(n)
    ]


def two_ball_shots(table: Table, rng: np.random.Generator, n: int) -> list[Shot]:
    """Cue and object ball anywhere; the cue aimed at the object ball with a random cut."""
    shots = []
    for _ in range(n):
        pos = random_layout(table, 2, rng)
        d = pos[1] - pos[0]
        cut = rng.uniform(-0.9, 0.9) * np.arcsin(min(1.0, 2 * table.ball_radius / np.hypot(*d)))
        shots.append((pos, float(np.arctan2(d[1], d[0]) + cut), rng.uniform(0.5, 8.0)))
    return shots


def break_shots(table: Table, rng: np.random.Generator, n: int, rack: str) -> list[Shot]:
    """A touching rack broken at 8 m/s, aimed at the apex with a jitter of +-5 mrad."""
    pos = break_scene(table, rack)
    return [(pos, float(rng.uniform(-0.005, 0.005)), 8.0) for _ in range(n)]


def time_shots(table: Table, shots: list[Shot], repeats: int) -> tuple[np.ndarray, np.ndarray]:
    """Per-call wall times (s) over ``repeats`` passes, and events per shot."""
    events = np.array([shoot(table, p, a, s).n_events for p, a, s in shots])  # warm-up
    times = []
    clock = time.perf_counter
    for _ in range(repeats):
        for p, a, s in shots:
            t0 = clock()
            shoot(table, p, a, s)
            times.append(clock() - t0)
    return np.array(times), events


def time_batched(table: Table, shots: list[Shot], repeats: int, size: int = 256) -> np.ndarray:
    """Per-shot wall times (s) of ``simulate_batch`` calls of ``size`` tables, serially."""
    positions = np.array([p for p, _, _ in shots])
    velocities = np.zeros_like(positions)
    angles = np.array([a for _, a, _ in shots])
    speeds = np.array([s for _, _, s in shots])
    velocities[:, 0, 0] = speeds * np.cos(angles)
    velocities[:, 0, 1] = speeds * np.sin(angles)
    simulate_batch(table, positions[:size], velocities[:size], parallel=False)  # warm-up
    per_shot = []
    for _ in range(repeats):
        for start in range(0, len(shots) - size + 1, size):
            chunk = slice(start, start + size)
            t0 = time.perf_counter()
            simulate_batch(table, positions[chunk], velocities[chunk], parallel=False)
            per_shot.append((time.perf_counter() - t0) / size)
    return np.array(per_shot)


def jaws_against_circles(rng: np.random.Generator, n: int, repeats: int) -> str:
    """The same one-ball shots on the jaw table and on capture circles, interleaved."""
    jaws, circles = Table(), Table(pockets="circles")
    shots = one_ball_shots(jaws, rng, n)
    medians = {"jaws": [], "circles": []}
    for _ in range(repeats):  # alternate, so load changes hit both alike
        for name, table in (("jaws", jaws), ("circles", circles)):
            times, _ = time_shots(table, shots, 1)
            medians[name].append(np.median(times))
    jaw_us = np.median(medians["jaws"]) * 1e6
    circle_us = np.median(medians["circles"]) * 1e6
    return (
        f"- one-ball shots, jaws against capture circles (the same {n} shots, alternating, "
        f"{repeats} passes): {jaw_us:.1f} us against {circle_us:.1f} us per shot, ratio "
        f"{jaw_us / circle_us:.2f} (target <= 1.3); load {os.getloadavg()[0]:.1f}"
    )


def cold_start(cache_dir: str) -> float:
    """Seconds from spawning a fresh interpreter to its first shot done."""
    code = (
        "from pool_env import Table, shoot\n"
        "from pool_env.sim.layouts import break_scene\n"
        "t = Table(); shoot(t, break_scene(t, 'nine'), 0.0, 8.0)\n"
    )
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", code], env=env, check=True)
    return time.perf_counter() - t0


def main() -> None:
    """Run every suite and the cold starts; print and write the report."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--shots", type=int, default=2000, help="shots per small suite")
    parser.add_argument("--breaks", type=int, default=300, help="shots per break suite")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--cold", type=int, default=3, help="cold starts of each kind")
    parser.add_argument("--out", type=Path, default=Path("results/simulator_speed.md"))
    parser.add_argument(
        "--jaws-only", action="store_true", help="only the jaws against capture circles line"
    )
    args = parser.parse_args()
    if args.jaws_only:
        print(jaws_against_circles(np.random.default_rng(1), args.shots, args.repeats))
        return
    table = Table()
    rng = np.random.default_rng(0)
    suites: dict[str, Callable[[], list[Shot]]] = {
        "one-ball": lambda: one_ball_shots(table, rng, args.shots),
        "two-ball": lambda: two_ball_shots(table, rng, args.shots),
        "9-ball break": lambda: break_shots(table, rng, args.breaks, "nine"),
        "16-ball break": lambda: break_shots(table, rng, args.breaks, "eight"),
    }
    rows = []
    batched = []
    for name, make in suites.items():
        shots = make()
        if name == "two-ball":
            per_shot = np.median(time_batched(table, shots, args.repeats)) * 1e6
            batched.append(
                f"- two-ball shots through `simulate_batch` (256 tables per call, one thread): "
                f"{per_shot:.2f} us per shot, {POOLTOOL_MS[name] * 1e3 / per_shot:.0f}x "
                "the pooltool figure"
            )
        times, events = time_shots(table, shots, args.repeats)
        med, p95 = np.median(times) * 1e6, np.percentile(times, 95) * 1e6
        per_event = med / max(np.median(events), 1)
        rows.append(
            f"| {name} | {med:.1f} | {p95:.1f} | {p95 / med:.2f} | {np.median(events):.0f} | "
            f"{per_event:.2f} | {TARGET_US[name]:.0f} | {'yes' if med <= TARGET_US[name] else 'NO'}"
            f" | {POOLTOOL_MS[name] * 1e3 / med:.0f}x |"
        )
        print(rows[-1], flush=True)

    batched.append(jaws_against_circles(np.random.default_rng(1), args.shots, args.repeats))
    print(batched[-1], flush=True)
    with tempfile.TemporaryDirectory() as cache:
        empty = []
        for _ in range(args.cold):
            shutil.rmtree(cache)
            os.mkdir(cache)
            empty.append(cold_start(cache))
        warm = [cold_start(cache) for _ in range(args.cold)]
    lines = [
        "# Simulator speed",
        "",
        f"Command: `python bench/simulator_speed.py --shots {args.shots} --breaks "
        f"{args.breaks} --repeats {args.repeats} --cold {args.cold}`",
        "",
        f"Machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores; "
        f"Python {platform.python_version()}, numpy {np.__version__}, numba {numba.__version__}; "
        f"load average at the end {os.getloadavg()[0]:.1f} (the machine is shared).",
        "",
        "Time per `shoot()` call, end to end from Python (validation, the compiled event loop,",
        "the result object, events recorded), warm, one process.",
        "",
        "| suite | median (us) | p95 (us) | p95/median | events/shot (median) | "
        "us/event | target (us) | met | vs pooltool 0.6.0* |",
        "|---|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        *batched,
        "",
        "*pooltool figures measured earlier on this machine (docs/sources.md: ~7 ms per one- or",
        "two-ball shot, ~80 ms per 9-ball break, ~150 ms per 16-ball break); its physics adds",
        "sliding and spin. `bench/speed_vs_error.py` compares the engines in one run.",
        "",
        f"Fresh process, `python -c` spawn to first 9-ball break done (median of {args.cold}):",
        "",
        f"- empty compile cache: {np.median(empty):.2f} s (target <= 20 s)",
        f"- warm compile cache: {np.median(warm):.2f} s (target <= 1.5 s)",
        "",
    ]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text("\n".join(lines))
    print("\n".join(lines))


if __name__ == "__main__":
    main()
