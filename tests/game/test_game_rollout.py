"""Candidate actions under the rules (``pool_env.game.candidate_actions``): each as one ``step``."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.game.candidate_actions import candidates_state, rollout_actions
from pool_env.game.state import new_state
from pool_env.game.step import step

IDS = ["pool_env/OneBallRoll-v1", "pool_env/OneBall-v1", "pool_env/NineBallGameRoll-v2",
       "pool_env/NineBallGame-v2", "pool_env/EightBallGameRoll-v1"]  # fmt: skip


@pytest.mark.parametrize("env_id", IDS)
@pytest.mark.parametrize("n_candidates", [3, 70])  # the serial batch, then the threads
def test_each_candidate_is_one_step(env_id: str, n_candidates: int) -> None:
    env = gym.make(env_id).unwrapped
    env.reset(seed=11)
    for _ in range(2):  # a position after a shot or two (a break on the 9-ball ids)
        env.step(env.action_space.sample())
    config, state = env.config, env._state
    space = env.action_space
    space.seed(5)
    actions = np.array([space.sample() for _ in range(n_candidates)], dtype=np.float64)
    before = [a.copy() for a in (state.positions, state.on_table, state.shots, state.rack)]
    bits = state.generators[0].bit_generator.state
    result, after = rollout_actions(config, state, 0, actions)
    for now, then in zip((state.positions, state.on_table, state.shots, state.rack), before,
                         strict=True):  # fmt: skip
        assert np.array_equal(now, then)  # the given state is left as it was
    assert state.generators[0].bit_generator.state == bits
    restore = state.snapshot()
    for k in range(n_candidates):
        one = step(config, state, np.zeros(1, np.intp), actions[k : k + 1])
        assert np.array_equal(one.rewards, result.rewards[k : k + 1]), k
        assert np.array_equal(one.flags, result.flags[k : k + 1]), k
        assert np.array_equal(one.hits, result.hits[k : k + 1]), k
        assert np.array_equal(one.shots, result.shots[k : k + 1]), k
        assert np.array_equal(state.positions[0], after.positions[k]), k
        assert np.array_equal(state.on_table[0], after.on_table[k]), k
        assert np.array_equal(state.rack[0], after.rack[k]), k
        restore()


def test_bad_candidates() -> None:
    state = new_state(2, 3)
    with pytest.raises(ValueError, match="table must be in"):
        candidates_state(state, 2, 4)
    with pytest.raises(ValueError, match="at least one candidate"):
        candidates_state(state, 0, 0)
    with pytest.raises(ValueError, match="no generator yet"):
        candidates_state(state, 0, 4)
