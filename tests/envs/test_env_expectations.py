"""PoolEnv and PoolVectorEnv against outcomes worked out by hand (tests/env_scenes.py).

The other env tests compare the fronts with each other, which cannot see a bug in the code
they share (the action decoding, observation and reward functions); these compare each
front with numbers derived from the documented rules and the physics' closed forms.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.envs.env import PoolEnv
from tests.env_scenes import SHOTS, Shot

OBS_ATOL = 1e-6  # float32 observations of positions known to ~1e-12 m


def _step_single(shot: Shot) -> tuple:
    env = gym.make(shot.env_id, **shot.kwargs)
    env.reset(seed=0, options={"positions": shot.positions, "on_table": shot.on_table})
    obs, reward, terminated, truncated, info = env.step(np.array(shot.action, np.float32))
    return obs, reward, terminated, truncated, info, env.unwrapped.positions


def _step_vector(shot: Shot) -> tuple:
    env = gym.make_vec(shot.env_id, 2, vectorization_mode="vector_entry_point", **shot.kwargs)
    env.reset(seed=0, options={"positions": shot.positions, "on_table": shot.on_table})
    actions = np.array([shot.action, shot.action], np.float32)
    obs, rewards, terminated, truncated, info = env.step(actions)
    for k in range(2):  # both tables played the same shot
        np.testing.assert_array_equal(obs[k], obs[0])
    table = {key: info[key][0] for key in ("potted", "scratch", "first_contact")}
    return obs[0], rewards[0], terminated[0], truncated[0], table, env.unwrapped.positions[0]


FRONTS = {"single": _step_single, "vector": _step_vector}


@pytest.mark.parametrize("front", list(FRONTS))
@pytest.mark.parametrize("shot", SHOTS, ids=lambda s: s.name)
def test_one_shot_gives_the_worked_out_outcome(front: str, shot: Shot) -> None:
    obs, reward, terminated, truncated, info, positions = FRONTS[front](shot)
    assert float(reward) == pytest.approx(shot.reward, abs=1e-12)
    assert (bool(terminated), bool(truncated)) == (shot.terminated, shot.truncated)
    for key, value in shot.info.items():
        assert info[key] == value, key
    np.testing.assert_allclose(obs, shot.observation, rtol=0, atol=OBS_ATOL)
    on = shot.final_on_table
    np.testing.assert_allclose(positions[on], np.array(shot.final_positions)[on], rtol=0, atol=1e-9)


def test_the_shots_are_not_trivial() -> None:
    """Each expectation differs from the one a broken rule would give."""
    by_name = {s.name: s for s in SHOTS}
    assert by_name["pot-shaped"].reward > by_name["pot"].reward + 0.1  # shaping pays
    assert by_name["scratch"].observation[:3].tolist() == [-0.5, 0.0, 1.0]  # head spot


@pytest.mark.parametrize("env_id", ["pool_env/OneBallRoll-v1", "pool_env/NineBallRoll-v1"])
def test_vector_table_i_is_the_single_env_seeded_seed_plus_i(env_id: str) -> None:
    """The documented seeding: table i of reset(seed=s) is gym.make(id).reset(seed=s + i)."""
    n, seed = 3, 11
    vec = gym.make_vec(env_id, n, vectorization_mode="vector_entry_point")
    obs, _ = vec.reset(seed=seed)
    assert vec.unwrapped.np_random_seed == tuple(seed + i for i in range(n))
    for i in range(n):
        single = PoolEnv(**_id_kwargs(env_id))
        expected, _ = single.reset(seed=seed + i)
        np.testing.assert_array_equal(obs[i], expected)
        np.testing.assert_array_equal(vec.unwrapped.positions[i], single.positions)
    assert not np.array_equal(obs[0], obs[1])


def _id_kwargs(env_id: str) -> dict:
    return dict(gym.spec(env_id).kwargs)
