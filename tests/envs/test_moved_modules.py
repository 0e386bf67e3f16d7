"""Public modules that moved keep their old import path for a release, with a warning."""

from __future__ import annotations

import importlib
import sys

import pytest

#: Old path -> where the module lives now (the fronts moved into pool_env.envs on 2026-12-04).
MOVED = {f"pool_env.{name}": f"pool_env.envs.{name}" for name in
         ("env", "vector", "multiagent", "record", "registration")}  # fmt: skip


@pytest.mark.parametrize(("old", "new"), list(MOVED.items()))
def test_an_old_path_warns_and_is_the_new_module(old: str, new: str) -> None:
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=f"{old} moved to {new}"):
        module = importlib.import_module(old)
    assert module is importlib.import_module(new)  # the same classes, not copies


def test_the_old_names_still_import() -> None:
    sys.modules.pop("pool_env.multiagent", None)
    with pytest.warns(DeprecationWarning, match="pool_env.multiagent moved"):
        from pool_env.multiagent import PoolDuelEnv
    from pool_env.envs import multiagent

    assert PoolDuelEnv is multiagent.PoolDuelEnv


@pytest.mark.parametrize("name", [old.split(".")[1] for old in MOVED])
def test_an_old_module_is_an_attribute_of_the_package_too(name: str) -> None:
    import pool_env

    sys.modules.pop(f"pool_env.{name}", None)
    pool_env.__dict__.pop(name, None)
    with pytest.warns(DeprecationWarning, match=f"pool_env.{name} moved"):
        module = getattr(pool_env, name)
    assert module is importlib.import_module(f"pool_env.envs.{name}")
