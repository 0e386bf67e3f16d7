"""Snooker played: random play ends, the frame state stays consistent, points are conserved.

Random actions play frames (``pool_env/SnookerFrameRoll-v1``, both sides by one agent)
and visits (``pool_env/SnookerBreakRoll-v1``); after every stroke the frame must be one
the rules can reach, and every point scored must sit in a score. The checkers
(Gymnasium, Stable-Baselines3, PettingZoo) run on the new ids and fronts.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.game.games.snooker.markings import markings

RED, COLOURS = slice(1, 16), slice(16, 22)


def _consistent(env: gym.Env, info: dict) -> None:
    """The frame after a stroke is one the rules can reach."""
    base = env.unwrapped
    rack, on, pos = base.rack, base.on_table, base.positions
    table = base.config.table
    assert on[0], "the cue ball is always on the table (in hand: in the D)"
    if on[RED].any():
        assert on[COLOURS].all(), "while reds remain every colour is on the table"
        assert rack["phase"] in ("red", "colour")
    else:
        assert rack["phase"] in ("colour", "in_order")
    if rack["phase"] == "in_order":  # colours in order: the ones potted are the lowest
        colours = on[COLOURS]
        assert list(colours) == sorted(colours), "in order, a higher colour left before a lower"
    balls = pos[on]
    gaps = np.hypot(*(balls[:, None] - balls[None]).transpose(2, 0, 1))
    np.fill_diagonal(gaps, np.inf)
    assert gaps.min() >= 2 * table.ball_radius - 1e-9, "balls overlap"
    if rack["ball_in_hand"]:
        mark = markings(table)
        assert pos[0][0] <= mark.baulk_x + 1e-9
        assert math.dist(pos[0], (mark.baulk_x, mark.centre_y)) <= mark.d_radius + 1e-9
    assert info["score_0"] == rack["score_0"] and info["score_1"] == rack["score_1"]


@pytest.mark.parametrize("seed", [0, 1])
def test_random_frames_stay_consistent_and_conserve_points(seed: int) -> None:
    env = gym.make("pool_env/SnookerFrameRoll-v1", max_episode_steps=120)
    env.reset(seed=seed)
    env.action_space.seed(seed)
    scored, fouls, steps = 0, 0, 0
    while True:
        _, reward, terminated, truncated, info = env.step(env.action_space.sample())
        steps += 1
        scored += info["points"] + info["penalty"]
        fouls += info["foul"] is not None
        assert reward == info["points"] - info["penalty"]  # the default scales
        _consistent(env, info)
        if terminated or truncated:
            break
    rack = env.unwrapped.rack
    assert scored == rack["score_0"] + rack["score_1"] > 0
    assert fouls > 0 and steps <= 120


def test_random_visits_end_and_score_the_break() -> None:
    env = gym.make("pool_env/SnookerBreakRoll-v1")
    env.action_space.seed(3)
    for episode in range(6):
        env.reset(seed=episode)
        total, ended = 0.0, False
        for _ in range(env.spec.max_episode_steps):
            _, reward, terminated, truncated, info = env.step(env.action_space.sample())
            total += reward
            _consistent(env, info)
            if terminated or truncated:
                ended = True
                break
        assert ended
        assert info["turn_over"] or info["winner"] >= 0 or truncated
        # the reward is the points of the visit (player 0's), a foul's penalty not counted
        assert total == env.unwrapped.rack["score_0"]
