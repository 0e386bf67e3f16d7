"""The cue ball's first contact under the rules (issue 20 items 4 and 5), through the env.

* A simultaneous first contact: the cue ball meets two balls at one instant (mirror images
  across its path). The simulator orders such impacts by ball number, so the same shot
  used to be legal for solids and a foul for stripes. The shooter gets the benefit now:
  legal if either ball may be hit first, whatever the numbers and the sides.
* The kitchen: with the cue ball in hand behind the head string, a first ball whose base
  lies behind the head string is a foul unless the cue ball crossed the line first.

Each case plays the shot through ``gym.make(id)`` (compiled rules, the fast path and its
replay) and judges the recorded shot with the plain-Python reference, which reads the
simultaneous balls, the kitchen and the crossing from the trajectory on its own.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from pool_env import shoot
from pool_env.game.games.wpa.first_contact import SIMULTANEOUS
from tests.game.test_games import IDS, KWARGS, MID, action, fit, layout, make
from tests.game.test_wpa import TABLE, R, parked
from tests.rules_harness import compiled_judge, same_verdict
from tests.wpa_reference import N_BALLS, OPEN, SOLIDS, STRIPES, RackState, judge, outcome_of

L = TABLE.length
HEAD = L / 4
TIE_X, TIE_OFF = 1.2, 1.2 * R  # two balls either side of the cue ball's path y = MID


def _tie(low: int, high: int) -> dict[int, tuple[float, float]]:
    return {0: (0.8, MID), low: (TIE_X, MID - TIE_OFF), high: (TIE_X, MID + TIE_OFF),
            8: parked(0), 5 if 5 not in (low, high) else 6: parked(1)}  # fmt: skip


def _reference(game: str, balls: dict, angle: float, speed: float, state: RackState):
    numbers = sorted(balls)
    result = shoot(TABLE, [balls[b] for b in numbers], angle, speed)
    out = outcome_of(result, numbers, head_x=HEAD)
    return judge(state, out)[0], out


@pytest.mark.parametrize("groups", [("solids", "stripes"), ("stripes", "solids")])
@pytest.mark.parametrize(("low", "high"), [(3, 11), (11, 3)])
def test_a_simultaneous_first_contact_gives_the_shooter_the_benefit(groups, low, high) -> None:
    balls = _tie(low, high)
    env = make("eight")
    env.reset(seed=0, options={**layout("eight", balls), "rules": {"groups": groups}})
    *_, info = env.step(fit(env, action(0.0, 2.0)))
    assert info["foul"] is None and info["legal"]
    mine = 3 if groups[0] == "solids" else 11
    assert info["first_contact"] == mine  # the ball the rules read
    # The premise, from the recorded trajectory: both met within the documented tolerance.
    code = {"solids": SOLIDS, "stripes": STRIPES}
    on = tuple(b in balls for b in range(N_BALLS["eight"]))
    state = RackState("eight", on, breaking=False, groups=(code[groups[0]], code[groups[1]]))
    verdict, out = _reference("eight", balls, 0.0, 2.0, state)
    assert {out.first_hit, *out.simultaneous} == {3, 11} and verdict.legal


def test_a_simultaneous_contact_with_no_legal_ball_is_a_foul() -> None:
    balls = {**_tie(3, 11), 8: (TIE_X, MID + TIE_OFF)}
    del balls[11]
    balls[11] = parked(2)
    env = make("eight")
    env.reset(seed=0, options={**layout("eight", balls),
                               "rules": {"groups": ("stripes", "solids")}})  # fmt: skip
    *_, info = env.step(fit(env, action(0.0, 2.0)))
    assert info["foul"] == "wrong_ball_first"


def _kitchen(cue: tuple[float, float], ball3: tuple[float, float]) -> dict:
    return {0: cue, 3: ball3, 8: parked(0), 11: parked(1)}


def _place(x: float, y: float) -> tuple[float, float]:
    """Action components 2 and 3 that put the cue ball in hand at (x, y) in the kitchen."""
    return ((x - R) / (HEAD - R) * 2 - 1, (y - R) / (TABLE.width - 2 * R) * 2 - 1)


# (name, cue, the 3, angle, speed, behind the head string, expected foul, the cue ball
# crossed the head string before its first contact)
KITCHEN = [
    ("straight-at-a-kitchen-ball", (0.2, MID), (0.5, MID), 0.0, 1.5, True,
     "kitchen_ball_first", False),
    ("kitchen-ball-with-ball-in-hand-anywhere", (0.2, MID), (0.5, MID), 0.0, 1.5, False, None,
     False),
    ("a-ball-on-the-head-string-is-playable", (0.2, MID), (HEAD, MID), 0.0, 1.5, True, None,
     False),
    ("a-ball-past-the-head-string", (0.2, MID), (1.0, MID), 0.0, 1.5, True, None, True),
    ("crossed-and-back-off-the-foot-rail", (0.5, 0.3), (0.2, 0.3), 0.0, 3.0, True, None, True),
]  # fmt: skip


@pytest.mark.parametrize("case", KITCHEN, ids=[c[0] for c in KITCHEN])
def test_the_kitchen_rule(case: tuple) -> None:
    _, cue, ball3, angle, speed, behind, foul, crossed = case
    balls = _kitchen(cue, ball3)
    env = make("eight")
    rules = {"ball_in_hand": True, "behind_head_string": behind}
    env.reset(seed=0, options={**layout("eight", balls), "rules": rules})
    place = (
        _place(*cue)
        if behind
        else ((cue[0] - R) / (L - 2 * R) * 2 - 1, (cue[1] - R) / (TABLE.width - 2 * R) * 2 - 1)
    )
    *_, info = env.step(fit(env, action(angle, speed, place)))
    assert info["first_contact"] == 3
    assert info["foul"] == foul
    # the reference, from the recorded trajectory, on its own
    on = tuple(b in balls for b in range(N_BALLS["eight"]))
    state = RackState("eight", on, breaking=False, groups=(OPEN, OPEN), ball_in_hand=True,
                      behind_head_string=behind)  # fmt: skip
    verdict, out = _reference("eight", balls, angle, speed, state)
    assert verdict.foul == foul
    assert out.crossed_head_string == crossed


def test_the_replay_agrees_with_the_compiled_rules_on_a_kitchen_shot() -> None:
    # The compiled rules with the crossing and the start position given, as the env feeds
    # them, against the reference, for the straight shot at a kitchen ball.
    balls = _kitchen((0.2, MID), (0.5, MID))
    numbers = sorted(balls)
    start = [balls[b] for b in numbers]
    result = shoot(TABLE, start, 0.0, 1.5, record=True)
    on = tuple(b in balls for b in range(16))
    state = RackState("eight", on, breaking=False, ball_in_hand=True, behind_head_string=True)
    out = outcome_of(result, numbers, head_x=HEAD)
    verdict, after = judge(state, out)
    got, got_after = compiled_judge(
        TABLE, state, result.positions, numbers, result.first_contact,
        result.cushions_after_contact, result.pocketed, result.pocket_order, None,
        crossed=out.crossed_head_string, start=start,
    )  # fmt: skip
    same_verdict(verdict, after, got, got_after)
    assert got["foul"] == "kitchen_ball_first"


def test_the_tolerance_is_far_above_rounding_and_far_below_sight() -> None:
    # 1e-9 s: the rounding of an event time after 1,000 s is ~2e-13 s; a ball at 10 m/s
    # moves 10 nm in that time.
    assert SIMULTANEOUS > 1000 * 2.2e-16 and 10.0 * SIMULTANEOUS <= 1e-8
    assert math.isclose(SIMULTANEOUS, 1e-9)


def test_the_vector_env_reads_the_first_contact_alike() -> None:
    # The batch path reports every ball's column (the single path only those on the table):
    # the replay maps its rows back alike. Table 0: a tie, the shooter on stripes; table 1:
    # a straight shot at a kitchen ball with the cue ball in hand behind the head string.
    env = gym.make_vec(IDS["eight"], 2, vectorization_mode="vector_entry_point", **KWARGS)
    env.reset(seed=0)
    stripes = {"groups": ("stripes", "solids")}
    in_hand = {"ball_in_hand": True, "behind_head_string": True}
    for k, (balls, rules) in enumerate(
        [(_tie(3, 11), stripes), (_kitchen((0.2, MID), (0.5, MID)), in_hand)]
    ):
        mask = np.arange(2) == k
        env.reset(options={**layout("eight", balls), "rules": rules, "reset_mask": mask})
    actions = np.stack([action(0.0, 2.0), action(0.0, 1.5, _place(0.2, MID))])
    *_, info = env.step(actions)
    assert list(info["foul"]) == [None, "kitchen_ball_first"]
    assert list(info["first_contact"]) == [11, 3]
