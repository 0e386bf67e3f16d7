"""Registration: every id exists once, carries its limits, and passes both env checkers."""

from __future__ import annotations

import subprocess
import sys
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env as gym_check_env

import pool_env
from pool_env.envs.registration import (
    CURRENT_IDS,
    EARLIER_VERSIONS,
    ENV_IDS,
    LEGACY_IDS,
    SPIN_ONLY,
    TASKS,
    register_envs,
    roll_id,
    spin_id,
)

IDS = list(ENV_IDS)
ROOT = Path(__file__).resolve().parents[2]


def test_every_id_is_registered_with_its_time_limit() -> None:
    assert set(IDS) >= {
        "pool_env/PoolRoll-v1",
        "pool_env/OneBallRoll-v1",
        "pool_env/NineBallRoll-v1",
        "pool_env/EightBallRoll-v1",
    }
    for env_id, (kwargs, max_steps) in ENV_IDS.items():
        spec = gym.spec(env_id)
        assert spec.max_episode_steps == max_steps
        assert spec.kwargs == {"id_defaults": kwargs}  # apart from the caller's keywords
        assert spec.entry_point == "pool_env.envs.env:PoolEnv"


def test_registration_is_idempotent() -> None:
    before = {k: gym.registry[k] for k in IDS}
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # re-registering would warn "Overriding environment"
        register_envs()
        register_envs()
    assert {k: gym.registry[k] for k in IDS} == before


def test_each_task_has_a_spin_id_and_a_roll_id_and_nothing_else() -> None:
    """Every task but the spin-only ones (three-cushion) has its roll twin."""
    assert {"ThreeCushion"} == SPIN_ONLY
    twins = [t for t in TASKS if t not in SPIN_ONLY]
    current = {spin_id(t) for t in TASKS} | {roll_id(t) for t in twins}
    earlier = {make(t, v) for t, v in EARLIER_VERSIONS for make in (spin_id, roll_id)}
    assert set(CURRENT_IDS) == current and len(current) == 2 * len(twins) + 1 == 15
    assert set(IDS) == current | earlier and len(IDS) == 17  # 9-ball's -v1 and -v2
    assert not any(roll_id(t) in gym.registry for t in SPIN_ONLY)
    for task in TASKS:
        assert gym.spec(spin_id(task)).kwargs["id_defaults"]["model"] == "spin"
    for task in twins:
        assert gym.spec(roll_id(task)).kwargs["id_defaults"]["model"] == "roll"


@pytest.mark.parametrize("env_id", CURRENT_IDS)
def test_no_current_id_is_reported_out_of_date(env_id: str) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # Gymnasium's "out of date" is a DeprecationWarning
        gym.make(env_id).close()
        gym.make_vec(env_id, num_envs=2).close()


@pytest.mark.parametrize(("old", "new"), list(LEGACY_IDS.items()))
def test_the_v0_ids_are_the_roll_ids_under_their_old_names(old: str, new: str) -> None:
    assert old == new.replace("Roll-v1", "-v0")
    assert gym.spec(old).kwargs == gym.spec(new).kwargs
    assert gym.spec(old).max_episode_steps == gym.spec(new).max_episode_steps
    # Gymnasium flags a lower version of a name: true for these, their name's newer id is v1.
    with pytest.warns(DeprecationWarning, match="out of date"):
        legacy = gym.make(old)
    current = gym.make(new)
    episodes = []
    for env in (legacy, current):
        env.action_space.seed(5)
        obs, _ = env.reset(seed=11)
        steps = [obs]
        for _ in range(3):
            obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
            steps += [obs, reward, terminated, truncated]
            if terminated or truncated:
                break
        episodes.append(steps)
    assert len(episodes[0]) == len(episodes[1])
    for a, b in zip(*episodes, strict=True):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize(
    ("env_id", "n_objects", "terminal_on_miss"),
    [
        ("pool_env/PoolRoll-v1", 3, False),
        ("pool_env/OneBallRoll-v1", 1, True),
        ("pool_env/NineBallRoll-v1", 9, False),
        ("pool_env/EightBallRoll-v1", 15, False),
    ],
)
def test_ids_configure_the_scene(env_id: str, n_objects: int, terminal_on_miss: bool) -> None:
    env = gym.make(env_id)
    assert env.observation_space.shape == (3 * (n_objects + 1),)
    assert env.unwrapped.config.end_on_miss is terminal_on_miss
    env = gym.make(env_id, aim="absolute", max_shots=7)  # any argument through make()
    assert env.unwrapped.config.aim == "absolute"
    assert env.unwrapped.config.max_shots == 7


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
        "import sys, pool_env, gymnasium as gym; gym.make('pool_env/PoolRoll-v1');"
        "heavy = {'pygame', 'matplotlib', 'imageio', 'torch', 'stable_baselines3'};"
        "heavy &= set(sys.modules);"
        "assert not heavy, heavy"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_module_colon_id_imports_the_package() -> None:
    env = gym.make("pool_env:pool_env/OneBallRoll-v1")
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
        "from pool_env.envs.registration import ENV_IDS, _GymnasiumHook;"
        "assert set(ENV_IDS) <= set(gym.registry), sorted(gym.registry);"
        "assert gym.make('pool_env/OneBallRoll-v1').observation_space.shape == (6,);"
        "assert type(gym.__loader__) is m.SourceFileLoader, gym.__loader__;"
        "assert gym.__spec__.loader is gym.__loader__;"
        "assert not [f for f in sys.meta_path if isinstance(f, _GymnasiumHook)]"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)
