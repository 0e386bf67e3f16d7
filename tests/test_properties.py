"""Property tests over random scenes and shots (hypothesis): G, P, E, T and D everywhere."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env import Table, simulate
from pool_env.sim.layouts import break_scene
from pool_env.testing.invariants import check_shot
from pool_env.testing.scenes_random import random_layout
from tests.profiles import examples

tables = st.builds(
    Table,
    e_ball=st.sampled_from([1.0, 0.95, 0.6, 0.2, 0.0]),
    e_cushion=st.sampled_from([1.0, 0.85, 0.5, 0.0]),
    pockets=st.sampled_from(["standard", "none"]),
)
speeds = st.one_of(st.floats(0.05, 15.0), st.floats(1e-6, 0.05), st.sampled_from([1e-6, 15.0]))
angles = st.floats(-math.pi, math.pi)


@settings(max_examples=examples(400))
@given(
    table=tables,
    n=st.integers(1, 10),
    seed=st.integers(0, 2**32 - 1),
    gap=st.sampled_from([0.0, 1e-3, 0.05]),
    speed=speeds,
    angle=angles,
)
def test_random_shot_invariants(table, n, seed, gap, speed, angle) -> None:
    rng = np.random.default_rng(seed)
    positions = random_layout(table, n, rng, min_gap=gap)
    velocities = np.zeros_like(positions)
    velocities[0] = speed * np.array([math.cos(angle), math.sin(angle)])
    result = simulate(table, positions, velocities)
    assert check_shot(table, result, samples=300) == []
    again = simulate(table, positions, velocities)
    np.testing.assert_array_equal(result.positions, again.positions)
    np.testing.assert_array_equal(result.event_times, again.event_times)
    # Every ball ends at rest on the table or in a pocket, never both.
    on_table = result.pocketed < 0
    assert np.all(on_table == ~result.pocketed_at(result.duration))


@settings(max_examples=examples(100))
@given(
    table=tables,
    rack=st.sampled_from(["nine", "eight"]),
    speed=st.floats(0.5, 15.0),
    angle=st.floats(-0.05, 0.05),
    masses_seed=st.one_of(st.none(), st.integers(0, 1000)),
)
def test_random_breaks(table, rack, speed, angle, masses_seed) -> None:
    positions = break_scene(table, rack)
    velocities = np.zeros_like(positions)
    velocities[0] = speed * np.array([math.cos(angle), math.sin(angle)])
    masses = None
    if masses_seed is not None:
        masses = np.random.default_rng(masses_seed).uniform(0.12, 0.25, len(positions))
    result = simulate(table, positions, velocities, masses)
    assert check_shot(table, result, masses, samples=300) == []


@settings(max_examples=examples(200))
@given(table=tables, n=st.integers(2, 8), seed=st.integers(0, 2**32 - 1))
def test_all_balls_moving(table, n, seed) -> None:
    """Several balls moving at once, some touching: the quartic path and the contact rule."""
    rng = np.random.default_rng(seed)
    positions = random_layout(table, n, rng, min_gap=float(rng.choice([0.0, 0.01])))
    velocities = rng.normal(0, 1.5, size=positions.shape)
    result = simulate(table, positions, velocities)
    assert check_shot(table, result, samples=300) == []
