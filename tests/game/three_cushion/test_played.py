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


def test_shots_observation_is_refused_with_the_reason() -> None:
    with pytest.raises(ValueError, match=r"observation='shots'.*no pocket and no ghost-ball"):
        gym.make(ID, observation="shots")
    from pool_env.envs.multiagent import PoolDuelEnv

    with pytest.raises(ValueError, match=r"observation='shots'"):
        PoolDuelEnv("three_cushion", observation="shots")


def test_an_encoded_shot_on_the_yellows_turn_plays_from_the_yellow() -> None:
    """Cut aim refers from the striker's cue ball: the yellow's nearest ball is the red.

    From the white the nearest object ball is the yellow; from the yellow it is the red.
    The encoded action decodes to the shot, and the env plays it as the absolute aim of
    the same direction does (the yellow struck).
    """
    from pool_env import Shot, decode_action, encode_action

    layout = np.array([[0.5, 0.5], [1.5, 0.7], [1.6, 1.0]])
    rules = {"shooter": 1, "innings": (1, 1)}
    angle = float(np.arctan2(0.3, 0.1)) + 0.05  # just off the yellow-red line
    shot = Shot(angle=angle, speed=2.0, tip=(0.1, 0.2))
    cut = gym.make(ID).unwrapped
    action = encode_action(cut.config, shot, layout, rack=rules)
    decoded = decode_action(cut.config, action, layout, rack=rules)
    assert decoded.angle == pytest.approx(angle, abs=1e-12)
    assert decoded.speed == pytest.approx(2.0) and decoded.tip == pytest.approx((0.1, 0.2))
    absolute = gym.make(ID, aim="absolute", aim_range=(-np.pi, np.pi)).unwrapped
    wanted = encode_action(absolute.config, shot, layout, rack=rules)
    for env, act in ((cut, action), (absolute, wanted)):
        env.reset(seed=0, options={"positions": layout, "rules": rules})
        info = env.step(act)[4]
        assert info["striker"] == 1 and info["angle"] == pytest.approx(angle, abs=1e-6)
    assert not np.allclose(cut.positions[1], layout[1])  # the yellow moved
    np.testing.assert_allclose(cut.positions, absolute.positions, atol=1e-6)


def test_vector_env_equals_pool_envs_on_a_match_config() -> None:
    """The native vector env equals a SyncVectorEnv of PoolEnvs under non-default rules."""
    from tests.envs.test_vector import NEXT, SAME, _compare, _pair

    kwargs = {"target": 2, "inning_limit": 0, "reward_point": 2.0, "reward_foul": -1.0}
    for mode in (NEXT, SAME):
        assert _compare(*_pair(ID, 4, mode, **kwargs), steps=40, seed=3) > 0


def test_sb3_and_versus_policy_fronts() -> None:
    from gymnasium.utils.env_checker import check_env as gym_check
    from stable_baselines3.common.env_checker import check_env

    from pool_env.envs.multiagent import VersusPolicyEnv

    check_env(gym.make(ID).unwrapped, warn=True)
    versus = VersusPolicyEnv(game="three_cushion", target=2, inning_limit=3)
    gym_check(versus, skip_render_check=True)
    check_env(VersusPolicyEnv(game="three_cushion", target=2, inning_limit=3), warn=True)
    versus.reset(seed=4)
    rng = np.random.default_rng(4)
    for _ in range(100):  # random play ends the match: a win, a loss or a draw
        _, reward, terminated, truncated, _ = versus.step(rng.uniform(-1, 1, 4))
        if terminated or truncated:
            break
    assert terminated and reward in (-1.0, 0.0, 1.0)
    rack = versus.duel.rack
    assert rack["innings"] == (3, 3) and rack["winner"] in (0, 1, 2)
    assert reward == {0: 1.0, 1: -1.0, 2: 0.0}[rack["winner"]]


@pytest.mark.parametrize(
    ("rules", "words"),
    [
        ({"score": 5}, r"score must be a pair .* got 5"),
        ({"innings": (1, 2, 3)}, r"innings must be a pair"),
        ({"winner": 7}, r"winner -1, 0, 1 or 2 .*got"),
        ({"shooter": 2}, r"shooter must be 0 or 1, got 2"),
        ({"colour": 1}, r"unknown three-cushion state key\(s\) \['colour'\]"),
    ],
)
def test_a_bad_rack_state_is_refused_and_changes_nothing(rules: dict, words: str) -> None:
    env = gym.make(ID).unwrapped
    env.reset(seed=0)
    before = (env.positions, env.rack)
    with pytest.raises(ValueError, match=words):
        env.reset(options={"positions": starting_layout(TABLE, 0), "rules": rules})
    assert np.array_equal(env.positions, before[0]) and env.rack == before[1]


def test_a_ball_off_the_table_is_refused_naming_on_table() -> None:
    env = gym.make(ID).unwrapped
    with pytest.raises(ValueError, match=r"on_table must be all True, got \[True, True, False\]"):
        env.reset(options={"positions": starting_layout(TABLE, 0), "on_table": [1, 1, 0]})
