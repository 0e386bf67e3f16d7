"""Same-run speed ratio against pooltool 0.6.0, by wall clock and by thread CPU time.

Run: ``python -m bench.pooltool_ratio`` (about a minute with pooltool's numba cache warm;
pooltool from ``bash bench/setup_pooltool.sh``). The seeded shots and breaks of
``bench/speed_vs_error.py`` (``--shots``, ``--breaks``) run through pooltool in its own
virtualenv and through :func:`pool_env.simulate` (``record=False``, the call a training
loop makes, end to end from Python), each scene's time the median of ``--repeats``.

On the shared machine the wall clock of a process depends on how much CPU the others
leave it; the CPU time of the timing thread (``time.thread_time``) much less. Both are
printed, with the medians over scenes and their ratios; nothing is written.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from bench.engines.pooltool_engine import run_pooltool
from bench.runners import worker_scene
from bench.scenes import break_suite, shot_suite
from pool_env import simulate
from tools.shots import Scene


def ours(scene: Scene, repeats: int) -> tuple[float, float]:
    """Median wall and thread CPU seconds of one ``simulate(record=False)`` of ``scene``."""
    wall, cpu = [], []
    for _ in range(repeats):
        t0, c0 = time.perf_counter(), time.thread_time()
        simulate(scene.table, scene.positions, scene.velocities, scene.masses, record=False)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.thread_time() - c0)
    return float(np.median(wall)), float(np.median(cpu))


def main() -> None:
    """Time both engines on the same scenes and print the ratios."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shots", type=int, default=40)
    parser.add_argument("--breaks", type=int, default=4)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    scenes = [*shot_suite(args.shots), *break_suite(args.breaks)]
    for s in scenes:  # warm up: load our compiled kernels
        simulate(s.table, s.positions, s.velocities, s.masses, record=False)
    load_start = os.getloadavg()[0]
    out = run_pooltool([worker_scene(s) for s in scenes], repeats=args.repeats)
    if not out.get("available"):
        raise SystemExit(f"pooltool did not run: {out.get('reason')}")
    pooltool = np.array(
        [[np.median(r["times"]), np.median(r["cpu_times"])] for r in out["results"]]
    )
    mine = np.array([ours(s, 2 * args.repeats + 1) for s in scenes])
    n = len(shot_suite(args.shots))
    when = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    print(
        f"pooltool {out['pooltool']} (numba {out['numba']}); load {load_start:.1f} at the "
        f"start, {os.getloadavg()[0]:.1f} at the end; {when}"
    )
    print(
        "| suite | scenes | pooltool wall | pooltool CPU | ours wall | ours CPU | ratio wall "
        "| ratio CPU |"
    )
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, part in (("shots (1-3 collisions)", slice(0, n)), ("breaks", slice(n, None))):
        pw, pc = np.median(pooltool[part], axis=0)
        ow, oc = np.median(mine[part], axis=0)
        print(
            f"| {name} | {len(scenes[part])} | {pw * 1e3:.2f} ms | {pc * 1e3:.2f} ms | "
            f"{ow * 1e6:.2f} us | {oc * 1e6:.2f} us | {pw / ow:.0f}x | {pc / oc:.0f}x |"
        )


if __name__ == "__main__":
    main()
