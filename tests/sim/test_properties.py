"""Property tests over random scenes and shots (hypothesis): G, P, E, T and D everywhere.

The CI sample of ``tools/fuzz.py``, including what issue 11 found: masses spread over
ratios up to 1e6, lumps of light balls driven into a rail, and scales at the numeric limits.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from pool_env import Table, shoot, simulate
from pool_env.sim.inputs import max_speed
from pool_env.sim.kernels import limits
from pool_env.sim.layouts import break_scene
from pool_env.testing.invariants import check_shot, check_termination
from pool_env.testing.scenes_random import (
    log_uniform_masses,
    lump_at_rail,
    random_layout,
    within_limits,
)
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


def _damped(table: Table) -> bool:
    return table.mu_roll >= 1e-3 and table.e_ball < 1.0 and table.e_cushion < 1.0


def _check_unequal(table: Table, result, masses) -> None:
    """G, P, E and D; T wherever the table is damped (an elastic one may rattle on)."""
    problems = check_shot(table, result, masses, samples=300)
    if not _damped(table):
        problems = [p for p in problems if p not in check_termination(result)]
    assert problems == []


damped_or_elastic = st.builds(
    Table,
    e_ball=st.sampled_from([1.0, 0.95, 0.5, 0.0]),
    e_cushion=st.sampled_from([1.0, 0.85, 0.5, 0.0]),
    mu_roll=st.sampled_from([0.01, 1e-3]),
    pockets=st.just("none"),
)


@settings(max_examples=examples(150), deadline=None)
@given(
    table=damped_or_elastic,
    n_pressed=st.integers(1, 3),
    log_ratio=st.floats(0.0, 6.0),
    gap=st.sampled_from([0.0, 1e-6, 0.01, 0.3]),
    speed=st.floats(0.05, 5.0),
    seed=st.integers(0, 2**32 - 1),
)
def test_lumps_driven_into_rails(table, n_pressed, log_ratio, gap, speed, seed) -> None:
    """A heavy ball drives a chain of light ones into a rail: G, P, E; T if damped."""
    rng = np.random.default_rng(seed)
    positions, velocities = lump_at_rail(table, rng, n_pressed, gap, speed)
    ratio = 10.0**log_ratio
    masses = np.full(len(positions), table.ball_mass / math.sqrt(ratio))
    masses[0] = table.ball_mass * math.sqrt(ratio)
    # Kept where no impact can drive a light ball past the speed limits (sim.inputs)
    velocities = within_limits(table, velocities, masses)
    result = simulate(table, positions, velocities, masses)
    _check_unequal(table, result, masses)


@settings(max_examples=examples(150), deadline=None)
@given(
    table=damped_or_elastic,
    n=st.integers(2, 8),
    seed=st.integers(0, 2**32 - 1),
    speed=speeds,
    angle=angles,
)
def test_masses_over_a_million_to_one(table, n, seed, speed, angle) -> None:
    rng = np.random.default_rng(seed)
    positions = random_layout(table, n, rng, min_gap=float(rng.choice([0.0, 0.01])))
    masses = log_uniform_masses(rng, n, table.ball_mass, 1e6)
    velocities = np.zeros_like(positions)
    velocities[0] = speed * np.array([math.cos(angle), math.sin(angle)])
    velocities = within_limits(table, velocities, masses)  # see test_lumps_driven_into_rails
    result = simulate(table, positions, velocities, masses)
    _check_unequal(table, result, masses)


@settings(max_examples=examples(80), deadline=None)
@given(
    log_scale=st.floats(
        math.log10(limits.MIN_LENGTH / Table().ball_radius),
        math.log10(limits.MAX_LENGTH / Table().length),
    ),
    n=st.integers(1, 6),
    seed=st.integers(0, 2**32 - 1),
    speed_fraction=st.one_of(st.floats(1e-6, 1.0), st.just(1.0)),
    angle=angles,
    e=st.sampled_from([0.95, 0.5]),
)
def test_scales_at_the_numeric_limits(log_scale, n, seed, speed_fraction, angle, e) -> None:
    """Tables from a 0.1 mm ball to a 10 km table, fast shots: G, P, E, T and D."""
    f = 10.0**log_scale
    base = Table()
    table = Table(
        length=base.length * f,
        width=base.width * f,
        ball_radius=base.ball_radius * f,
        e_ball=e,
        e_cushion=e,
        pockets=base.pockets * f,
    )
    rng = np.random.default_rng(seed)
    positions = random_layout(table, n, rng)
    # Playing speeds scaled with the table (the same number of rail lengths), or the limit.
    speed = speed_fraction * min(0.999 * max_speed(table), 15.0 * math.sqrt(f))
    result = shoot(table, positions, angle, speed)
    assert check_shot(table, result, samples=300) == []
    again = shoot(table, positions, angle, speed)
    np.testing.assert_array_equal(result.positions, again.positions)
