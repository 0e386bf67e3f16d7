"""Snooker's compiled rules equal the plain-Python reference on random outcomes.

Each case is a stroke's outcome drawn by :func:`tests.game.snooker.harness.random_case`
(a frame state, where the balls stopped, the first ball hit, the balls potted, the
nomination, the balls touched), biased towards the rules' corners: covered spots, the
last black, free balls, touching balls. The compiled judge
(:func:`pool_env.game.games.snooker.rules.judge_stroke`) and the reference
(:mod:`pool_env.testing.reference.snooker_rules`, written from the WPBSA text, sharing
no code) must give the same verdict, frame state and ball positions.
``python -m tests.game.snooker.sweep 100000`` runs the 100,000-outcome sweep.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env.game.games.snooker import rack_state as sk
from pool_env.game.games.snooker.rules import R_TIE
from tests.game.snooker.harness import Case, compare, compiled, random_case, referenced, spec
from tests.profiles import examples


@settings(max_examples=examples(300))
@given(st.integers(0, 2**32 - 1))
def test_random_outcomes_match_reference(seed: int) -> None:
    case = random_case(np.random.default_rng(seed))
    assert compare(case) == []


def test_seeded_sweep_matches_reference() -> None:
    rng = np.random.default_rng(45)
    failures = [(k, d) for k in range(2000) if (d := compare(random_case(rng)))]
    assert failures == []


def test_a_tie_respots_the_black_on_its_own_spot_though_it_lay_on_it() -> None:
    """A level frame re-spots the black on its own spot even when it lay over it.

    The 100,000-outcome sweep's find: a foul on the last black levels the scores while the
    black lies over its own spot; picked up to be re-spotted, it does not cover that spot
    itself (the reference had put it on the pink's).
    """
    row = np.array([1, 3, 10, 2, 0, 0, 33, 0, -1], dtype=np.int64)  # player 1 on the black
    on = np.zeros(22, dtype=bool)
    on[[0, 21]] = True
    after = np.zeros((22, 2))
    after[0], after[21] = (0.758, 0.596), (3.2531, 0.9141)  # 26 mm off the black spot
    case = Case(row, on, after, np.zeros(22, dtype=bool), -1, 0, np.zeros(22, dtype=bool))
    res, row_after, on_after, pos = compiled(case)
    assert on_after[21] and on_after[0]
    assert res[R_TIE] == 1 and row_after[sk.RESPOTTED] == 1  # 10 + 7 on the foul: 10 each
    assert np.allclose(pos[21], spec().spot(21))
    assert compare(case) == []


def test_a_tie_respots_the_black_on_its_own_spot_though_the_cue_ball_lay_on_it() -> None:
    """S3 R4(b): the cue ball goes in hand (off the table) before the black is re-spotted.

    A foul that levels the frame leaves the cue ball resting on the black spot; in hand it
    covers nothing, so the black goes to its own spot (both judges had sent it elsewhere).
    """
    row = np.array([0, 24, 17, 2, 0, 0, 0, 0, -1], dtype=np.int64)  # player 0 on the black
    on = np.zeros(22, dtype=bool)
    on[[0, 21]] = True
    after = np.zeros((22, 2))
    after[0], after[21] = spec().spot(21), (1.0, 0.5)  # the cue ball on the black spot
    case = Case(row, on, after, np.zeros(22, dtype=bool), -1, 0, np.zeros(22, dtype=bool))
    res, row_after, on_after, pos = compiled(case)
    assert res[R_TIE] == 1 and row_after[sk.IN_HAND] == 1  # 17 + 7 on the miss: 24 each
    assert on_after[21] and np.allclose(pos[21], spec().spot(21))
    assert on_after[0] and np.hypot(*(pos[0] - pos[21])) > 1.0  # in the D
    _, balls, verdict = referenced(case)
    assert verdict.tie and np.allclose(balls[21], spec().spot(21))
    assert compare(case) == []
