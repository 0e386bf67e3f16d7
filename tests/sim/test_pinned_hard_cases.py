"""Hard cases that were checked by invariants only, now pinned by the reference or a closed form.

Invariants (no overlap, momentum, energy) cannot see a wrong restitution: balls that pass
through, re-collide at once and stick conserve momentum, lose energy and never overlap.
So each case here also has its exact outcome: the 50-digit reference (pool_env/testing/reference/)
where it resolves the scene, else a closed form of the documented rules.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from pool_env import Table, simulate
from pool_env.testing.reference import ReferenceSimulationError, reference_simulate
from pool_env.testing.scenes_random import random_layout
from tests.profiles import examples

R = Table().ball_radius


def _assert_matches_reference(table: Table, positions, velocities, atol: float) -> None:
    ours = simulate(table, positions, velocities)
    ref = reference_simulate(table, positions, velocities, max_events=400)
    assert [(e.kind, e.i, e.j) for e in ours.events] == [(k, i, j) for _, k, i, j in ref.events]
    assert ours.pocketed.tolist() == ref.pocketed
    with mp.workdps(50):
        for (x, y), (rx, ry) in zip(ours.positions, ref.positions, strict=True):
            assert abs(mp.mpf(float(x)) - rx) < atol
            assert abs(mp.mpf(float(y)) - ry) < atol


@pytest.mark.parametrize("e_cushion", [0.85, 0.3])
@pytest.mark.parametrize("e_ball", [0.95, 0.5])
def test_ball_wedged_between_ball_and_rail_matches_the_reference(e_ball, e_cushion) -> None:
    """The pusher drives the wedged ball into the rail; they bounce apart (6 events)."""
    table = Table(e_ball=e_ball, e_cushion=e_cushion, pockets="none")
    _assert_matches_reference(table, [[R, 0.6], [3 * R, 0.6]], [[0, 0], [-0.8, 0.05]], 1e-12)


@pytest.mark.parametrize("e_ball", [0.95, 0.5, 0.0])
def test_ball_wedged_against_a_dead_rail_leaves_as_a_lump_along_it(e_ball: float) -> None:
    """e_cushion = 0: the rail takes every x impulse, the balls share the y momentum.

    The impacts are along x (both centres on y = 0.6), so the pair's y momentum,
    ``m * 0.05``, is conserved; the Zeno rule ends the cascade with the pair stuck against
    the rail, so each ball rolls along it at 0.025 m/s: ``0.025^2 / 2a`` further in y.
    """
    table = Table(e_ball=e_ball, e_cushion=0.0, pockets="none")
    result = simulate(table, [[R, 0.6], [3 * R, 0.6]], [[0, 0], [-0.8, 0.05]])
    y = 0.6 + 0.025**2 / (2 * table.deceleration)
    np.testing.assert_allclose(result.positions, [[R, y], [3 * R, y]], rtol=0, atol=1e-12)
    assert not result.hit_event_cap


@settings(max_examples=examples(30))
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(2, 3),
    gap=st.sampled_from([0.0, 1e-3]),
    e_ball=st.sampled_from([1.0, 0.95, 0.6]),
    speed=st.floats(0.1, 1.5),
)
def test_random_touching_scenes_match_the_reference(seed, n, gap, e_ball, speed) -> None:
    """Property scenes with touching balls, compared with the reference where it resolves them."""
    table = Table(e_ball=e_ball, pockets="none")
    rng = np.random.default_rng(seed)
    positions = random_layout(table, n, rng, min_gap=gap)
    target = positions[1] - positions[0]
    angle = math.atan2(target[1], target[0]) + rng.normal(0, 0.3)
    velocities = np.zeros_like(positions)
    velocities[0] = speed * np.array([math.cos(angle), math.sin(angle)])
    ours = simulate(table, positions, velocities)
    assume(ours.n_events <= 10)  # short scenes: well conditioned at 1e-9 m
    try:
        ref = reference_simulate(table, positions, velocities, max_events=60)
    except ReferenceSimulationError:
        assume(False)  # a sustained contact the reference cannot express
    assert [(e.kind, e.i, e.j) for e in ours.events] == [(k, i, j) for _, k, i, j in ref.events]
    with mp.workdps(50):
        for (x, y), (rx, ry) in zip(ours.positions, ref.positions, strict=True):
            assert abs(mp.mpf(float(x)) - rx) < 1e-9
            assert abs(mp.mpf(float(y)) - ry) < 1e-9


def test_a_slow_curving_approach_is_bracketed_right() -> None:
    """Both balls slow and on different headings: the relative path curves (quartic gap).

    Found by a search over slow two-ball scenes for one where a wrongly placed inflection
    point of the gap (the roots of D'') hides the contact from the bracketing; the
    reference has the impact, then both stops.
    """
    table = Table(e_ball=0.95, pockets="none")
    positions = [[1.0, 0.6], [1.0519219053091213, 0.6369854060750171]]
    velocities = [
        [0.1272905709221757, 0.054336801083148395],
        [0.019041959817394614, 0.10879259152830122],
    ]
    _assert_matches_reference(table, positions, velocities, 1e-12)
