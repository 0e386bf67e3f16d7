"""Pots re-aimed at the middle of their pot windows, and the search's safeties switch."""

from __future__ import annotations

from dataclasses import replace

import gymnasium as gym
import numpy as np
import pytest

from agents.baselines.rule_play import rule_action
from agents.learned.game_model import GameModel
from agents.learned.layout_value import LAYOUT_FEATURES, LayoutValue, design
from agents.learned.search_player import SearchPlayer, SearchSettings
from agents.learned.shot_fans import FAN_STEP, AimWindows, window_centres
from pool_env.game.codec import encode_shots
from pool_env.game.games.wpa import rack_row
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER

ENV_ID = "pool_env/NineBallGame-v2"


@pytest.mark.parametrize(
    ("row", "expected"),
    [
        ("..xxxxx..", 0.0),  # the planned aim in the middle of its window
        ("....xxxx.", 1.5),  # the planned aim at the window's left edge
        ("xxxxx....", -2.0),  # the planned aim at the window's right edge
        ("xx......x", -3.5),  # the planned aim misses: the nearest success (1, 3 away)
        ("x.......x", -4.0),  # two runs as near: the left one
        ("...x.xx..", -1.0),  # successes 1 away either side: the left one's run
        (".........", 0.0),  # nothing pots: the aim stays
    ],
)
def test_window_centres_are_the_middle_of_the_run_nearest_the_planned_aim(row, expected) -> None:
    success = np.array([[c == "x" for c in row]])
    assert window_centres(success)[0] == expected


def _straight_in(config):
    """The 9 1 m up the diagonal from the far corner, the cue ball 1 m behind it on that line.

    Its window is about 1.7 mrad either side of the line (ghost_shots' tolerance), narrower
    than the fan: aims a few steps off miss.
    """
    table = config.table
    u = np.array([table.length, table.width]) / np.hypot(table.length, table.width)
    nine = np.array([table.length, table.width]) - u * 1.0
    positions = np.tile([0.1, 0.05], (10, 1))
    on = np.zeros(10, dtype=bool)
    positions[9], positions[0] = nine, nine - u * 1.0
    on[[0, 9]] = True
    return positions, on, float(np.arctan2(u[1], u[0]))


def _actions(config, positions, reference, angles, speed=1.5):
    parts, ok = encode_shots(
        config, positions[None], reference[None], np.array([angles]),
        np.full((1, len(angles)), speed),
    )  # fmt: skip
    assert ok.all()
    return np.stack([rule_action(config, np.r_[p, 0.0, 0.0]) for p in parts[0]])


def _pot_rate(config, positions, on, actions, samples=256):
    result, _, _ = GameModel(config, seed=5).play(positions, on, rack_row({}), actions, samples)
    hits = result.hits
    made = (hits[:, WINNER] == 0) | ((hits[:, FOUL] == 0) & (hits[:, KEEPS] != 0))
    return made.reshape(len(actions), samples).mean(axis=1)


def test_a_straight_in_pot_aimed_off_its_window_is_brought_back_to_the_line() -> None:
    config = gym.make(ENV_ID, noise="fastfiz").unwrapped.config
    positions, on, line = _straight_in(config)
    reference = on.copy()
    # Straight in to a corner along its diagonal: the window is symmetric about the line.
    off = np.array([-5, -3, 0, 3, 5]) * FAN_STEP
    planned = _actions(config, positions, reference, line + off)
    centred, shifts = AimWindows(config, 8).centre(positions, on, reference, rack_row({}), planned)
    np.testing.assert_allclose(off + shifts, 0.0, atol=FAN_STEP)  # back within one step
    assert abs(shifts[2]) <= FAN_STEP  # the line itself stays (within a step)
    before = _pot_rate(config, positions, on, planned)
    after = _pot_rate(config, positions, on, centred)
    # Under FastFiz's noise the shots aimed 5 steps (5.5 mrad) off miss more often than the
    # re-aimed ones (common noise: the same errors for both).
    assert after[[0, 4]].min() > before[[0, 4]].max() + 0.05
    assert np.all(centred[:, 1:] == planned[:, 1:])  # only the aim column moves


