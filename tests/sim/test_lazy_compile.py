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

ROOT = Path(__file__).resolve().parents[2]

CHILD = r"""
import json, sys
import gymnasium as gym
import numba
import pool_env

env = gym.make(sys.argv[1])
env.reset(seed=0)
env.step(env.action_space.sample())
# Each kernel with the types it was compiled for: the shared kernels (the event loop, the
# batch) are one function per model level, told apart by the level marker's type.
# A level's entry points sit in its ENTRIES tuple (closures made by kernels.entries).
def dispatchers(module):
    for attr, value in vars(module).items():
        if isinstance(value, tuple) and hasattr(value, "_fields"):
            for field, item in zip(value._fields, value):
                yield f"{attr}.{field}", item
        else:
            yield attr, value
loaded = sorted(
    f"{name}.{attr}" + "".join(f" {sig}" for sig in value.signatures)
    for name, module in list(sys.modules.items())
    if name.startswith("pool_env.")
    for attr, value in dispatchers(module)
    if isinstance(value, numba.core.registry.CPUDispatcher) and value.overloads
    and (value.py_func.__module__ == name or attr.startswith("ENTRIES."))
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
    """A kernel of the spin level: one of its package's, or a shared one compiled for it."""
    name, _, signature = kernel.partition(" ")
    return ".kernels.spin." in name or "SpinLevel" in signature


def _rules(kernel: str) -> bool:
    name = kernel.partition(" ")[0]
    return name.startswith("pool_env.game.games.wpa.")


@pytest.mark.parametrize(
    ("env_id", "spin", "rules"),
    [
        ("pool_env/OneBallRoll-v1", False, False),
        ("pool_env/NineBall-v1", True, False),
        ("pool_env/NineBallGameRoll-v2", False, True),
    ],
)
def test_a_first_shot_compiles_only_its_model_and_its_rules(
    env_id: str, spin: bool, rules: bool
) -> None:
    kernels = compiled_for(env_id)
    assert kernels, "no kernel found: the probe is broken"
    assert any(map(_spin, kernels)) is spin, [k for k in kernels if _spin(k)]
    assert any(map(_rules, kernels)) is rules, [k for k in kernels if _rules(k)]
