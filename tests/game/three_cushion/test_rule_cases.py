"""Three-cushion's rules played: exact layouts on the carom table, real shots, through the env.

The shots are found, not assumed: :func:`found` plays a grid of absolute aims from one
layout and keeps, for each kind of outcome the cases need (a point off three cushions or
more, two cushions or one before the second ball, no ball met), the
first action that makes it. Each case then replays its action through a front (the
one-inning ``ThreeCushion-v1`` or the two-player duel) from a given rack state and
asserts the rule's consequence: the scores, the striker, the end, the ``info`` keys. The
yellow's shots replay white's from the layout with the two cue balls' places swapped, so
the same action plays the same shot with the other cue ball.
"""

from __future__ import annotations

import math
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env import Table
from pool_env.envs.multiagent import PoolDuelEnv
from pool_env.game import step as step_module
from pool_env.game.games.three_cushion.layout import starting_layout

ID = "pool_env/ThreeCushion-v1"
TABLE = Table.preset("carom")
R = TABLE.ball_radius
AIM = {"aim": "absolute", "aim_range": (-math.pi, math.pi)}
#: White, yellow, red: an open layout, away from the spots and the cushions.
LAYOUT = np.array([[1.2, 0.7], [1.6, 0.8], [2.6, 1.2]])
#: The same balls with the two cue balls' places swapped: the yellow plays white's shots.
SWAPPED = LAYOUT[[1, 0, 2]]

OUTCOMES = {
    "point": lambda info: info["point"] and info["cushions"] >= 3,
    "two_cushions": lambda info: info["second_ball"] >= 0 and info["cushions"] == 2,
    "one_cushion": lambda info: info["second_ball"] >= 0 and info["cushions"] == 1,
    "no_ball": lambda info: info["first_contact"] == -1,
}
#: Where to look for each outcome: a window of absolute aims (action units: its centre
#: and half-width), the speed component and the tip. Found by a coarse grid of 360 aims at
#: full speed: a point off three cushions is rare at 4.5 m/s (4 aims in 2,160 of this
#: layout), this one a window of 0.0011 in aim.
WINDOWS = {
    "point": (-0.8446, 0.0006, 1.0, (-0.5, 0.0)),
    "two_cushions": (-0.417, 0.02, 1.0, (0.0, 0.0)),
    "one_cushion": (0.117, 0.02, 1.0, (0.5, 0.0)),
    "no_ball": (0.5, 0.02, -0.8, (0.0, 0.0)),
}


@pytest.fixture(scope="module")
def found() -> dict[str, np.ndarray]:
    """The first action of each outcome of :data:`OUTCOMES` in its window, from LAYOUT."""
    env = gym.make(ID, **AIM).unwrapped
    actions: dict[str, np.ndarray] = {}
    for name, (centre, half, speed, tip) in WINDOWS.items():
        for aim in centre + np.linspace(-half, half, 13):
            action = np.array([aim, speed, *tip], np.float32)
            env.reset(seed=0, options={"positions": LAYOUT})
            if OUTCOMES[name](env.step(action)[4]):
                actions[name] = action
                break
    assert set(actions) == set(OUTCOMES), f"the windows found only {sorted(actions)}"
    return actions


def duel(rules: dict[str, Any], layout: np.ndarray, **kwargs: Any) -> PoolDuelEnv:
    """A two-player match from ``layout`` and the rack state ``rules``."""
    env = PoolDuelEnv("three_cushion", **AIM, **kwargs)
    env.reset(seed=0, options={"positions": layout, "rules": rules})
    return env


def test_the_grid_shots_are_what_they_are_named(found: dict[str, np.ndarray]) -> None:
    """The one-inning task: a point scores 1 and the inning goes on; the rest end it."""
    env = gym.make(ID, **AIM)
    for name, action in found.items():
        env.reset(seed=0, options={"positions": LAYOUT})
        _, reward, terminated, _, info = env.step(action)
        rack = env.unwrapped.rack
        if name == "point":
            assert info["cushions"] >= 3 and info["second_ball"] in (1, 2)
            assert (reward, terminated, info["turn_over"]) == (1.0, False, False)
            assert rack["score"] == (1, 0) and rack["run"] == 1 and info["score_0"] == 1
        else:  # two cushions or one before the second ball, nothing met: no point, over
            assert not info["point"] and info["foul"] == "", name
            assert (reward, terminated, info["turn_over"]) == (0.0, True, True), name
            assert rack["score"] == (0, 0) and rack["run"] == 0, name


