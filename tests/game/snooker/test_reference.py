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

from tests.game.snooker.harness import compare, random_case
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
