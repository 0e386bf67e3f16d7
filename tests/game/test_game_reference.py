"""The decision process against its plain-Python reference, on random episodes of every id."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env import ENV_IDS
from pool_env.envs.registration import GAME_IDS
from tests.game_reference import ReferenceEnv

# The rules ids have their own reference (tests/wpa_reference.py, tests/game/test_games.py).
SOLITAIRE_IDS = [env_id for env_id in ENV_IDS if env_id not in GAME_IDS]

VARIANTS = [
    {},
    {"noise": (0.02, 0.3)},
    {"aim": "relative", "reward_shaping": 0.5, "reward_no_contact": -0.25},
    {"aim": "absolute", "noise": (0.05, 2.0), "speed_range": (0.1, 3.0), "rack_order": "fixed"},
]


@pytest.mark.parametrize("variant", range(len(VARIANTS)))
@pytest.mark.parametrize("env_id", SOLITAIRE_IDS)
def test_random_episodes_equal_the_plain_python_reference(env_id: str, variant: int) -> None:
    kwargs, limit = ENV_IDS[env_id]
    kwargs = {**kwargs, **VARIANTS[variant]}
    env, ref = gym.make(env_id, **VARIANTS[variant]), ReferenceEnv(limit, **kwargs)
    rng = np.random.default_rng(100 + variant)
    episodes, steps = 0, 0
    for seed in range(3):
        a, b = env.reset(seed=seed), ref.reset(seed=seed)
        np.testing.assert_array_equal(a[0], b[0])
        assert a[1] == b[1] == {}
        done = False
        while not done and steps < 400:
            # clipping included; a v1 id's tip too (its last two components)
            action = rng.uniform(-1.2, 1.2, env.action_space.shape).astype(np.float32)
            got, want = env.step(action), ref.step(action)
            np.testing.assert_array_equal(got[0], want[0])
            assert got[1:] == want[1:], (
                f"{env_id} seed {seed} step {steps}: {got[1:]} != {want[1:]}"
            )
            np.testing.assert_array_equal(env.unwrapped.positions, ref.pos)
            done = got[2] or got[3]
            steps += 1
        episodes += done
    assert episodes >= 1 and steps >= 3
