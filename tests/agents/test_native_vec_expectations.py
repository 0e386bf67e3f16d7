"""The SB3 adapter (agents/vec/native_vec.py) against outcomes worked out by hand.

``test_native_vec.py`` compares the adapter with a ``DummyVecEnv`` of the same
environments, which shares every reward, observation and seeding function with it; here
the rewards, terminal observations, flags and seeds come from tests/env_scenes.py, derived
from the documented rules and the physics' closed forms.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from agents.vec.native_vec import make_native_vec_env
from pool_env.envs.env import PoolEnv
from tests.env_scenes import SHOTS, Shot


@pytest.mark.parametrize("shot", SHOTS, ids=lambda s: s.name)
def test_a_finished_episode_reports_the_worked_out_outcome(shot: Shot) -> None:
    n = 3
    env = make_native_vec_env(shot.env_id, n, 0, shot.kwargs)
    env.set_options({"positions": shot.positions, "on_table": shot.on_table})
    env.reset()
    obs, rewards, dones, infos = env.step(np.array([shot.action] * n, np.float32))
    assert rewards.dtype == np.float32
    np.testing.assert_array_equal(rewards, np.float32(shot.reward))
    done = shot.terminated or shot.truncated
    assert dones.tolist() == [done] * n
    for i, info in enumerate(infos):
        for key, value in shot.info.items():
            assert info[key] == value, key
        assert info["TimeLimit.truncated"] == (shot.truncated and not shot.terminated)
        if done:
            np.testing.assert_allclose(
                info["terminal_observation"], shot.observation, rtol=0, atol=1e-6
            )
            # SB3 convention: the returned observation is the next episode's first one.
            assert not np.allclose(obs[i], shot.observation)
        else:
            assert "terminal_observation" not in info
            np.testing.assert_allclose(obs[i], shot.observation, rtol=0, atol=1e-6)


def test_table_i_is_seeded_seed_plus_i() -> None:
    """make_native_vec_env(id, n, seed): table i starts as gym.make(id).reset(seed=seed + i)."""
    n, seed = 3, 21
    env = make_native_vec_env("pool_env/OneBallRoll-v1", n, seed)
    obs = env.reset()
    kwargs = dict(gym.spec("pool_env/OneBallRoll-v1").kwargs)
    for i in range(n):
        expected, _ = PoolEnv(**kwargs).reset(seed=seed + i)
        np.testing.assert_array_equal(obs[i], expected)
    assert env.get_attr("np_random_seed") == [seed + i for i in range(n)]
