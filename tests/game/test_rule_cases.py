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
from tests.wpa_reference import OPEN, SOLIDS, STRIPES, RackState, ShotOutcome, judge

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