def test_a_point_at_the_one_player_target_ends_the_inning(found: dict[str, np.ndarray]) -> None:
    env = gym.make(ID, target=1, **AIM)
    env.reset(seed=0, options={"positions": LAYOUT})
    _, reward, terminated, _, info = env.step(found["point"])
    assert (reward, terminated, info["winner"]) == (1.0, True, 0)


# name, the outcome played, the rack state before it, the match options, and the rule's
# consequence: the rack state after it, whether the match is over, the rewards (p0, p1).
START = {"shooter": 0, "score": (0, 0), "innings": (1, 0), "equalizing": False}
YELLOW = {"shooter": 1, "score": (0, 0), "innings": (1, 1), "equalizing": False}
CASES = [
    ("white scores, plays on", "point", START, {},
     {"shooter": 0, "score": (1, 0), "innings": (1, 0), "run": 1}, False, (0, 0)),
    ("two cushions: the inning passes", "two_cushions", START, {},
     {"shooter": 1, "score": (0, 0), "innings": (1, 1), "run": 0}, False, (0, 0)),
    ("both balls before the third cushion (one): no point", "one_cushion", START, {},
     {"shooter": 1, "score": (0, 0), "innings": (1, 1)}, False, (0, 0)),
    ("a miss passes the inning", "no_ball", {**START, "run": 4, "score": (4, 2)}, {},
     {"shooter": 1, "score": (4, 2), "innings": (1, 1), "run": 0}, False, (0, 0)),
    ("the yellow scores for player 1", "point", YELLOW, {},
     {"shooter": 1, "score": (0, 1), "innings": (1, 1), "run": 1}, False, (0, 0)),
    ("the yellow misses: white's inning", "no_ball", YELLOW, {},
     {"shooter": 0, "score": (0, 0), "innings": (2, 1)}, False, (0, 0)),
    ("target, no equalizing inning: white wins", "point", {**START, "score": (2, 0)},
     {"target": 3, "equalizing_inning": False},
     {"shooter": 0, "score": (3, 0), "winner": 0}, True, (1, -1)),
    ("target: the yellow's equalizing inning", "point", {**START, "score": (2, 0)},
     {"target": 3}, {"shooter": 1, "score": (3, 0), "innings": (1, 1), "equalizing": True,
                     "winner": -1}, False, (0, 0)),
    ("the equalizing inning reaches the target: a draw", "point",
     {**YELLOW, "score": (3, 2), "equalizing": True}, {"target": 3},
     {"score": (3, 3), "winner": 2}, True, (0, 0)),
    ("the equalizing inning falls short: white wins", "no_ball",
     {**YELLOW, "score": (3, 2), "equalizing": True}, {"target": 3},
     {"score": (3, 2), "winner": 0}, True, (1, -1)),
    ("the yellow reaches the target first: yellow wins", "point",
     {**YELLOW, "score": (1, 2)}, {"target": 3}, {"score": (1, 3), "winner": 1}, True,
     (-1, 1)),
    ("the inning limit: the higher score wins", "no_ball",
     {**YELLOW, "score": (1, 3), "innings": (4, 4)}, {"inning_limit": 4},
     {"score": (1, 3), "innings": (4, 4), "winner": 1}, True, (-1, 1)),
    ("the inning limit on equal scores: a draw", "two_cushions",
     {**YELLOW, "score": (2, 2), "innings": (4, 4)}, {"inning_limit": 4},
     {"score": (2, 2), "winner": 2}, True, (0, 0)),
    ("before the limit the match goes on", "no_ball",
     {**YELLOW, "score": (1, 3), "innings": (3, 3)}, {"inning_limit": 4},
     {"shooter": 0, "innings": (4, 3), "winner": -1}, False, (0, 0)),
    ("white at the limit: the yellow still has its inning", "no_ball",
     {**START, "score": (1, 3), "innings": (4, 3)}, {"inning_limit": 4},
     {"shooter": 1, "innings": (4, 4), "winner": -1}, False, (0, 0)),
]  # fmt: skip


@pytest.mark.parametrize(
    ("outcome", "before", "match", "after", "over", "rewards"),
    [case[1:] for case in CASES],
    ids=[case[0] for case in CASES],
)
def test_rule_case(
    found: dict[str, np.ndarray],
    outcome: str,
    before: dict[str, Any],
    match: dict[str, Any],
    after: dict[str, Any],
    over: bool,
    rewards: tuple[int, int],
) -> None:
    striker = before["shooter"]
    env = duel(before, SWAPPED if striker == 1 else LAYOUT, **match)
    env.step(found[outcome])
    info = env.infos["player_0"]
    assert OUTCOMES[outcome](info)
    assert info["striker"] == striker and info["point"] == (outcome == "point")
    rack = env.rack
    for key, value in after.items():
        assert rack[key] == value, (key, rack)
    assert (info["score_0"], info["score_1"]) == rack["score"]
    assert set(env.terminations.values()) == {over}
    assert (env.rewards["player_0"], env.rewards["player_1"]) == rewards
    winner = rack["winner"]
    assert info["winner"] == (f"player_{winner}" if winner in (0, 1) else None)
    if not over:
        assert env.agent_selection == f"player_{rack['shooter']}"


