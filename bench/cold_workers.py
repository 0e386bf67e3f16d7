"""Many processes starting on an empty compile cache: one compile between them, or one each?

``gym.make_vec(id, n, vectorization_mode="async")`` starts ``n`` worker processes; on an
empty cache each needs every kernel at once. This times, from spawn to the end of the first
``step``, a fresh interpreter making one env and one making the async vector env of
``--workers`` processes, each from an empty cache (``NUMBA_CACHE_DIR`` a fresh folder), for
this tree and, in the same run, for a clone of ``--base`` (a commit before the compile
locks), alternating the trees. The ratio ``workers / one process`` is the figure: 1.0 would
be the workers costing nothing beyond the one compile; ``n / cores`` is each compiling alone.

    python -m bench.cold_workers --base 51b3bb5 --runs 2

Writes ``results/cold_workers.md``. CPU-heavy (every run compiles from scratch): run alone.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench.first_shot import head_commit, publish

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "results" / "cold_workers.md"

CHILD = """
import sys, time, warnings
t0 = time.perf_counter()
warnings.filterwarnings("ignore", message=".*out of date.*")
import gymnasium as gym
import pool_env
env_id, n = sys.argv[1], int(sys.argv[2])
if n == 1:
    env = gym.make(env_id)
else:
    env = gym.make_vec(env_id, n, vectorization_mode="async")
env.reset(seed=0)
env.action_space.seed(0)
env.step(env.action_space.sample())
print("first step", time.perf_counter() - t0, flush=True)
env.close()
"""


def run_child(tree: Path, env_id: str, n: int, cache: Path) -> tuple[float, float]:
    """Seconds to the first step (as the child times it) and the CPU seconds of all."""
    env = dict(os.environ, PYTHONPATH=str(tree), NUMBA_CACHE_DIR=str(cache))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(
        [sys.executable, "-c", CHILD, env_id, str(n)],
        cwd=tree,
        env=env,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    if proc.returncode != 0:
        raise RuntimeError(f"{tree} {env_id} x{n} failed:\n{proc.stderr}")
    first = next(line for line in proc.stdout.splitlines() if line.startswith("first step"))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return float(first.split()[-1]), cpu


def main(argv: list[str] | None = None) -> int:
    """Time one process and ``--workers`` async workers from empty caches; write the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--id", default="pool_env/NineBall-v1", help="env id")
    parser.add_argument("--workers", type=int, default=8, help="async vector env workers")
    parser.add_argument("--runs", type=int, default=2, help="runs of each kind and tree")
    parser.add_argument("--base", default=None, help="a commit to compare, same run")
    args = parser.parse_args(argv)
    head = head_commit()
    load_before = os.getloadavg()[0]
    rows: dict[tuple[str, int], list[tuple[float, float]]] = {}
    with tempfile.TemporaryDirectory() as scratch:
        trees = {f"this tree ({head})": ROOT}
        if args.base:
            clone = Path(scratch) / "base"
            subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
            subprocess.run(["git", "checkout", "-q", args.base], cwd=clone, check=True)
            trees = {f"base ({args.base})": clone, **trees}
        counter = 0
        for _ in range(args.runs):
            for name, tree in trees.items():
                for n in (1, args.workers):
                    counter += 1
                    cache = Path(scratch) / f"cache{counter}"
                    figures = run_child(tree, args.id, n, cache)
                    rows.setdefault((name, n), []).append(figures)
                    print(name, n, figures, flush=True)
    load_after = os.getloadavg()[0]
    lines = [
        "# Processes starting together on an empty compile cache",
        "",
        f"Command: `python -m bench.cold_workers --id {args.id} --workers {args.workers} "
        f"--runs {args.runs}"
        + (f" --base {args.base}`" if args.base else "`")
        + f" at `{head}`, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
        f"{os.cpu_count()} cores, load {load_before:.1f} before and {load_after:.1f} after. "
        "Each run is a fresh interpreter with an empty `NUMBA_CACHE_DIR`, timed from the "
        "start of its script to the end of its first `step` (medians of the runs, seconds); "
        "CPU is the child's and its workers' user + system time.",
        "",
        "| tree | processes | first step (s) | CPU (s) | workers / one process |",
        "|---|---|---|---|---|",
    ]
    for name in trees:
        one = statistics.median(w for w, _ in rows[(name, 1)])
        for n in (1, args.workers):
            wall = statistics.median(w for w, _ in rows[(name, n)])
            cpu = statistics.median(c for _, c in rows[(name, n)])
            kind = "1 (`gym.make`)" if n == 1 else f"{n} (`make_vec`, async)"
            lines.append(f"| {name} | {kind} | {wall:.1f} | {cpu:.0f} | {wall / one:.2f} |")
    publish(lines, OUT)
    return 0


if __name__ == "__main__":
    sys.exit(main())
