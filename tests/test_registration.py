"""Registration: every id exists once, carries its limits, and passes both env checkers."""

from __future__ import annotations

import subprocess
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import pytest
from gymnasium.utils.env_checker import check_env as gym_check_env

import pool_env
from pool_env.registration import ENV_IDS, register_envs

IDS = list(ENV_IDS)
ROOT = Path(__file__).resolve().parents[1]


def test_every_id_is_registered_with_its_time_limit() -> None:
    assert set(IDS) >= {
        "pool_env/Pool-v0",
        "pool_env/OneBall-v0",
        "pool_env/NineBall-v0",
        "pool_env/EightBall-v0",
    }
    for env_id, (kwargs, max_steps) in ENV_IDS.items():
        spec = gym.spec(env_id)
        assert spec.max_episode_steps == max_steps
        assert spec.kwargs == kwargs
        assert spec.entry_point == "pool_env.env:PoolEnv"


def test_registration_is_idempotent() -> None:
    before = {k: gym.registry[k] for k in IDS}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # re-registering would warn "Overriding environment"
        register_envs()
        register_envs()
    assert {k: gym.registry[k] for k in IDS} == before


@pytest.mark.parametrize(
    ("env_id", "n_objects", "terminal_on_miss"),
    [
        ("pool_env/Pool-v0", 3, False),
        ("pool_env/OneBall-v0", 1, True),
        ("pool_env/NineBall-v0", 9, False),
        ("pool_env/EightBall-v0", 15, False),
    ],
)
def test_ids_configure_the_scene(env_id: str, n_objects: int, terminal_on_miss: bool) -> None:
    env = gym.make(env_id)
    assert env.observation_space.shape == (3 * (n_objects + 1),)
    assert env.unwrapped.end_on_miss is terminal_on_miss
    env = gym.make(env_id, aim="absolute", max_shots=7)  # any argument through make()
    assert env.unwrapped.aim == "absolute"
    assert env.unwrapped.max_shots == 7


@pytest.mark.parametrize("render_mode", [None, "rgb_array"])
@pytest.mark.parametrize("env_id", IDS)
def test_gymnasium_check_env_passes_without_warnings(env_id: str, render_mode: str | None) -> None:
    env = gym.make(env_id, render_mode=render_mode)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gym_check_env(env.unwrapped)


@pytest.mark.parametrize("env_id", IDS)
def test_stable_baselines3_check_env_passes_without_warnings(env_id: str) -> None:
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    for env in (gym.make(env_id), gym.make(env_id).unwrapped):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            sb3_check_env(env, warn=True)


def test_import_stays_light() -> None:
    code = (
        "import sys, pool_env, gymnasium as gym; gym.make('pool_env/Pool-v0');"
        "heavy = {'pygame', 'matplotlib', 'imageio', 'torch', 'stable_baselines3'};"
        "heavy &= set(sys.modules);"
        "assert not heavy, heavy"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_module_colon_id_imports_the_package() -> None:
    env = gym.make("pool_env:pool_env/OneBall-v0")
    assert isinstance(env.unwrapped, pool_env.PoolEnv)


@pytest.mark.parametrize(
    "imports",
    [
        "import pool_env; import gymnasium as gym",
        "import gymnasium as gym; import pool_env",
        "import pool_env.sim; import gymnasium.spaces; import gymnasium as gym",
    ],
)
def test_ids_are_registered_whichever_is_imported_first(imports: str) -> None:
    """pool_env's import registers the ids without loading Gymnasium itself.

    They are registered when Gymnasium's import completes; Gymnasium keeps its own loader
    and no import hook stays behind.
    """
    code = (
        f"{imports}; import sys, importlib.machinery as m;"
        "from pool_env.registration import ENV_IDS, _GymnasiumHook;"
        "assert set(ENV_IDS) <= set(gym.registry), sorted(gym.registry);"
        "assert gym.make('pool_env/OneBall-v0').observation_space.shape == (6,);"
        "assert type(gym.__loader__) is m.SourceFileLoader, gym.__loader__;"
        "assert gym.__spec__.loader is gym.__loader__;"
        "assert not [f for f in sys.meta_path if isinstance(f, _GymnasiumHook)]"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)