def test_the_yellow_plays_whites_shot_mirrored(found: dict[str, np.ndarray]) -> None:
    """Player 1 strikes ball 1: the same action moves the yellow as it moved the white."""
    white = duel(START, LAYOUT)
    yellow = duel(YELLOW, SWAPPED)
    white.step(found["point"])
    yellow.step(found["point"])
    np.testing.assert_array_equal(yellow.positions, white.positions[[1, 0, 2]])
    assert not np.allclose(yellow.positions[1], SWAPPED[1])  # the yellow moved


# -- the frozen cue ball (UMB art. 27): re-spotted in the starting position ---------------


def frozen_layout(cue: int, to: int) -> np.ndarray:
    """:data:`LAYOUT` with ball ``cue`` moved to touch ball ``to`` (centres 2R apart)."""
    layout = LAYOUT.copy()
    layout[cue] = layout[to] + (0.0, 2.0 * R)
    return layout


def test_a_miss_leaving_the_next_cue_ball_frozen_respots_it(
    found: dict[str, np.ndarray],
) -> None:
    """White misses; the yellow lies against the red: the yellow's inning from the start."""
    env = duel(START, frozen_layout(1, 2))
    env.step(found["no_ball"])
    info = env.infos["player_0"]
    assert info["first_contact"] == -1 and info["respotted"] and info["turn_over"]
    assert env.rack["shooter"] == 1
    np.testing.assert_array_equal(env.positions, starting_layout(TABLE, 1))


def test_a_point_by_a_cue_ball_not_frozen_is_not_respotted(
    found: dict[str, np.ndarray],
) -> None:
    env = duel(START, LAYOUT)
    env.step(found["point"])
    assert not env.infos["player_0"]["respotted"]
    assert not np.array_equal(env.positions, starting_layout(TABLE, 0))


@pytest.mark.parametrize(("shooter", "cue", "to"), [(0, 0, 2), (0, 0, 1), (1, 1, 2)])
def test_a_cue_ball_frozen_in_a_layout_given_at_reset_is_respotted(
    shooter: int, cue: int, to: int
) -> None:
    env = duel({"shooter": shooter}, frozen_layout(cue, to))
    np.testing.assert_array_equal(env.positions, starting_layout(TABLE, shooter))
    single = gym.make(ID).unwrapped
    single.reset(seed=0, options={"positions": frozen_layout(0, to)})
    np.testing.assert_array_equal(single.positions, starting_layout(TABLE, 0))


def test_only_the_strikers_cue_ball_is_respotted_at_reset() -> None:
    """The opponent's ball touching the red is no matter for white's shot."""
    layout = frozen_layout(1, 2)
    env = duel({"shooter": 0}, layout)
    np.testing.assert_array_equal(env.positions, layout)


def test_a_frozen_cue_ball_after_the_last_shot_stays_where_it_stopped(
    found: dict[str, np.ndarray], monkeypatch: pytest.MonkeyPatch
) -> None:
    """The match ends on the yellow's miss at the inning limit, the yellow against the red.

    No inning follows, so nothing is re-spotted: the final observation shows the balls
    where they stopped, and ``info`` says so. (Where the yellow stops is set in the
    simulator's answer: a real shot ending exactly against a ball is not to be found.)
    """
    real = step_module._simulate

    def stopped_against_the_red(*args: Any, **kwargs: Any) -> Any:
        out = real(*args, **kwargs)
        final = out.final.copy()
        final[0, 1] = final[0, 2] + (0.0, 2.0 * R)  # the yellow at rest against the red
        return out._replace(final=final)

    monkeypatch.setattr(step_module, "_simulate", stopped_against_the_red)
    rules = {**YELLOW, "score": (1, 3), "innings": (4, 4)}
    env = duel(rules, SWAPPED, inning_limit=4)
    env.step(found["no_ball"])
    info = env.infos["player_0"]
    assert info["first_contact"] == -1 and not info["respotted"]
    assert set(env.terminations.values()) == {True} and env.rack["shooter"] == 1
    np.testing.assert_array_equal(env.positions[2], SWAPPED[2])  # not struck
    np.testing.assert_allclose(env.positions[1], SWAPPED[2] + (0.0, 2.0 * R))
    np.testing.assert_array_equal(env.positions[0], SWAPPED[0])
