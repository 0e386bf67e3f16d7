"""A scene compiles only what it needs: the roll table no spin kernel, solitaire no rules.

Each case plays one episode's first shot in a fresh process (loading kernels from the disk
cache, or compiling them) and lists the kernels that process holds machine code for.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import json, sys
import gymnasium as gym
import numba
import pool_env

env = gym.make(sys.argv[1])
env.reset(seed=0)
env.step(env.action_space.sample())
loaded = sorted(
    f"{name}.{attr}"
    for name, module in list(sys.modules.items())
    if name.startswith("pool_env.")
    for attr, value in vars(module).items()
    if isinstance(value, numba.core.registry.CPUDispatcher) and value.overloads
    and value.py_func.__module__ == name
)
print(json.dumps(loaded))
"""


def compiled_for(env_id: str) -> list[str]:
    """The kernels (module.function) a first shot of ``env_id`` has machine code for."""
    run = subprocess.run(
        [sys.executable, "-c", CHILD, env_id], check=True, cwd=ROOT, capture_output=True, text=True
    )
    return json.loads(run.stdout.splitlines()[-1])


def _spin(kernel: str) -> bool:
    return "spin" in kernel.rsplit(".", 1)[0]


def _rules(kernel: str) -> bool:
    return kernel.startswith("pool_env.game.kernels.wpa.") or kernel.endswith(".judge_rules")


@pytest.mark.parametrize(
    ("env_id", "spin", "rules"),
    [
        ("pool_env/OneBallRoll-v1", False, False),
        ("pool_env/NineBall-v1", True, False),
        ("pool_env/NineBallGameRoll-v1", False, True),
    ],
)
def test_a_first_shot_compiles_only_its_model_and_its_rules(
    env_id: str, spin: bool, rules: bool
) -> None:
    kernels = compiled_for(env_id)
    assert kernels, "no kernel found: the probe is broken"
    assert any(map(_spin, kernels)) is spin, [k for k in kernels if _spin(k)]
    assert any(map(_rules, kernels)) is rules, [k for k in kernels if _rules(k)]
