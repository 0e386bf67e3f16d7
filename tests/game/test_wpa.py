"""Rule cases: a constructed layout, a shot simulated by the real physics, the verdict.

Every case shoots with :func:`pool_env.shoot` and judges the simulated outcome with the
plain-Python reference (:mod:`tests.wpa_reference`), whose verdict the case asserts, and
with the product's compiled rules (:func:`pool_env.game.games.wpa.judge.judge_rules`), which must
agree with it on the verdict and the rack after the shot. Pots are
straight in along a corner pocket's diagonal from close range (the most forgiving pot on any
pocket model); each case also asserts its premise (what the physics did), so that a change
of the pocket model shows up as a broken premise, not as a wrong verdict.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from pool_env import Table, free_spot, shoot
from pool_env.game.scenes import CLEARANCE
from pool_env.sim.batch import simulate_batch
from pool_env.sim.layouts import break_scene, foot_spot
from tests.rules_harness import compiled_judge, same_verdict
from tests.wpa_reference import (
    N_BALLS,
    OPEN,
    SOLIDS,
    STRIPES,
    RackState,
    ShotOutcome,
    batch_outcome,
    judge,
    outcome_of,
)

# The table these scenes were laid out and aimed for: capture circles and the earlier
# cushion restitution. The rules are pure functions of a shot's outcome, so the cases pin the
# rules on one fixed table (each still asserts its physical premise).
TABLE = Table(pockets="circles", e_cushion=0.85)
R = TABLE.ball_radius
TOWARD_CORNER = -3 * math.pi / 4  # along the diagonal into pocket 0 at (0, 0)
FAR = (1.9, 0.9)  # a parking place far from every shot below


def diag(s: float) -> tuple[float, float]:
    """The point ``s`` from pocket 0's centre along its diagonal."""
    return (s / math.sqrt(2.0), s / math.sqrt(2.0))


def parked(k: int) -> tuple[float, float]:
    """The ``k``-th of a row of parking places, far from the shots."""
    return (1.7 + 3 * R * (k % 5), 0.75 + 3 * R * (k // 5))


def play(
    game: str,
    balls: dict[int, tuple[float, float]],
    angle: float,
    speed: float,
    state: RackState | None = None,
    called: int | None = None,
):
    """Simulate the shot on the balls given and judge it; return (verdict, after, outcome)."""
    numbers = sorted(balls)
    result = shoot(TABLE, [balls[b] for b in numbers], angle, speed)
    outcome = outcome_of(result, numbers)
    if state is None:
        on = tuple(b in balls for b in range(N_BALLS[game]))
        state = RackState(game=game, on_table=on, breaking=False)
    verdict, after = judge(state, outcome, called)
    # The product's compiled rules judge the same outcome alike.
    got, got_after = compiled_judge(
        TABLE, state, result.positions, numbers, result.first_contact,
        result.cushions_after_contact, result.pocketed, result.pocket_order, called,
    )  # fmt: skip
    same_verdict(verdict, after, got, got_after)
    return verdict, after, outcome


def nine(on: dict[int, tuple[float, float]], **kw) -> RackState:
    state = RackState(game="nine", on_table=tuple(b in on for b in range(10)), breaking=False)
    return replace(state, **kw)


def eight(on: dict[int, tuple[float, float]], **kw) -> RackState:
    state = RackState(game="eight", on_table=tuple(b in on for b in range(16)), breaking=False)
    return replace(state, **kw)


def straight_in(obj: int, cue_at: float = 0.45, obj_at: float = 0.25) -> dict:
    return {0: diag(cue_at), obj: diag(obj_at)}


# --- 9-ball -----------------------------------------------------------------------------


def test_nine_legal_pot_of_the_ball_on_keeps_the_table() -> None:
    balls = {**straight_in(1), 2: parked(0), 9: parked(1)}
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, 1.5)
    assert shot.potted == (1,) and shot.pockets == (0,) and not shot.scratch
    assert verdict.legal and verdict.foul is None and verdict.ball_on == 1
    assert verdict.shooter_continues and after.shooter == 0 and not after.ball_in_hand
    assert after.ball_on == 2 and after.winner is None


def test_nine_wrong_ball_first_is_a_foul_and_the_pot_stays_down() -> None:
    balls = {**straight_in(2), 1: parked(0), 9: parked(1)}
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, 1.5)
    assert shot.first_hit == 2 and shot.potted == (2,)
    assert verdict.foul == "wrong_ball_first" and not verdict.legal
    assert after.shooter == 1 and after.ball_in_hand and not after.behind_head_string
    assert not after.on_table[2] and after.fouls == (1, 0)


