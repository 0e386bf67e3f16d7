"""Same-run A/B timing of the compiled shot loop: this tree against a git revision.

Run: ``python bench/kernel_ab.py --ref main`` (a few minutes: each side compiles once);
``--env`` times a Gymnasium ``env.step`` of four ids instead (the decision process end to
end: decoding, noise, the simulator, the rules, the observation and ``info``).
Exports ``--ref`` with ``git archive`` to a temporary folder, then alternates fresh
processes of the two trees (``--rounds`` times each), every one timing the roll level's
event loop from a compiled loop (no Python in the measured path) and
``shoot``/``simulate_batch`` end to end.
Times are thread CPU time (``time.thread_time``), the minimum over repeats: on a shared
machine that is far steadier than wall time. Prints the minimum of each figure over the
rounds and the ratio this tree / ref; nothing is written. The compiled loop is each tree's
own roll loop: ``loop.shoot`` with the roll marker since the model levels (issue 30),
``loop._shoot`` before.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# The timed child: prints "name=microseconds" pairs.
CHILD = r"""
import time
import numba
import numpy as np
from pool_env import Table, shoot
from pool_env.sim.batch import simulate_batch
from pool_env.sim.kernels import loop
from pool_env.sim.layouts import break_scene
from pool_env.testing.scenes_random import random_layout

table = Table()
try:  # the one event loop of the model levels (issue 30), given the roll level's marker
    from pool_env.sim.kernels.roll.level import ROLL

    @numba.njit
    def one(p, v, w, m, params, pockets, record):
        return loop.shoot(ROLL, p, v, w, m, params, pockets, 10000, record)[5]
except ImportError:  # a tree before the model levels: the roll level's own loop
    @numba.njit
    def one(p, v, w, m, params, pockets, record):
        return loop._shoot(p, v, m, params, pockets, 10000, record)[4]


@numba.njit
def many(p, v, m, params, pockets, k, record):
    s = 0
    w = np.zeros((p.shape[0], 3))  # angular velocities: read by neither tree's roll loop
    for _ in range(k):
        s += one(p, v, w, m, params, pockets, record)
    return s


def best(f, reps=15):
    f()
    out = 1e9
    for _ in range(reps):
        t0 = time.thread_time()
        k = f()
        out = min(out, (time.thread_time() - t0) / k)
    return out * 1e6


none = np.empty(0)
two = np.array([[0.5, 0.6], [1.0, 0.62]])
two_v = np.array([[3.0, 0.0], [0.0, 0.0]])
rack = break_scene(table, "nine")
rack_v = np.zeros_like(rack)
rack_v[0] = 8.0 * (rack[1] - rack[0]) / np.hypot(*(rack[1] - rack[0]))
rng = np.random.default_rng(0)
pos = np.stack([random_layout(table, 2, rng) for _ in range(256)])
vel = np.zeros_like(pos)
d = pos[:, 1] - pos[:, 0]
angle = np.arctan2(d[:, 1], d[:, 0]) + rng.uniform(-0.3, 0.3, 256)
vel[:, 0] = 3.0 * np.stack([np.cos(angle), np.sin(angle)], axis=1)
P, K = table.params, table.pocket_geometry  # the jaw rows of the default table


def loop_of(p, v, k, record):
    return lambda: many(p, v, none, P, K, k, record) * 0 + k


def shoot_of(p, record):
    def f():
        for _ in range(2000):
            shoot(table, p, 0.0, 3.0, record=record)
        return 2000
    return f


def batch():
    for _ in range(5):
        simulate_batch(table, pos, vel, parallel=False)
    return 5 * 256


figures = {
    "loop_two_final": best(loop_of(two, two_v, 3000, False)),
    "loop_two_recorded": best(loop_of(two, two_v, 3000, True)),
    "loop_break_final": best(loop_of(rack, rack_v, 100, False)),
    "loop_break_recorded": best(loop_of(rack, rack_v, 100, True)),
    "shoot_two_final": best(shoot_of(two, False), 7),
    "shoot_two_recorded": best(shoot_of(two, True), 7),
    "batch256_per_table": best(batch, 7),
}
print(" ".join(f"{k}={v:.3f}" for k, v in figures.items()))
"""


# The env-step child: the same seeded actions on both trees, a step's thread CPU time.
ENV_CHILD = r"""
import time

import gymnasium as gym
import pool_env  # noqa: F401  (registers the ids)

figures = {}
for name in ("OneBallRoll-v1", "OneBall-v1", "NineBallGameRoll-v1", "NineBallGame-v1"):
    env = gym.make("pool_env/" + name)
    env.reset(seed=0)
    env.action_space.seed(0)
    actions = [env.action_space.sample() for _ in range(2000)]
    best = 1e9
    for block in range(9):  # the first block compiles or loads the kernels: not counted
        env.reset(seed=block)
        t0 = time.thread_time()
        for a in actions:
            if any(env.step(a)[2:4]):
                env.reset()
        if block:
            best = min(best, (time.thread_time() - t0) / len(actions))
    figures["step_" + name] = best * 1e6
print(" ".join(f"{k}={v:.3f}" for k, v in figures.items()))
"""


def run(tree: Path, cache: Path, child: str = CHILD) -> dict[str, float]:
    env = {**os.environ, "PYTHONPATH": str(tree), "NUMBA_CACHE_DIR": str(cache)}
    out = subprocess.run(
        [sys.executable, "-c", child], cwd=tree, env=env, capture_output=True, text=True
    )
    if out.returncode:
        raise RuntimeError(out.stderr)
    return {k: float(v) for k, v in (kv.split("=") for kv in out.stdout.split())}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--ref", default="main", help="git revision to compare against")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--env", action="store_true", help="time env.step of four ids")
    args = parser.parse_args()
    child = ENV_CHILD if args.env else CHILD
    with tempfile.TemporaryDirectory() as tmp:
        ref_tree = Path(tmp) / "ref"
        ref_tree.mkdir()
        archive = subprocess.run(
            ["git", "archive", args.ref], cwd=ROOT, capture_output=True, check=True
        ).stdout
        subprocess.run(["tar", "-x", "-C", str(ref_tree)], input=archive, check=True)
        results: dict[str, list[dict[str, float]]] = {"ref": [], "this": []}
        for _ in range(args.rounds):
            results["ref"].append(run(ref_tree, Path(tmp) / "cache-ref", child))
            results["this"].append(run(ROOT, Path(tmp) / "cache-this", child))
    load = os.getloadavg()[0]
    print(f"# kernel_ab: this tree vs {args.ref}, {args.rounds} rounds, load {load:.1f}")
    print("| figure (us, min) | ref | this | this / ref |")
    print("|---|---|---|---|")
    for name in results["ref"][0]:
        ref = min(r[name] for r in results["ref"])
        this = min(r[name] for r in results["this"])
        print(f"| {name} | {ref:.2f} | {this:.2f} | {this / ref:.3f} |")


if __name__ == "__main__":
    main()
