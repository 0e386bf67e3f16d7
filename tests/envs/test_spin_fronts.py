"""The v1 (spin) ids through every front: SB3 adapter, gym_vec, RLlib's creator, two players."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import data_equivalence

import pool_env  # noqa: F401
from pool_env.envs.vector import PoolVectorEnv

ONE = "pool_env/OneBall-v1"


@pytest.mark.parametrize(
    ("env_id", "kwargs"),
    [
        (ONE, {"noise": (0.003, 0.05, 0.02)}),
        ("pool_env/NineBallGame-v2", {"noise": (0.003, 0.05, 0.02)}),
        ("pool_env/EightBallGame-v1", {"end_on_foul": True}),
    ],
)
def test_the_sb3_adapter_plays_a_dummy_vec_env_bit_for_bit(env_id: str, kwargs: dict) -> None:
    pytest.importorskip("stable_baselines3")
    from stable_baselines3.common.vec_env import DummyVecEnv

    from agents.vec.native_vec import make_native_vec_env

    n = 4
    native = make_native_vec_env(env_id, n, 3, kwargs)
    dummy = DummyVecEnv([lambda: gym.make(env_id, **kwargs) for _ in range(n)])
    dummy.seed(3)
    assert native.action_space == dummy.action_space
    assert native.action_space.shape == {ONE: (4,), "pool_env/EightBallGame-v1": (7,)}.get(
        env_id, (8,)
    )
    assert data_equivalence(native.reset(), dummy.reset(), exact=True)
    rng = np.random.default_rng(3)
    dones = 0
    for t in range(30):
        actions = rng.uniform(-1, 1, (n, *native.action_space.shape)).astype(np.float32)
        ours, theirs = native.step(actions), dummy.step(actions)
        for x, y, name in zip(ours, theirs, ("obs", "rewards", "dones", "infos"), strict=True):
            assert data_equivalence(x, y, exact=True), f"step {t}: {name}"
        dones += int(ours[2].sum())
    assert dones > 0
    assert all(len(info["tip"]) == 2 for info in ours[3])


def test_gym_vec_same_step_autoreset_on_a_spin_id() -> None:
    from agents.vec.gym_vec import make_cleanrl_envs, make_vec

    envs = make_vec(ONE, 8)
    envs.reset(seed=0)
    ended = 0
    for _ in range(5):
        *_, terminated, truncated, info = envs.step(envs.action_space.sample())
        ended += int(np.sum(terminated | truncated))
    assert ended == 40  # one shot per episode, a new one every step
    assert "tip" in info["final_info"]
    cleanrl = make_cleanrl_envs(ONE, 4, gamma=0.9)
    cleanrl.reset(seed=0)
    obs, reward, *_ = cleanrl.step(np.zeros((4, 4), np.float32))
    assert obs.shape == (4, 6) and np.isfinite(reward).all()


def test_the_rllib_creator_builds_spin_tables() -> None:
    pytest.importorskip("ray")
    from agents.integrations.rllib_env import make_env

    env = make_env({"num_envs": 3, "env_kwargs": {"noise": (0.0, 0.0, 0.05)}}, env_id=ONE)
    assert isinstance(env, PoolVectorEnv) and env.config.table.model == "spin"
    assert env.single_action_space.shape == (4,) and env.config.noise == (0.0, 0.0, 0.05)


def test_agents_make_env_and_factory_take_a_spin_id() -> None:
    from agents.learned.envs import EnvFactory, make_env

    env = make_env(ONE, {"tip_limit": 0.5})
    assert env.unwrapped.config.tip_limit == 0.5 and env.action_space.shape == (4,)
    assert EnvFactory("pool_env/NineBallGame-v2")().action_space.shape == (8,)
    assert EnvFactory("pool_env/TenBallGame-v1")().action_space.shape == (9,)


@pytest.mark.parametrize(("game", "width"), [("nine", 8), ("ten", 9), ("eight", 7)])
def test_two_players_on_the_spin_table(game: str, width: int) -> None:
    pytest.importorskip("pettingzoo")
    from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

    duel = PoolDuelEnv(game, model="spin", noise=(0.003, 0.05, 0.02))
    assert duel.action_space("player_0").shape == (width,)
    duel.reset(seed=0)
    rng = np.random.default_rng(0)
    for _ in range(6):
        if any(duel.terminations.values()) or any(duel.truncations.values()):
            break
        duel.step(rng.uniform(-1, 1, width).astype(np.float32))
        info = duel.infos[duel.agent_selection]
        assert len(info["tip"]) == 2
    versus = VersusPolicyEnv(game=game, model="spin")
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sb3_check_env(versus, warn=True)