def test_nine_no_contact() -> None:
    balls = {0: (0.9, TABLE.width / 2), 1: parked(0), 9: parked(1)}
    verdict, after, shot = play("nine", balls, math.pi / 2, 0.3)
    assert shot.first_hit == -1 and not shot.rail_after_contact and not shot.scratch
    assert verdict.foul == "no_contact" and after.ball_in_hand and after.shooter == 1


def test_nine_no_rail_after_a_soft_contact() -> None:
    y = TABLE.width / 2
    balls = {0: (0.8, y), 1: (1.0, y), 9: parked(3)}
    verdict, after, shot = play("nine", balls, 0.0, 0.4)
    assert shot.first_hit == 1 and not shot.potted and not shot.rail_after_contact
    assert verdict.foul == "no_rail" and after.ball_in_hand


def test_nine_rail_after_contact_is_legal_and_passes_the_turn() -> None:
    y = TABLE.width / 2
    balls = {0: (0.8, y), 1: (1.0, y), 9: parked(3)}
    verdict, after, shot = play("nine", balls, 0.0, 1.0)
    assert shot.first_hit == 1 and shot.rail_after_contact and not shot.potted
    assert verdict.legal and not verdict.shooter_continues
    assert after.shooter == 1 and not after.ball_in_hand


def test_nine_rail_before_contact_does_not_count() -> None:
    """Cue ball down into the rail, back up onto the 1, which stops short of the far rail."""
    balls = {0: (1.0, 0.3), 1: (1.0, 0.75), 9: parked(3)}
    verdict, _, shot = play("nine", balls, -math.pi / 2, 0.55)
    assert shot.first_hit == 1 and not shot.potted and not shot.rail_after_contact
    assert verdict.foul == "no_rail"


def test_nine_rail_first_then_ball_then_rail_is_legal() -> None:
    balls = {0: (1.0, 0.3), 1: (1.0, 0.75), 9: parked(3)}
    verdict, _, shot = play("nine", balls, -math.pi / 2, 2.5)
    assert shot.first_hit == 1 and shot.rail_after_contact
    assert verdict.legal


def _graze_into_corner(obj: int) -> dict:
    """The cue ball rolls along the diagonal into pocket 0, grazing ``obj`` on the way.

    ``obj`` sits 1.999 R off the cue ball's path: a glancing contact that turns the cue
    ball by about 2 degrees (closed form: the impulse is along the line of centres, which
    is nearly perpendicular to the path), far less than the pocket accepts.
    """
    s = 0.3
    off = 1.999 * R
    x, y = diag(s)
    return {0: diag(0.6), obj: (x + off / math.sqrt(2.0), y - off / math.sqrt(2.0))}


def test_nine_scratch_after_a_legal_contact() -> None:
    balls = {**_graze_into_corner(1), 9: parked(1)}
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, 1.5)
    assert shot.first_hit == 1 and shot.scratch
    assert verdict.foul == "scratch" and after.ball_in_hand and not after.behind_head_string


def test_nine_scratch_without_contact_reports_the_scratch() -> None:
    balls = {0: diag(0.4), 1: parked(0), 9: parked(1)}
    verdict, _, shot = play("nine", balls, TOWARD_CORNER, 1.0)
    assert shot.scratch and shot.first_hit == -1
    assert verdict.foul == "scratch"


def test_nine_the_nine_on_a_combination_wins() -> None:
    balls = {0: diag(0.55), 1: diag(0.4), 9: diag(0.25), 3: parked(0)}
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, 2.0)
    assert shot.first_hit == 1 and 9 in shot.potted and not shot.scratch
    assert verdict.legal and verdict.winner == 0 and after.winner == 0
    assert not verdict.shooter_continues


