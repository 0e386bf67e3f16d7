"""Property tests of the spin level over random scenes (hypothesis): G, E, T, D.

Random tables (every pocket model, ball-ball friction modes, restitutions), random layouts,
a random strike (speed, aim, tip, elevation) or random velocities and spins for every ball.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env import Table, shoot, simulate
from pool_env.testing.invariants import check_geometry, check_spin_energy, check_termination
from pool_env.testing.scenes_random import random_layout
from tests.profiles import examples

tables = st.builds(
    Table,
    model=st.just("spin"),
    pockets=st.sampled_from(["jaws", "circles", "none"]),
    e_ball=st.sampled_from([1.0, 0.95, 0.5]),
    e_cushion=st.sampled_from([1.0, 0.65, 0.2]),
    ball_friction=st.sampled_from(["alciatore", 0.0, 0.2]),
)


@settings(max_examples=examples(60))
@given(
    table=tables,
    n=st.integers(1, 8),
    seed=st.integers(0, 2**32 - 1),
    gap=st.sampled_from([0.0, 1e-3, 0.05]),
    speed=st.floats(0.01, 9.0),
    angle=st.floats(-math.pi, math.pi),
    tip=st.tuples(st.floats(-0.6, 0.6), st.floats(-0.6, 0.6)),
    elevation=st.floats(0.0, 0.5),
)
def test_random_strike(table, n, seed, gap, speed, angle, tip, elevation) -> None:
    positions = random_layout(table, n, np.random.default_rng(seed), min_gap=gap)
    result = shoot(table, positions, angle, speed, tip=tip, elevation=elevation)
    assert check_termination(result) == []
    assert check_geometry(table, result, samples=300) == []
    assert check_spin_energy(table, result) == []
    again = shoot(table, positions, angle, speed, tip=tip, elevation=elevation)
    np.testing.assert_array_equal(result.positions, again.positions)
    np.testing.assert_array_equal(result.event_times, again.event_times)
    assert np.all((result.motion_states == 4) == (result.pocketed >= 0))
    assert np.all(result.motion_states[result.pocketed < 0] == 0)


@settings(max_examples=examples(40))
@given(table=tables, n=st.integers(2, 6), seed=st.integers(0, 2**32 - 1))
def test_random_velocities_and_spins(table, n, seed) -> None:
    rng = np.random.default_rng(seed)
    positions = random_layout(table, n, rng, min_gap=0.0)
    velocities = rng.normal(0.0, 1.5, (n, 2))
    spins = rng.normal(0.0, 40.0, (n, 3))
    result = simulate(table, positions, velocities, angular_velocities=spins)
    assert check_termination(result) == []
    assert check_geometry(table, result, samples=300) == []
    assert check_spin_energy(table, result) == []
