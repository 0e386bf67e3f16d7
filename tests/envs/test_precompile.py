"""``python -m pool_env.precompile``: after it, a first shot compiles nothing.

The README's install ends with the command, and its promise is that the quick start (and a
first training step) then loads every kernel from the cache. The check runs the command into
an empty cache of its own (a warm one would hide a kernel it misses; about a minute and a
half of CPU) and then, in a fresh process, the README's quick start and a vector env of the
training default, counting the kernels that process compiled.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import pytest

from pool_env import precompile
from pool_env.envs.registration import CURRENT_IDS

ROOT = Path(__file__).resolve().parents[2]

# Every pool_env kernel signature the process compiled (a cache miss), by name.
COMPILED = """
import gc, json
from numba.core.registry import CPUDispatcher
print(json.dumps(sorted(
    f"{k.py_func.__module__}.{k.py_func.__qualname__}{sig}"
    for k in gc.get_objects()
    if isinstance(k, CPUDispatcher) and k.py_func.__module__.startswith("pool_env")
    for sig, n in k.stats.cache_misses.items() if n
)))
"""

# The training default and the short game run (an earlier version of 9-ball), as
# SB3 plays them (single envs, no render mode) and as the native vector env does.
TRAINING_DEFAULT = """
import gymnasium as gym
import numpy as np
for env_id in ("pool_env/OneBall-v1", "pool_env/NineBallGame-v1"):
    for env in (gym.make(env_id, observation="shots"), gym.make_vec(env_id, 4)):
        env.reset(seed=1)
        env.action_space.seed(1)
        for _ in range(3):
            _, _, terminated, truncated, _ = env.step(env.action_space.sample())
            if np.any(terminated) or np.any(truncated):
                env.reset()
"""


def quick_start() -> str:
    """The README's first Python block."""
    block = re.search(r"```python\n(.*?)```", (ROOT / "README.md").read_text(), re.S)
    assert block is not None, "README.md has no python block"
    return block.group(1)


def test_every_registered_id_is_a_job_once_of_each_kind() -> None:
    jobs = precompile.jobs()
    kinds = ("env", "vector", "shots")
    ids = [i for i in gym.registry if i.startswith("pool_env/")]
    # Every kind of every id, but "shots" where the game refuses it (three-cushion: no
    # pocket, no ghost-ball shot).
    refused = {"pool_env/ThreeCushion-v1"}
    assert {i for i in ids if not precompile.plays_shots(i)} == refused
    wanted = [(i, k) for i in ids for k in kinds if k != "shots" or i not in refused]
    assert sorted(jobs) == sorted(wanted)
    assert "Roll-" not in jobs[0][0]  # the costliest compile (the spin loop) starts first
    n_roll = sum("Roll-" in i for i in CURRENT_IDS)
    assert all("Roll-" in i for i, _ in jobs[1 : 1 + len(kinds) * n_roll])
    current = len(kinds) * len(CURRENT_IDS) - len(refused & set(CURRENT_IDS))
    assert {i for i, _ in jobs[:current]} == set(CURRENT_IDS)  # the earlier versions last


def _run(args: list[str], env: dict[str, str] | None = None) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, *args], capture_output=True, text=True, cwd=ROOT, env=env, timeout=1800
    )


def test_bad_workers_are_a_usage_error() -> None:
    proc = _run(["-m", "pool_env.precompile", "--workers", "0"])
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert "--workers must be at least 1" in proc.stderr


@pytest.mark.slow
def test_after_precompile_the_quick_start_compiles_nothing(tmp_path: Path) -> None:
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    done = _run(["-m", "pool_env.precompile", "--quiet"], env)
    assert done.returncode == 0, done.stderr
    assert "compiled in" in done.stdout
    proc = _run(["-c", quick_start() + TRAINING_DEFAULT + COMPILED], env)
    assert proc.returncode == 0, proc.stderr
    compiled = json.loads(proc.stdout.splitlines()[-1])
    assert compiled == [], f"compiled after the precompile: {compiled[:5]}"
    assert "compiling the simulator's kernels" not in proc.stderr