def test_nine_the_nine_potted_on_a_foul_is_respotted() -> None:
    balls = {**straight_in(9), 1: parked(0)}
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, 1.5)
    assert shot.first_hit == 9 and shot.potted == (9,)
    assert verdict.foul == "wrong_ball_first" and verdict.respot == (9,)
    assert verdict.winner is None and after.on_table[9] and after.ball_in_hand


def test_nine_the_nine_potted_with_a_scratch_is_respotted() -> None:
    """The 9 is the ball on; the cue ball follows it into the pocket: a foul, no win."""
    # The cue ball keeps (1 - e) / 2 of its speed in a full hit: fast enough here to
    # roll after the 9 into the pocket (closed form below).
    balls = {0: diag(0.2 + 2 * R), 9: diag(0.095)}
    speed = 6.0
    kept = (1 - TABLE.e_ball) / 2 * math.sqrt(speed**2 - 2 * TABLE.deceleration * 0.105)
    assert kept**2 / (2 * TABLE.deceleration) > 0.095 + 2 * R - TABLE.pockets[0, 2]
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, speed)
    assert shot.first_hit == 9 and shot.scratch and 9 in shot.potted
    assert verdict.foul == "scratch" and verdict.respot == (9,) and verdict.winner is None
    assert after.on_table[9]


def test_nine_the_nine_as_ball_on_wins() -> None:
    balls = straight_in(9)
    verdict, after, _ = play("nine", balls, TOWARD_CORNER, 1.5)
    assert verdict.ball_on == 9 and verdict.winner == 0 and after.winner == 0


def test_nine_a_combination_of_the_ball_on_keeps_the_table() -> None:
    balls = {0: diag(0.55), 1: diag(0.4), 4: diag(0.25), 9: parked(0)}
    verdict, after, shot = play("nine", balls, TOWARD_CORNER, 2.0)
    assert shot.first_hit == 1 and 4 in shot.potted
    assert verdict.legal and verdict.shooter_continues and not after.on_table[4]


def test_nine_third_foul_in_a_row_loses() -> None:
    balls = {0: (0.9, TABLE.width / 2), 1: parked(0), 9: parked(1)}
    state = nine(balls, fouls=(2, 0))
    verdict, after, _ = play("nine", balls, math.pi / 2, 0.3, state=state)
    assert verdict.foul == "no_contact" and verdict.loss == "three_fouls"
    assert verdict.winner == 1 and after.winner == 1


def test_nine_a_legal_shot_resets_the_foul_count() -> None:
    y = TABLE.width / 2
    balls = {0: (0.8, y), 1: (1.0, y), 9: parked(3)}
    verdict, after, _ = play("nine", balls, 0.0, 1.0, state=nine(balls, fouls=(2, 1)))
    assert verdict.legal and after.fouls == (0, 1) and after.winner is None


def test_nine_two_fouls_do_not_lose() -> None:
    balls = {0: (0.9, TABLE.width / 2), 1: parked(0), 9: parked(1)}
    verdict, after, _ = play("nine", balls, math.pi / 2, 0.3, state=nine(balls, fouls=(1, 2)))
    assert verdict.foul and verdict.loss is None and after.fouls == (2, 2) and after.winner is None


def _break(game: str, speed: float, angle_offset: float = 0.0):
    pos = break_scene(TABLE, game)
    d = pos[1] - pos[0]
    angle = math.atan2(d[1], d[0]) + angle_offset
    balls = {k: tuple(p) for k, p in enumerate(pos)}
    return play(game, balls, angle, speed, state=RackState.new_rack(game))


def test_nine_hard_break_is_legal() -> None:
    verdict, after, shot = _break("nine", 9.0)
    assert shot.first_hit == 1 and not shot.scratch
    assert shot.potted or shot.object_balls_to_rail >= 4
    assert verdict.legal and not after.breaking
    assert (verdict.winner == 0) == (9 in shot.potted)


def test_nine_soft_break_is_illegal() -> None:
    verdict, after, shot = _break("nine", 0.8)
    assert shot.first_hit == 1 and not shot.potted and shot.object_balls_to_rail < 4
    assert verdict.foul == "illegal_break" and after.ball_in_hand and after.shooter == 1


