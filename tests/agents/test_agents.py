"""Baseline agents: the search planner, the action inversion, SB3 compatibility.

The geometric ghost-ball agent has its own tests in ``test_ghost_ball.py``.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from agents import GhostBallAgent, RandomAgent, SearchAgent, run_episodes
from agents.baselines.aiming import decode, shot_to_action
from agents.baselines.base import decode_observation, env_spec
from agents.baselines.random_agent import ConstantAgent
from agents.learned.features import PocketFeatures

ONE = "pool_env/OneBallRoll-v1"


def test_search_beats_random_by_a_wide_margin() -> None:
    env = gym.make(ONE)
    ghost = run_episodes(SearchAgent(env), env, 100, seed=123).summary()
    rand = run_episodes(RandomAgent(env, seed=0), env, 100, seed=123).summary()
    assert ghost["pots_per_shot"].value >= 0.95
    assert ghost["scratch_rate"].value <= 0.03
    assert ghost["clean_pot_rate"].value - rand["clean_pot_rate"].value >= 0.4
    assert ghost["episode_reward"].value - rand["episode_reward"].value >= 0.5


@pytest.mark.parametrize("aim", ["relative", "absolute"])
def test_search_pots_in_every_aim_mode(aim: str) -> None:
    env = gym.make(ONE, aim=aim)
    stats = run_episodes(SearchAgent(env), env, 40, seed=7).summary()
    assert stats["clean_pot_rate"].value >= 0.9


def test_search_clears_a_nine_ball_rack() -> None:
    env = gym.make("pool_env/NineBallRoll-v1")
    stats = run_episodes(SearchAgent(env), env, 2, seed=0).summary()
    assert stats["pots_per_shot"].value > 0.5
    assert stats["clear_rate"].value > 0.0


def test_search_decodes_observations_without_the_env_state() -> None:
    env = gym.make(ONE)
    agent = SearchAgent(env)
    agent.source.env = None  # observations only: float32 positions
    stats = run_episodes(agent, env, 30, seed=3).summary()
    assert stats["clean_pot_rate"].value >= 0.9


def test_baselines_work_with_sb3_evaluate_policy() -> None:
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.evaluation import evaluate_policy

    vec = make_vec_env(ONE, n_envs=2, seed=0)
    ghost_mean, _ = evaluate_policy(SearchAgent(vec), vec, n_eval_episodes=20)
    random_mean, _ = evaluate_policy(RandomAgent(vec, seed=0), vec, n_eval_episodes=20)
    assert ghost_mean >= 0.9
    assert ghost_mean > random_mean


@pytest.mark.parametrize("aim", ["cut", "relative", "absolute"])
def test_shot_to_action_inverts_the_env_decoding(aim: str) -> None:
    env = gym.make("pool_env/PoolRoll-v1", aim=aim)
    spec = env_spec(env)
    rng = np.random.default_rng(0)
    checked = 0
    for seed in range(20):
        env.reset(seed=seed)
        pos, on = env.unwrapped.positions, env.unwrapped.on_table
        for angle in rng.uniform(-math.pi, math.pi, 20):
            speed = float(rng.uniform(*spec.speed_range))
            action = shot_to_action(float(angle), speed, pos, on, spec)
            if action is None:
                continue
            angles, speeds = decode(action[None], pos, on, spec)
            assert abs(math.remainder(angles[0] - angle, 2 * math.pi)) < 1e-5
            assert speeds[0] == pytest.approx(speed, abs=1e-5)
            checked += 1
    assert checked > 5  # cut aim: only the cone that hits the nearest ball


def test_unrepresentable_shot_gives_none() -> None:
    env = gym.make(ONE)  # cut aim: only directions that hit the nearest ball
    env.reset(seed=0)
    pos, on = env.unwrapped.positions, env.unwrapped.on_table
    away = math.atan2(*(pos[0] - pos[1])[::-1])  # from the object ball towards the cue
    assert shot_to_action(away, 2.0, pos, on, env_spec(env)) is None


def test_decode_observation_round_trip() -> None:
    env = gym.make("pool_env/NineBallRoll-v1")
    obs, _ = env.reset(seed=1)
    pos, on = decode_observation(obs, env.unwrapped.config.table)
    assert np.array_equal(on, env.unwrapped.on_table)
    assert np.max(np.abs(pos - env.unwrapped.positions)) < 1e-6
    pool_env.shoot(env.unwrapped.config.table, pos, 0.0, 0.0)  # a touching rack decodes valid


def test_predict_shapes_and_state() -> None:
    env = gym.make(ONE)
    obs, _ = env.reset(seed=0)
    agents = (RandomAgent(env, seed=1), SearchAgent(env), GhostBallAgent(env), ConstantAgent(env))
    for agent in agents:
        action, state = agent.predict(obs, state=None, deterministic=True)
        assert action.shape == (2,) and action.dtype == np.float32
        assert state is None
        assert env.action_space.contains(action)
        batch, _ = agent.predict(np.stack([obs, obs]))
        assert batch.shape == (2, 2)


def test_random_agent_is_seeded() -> None:
    env = gym.make(ONE)
    obs, _ = env.reset(seed=0)
    a = RandomAgent(env, seed=5).predict(obs)[0]
    b = RandomAgent(env, seed=5).predict(obs)[0]
    assert np.array_equal(a, b)


def test_pocket_features_bounded_and_aligned() -> None:
    env = PocketFeatures(gym.make(ONE))
    obs, _ = env.reset(seed=0)
    assert env.observation_space.contains(obs)
    pos = env.unwrapped.positions
    feats = obs[-(1 + 3 * 6) :]
    assert feats[0] == pytest.approx(np.hypot(*(pos[1] - pos[0])) / np.hypot(2.54, 1.27), 1e-5)
    assert np.allclose(feats[1::3] ** 2 + feats[2::3] ** 2, 1.0, atol=1e-5)


def test_search_with_execution_noise_and_on_pool_v0() -> None:
    env = gym.make(ONE, noise=(0.003, 0.05))
    search = run_episodes(SearchAgent(env), env, 60, seed=11).summary()
    rand = run_episodes(RandomAgent(env, seed=0), env, 60, seed=11).summary()
    assert search["clean_pot_rate"].value - rand["clean_pot_rate"].value >= 0.15
    pool = gym.make("pool_env/PoolRoll-v1")
    stats = run_episodes(SearchAgent(pool), pool, 4, seed=2).summary()
    assert stats["clear_rate"].value == 1.0 and stats["pots_per_turn"].value >= 2.0
