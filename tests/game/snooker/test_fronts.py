"""Snooker on every front: the checkers, the duel, the vs-policy env, the shots features.

The vector env against a ``SyncVectorEnv`` of single envs is ``tests/envs/test_vector.py``'s,
over every registered id (the snooker ids among them).
"""

from __future__ import annotations

import warnings

import gymnasium as gym
import pytest
from gymnasium.utils.env_checker import check_env

import pool_env

IDS = ["pool_env/SnookerBreak-v1", "pool_env/SnookerBreakRoll-v1",
       "pool_env/SnookerFrame-v1", "pool_env/SnookerFrameRoll-v1"]  # fmt: skip


@pytest.mark.parametrize("env_id", IDS)
def test_the_checkers_pass_on_the_ids(env_id: str) -> None:
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    env = gym.make(env_id)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        check_env(env.unwrapped, skip_render_check=True)
        sb3_check_env(gym.make(env_id), warn=True)
    assert env.action_space.shape == ((7,) if "Roll" not in env_id else (5,))
    assert env.observation_space.shape == (100,)


def test_the_duel_plays_a_frame_and_passes_pettingzoo_api_test() -> None:
    pytest.importorskip("pettingzoo")
    from pettingzoo.test import api_test

    from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

    api_test(PoolDuelEnv("snooker", max_shots=40, model="roll"), num_cycles=60)
    duel = PoolDuelEnv("snooker", max_shots=40, model="roll")
    duel.reset(seed=4)
    assert duel.rack["ball_in_hand"] and duel.rack["phase"] == "red"
    env = VersusPolicyEnv(game="snooker", max_shots=30, model="roll")
    check_env(env, skip_render_check=True)


def test_the_shots_observation_refers_to_the_balls_on() -> None:
    env = pool_env.PoolEnv(game="snooker", scene="snooker", observation="shots",
                           table=pool_env.Table.preset("snooker", model="roll"))  # fmt: skip
    obs, _ = env.reset(seed=0)
    assert obs.shape[0] > 100
    assert env.observation_space.contains(obs)
