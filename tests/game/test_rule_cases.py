"""Rule cases on hand-built shot outcomes: each row is one WPA rule, checked without physics.

They pin the plain-Python reference (``tests/wpa_reference.py``) that the compiled rules
are compared with in ``tests/game/test_wpa.py`` and ``tests/game/test_games.py``: an oracle must be
right on its own. The table builds the :class:`ShotOutcome` directly, so a case can isolate
one rule exactly at its edge (three object balls to a rail against four, the second foul
against the third, two balls of different groups dropping in a known order). Every expected
value is the WPA rule as the reference's module docstring states it.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from pool_env import Table
from tests.wpa_reference import (
    OPEN,
    SOLIDS,
    STRIPES,
    RackState,
    ShotOutcome,
    judge,
    run_out_ends,
)

TABLE = Table(pockets="circles")
R = TABLE.ball_radius


def shot(
    first: int = 1,
    potted: tuple[int, ...] = (),
    pockets: tuple[int, ...] | None = None,
    scratch: bool = False,
    rail: bool = True,
    to_rail: int = 0,
    simultaneous: tuple[int, ...] = (),
    kitchen: tuple[int, ...] = (),
    crossed: bool = False,
) -> ShotOutcome:
    """An outcome by hand (every potted ball into pocket 0 unless told)."""
    where = (0,) * len(potted) if pockets is None else pockets
    return ShotOutcome(first, potted, where, scratch, rail, to_rail, simultaneous, kitchen,
                       crossed)  # fmt: skip


def nine(off: tuple[int, ...] = (), **kw) -> RackState:
    """A 9-ball rack in play, the balls ``off`` already potted."""
    on = tuple(b not in off for b in range(10))
    return replace(RackState(game="nine", on_table=on, breaking=False), **kw)


def eight(off: tuple[int, ...] = (), **kw) -> RackState:
    """An 8-ball rack in play, the balls ``off`` already potted."""
    on = tuple(b not in off for b in range(16))
    return replace(RackState(game="eight", on_table=on, breaking=False), **kw)


def ten(off: tuple[int, ...] = (), **kw) -> RackState:
    """A 10-ball rack in play, the balls ``off`` already potted."""
    on = tuple(b not in off for b in range(11))
    return replace(RackState(game="ten", on_table=on, breaking=False), **kw)


ROTATION_GAMES = {"nine": nine, "ten": ten}


# --- the break ------------------------------------------------------------------------------


@pytest.mark.parametrize("game", ["nine", "eight"])
@pytest.mark.parametrize(("to_rail", "legal"), [(3, False), (4, True), (5, True)])
def test_a_break_without_a_pot_needs_four_object_balls_to_a_rail(
    game: str, to_rail: int, legal: bool
) -> None:
    verdict, after = judge(RackState.new_rack(game), shot(first=1, to_rail=to_rail))
    assert verdict.legal == legal
    assert verdict.foul == (None if legal else "illegal_break")
    assert after.ball_in_hand == (not legal) and after.shooter == 1
    assert not after.breaking


def test_a_nine_ball_break_must_hit_the_one_first() -> None:
    verdict, _ = judge(RackState.new_rack("nine"), shot(first=2, potted=(3,), to_rail=6))
    assert verdict.foul == "illegal_break"
    verdict, after = judge(RackState.new_rack("nine"), shot(first=1, potted=(3,), to_rail=6))
    assert verdict.legal and verdict.shooter_continues and after.shooter == 0


@pytest.mark.parametrize("game", ["nine", "ten"])
def test_a_rotation_break_set_up_without_the_one_needs_its_lowest_ball_first(game: str) -> None:
    # Found by 120,000 random outcomes: the legal first ball of a break and the shooter's
    # benefit of a simultaneous hit read the same ball, the lowest on the table.
    state = replace(ROTATION_GAMES[game](off=(1, 2)), breaking=True)
    verdict, _ = judge(state, shot(first=3, to_rail=4))
    assert verdict.legal
    verdict, _ = judge(state, shot(first=4, to_rail=4, simultaneous=(3,)))
    assert verdict.legal  # the 3, met at the same instant, gives the benefit
    verdict, _ = judge(state, shot(first=4, to_rail=4))
    assert verdict.foul == "illegal_break"


def test_groups_stay_open_after_an_eight_ball_break_that_pots() -> None:
    verdict, after = judge(RackState.new_rack("eight"), shot(first=1, potted=(3,), to_rail=4))
    assert verdict.legal and verdict.shooter_continues
    assert after.groups == (OPEN, OPEN) and not after.on_table[3]


@pytest.mark.parametrize(("potted", "to_rail"), [((8,), 0), ((8, 3), 4), ((8, 12), 0)])
def test_the_eight_on_a_legal_break_is_respotted_and_the_breaker_continues(
    potted: tuple[int, ...], to_rail: int
) -> None:
    # WPA 8-ball 3.3(e): the breaker may have the 8 re-spotted and continue; the rules
    # always take that choice. The 8 alone counts as the break's pot.
    verdict, after = judge(RackState.new_rack("eight"), shot(first=1, potted=potted,
                                                             to_rail=to_rail))  # fmt: skip
    assert verdict.legal and verdict.respot == (8,) and verdict.winner is None
    assert verdict.shooter_continues and after.shooter == 0 and not after.ball_in_hand
    assert after.on_table[8] and after.groups == (OPEN, OPEN)


def test_the_eight_on_a_break_scratch_is_respotted_and_the_turn_passes() -> None:
    verdict, after = judge(RackState.new_rack("eight"), shot(first=1, potted=(8,),
                                                             scratch=True))  # fmt: skip
    assert verdict.foul == "scratch" and verdict.respot == (8,) and verdict.winner is None
    assert not verdict.shooter_continues and after.shooter == 1
    assert after.ball_in_hand and after.behind_head_string and after.on_table[8]


@pytest.mark.parametrize(("breaking", "behind"), [(True, True), (False, False)])
def test_behind_the_head_string_only_after_an_eight_ball_break_scratch(
    breaking: bool, behind: bool
) -> None:
    state = replace(eight(), breaking=breaking)
    verdict, after = judge(state, shot(first=3, scratch=True, to_rail=5))
    assert verdict.foul == "scratch"
    assert after.ball_in_hand and after.behind_head_string == behind and after.shooter == 1


# --- fouls and the turn ---------------------------------------------------------------------


def test_a_pot_needs_no_rail() -> None:
    verdict, after = judge(nine(), shot(first=1, potted=(1,), rail=False))
    assert verdict.legal and verdict.shooter_continues and after.ball_on == 2


def test_no_pot_and_no_rail_is_a_foul() -> None:
    verdict, after = judge(nine(), shot(first=1, rail=False))
    assert verdict.foul == "no_rail" and after.ball_in_hand and after.shooter == 1


@pytest.mark.parametrize(
    ("first", "foul"), [(1, None), (2, "wrong_ball_first"), (9, "wrong_ball_first")]
)
def test_nine_ball_the_lowest_ball_first(first: int, foul: str | None) -> None:
    verdict, _ = judge(nine(), shot(first=first))
    assert verdict.foul == foul and verdict.ball_on == 1


def test_potting_on_a_foul_passes_the_turn_with_ball_in_hand() -> None:
    verdict, after = judge(nine(), shot(first=2, potted=(2,)))
    assert verdict.foul == "wrong_ball_first" and not verdict.shooter_continues
    assert after.shooter == 1 and after.ball_in_hand and not after.on_table[2]


def test_a_legal_miss_passes_the_turn_without_ball_in_hand() -> None:
    verdict, after = judge(nine(), shot(first=1))
    assert verdict.legal and not verdict.shooter_continues
    assert after.shooter == 1 and not after.ball_in_hand


@pytest.mark.parametrize(("before", "loses"), [(0, False), (1, False), (2, True)])
def test_the_third_successive_foul_loses(before: int, loses: bool) -> None:
    verdict, after = judge(nine(fouls=(before, 0)), shot(first=2))
    assert verdict.foul == "wrong_ball_first"
    assert (verdict.loss == "three_fouls") == loses
    assert after.winner == (1 if loses else None)
    assert after.fouls == (before + 1, 0)


def test_a_legal_shot_resets_the_shooters_foul_count() -> None:
    _, after = judge(nine(fouls=(2, 1)), shot(first=1))
    assert after.fouls == (0, 1)


def test_the_nine_on_a_legal_shot_wins_and_stays_down() -> None:
    verdict, after = judge(nine(), shot(first=1, potted=(9,)))
    assert verdict.winner == 0 and verdict.respot == () and after.winner == 0
    assert not after.on_table[9]


def test_the_nine_on_a_foul_is_respotted() -> None:
    verdict, after = judge(nine(), shot(first=3, potted=(9,)))
    assert verdict.foul == "wrong_ball_first" and verdict.respot == (9,)
    assert verdict.winner is None and after.on_table[9]


# --- 8-ball groups and the 8 ----------------------------------------------------------------


def test_an_open_table_takes_the_group_of_the_first_ball_dropped() -> None:
    state = eight()
    verdict, after = judge(state, shot(first=12, potted=(12, 3)))
    assert verdict.legal and after.groups == (STRIPES, SOLIDS)
    _, after = judge(state, shot(first=3, potted=(3, 12)))
    assert after.groups == (SOLIDS, STRIPES)


def test_the_eight_is_no_legal_first_ball_on_an_open_table() -> None:
    state = eight()
    assert 8 not in state.legal_first_balls()
    assert set(state.legal_first_balls()) == set(range(1, 16)) - {8}
    verdict, _ = judge(state, shot(first=8))
    assert verdict.foul == "wrong_ball_first"


def test_potting_only_an_opponents_ball_passes_the_turn() -> None:
    verdict, after = judge(eight(groups=(SOLIDS, STRIPES)), shot(first=3, potted=(10,)))
    assert verdict.legal and not verdict.shooter_continues and after.shooter == 1


@pytest.mark.parametrize(("group", "members"), [(SOLIDS, range(1, 8)), (STRIPES, range(9, 16))])
def test_on_the_eight_only_once_the_whole_group_is_down(group: int, members: range) -> None:
    groups = (group, SOLIDS + STRIPES - group)
    for k in range(len(members)):
        state = eight(off=tuple(members[: k + 1]), groups=groups)
        cleared = k + 1 == len(members)
        assert state.ball_on == (8 if cleared else None)
        expected = (8,) if cleared else tuple(members[k + 1 :])
        assert state.legal_first_balls() == expected


def test_the_eight_in_the_called_pocket_wins_and_elsewhere_or_uncalled_loses() -> None:
    state = eight(off=tuple(range(1, 8)), groups=(SOLIDS, STRIPES))
    pot = shot(first=8, potted=(8,), pockets=(3,))
    verdict, _ = judge(state, pot, called_pocket=3)
    assert verdict.winner == 0 and verdict.loss is None
    for called in (None, 2):
        verdict, after = judge(state, pot, called_pocket=called)
        assert verdict.loss == "eight_wrong_pocket" and after.winner == 1


@pytest.mark.parametrize("scratch", [False, True])
def test_the_eight_on_any_foul_loses(scratch: bool) -> None:
    state = eight(off=tuple(range(1, 8)), groups=(SOLIDS, STRIPES))
    # A wrong ball first (a stripe) with the 8 dropping, with or without the cue ball.
    verdict, after = judge(state, shot(first=11, potted=(8,), scratch=scratch), called_pocket=0)
    assert verdict.foul == ("scratch" if scratch else "wrong_ball_first")
    assert verdict.loss == "eight_on_foul" and after.winner == 1


# --- the first contact: simultaneous hits and the kitchen -----------------------------------


@pytest.mark.parametrize(
    ("groups", "first", "simultaneous", "foul"),
    [
        ((SOLIDS, STRIPES), 3, (11,), None),
        ((SOLIDS, STRIPES), 11, (3,), None),  # the order of the simulator does not matter
        ((STRIPES, SOLIDS), 3, (11,), None),
        ((STRIPES, SOLIDS), 11, (3,), None),
        ((STRIPES, SOLIDS), 3, (8,), "wrong_ball_first"),  # neither may be hit first
        ((STRIPES, SOLIDS), 3, (), "wrong_ball_first"),
    ],
)
def test_a_simultaneous_first_contact_gives_the_shooter_the_benefit(
    groups: tuple[int, int], first: int, simultaneous: tuple[int, ...], foul: str | None
) -> None:
    verdict, _ = judge(eight(groups=groups), shot(first=first, simultaneous=simultaneous))
    assert verdict.foul == foul


def test_a_simultaneous_contact_on_a_nine_ball_break_with_the_one_is_legal() -> None:
    verdict, _ = judge(RackState.new_rack("nine"), shot(first=2, simultaneous=(1,), to_rail=4))
    assert verdict.legal


@pytest.mark.parametrize(
    ("behind", "kitchen", "crossed", "foul"),
    [
        (True, (3,), False, "kitchen_ball_first"),
        (True, (3,), True, None),  # it crossed the head string first
        (True, (), False, None),  # the 3 lies on or past the head string
        (False, (3,), False, None),  # ball in hand anywhere: no kitchen rule
    ],
)
def test_the_kitchen_rule(
    behind: bool, kitchen: tuple[int, ...], crossed: bool, foul: str | None
) -> None:
    state = eight(ball_in_hand=True, behind_head_string=behind)
    verdict, after = judge(state, shot(first=3, kitchen=kitchen, crossed=crossed))
    assert verdict.foul == foul
    if foul:
        assert after.shooter == 1 and after.ball_in_hand and not after.behind_head_string


def test_the_kitchen_rule_comes_after_a_scratch_and_before_the_break_check() -> None:
    state = replace(RackState.new_rack("eight"), ball_in_hand=True, behind_head_string=True)
    verdict, _ = judge(state, shot(first=3, kitchen=(3,), scratch=True))
    assert verdict.foul == "scratch"
    verdict, _ = judge(state, shot(first=3, kitchen=(3,), to_rail=0))
    assert verdict.foul == "kitchen_ball_first"


# --- the outcome the rules read ------------------------------------------------------------


def test_the_outcome_lists_potted_balls_in_the_order_they_dropped() -> None:
    # Rows: cue, 1, 2, 3; the 3 dropped first (into pocket 5), then the 1 (into pocket 2).
    out = ShotOutcome.from_arrays(
        first_hit=[3, 0, -1, 0],
        cushions_after_contact=[0, 0, 0, 0],
        pocketed=[-1, 2, -1, 5],
        pocket_order=[-1, 1, -1, 0],
    )
    assert out.potted == (3, 1) and out.pockets == (5, 2) and out.first_hit == 3


def test_the_cue_ball_is_not_an_object_ball_driven_to_a_rail() -> None:
    out = ShotOutcome.from_arrays(
        first_hit=[1, 0, -1, -1, -1],
        cushions_after_contact=[2, 1, 0, 1, 1],
        pocketed=[-1] * 5,
        pocket_order=[-1] * 5,
    )
    assert out.object_balls_to_rail == 3 and out.rail_after_contact
    verdict, _ = judge(RackState.new_rack("nine"), out)
    assert verdict.foul == "illegal_break"  # three object balls, not four


# --- the push-out and the option (WPA 9-ball 1.7, 10-ball 4) ---------------------------------


@pytest.mark.parametrize(("game", "offered"), [("nine", True), ("ten", True), ("eight", False)])
def test_a_legal_break_offers_the_push_out_in_the_rotation_games(game: str, offered: bool) -> None:
    _, after = judge(RackState.new_rack(game), shot(first=1, potted=(2,), to_rail=4))
    assert after.push_out == offered and after.shooter == 0  # the breaker may push out
    _, after = judge(RackState.new_rack(game), shot(first=1, to_rail=3))  # illegal break
    assert not after.push_out and after.ball_in_hand and after.shooter == 1


def test_nine_ball_without_the_push_out_offers_none_after_a_legal_break() -> None:
    """``push_out=False`` (9-ball as ``NineBallGame-v1``): the breaker simply shoots on."""
    state = replace(RackState.new_rack("nine"), offers_push_out=False)
    _, after = judge(state, shot(first=1, potted=(2,), to_rail=4))
    assert not after.push_out and not after.option and after.shooter == 0
    verdict, after = judge(after, shot(first=1, rail=False), push_out=True)  # no push-out
    assert verdict.foul == "no_rail" and not verdict.push_out and after.shooter == 1


@pytest.mark.parametrize("game", ["nine", "ten"])
@pytest.mark.parametrize(
    "outcome",
    [shot(first=-1, rail=False), shot(first=5, rail=False), shot(first=3, to_rail=1)],
    ids=["no-contact", "wrong-ball-no-rail", "wrong-ball"],
)
def test_a_push_out_fouls_only_by_a_scratch_and_gives_the_opponent_the_option(
    game: str, outcome: ShotOutcome
) -> None:
    state = ROTATION_GAMES[game](push_out=True, fouls=(2, 0))
    verdict, after = judge(state, outcome, push_out=True)
    assert verdict.legal and verdict.push_out and not verdict.shooter_continues
    assert after.shooter == 1 and after.option and not after.push_out
    assert after.fouls == (0, 0) and not after.ball_in_hand  # a legal shot: the count resets
    # Declared where no push-out is offered, the same shot is a foul.
    verdict, _ = judge(replace(state, push_out=False), outcome, push_out=True)
    assert not verdict.legal and not verdict.push_out


@pytest.mark.parametrize("game", ["nine", "ten"])
def test_a_push_out_scratch_is_a_foul_with_ball_in_hand_and_no_option(game: str) -> None:
    state = ROTATION_GAMES[game](push_out=True, fouls=(2, 0))
    verdict, after = judge(state, shot(first=-1, scratch=True), push_out=True)
    assert verdict.foul == "scratch" and verdict.loss == "three_fouls" and verdict.winner == 1
    verdict, after = judge(replace(state, fouls=(0, 0)), shot(first=-1, scratch=True),
                           push_out=True)  # fmt: skip
    assert verdict.foul == "scratch" and after.ball_in_hand and not after.option


@pytest.mark.parametrize(("game", "money"), [("nine", 9), ("ten", 10)])
def test_the_money_ball_potted_on_a_push_out_is_spotted_and_the_rest_stay_down(
    game: str, money: int
) -> None:
    state = ROTATION_GAMES[game](push_out=True)
    verdict, after = judge(state, shot(first=1, potted=(4, money)), push_out=True)
    assert verdict.winner is None and verdict.respot == (money,)
    assert not verdict.shooter_continues and after.option and after.shooter == 1
    assert after.on_table[money] and not after.on_table[4]


@pytest.mark.parametrize("game", ["nine", "ten"])
@pytest.mark.parametrize(
    ("outcome", "push_out", "ends"),
    [
        (shot(first=-1, rail=False), True, False),  # a legal push-out: one agent shoots on
        (shot(first=1, potted=(4, 9)), True, False),  # its pots count for nothing, still on
        (shot(first=-1, scratch=True), True, True),  # a push-out scratch is a foul
        (shot(first=1), False, True),  # a legal shot that pots nothing: the turn is over
        (shot(first=-1, rail=False), False, True),  # the same miss, not declared: a foul
    ],
    ids=["push-out", "push-out-pots", "push-out-scratch", "safety", "no-contact"],
)
def test_a_run_out_goes_on_after_a_legal_push_out(
    game: str, outcome: ShotOutcome, push_out: bool, ends: bool
) -> None:
    # Run-out mode (one agent, end_on_foul=True) ends at a foul or a legal shot that does
    # not keep the table; the push-out passes the turn only to an opponent, who has the
    # option: alone, the agent shoots on (docs/environments/specification.md, "One player").
    state = ROTATION_GAMES[game](push_out=True)
    called = {"called_pocket": 0, "called_ball": 1} if game == "ten" else {}
    verdict, _ = judge(state, outcome, push_out=push_out, **called)
    assert verdict.push_out == push_out
    assert run_out_ends(verdict) == ends


@pytest.mark.parametrize("game", ["nine", "ten"])
def test_the_option_hands_the_table_back_as_it_lies(game: str) -> None:
    state = ROTATION_GAMES[game](off=(1,), option=True, shooter=1)
    verdict, after = judge(state, shot(first=5, scratch=True), hand_back=True)  # no shot read
    assert verdict.handed_back and verdict.legal and verdict.foul is None
    assert after == replace(state, shooter=0, option=False)
    # Taking the table instead: the shot is played, the option lapses.
    verdict, after = judge(state, shot(first=2, potted=(2,)), called_pocket=0, called_ball=2)
    assert not verdict.handed_back and verdict.legal and after.shooter == 1
    assert not after.option and not after.push_out


# --- 10-ball: the rack of ten, called shots (WPA 10-ball rules) ------------------------------


def test_the_ten_on_the_break_is_spotted_and_the_breaker_continues() -> None:
    verdict, after = judge(RackState.new_rack("ten"), shot(first=1, potted=(10, 3)),
                           called_pocket=0, called_ball=10)  # fmt: skip
    assert verdict.legal and verdict.winner is None and verdict.respot == (10,)
    assert verdict.shooter_continues and after.on_table[10] and not after.on_table[3]


@pytest.mark.parametrize(
    ("called_ball", "called_pocket", "continues"),
    [(3, 2, True), (3, 1, False), (1, 2, False), (None, 2, False), (3, None, False)],
    ids=["made", "wrong-pocket", "other-ball", "no-ball", "no-pocket"],
)
def test_ten_ball_keeps_the_table_only_when_the_call_is_made(
    called_ball: int | None, called_pocket: int | None, continues: bool
) -> None:
    state = ten(off=(1, 2))
    verdict, after = judge(state, shot(first=3, potted=(3, 5), pockets=(2, 4)), called_pocket,
                           called_ball)  # fmt: skip
    assert verdict.legal and verdict.shooter_continues == continues
    assert not after.on_table[3] and not after.on_table[5]  # pots stay down either way
    assert after.option == (not continues) and after.shooter == (0 if continues else 1)


def test_ten_ball_a_missed_call_that_pots_nothing_gives_no_option() -> None:
    verdict, after = judge(ten(), shot(first=1), called_pocket=0, called_ball=1)
    assert verdict.legal and not verdict.shooter_continues
    assert after.shooter == 1 and not after.option and not after.ball_in_hand


def test_ten_ball_the_called_ten_on_a_combination_wins() -> None:
    verdict, _ = judge(ten(), shot(first=1, potted=(10,), pockets=(5,)), called_pocket=5,
                       called_ball=10)  # fmt: skip
    assert verdict.winner == 0 and verdict.respot == ()


@pytest.mark.parametrize(
    ("called_ball", "called_pocket", "continues"),
    [(1, 0, True), (1, 3, False), (10, 3, False)],
    ids=["beside-a-made-call", "call-missed", "ten-called-wrong-pocket"],
)
def test_ten_ball_an_uncalled_ten_is_spotted(
    called_ball: int, called_pocket: int, continues: bool
) -> None:
    verdict, after = judge(ten(), shot(first=1, potted=(1, 10), pockets=(0, 0)), called_pocket,
                           called_ball)  # fmt: skip
    assert verdict.winner is None and verdict.respot == (10,) and after.on_table[10]
    assert verdict.shooter_continues == continues and after.option == (not continues)


def test_ten_ball_fouls_are_nine_balls_and_pots_on_a_foul_give_no_option() -> None:
    verdict, after = judge(ten(), shot(first=2, potted=(2, 10)), called_pocket=0, called_ball=2)
    assert verdict.foul == "wrong_ball_first" and verdict.respot == (10,)
    assert after.ball_in_hand and not after.option and not after.on_table[2]
    verdict, _ = judge(ten(fouls=(2, 0)), shot(first=1, rail=False), 0, 1)
    assert verdict.foul == "no_rail" and verdict.winner == 1 and verdict.loss == "three_fouls"
