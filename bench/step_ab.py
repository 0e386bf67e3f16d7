"""Same-run A/B of the environment step: two source trees, the same ids, steps and seeds.

A change above the simulator (the config, the rulesets, the fronts) must not slow a step.
This times ``env.step`` on two trees in fresh child processes, interleaved (A, B, A, B,
...), so that both see the same machine state: each child imports the package from its
tree (``PYTHONPATH``), makes each id (one ``PoolEnv`` through ``gym.make``, and a
``PoolVectorEnv`` of 64 tables through ``gym.make_vec``), warms it up (compiling or loading
the kernels), then times a fixed number of steps with actions drawn beforehand, resetting
as a training loop does. The table gives each tree's median over the repeats and the ratio
B / A (above 1: B is slower).

Usage (A: a checkout of the baseline commit, e.g. ``git worktree add /tmp/base <commit>``)::

    python -m bench.step_ab --a /tmp/base --b . --repeats 5

Writes ``results/step_ab.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

#: The ids timed, with the steps of one repeat (single env; the vector env takes a tenth).
#: Each must name the same task in both trees: 10-ball stands for the rotation games since
#: 9-ball's push-out moved to NineBallGame-v2 (-v1 is 9-ball before it).
IDS: dict[str, int] = {
    "pool_env/OneBallRoll-v1": 20_000,
    "pool_env/OneBall-v1": 10_000,
    "pool_env/TenBallGame-v1": 2_000,
    "pool_env/EightBallGameRoll-v1": 2_000,
}

#: Tables of the vector env.
NUM_ENVS = 64

CHILD = r"""
import json, sys, time
import gymnasium as gym
import numpy as np
import pool_env

env_id, steps, vector = sys.argv[1], int(sys.argv[2]), sys.argv[3] == "1"
if vector:
    env = gym.make_vec(env_id, num_envs=64, vectorization_mode="vector_entry_point")
else:
    env = gym.make(env_id)
rng = np.random.default_rng(0)
shape = env.action_space.shape
actions = rng.uniform(-1.0, 1.0, (steps, *shape)).astype(np.float32)
env.reset(seed=0)
for a in actions[: max(10, steps // 20)]:  # warm-up: kernels loaded, caches touched
    out = env.step(a)
    if not vector and (out[2] or out[3]):
        env.reset()
env.reset(seed=1)
start = time.perf_counter()
for a in actions:
    out = env.step(a)
    if not vector and (out[2] or out[3]):
        env.reset()
elapsed = time.perf_counter() - start
print(json.dumps({"us_per_step": 1e6 * elapsed / steps, "package": pool_env.__file__}))
"""


def time_tree(tree: Path, env_id: str, steps: int, vector: bool) -> float:
    """Microseconds per step of ``env_id`` with the package imported from ``tree``."""
    env = {**os.environ, "PYTHONPATH": str(tree.resolve())}
    out = subprocess.run(
        [sys.executable, "-c", CHILD, env_id, str(steps), "1" if vector else "0"],
        env=env, capture_output=True, text=True, check=True, cwd=tree,
    )  # fmt: skip
    report = json.loads(out.stdout.strip().splitlines()[-1])
    if not Path(report["package"]).resolve().is_relative_to(tree.resolve()):
        raise RuntimeError(f"{tree}: the child imported pool_env from {report['package']}")
    return float(report["us_per_step"])


def _commit(tree: Path) -> str:
    """The short commit a tree has checked out (``?`` outside git)."""
    out = subprocess.run(
        ["git", "-C", str(tree), "rev-parse", "--short", "HEAD"], capture_output=True, text=True
    )
    return out.stdout.strip() or "?"


def main() -> int:
    """Time both trees on every id and write the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--a", type=Path, required=True, help="the baseline tree")
    parser.add_argument("--b", type=Path, default=Path("."), help="the tree under test")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--scale", type=float, default=1.0, help="multiply the step counts")
    parser.add_argument("--out", type=Path, default=Path("results/step_ab.md"))
    args = parser.parse_args()
    rows = []
    for env_id, base_steps in IDS.items():
        for vector in (False, True):
            steps = max(10, int(base_steps * args.scale / (10 if vector else 1)))
            times: dict[str, list[float]] = {"a": [], "b": []}
            for _ in range(args.repeats):
                for name, tree in (("a", args.a), ("b", args.b)):
                    times[name].append(time_tree(tree, env_id, steps, vector))
            a, b = statistics.median(times["a"]), statistics.median(times["b"])
            front = f"PoolVectorEnv x{NUM_ENVS}" if vector else "PoolEnv"
            rows.append(f"| `{env_id}` | {front} | {steps} | {a:.1f} | {b:.1f} | {b / a:.3f} |")
            print(rows[-1], flush=True)
    commits = {name: _commit(tree) for name, tree in (("A", args.a), ("B", args.b))}
    lines = [
        "# Environment step: same-run A/B of two trees",
        "",
        f"A: `{commits['A']}`, B: `{commits['B']}` (the trees' commits; B may hold changes "
        "not yet committed).",
        "",
        f"`python -m bench.step_ab --a {args.a} --b {args.b} --repeats {args.repeats}"
        f"{f' --scale {args.scale:g}' if args.scale != 1.0 else ''}`: "
        "microseconds per step (per vector step: all tables), the median of "
        f"{args.repeats} interleaved fresh processes per tree; ratio B / A (above 1: B slower).",
        "",
        "| id | front | steps | A (us) | B (us) | B / A |",
        "|---|---|---|---|---|---|",
        *rows,
        "",
    ]
    args.out.write_text("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
