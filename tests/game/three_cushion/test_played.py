"""Three-cushion played: rule cases from exact layouts, random play ends, the fronts."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env import Table
from pool_env.game.games.three_cushion.layout import frozen, starting_layout

ID = "pool_env/ThreeCushion-v1"
TABLE = Table.preset("carom")


def test_the_roll_level_is_refused_with_the_reason() -> None:
    with pytest.raises(ValueError, match=r"spin level only.*english and follow"):
        gym.make(ID, model="roll")


def test_the_starting_position_is_umbs() -> None:
    """Red on the top spot, yellow on the head spot, white on the head string beside it."""
    layout = starting_layout(TABLE, 0)
    assert layout.tolist() == [[0.71, 0.71 + 0.1825], [0.71, 0.71], [2.13, 0.71]]
    assert starting_layout(TABLE, 1)[[1, 0]].tolist() == layout[[0, 1]].tolist()


def test_frozen_balls_are_found() -> None:
    r = TABLE.ball_radius
    pos = np.array([[[1.0, 0.7], [1.0 + 2 * r, 0.7], [2.0, 0.7]]])
    assert frozen(pos, np.array([0]), r).tolist() == [True]
    assert frozen(pos, np.array([1]), r).tolist() == [True]
    pos[0, 1, 0] += 1e-3
    assert frozen(pos, np.array([0]), r).tolist() == [False]


def test_the_break_must_hit_the_red_first() -> None:
    """The opening shot at the yellow (straight across the head string) is a foul."""
    env = gym.make(ID, aim="absolute", aim_range=(-np.pi, np.pi))
    env.reset(seed=0)
    action = np.array([-0.5, 0.0, 0.0, 0.0], np.float32)  # -pi/2: at the yellow
    _, reward, terminated, _, info = env.step(action)
    assert info["first_contact"] == 1 and info["foul"] == "break_not_red"
    assert terminated and reward == 0.0 and not info["point"]


def test_random_play_ends_and_scores_with_points_only_from_three_cushions() -> None:
    env = gym.make(ID)
    env.reset(seed=1)
    rng = np.random.default_rng(1)
    episodes = 0
    for _ in range(400):
        _, reward, terminated, truncated, info = env.step(rng.uniform(-1, 1, 4).astype(np.float32))
        assert info["point"] == (info["cushions"] >= 3 and info["second_ball"] >= 0)
        assert reward == float(info["point"])
        if terminated or truncated:
            episodes += 1
            env.reset()
    assert episodes > 100


def test_checkers() -> None:
    from gymnasium.utils.env_checker import check_env

    check_env(gym.make(ID).unwrapped, skip_render_check=True)


def test_pettingzoo_api_on_a_match() -> None:
    from pettingzoo.test import api_test

    from pool_env.envs.multiagent import PoolDuelEnv

    api_test(PoolDuelEnv("three_cushion", target=2, inning_limit=3), num_cycles=60)


def test_a_match_ends_at_the_inning_limit() -> None:
    from pool_env.envs.multiagent import PoolDuelEnv

    duel = PoolDuelEnv("three_cushion", target=50, inning_limit=2)
    duel.reset(seed=3)
    rng = np.random.default_rng(3)
    for _ in range(200):
        if all(duel.terminations.values()) or all(duel.truncations.values()):
            break
        duel.step(rng.uniform(-1, 1, 4).astype(np.float32))
    rack = duel.rack
    assert rack["innings"] == (2, 2) and rack["winner"] in (0, 1, 2)
    assert all(duel.terminations.values())
