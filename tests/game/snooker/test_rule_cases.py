"""Snooker's rules as a table of cases, each played on the table from an exact layout.

Each case lays the balls out (``options["positions"]``, ``on_table``), sets the frame
state (``options["rules"]``), plays one exact stroke (absolute aim, the roll table, no
noise) and checks the verdict, the scores, the frame state and where the balls are.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from pool_env import PoolEnv, Shot, encode_action
from pool_env.game.games.snooker.markings import frame_layout, markings
from pool_env.sim.table import Table

TABLE = Table.preset("snooker", model="roll")
R = TABLE.ball_radius
L, W = TABLE.length, TABLE.width
MARK = markings(TABLE)
SPOT = {c: MARK.spots[c - 16] for c in range(16, 22)}
TOP_LEFT = np.array([L, W])  # the top cushion's corner pocket on the +y side


@pytest.fixture(scope="module")
def env() -> PoolEnv:
    # slow strokes too (a foul that leaves the cue ball where it was)
    return PoolEnv(game="snooker", scene="snooker", table=TABLE, aim="absolute",
                   speed_range=(0.05, 4.0))  # fmt: skip


def layout(reds: dict[int, tuple[float, float]], **moved: tuple[float, float]) -> tuple:
    """The colours on their spots (or ``moved``), these reds, the cue ball at ``cue``."""
    pos = frame_layout(TABLE)
    on = np.zeros(22, dtype=bool)
    on[0] = True
    on[16:] = True
    for j, p in reds.items():
        pos[j], on[j] = p, True
    names = {"cue": 0, "yellow": 16, "green": 17, "brown": 18, "blue": 19, "pink": 20,
             "black": 21}  # fmt: skip
    for name, p in moved.items():
        if p is None:
            on[names[name]] = False
        else:
            pos[names[name]] = p
    return pos, on


def behind(ball: np.ndarray, target: np.ndarray, gap: float = 0.3) -> tuple[np.ndarray, float]:
    """The cue ball ``gap`` behind ``ball`` on the line to ``target``, and the angle."""
    d = (target - ball) / np.linalg.norm(target - ball)
    return ball - gap * d, math.atan2(d[1], d[0])


def play(env: PoolEnv, pos: np.ndarray, on: np.ndarray, rules: dict[str, Any],
         angle: float, speed: float, ball: int | None = None) -> dict[str, Any]:  # fmt: skip
    env.reset(seed=0, options={"positions": pos, "on_table": on, "rules": rules})
    action = encode_action(env.config, Shot(angle, speed, ball=ball), env.positions,
                           env.on_table, rack=env.rack)  # fmt: skip
    _, reward, terminated, _, info = env.step(action)
    return {**info, "reward": reward, "terminated": terminated, "rack": env.rack,
            "positions": env.positions, "on": env.on_table}  # fmt: skip


def test_a_red_potted_scores_one_and_a_colour_is_on(env: PoolEnv) -> None:
    red = np.array([3.2, 1.45])
    cue, angle = behind(red, TOP_LEFT)
    pos, on = layout({1: red, 2: (1.0, 0.3)}, cue=cue)
    out = play(env, pos, on, {}, angle, 1.5)
    assert (out["foul"], out["points"], out["reward"]) == (None, 1, 1.0)
    assert out["rack"]["phase"] == "colour" and out["rack"]["break"] == 1
    assert not out["turn_over"] and out["rack"]["score_0"] == 1


def test_the_nominated_colour_potted_scores_and_is_respotted(env: PoolEnv) -> None:
    black = np.array([3.0, 1.3])
    cue, angle = behind(black, TOP_LEFT)
    pos, on = layout({1: (1.0, 0.3)}, cue=cue, black=black)
    out = play(env, pos, on, {"phase": "colour", "break": 1}, angle, 1.5, ball=21)
    assert (out["foul"], out["points"], out["nominated"]) == (None, 7, 21)
    assert out["rack"]["phase"] == "red" and out["rack"]["break"] == 8
    assert out["on"][21] and np.allclose(out["positions"][21], SPOT[21])


def test_a_colour_first_with_a_red_on_is_a_foul_of_its_value(env: PoolEnv) -> None:
    cue, angle = behind(SPOT[19], SPOT[19] + np.array([1.0, 0.0]))  # straight at the blue
    pos, on = layout({1: (3.0, 0.2)}, cue=cue)
    out = play(env, pos, on, {}, angle, 0.8)
    assert (out["foul"], out["penalty"], out["points"]) == ("wrong_ball_first", 5, 0)
    assert out["rack"]["score_1"] == 5 and out["rack"]["shooter"] == 1
    assert out["reward"] == -5.0 and out["turn_over"]


def test_hitting_the_black_when_pink_is_nominated_gives_seven(env: PoolEnv) -> None:
    cue, angle = behind(SPOT[21], SPOT[21] + np.array([1.0, 0.0]))
    pos, on = layout({1: (1.0, 0.2)}, cue=cue)
    out = play(env, pos, on, {"phase": "colour"}, angle, 0.5, ball=20)
    assert (out["foul"], out["penalty"]) == ("wrong_ball_first", 7)


def test_missing_every_ball_is_four_and_the_cue_ball_potted_is_in_hand(env: PoolEnv) -> None:
    cue = np.array([3.3, 1.55])
    angle = math.atan2(*(TOP_LEFT - cue)[::-1])
    pos, on = layout({1: (1.0, 0.2)}, cue=cue)
    out = play(env, pos, on, {}, angle, 1.0)
    assert (out["foul"], out["penalty"]) == ("no_contact", 4)
    rack, p = out["rack"], out["positions"][0]
    assert rack["ball_in_hand"] and out["on"][0]
    assert p[0] <= MARK.baulk_x and math.dist(p, (MARK.baulk_x, MARK.centre_y)) <= MARK.d_radius


def test_a_foul_that_leaves_the_opponent_snookered_gives_a_free_ball(env: PoolEnv) -> None:
    # The cue ball behind the blue, the only red straight beyond it: rolled back a little
    # (a foul: no ball hit), it leaves the opponent snookered.
    red = (2.6, MARK.centre_y)
    pos, on = layout({1: red}, cue=(1.5, MARK.centre_y))
    out = play(env, pos, on, {}, math.pi, 0.2)
    assert out["foul"] == "no_contact" and out["rack"]["free_ball"]
    # off the line, the opponent sees both edges of the red: no free ball
    pos, on = layout({1: red}, cue=(1.5, MARK.centre_y + 0.3))
    out = play(env, pos, on, {}, math.pi, 0.2)
    assert out["foul"] == "no_contact" and not out["rack"]["free_ball"]


def test_a_free_ball_potted_counts_as_a_red_and_is_respotted(env: PoolEnv) -> None:
    green = np.array([3.0, 1.4])
    cue, angle = behind(green, TOP_LEFT)
    pos, on = layout({1: (1.0, 0.2)}, cue=cue, green=green)
    out = play(env, pos, on, {"free_ball": True, "shooter": 1}, angle, 1.5, ball=17)
    assert (out["foul"], out["points"], out["free_ball"]) == (None, 1, True)
    assert out["rack"]["phase"] == "colour" and out["rack"]["score_1"] == 1
    assert np.allclose(out["positions"][17], SPOT[17])
    # nominating the free ball and hitting a red first is a foul of the free ball's value
    red = np.array([3.0, 1.4])
    cue, angle = behind(red, TOP_LEFT)
    pos, on = layout({1: red}, cue=cue)
    out = play(env, pos, on, {"free_ball": True}, angle, 1.5, ball=20)
    assert (out["foul"], out["penalty"]) == ("wrong_ball_first", 6)


def test_a_colour_goes_to_the_highest_free_spot_when_its_own_is_covered(env: PoolEnv) -> None:
    black = np.array([3.0, 1.3])
    cue, angle = behind(black, TOP_LEFT)
    pos, on = layout({1: tuple(SPOT[21])}, cue=cue, black=black, pink=(2.0, 1.5))
    out = play(env, pos, on, {"phase": "colour"}, angle, 1.5, ball=21)
    assert out["points"] == 7 and np.allclose(out["positions"][21], SPOT[20])
    # every spot covered: towards the top cushion, touching-close past the red on its spot
    pos, on = layout({1: tuple(SPOT[21])}, cue=cue, black=black)
    out = play(env, pos, on, {"phase": "colour"}, angle, 1.5, ball=21)
    x, y = out["positions"][21]
    assert y == pytest.approx(SPOT[21][1]) and x == pytest.approx(SPOT[21][0] + 2 * R, abs=1e-6)


def test_the_colours_in_order_stay_off_and_the_next_is_on(env: PoolEnv) -> None:
    yellow = np.array([3.0, 1.3])
    cue, angle = behind(yellow, TOP_LEFT)
    pos, on = layout({}, cue=cue, yellow=yellow)
    out = play(env, pos, on, {"phase": "in_order"}, angle, 1.5)
    assert (out["foul"], out["points"], out["ball_on"]) == (None, 2, 16)
    assert not out["on"][16] and out["rack"]["phase"] == "in_order"
    # on the yellow, the green first: 4 (the yellow's 2 and the green's 3 are less)
    cue, angle = behind(SPOT[17], SPOT[17] + np.array([1.0, 0.0]))
    pos, on = layout({}, cue=cue)
    out = play(env, pos, on, {"phase": "in_order"}, angle, 0.5)
    assert (out["foul"], out["penalty"]) == ("wrong_ball_first", 4)


def test_a_touching_ball_must_be_played_away_from(env: PoolEnv) -> None:
    red = np.array([2.4, 1.2])
    cue = red - np.array([2 * R, 0.0])  # touching, on the red's -x side
    pos, on = layout({1: red}, cue=cue)
    out = play(env, pos, on, {}, math.pi, 0.3)  # away from it: nothing else to hit
    assert out["foul"] is None and out["turn_over"]
    out = play(env, pos, on, {}, 0.0, 0.5)  # into it: a push
    assert (out["foul"], out["penalty"]) == ("push", 4)


def test_a_level_frame_goes_to_a_respotted_black(env: PoolEnv) -> None:
    black = np.array([3.0, 1.3])
    cue, angle = behind(black, TOP_LEFT)
    pos, on = layout({}, cue=cue, black=black, yellow=None, green=None, brown=None,
                     blue=None, pink=None)  # fmt: skip
    rules = {"phase": "in_order", "score_0": 3, "score_1": 10, "break": 12}
    out = play(env, pos, on, rules, angle, 1.5)
    rack = out["rack"]
    assert out["points"] == 7 and rack["winner"] is None and not out["terminated"]
    assert out["break"] == 19 and rack["break"] == 0  # the striker's break; the next's
    assert rack["respotted_black"] and rack["ball_in_hand"]
    assert out["on"][21] and np.allclose(out["positions"][21], SPOT[21])
    # ahead by more than the black, potting it ends the frame: the striker wins it
    out = play(env, pos, on, {**rules, "score_0": 20}, angle, 1.5)
    assert out["winner"] == 0 and out["terminated"] and out["rack"]["score_0"] == 27
