"""The SB3 adapter: DummyVecEnv's trajectories and conventions, wrappers, PPO on top."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3")

from gymnasium.utils.env_checker import data_equivalence
from stable_baselines3.common.vec_env import DummyVecEnv, VecMonitor, VecNormalize

import pool_env  # noqa: F401
from agents.vec.native_vec import NativeVecEnv, make_native_vec_env
from pool_env.envs.vector import PoolVectorEnv


@pytest.mark.parametrize(
    ("env_id", "kwargs"),
    [
        ("pool_env/OneBallRoll-v1", {}),
        ("pool_env/PoolRoll-v1", {"max_shots": 4, "noise": (0.02, 0.2)}),
        ("pool_env/NineBallRoll-v1", {"aim": "relative"}),
        ("pool_env/NineBallGameRoll-v2", {"noise": (0.003, 0.05)}),
        ("pool_env/EightBallGameRoll-v1", {"end_on_foul": True}),
    ],
)
def test_same_trajectories_as_a_dummy_vec_env(env_id: str, kwargs: dict) -> None:
    n = 4
    native = make_native_vec_env(env_id, n, 7, kwargs)
    dummy = DummyVecEnv([lambda: gym.make(env_id, **kwargs) for _ in range(n)])
    dummy.seed(7)
    assert native.observation_space == dummy.observation_space
    assert native.action_space == dummy.action_space
    assert data_equivalence(native.reset(), dummy.reset(), exact=True)
    rng = np.random.default_rng(1)
    dones = 0
    for t in range(60):
        actions = rng.uniform(-1, 1, (n, *native.action_space.shape)).astype(np.float32)
        ours, theirs = native.step(actions), dummy.step(actions)
        for x, y, name in zip(ours, theirs, ("obs", "rewards", "dones", "infos"), strict=True):
            assert data_equivalence(x, y, exact=True), f"step {t}: {name}\n{x}\n{y}"
        dones += int(ours[2].sum())
    assert dones > 0
    for info in ours[3]:
        assert "TimeLimit.truncated" in info


def test_terminal_observation_and_time_limit_flags() -> None:
    env = make_native_vec_env("pool_env/PoolRoll-v1", 3, 0, {"max_shots": 1})
    env.reset()
    obs, rewards, dones, infos = env.step(np.zeros((3, 2), dtype=np.float32))
    assert dones.all() and rewards.dtype == np.float32
    for i, info in enumerate(infos):
        assert info["terminal_observation"].shape == (12,)
        assert info["TimeLimit.truncated"] == (not info["is_success"])
        assert not np.array_equal(info["terminal_observation"], obs[i])  # obs is the reset one


def test_vec_monitor_and_vec_normalize_on_top_and_ppo_learns_a_few_updates() -> None:
    from stable_baselines3 import PPO

    env = VecNormalize(VecMonitor(make_native_vec_env("pool_env/OneBallRoll-v1", 8, 0)), gamma=0.0)
    model = PPO(
        "MlpPolicy", env, n_steps=16, batch_size=64, n_epochs=2, gamma=0.0, seed=0, device="cpu"
    )
    before = [p.detach().clone() for p in model.policy.parameters()]
    model.learn(8 * 16 * 3)
    assert model.num_timesteps == 8 * 16 * 3
    after = list(model.policy.parameters())
    assert any(not (a == b).all() for a, b in zip(after, before, strict=True))  # it updated
    assert len(model.ep_info_buffer) == 100  # one shot per OneBall episode: many episodes
    assert all(ep["l"] == 1 for ep in model.ep_info_buffer)
    assert env.obs_rms.count > 8 * 16 * 3  # VecNormalize saw every observation


def test_seed_attributes_methods_and_options() -> None:
    env = make_native_vec_env("pool_env/OneBallRoll-v1", 3, 5)
    first = env.reset()
    env.seed(5)
    np.testing.assert_array_equal(env.reset(), first)
    assert env.get_attr("render_mode") == [None, None, None]
    assert env.get_attr("np_random_seed") == [5, 6, 7]
    assert env.get_attr("shots", indices=[2]) == [0]
    assert env.env_is_wrapped(gym.Wrapper) == [False] * 3
    assert env.has_attr("config") and not env.has_attr("no_such_thing")
    env.set_attr("render_width", 640)
    assert env.get_attr("render_width") == [640] * 3
    with pytest.raises(ValueError, match="share"):
        env.set_attr("end_on_miss", True, indices=[0])
    with pytest.raises(NotImplementedError):
        env.env_method("step", np.zeros(2))
    layout = [[0.5, 0.5], [1.0, 0.5]]
    env.set_options({"positions": layout})
    obs = env.reset()
    assert (obs == obs[0]).all()
    env.close()


def test_the_adapter_needs_same_step_autoreset() -> None:
    with pytest.raises(ValueError, match="SAME_STEP"):
        NativeVecEnv(PoolVectorEnv(2))
    with pytest.raises(ValueError, match="not a pool_env id"):
        make_native_vec_env("CartPole-v1", 2, 0)
    assert make_native_vec_env("pool_env:pool_env/OneBallRoll-v1", 2, 0).num_envs == 2