def test_nine_break_that_misses_the_one_is_illegal() -> None:
    """The cue ball comes in from the side rail onto the 2, which the 1 does not shield."""
    pos = break_scene(TABLE, "nine")
    balls = {k: tuple(p) for k, p in enumerate(pos)}
    two = pos[2]
    balls[0] = (float(two[0]), 0.3)
    verdict, _, shot = play(
        "nine", balls, math.atan2(two[1] - 0.3, 0.0), 6.0, state=RackState.new_rack("nine")
    )
    assert shot.first_hit == 2
    assert verdict.foul == "illegal_break"


BREAK_SPEEDS = (7.0, 8.0, 8.5, 9.0, 9.5, 10.0)


@pytest.mark.parametrize("game", ["nine", "eight"])
def test_real_breaks_are_judged_by_their_outcome(game: str) -> None:
    """Full-rack breaks at several speeds: each verdict follows from what the physics did.

    Across the speeds these breaks include a 9 (9-ball) and an 8 (8-ball) potted on the
    break and an 8-ball break scratch; the coverage is asserted, so a change of physics
    that loses one of them asks for other speeds rather than passing silently.
    """
    seen = set()
    for speed in BREAK_SPEEDS:
        verdict, after, shot = _break(game, speed)
        spread = bool(shot.potted) or shot.object_balls_to_rail >= 4
        first_ok = game == "eight" or shot.first_hit == 1
        if shot.scratch:
            seen.add("scratch")
            assert verdict.foul == "scratch" and after.ball_in_hand and after.shooter == 1
            assert after.behind_head_string == (game == "eight")
        elif not (first_ok and spread):
            assert verdict.foul == "illegal_break"
        else:
            assert verdict.legal
        if game == "nine" and 9 in shot.potted:
            seen.add("nine_down")
            assert (verdict.winner == 0) == verdict.legal
            assert after.on_table[9] == (not verdict.legal)
        if game == "eight":
            assert after.groups == (OPEN, OPEN)
            if 8 in shot.potted:
                seen.add("eight_down")
                assert verdict.respot == (8,) and verdict.winner is None and after.on_table[8]
    want = {"nine_down"} if game == "nine" else {"eight_down", "scratch"}
    assert want <= seen


# --- 8-ball -----------------------------------------------------------------------------


def test_eight_break_leaves_the_table_open() -> None:
    verdict, after, shot = _break("eight", 8.0)
    assert not shot.scratch and (shot.potted or shot.object_balls_to_rail >= 4)
    assert verdict.legal and after.groups == (OPEN, OPEN)


def test_eight_break_scratch_gives_ball_in_hand_behind_the_head_string() -> None:
    """A break aimed past the rack into the far corner: no contact and a scratch."""
    pos = break_scene(TABLE, "eight")
    balls = {k: tuple(p) for k, p in enumerate(pos)}
    balls[0] = (TABLE.length - 0.4, 0.3)
    corner = TABLE.pockets[2, :2]
    angle = math.atan2(corner[1] - 0.3, corner[0] - balls[0][0])
    verdict, after, shot = play("eight", balls, angle, 1.5, state=RackState.new_rack("eight"))
    assert shot.scratch
    assert verdict.foul == "scratch" and after.ball_in_hand and after.behind_head_string


def test_eight_on_the_break_is_respotted() -> None:
    """A 'break' that pots the 8 straight in: re-spotted, not lost."""
    balls = {**straight_in(8), 1: parked(0), 12: parked(1)}
    for b in range(2, 16):
        if b not in (8, 12):
            balls[b] = parked(b)
    state = RackState.new_rack("eight")
    verdict, after, shot = play("eight", balls, TOWARD_CORNER, 1.5, state=state)
    assert shot.potted == (8,)
    assert verdict.respot == (8,) and verdict.winner is None and after.on_table[8]


@pytest.mark.parametrize(("ball", "group"), [(3, SOLIDS), (12, STRIPES)])
def test_eight_first_legal_pot_assigns_the_group(ball: int, group: int) -> None:
    balls = {**straight_in(ball), 8: parked(0), 5: parked(1), 10: parked(2)}
    verdict, after, shot = play("eight", balls, TOWARD_CORNER, 1.5)
    assert shot.potted == (ball,)
    assert verdict.legal and verdict.shooter_continues
    assert after.groups == (group, SOLIDS + STRIPES - group)