def test_a_shot_that_pots_nowhere_in_the_fan_keeps_its_aim() -> None:
    config = gym.make(ENV_ID).unwrapped.config
    positions, on, line = _straight_in(config)
    away = _actions(config, positions, on.copy(), [line + 0.03])  # 27 steps off: a thin cut
    centred, shifts = AimWindows(config, 4).centre(positions, on, on.copy(), rack_row({}), away)
    assert shifts[0] == 0.0 and np.array_equal(centred, away)


def _value() -> LayoutValue:
    w = np.zeros(design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1])
    w[0], w[1 + LAYOUT_FEATURES.index("p_best")] = -2.0, 4.0
    return LayoutValue(w)


def test_without_safeties_the_search_plays_among_pots_only() -> None:
    env = gym.make(ENV_ID, noise="fastfiz")
    positions, on, _ = _straight_in(env.unwrapped.config)
    on[[1, 2]] = True  # two more balls: the 1 is on, far from the 9
    positions[1], positions[2] = (1.0, 0.3), (1.6, 0.9)
    obs, _ = env.reset(options={"positions": positions, "on_table": on,
                                "rules": {"break": False, "ball_in_hand": False}})  # fmt: skip
    counts = {}
    for safeties in (True, False):
        settings = SearchSettings(budget=0.01, samples=2, finalists=2, round_samples=2,
                                  safeties=safeties, fans=2)  # fmt: skip
        agent = SearchPlayer(env, _value(), settings=settings)
        agent.predict(obs)
        counts[safeties] = agent.last_search["candidates"]
        assert agent.last_plan["shot"] != "grid" or safeties
    assert counts[False] < counts[True]  # the grid's shots are gone


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"fans": -1}, r"fans must be an integer in \[0, 32\]"),
        ({"fans": 2.5}, r"fans must be an integer in \[0, 32\]"),
        ({"fans": 33}, r"fans must be an integer in \[0, 32\]"),
        ({"safeties": "no"}, "safeties must be true or false, got 'no'"),
        ({"safeties": 0}, "safeties must be true or false, got 0"),
    ],
)
def test_bad_fan_and_safety_settings_are_refused(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        replace(SearchSettings(), **kwargs)


def test_bank_pots_join_the_candidates_when_asked_for() -> None:
    env = gym.make(ENV_ID)
    positions = np.tile([0.1, 0.05], (10, 1))
    on = np.zeros(10, dtype=bool)
    # The 1 off the middle of a long rail, the cue ball on the head spot: pots off the rails.
    positions[0], positions[1], positions[9] = (0.6, 0.635), (1.27, 0.3), (0.3, 1.1)
    on[[0, 1, 9]] = True
    found = {}
    for banks in (0, 4):
        settings = SearchSettings(budget=0.01, samples=2, finalists=2, round_samples=2,
                                  banks=banks)  # fmt: skip
        agent = SearchPlayer(env, _value(), settings=settings)
        agent._targets = [1]  # the rules' legal balls, as the observation gives them
        reference = np.zeros_like(on)
        reference[[0, 1]] = True  # the aim refers to the cue ball and the ball on
        found[banks] = agent._banks(positions, on, reference)
    assert found[0] == [] and 1 <= len(found[4]) <= 4
    pockets = [pocket for _, pocket in found[4]]
    assert len(set(pockets)) == len(pockets)  # one per pocket
    # Traced in closed form (no spin, no throw): on the model, played without noise, at
    # least one drops the 1 legally.
    model = GameModel(env.unwrapped.config)
    acts = np.stack([a for a, _ in found[4]])
    result, _, left = model.play(positions, on, rack_row({}), acts, 1)
    assert (~left[:, 1] & (result.hits[:, FOUL] == 0)).any()