def test_eight_open_table_eight_first_is_a_foul() -> None:
    y = TABLE.width / 2
    balls = {0: (0.8, y), 8: (1.0, y), 3: parked(0), 11: parked(1)}
    verdict, after, shot = play("eight", balls, 0.0, 1.0)
    assert shot.first_hit == 8 and 8 not in shot.potted and shot.rail_after_contact
    assert verdict.foul == "wrong_ball_first" and after.groups == (OPEN, OPEN)


def test_eight_opponents_group_first_is_a_foul() -> None:
    balls = {**straight_in(12), 3: parked(0), 8: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    verdict, after, _ = play("eight", balls, TOWARD_CORNER, 1.5, state=state)
    assert verdict.foul == "wrong_ball_first" and after.shooter == 1 and after.ball_in_hand


def test_eight_own_ball_caroms_an_opponents_ball_in_legal_but_turn_passes() -> None:
    balls = {0: diag(0.55), 3: diag(0.4), 10: diag(0.25), 8: parked(0), 11: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    verdict, after, shot = play("eight", balls, TOWARD_CORNER, 2.0, state=state)
    assert shot.first_hit == 3 and shot.potted == (10,)
    assert verdict.legal and not verdict.shooter_continues and after.shooter == 1


def test_eight_potted_early_loses() -> None:
    """Own ball first, but the 8 drops while a solid is still on the table."""
    balls = {0: diag(0.55), 3: diag(0.4), 8: diag(0.25), 5: parked(0), 11: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    verdict, after, shot = play("eight", balls, TOWARD_CORNER, 2.0, state=state)
    assert shot.first_hit == 3 and 8 in shot.potted and verdict.legal
    assert verdict.loss == "eight_early" and verdict.winner == 1 and after.winner == 1


def test_eight_in_the_called_pocket_wins() -> None:
    balls = {**straight_in(8), 11: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    assert state.ball_on == 8
    verdict, after, shot = play("eight", balls, TOWARD_CORNER, 1.5, state=state, called=0)
    assert shot.pockets == (0,)
    assert verdict.legal and verdict.winner == 0 and after.winner == 0


def test_eight_in_an_uncalled_pocket_loses() -> None:
    balls = {**straight_in(8), 11: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    verdict, _, _ = play("eight", balls, TOWARD_CORNER, 1.5, state=state, called=5)
    assert verdict.loss == "eight_wrong_pocket" and verdict.winner == 1


def test_eight_with_a_scratch_loses() -> None:
    balls = {0: diag(0.2 + 2 * R), 8: diag(0.095), 11: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    verdict, _, shot = play("eight", balls, TOWARD_CORNER, 6.0, state=state, called=0)
    assert shot.scratch and 8 in shot.potted
    assert verdict.foul == "scratch" and verdict.loss == "eight_on_foul" and verdict.winner == 1


def test_eight_clearing_the_group_puts_the_shooter_on_the_eight() -> None:
    balls = {**straight_in(7), 8: parked(0), 11: parked(1)}
    state = eight(balls, groups=(SOLIDS, STRIPES))
    verdict, after, _ = play("eight", balls, TOWARD_CORNER, 1.5, state=state)
    assert verdict.legal and verdict.shooter_continues and after.ball_on == 8


# --- ball in hand and re-spotting ---------------------------------------------------------


def _shoot_from(balls: dict[int, tuple[float, float]]) -> None:
    """The simulator accepts the layout (no overlap, nothing in a pocket, on the table)."""
    shoot(TABLE, [balls[b] for b in sorted(balls)], 0.0, 0.0)


REACH = 2 * R + CLEARANCE  # the distance free_spot keeps between centres


def _free(positions, on, target, behind: bool = False) -> np.ndarray:
    pos = np.asarray(positions, dtype=np.float64).reshape(-1, 2)
    return free_spot(TABLE, pos, np.asarray(on, dtype=bool), np.asarray(target, float), behind)


def test_ball_in_hand_onto_an_occupied_spot_moves_to_the_nearest_free_point() -> None:
    ball = np.array([1.0, 0.6])
    target = ball + [0.01, 0.0]
    got = _free([ball], [True], target)
    np.testing.assert_allclose(got, ball + [REACH, 0.0], rtol=0, atol=1e-12)
    _shoot_from({0: tuple(got), 1: tuple(ball)})


def test_ball_in_hand_between_two_balls_goes_to_their_circles_crossing() -> None:
    a, b = np.array([1.0, 0.6]), np.array([1.0 + 3 * R, 0.6])
    target = (a + b) / 2 + [0.0, 1e-4]
    got = _free([a, b], [True, True], target)
    h = math.sqrt(REACH**2 - (1.5 * R) ** 2)
    # free_spot lifts the crossing 1e-6 (relative) off both circles, so rounding cannot
    # put it inside either: the crossing's height h, times 1.000001.
    want = (a + b) / 2 + [0.0, h * 1.000001]
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-12)
    _shoot_from({0: tuple(got), 1: tuple(a), 2: tuple(b)})


def test_ball_in_hand_in_a_pocket_or_off_the_table() -> None:
    none = np.zeros((0, 2))
    corner = _free(none, [], [0.03, 0.03])
    r = TABLE.pockets[0, 2]
    # radially out of the capture circle, by the placement clearance (2 CLEARANCE)
    np.testing.assert_allclose(corner, [(r + 2 * CLEARANCE) / math.sqrt(2)] * 2, atol=1e-12)
    off = _free(none, [], [1.0, -0.5])
    np.testing.assert_allclose(off, [1.0, R])
    behind = _free(none, [], [1.5, 0.6], behind=True)
    np.testing.assert_allclose(behind, [TABLE.length / 4, 0.6])
    _shoot_from({0: tuple(corner)})


def test_ball_in_hand_is_deterministic_and_ignores_balls_off_the_table() -> None:
    ball = np.array([1.0, 0.6])
    first = _free([ball], [False], ball)
    np.testing.assert_array_equal(first, ball)
    a = _free([ball], [True], ball)
    b = _free([ball], [True], ball)
    np.testing.assert_array_equal(a, b)
    assert math.isclose(np.hypot(*(a - ball)), REACH, rel_tol=1e-12)


def test_respotted_nine_goes_behind_a_ball_on_the_foot_spot() -> None:
    spot = foot_spot(TABLE)
    got = _free([spot], [True], spot)
    np.testing.assert_allclose(got, spot + [REACH, 0.0], rtol=0, atol=1e-12)
    free = _free([spot], [False], spot)
    np.testing.assert_array_equal(free, spot)


def test_batch_and_single_outcomes_agree() -> None:
    """The batched training path gives the rules the same outcome as a recorded shot."""
    pos = break_scene(TABLE, "nine")
    d = pos[1] - pos[0]
    angle = math.atan2(d[1], d[0])
    vel = np.zeros((3, 10, 2))
    speeds = (2.0, 6.0, 9.0)
    for b, speed in enumerate(speeds):
        vel[b, 0] = speed * math.cos(angle), speed * math.sin(angle)
    batch = simulate_batch(TABLE, np.stack([pos] * 3), vel)
    for b, speed in enumerate(speeds):
        assert batch_outcome(batch, b) == outcome_of(shoot(TABLE, pos, angle, speed))


def test_judge_refuses_a_decided_rack_and_an_impossible_pot() -> None:
    state = replace(RackState.new_rack("nine"), winner=1)
    shot = ShotOutcome(1, (), (), False, True, 0)
    with pytest.raises(ValueError, match="rack is over"):
        judge(state, shot)
    with pytest.raises(ValueError, match="on_table"):
        RackState(game="eight", on_table=(True,) * 10)
    with pytest.raises(ValueError, match="player 0 or 1"):
        RackState(game="nine", on_table=(True,) * 10, shooter=2)
    gone = replace(RackState.new_rack("nine"), on_table=(True,) * 3 + (False,) * 7)
    with pytest.raises(ValueError, match="not on the table"):
        judge(gone, ShotOutcome(1, (5,), (0,), False, True, 1))
