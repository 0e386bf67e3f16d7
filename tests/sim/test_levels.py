"""Model levels as strategies of one event loop (issue 30, item 0).

The loop, the batch and the rollout are compiled once per level marker from the same
source; these tests hold the Python side's picker to the table's model, the unchecked entry
point of the game layer to :func:`pool_env.simulate` bit for bit, and the interface to
running a level from plain Python and refusing anything that is no level's marker.
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.sim.kernels import level
from pool_env.sim.kernels.roll.marker import ROLL
from pool_env.sim.kernels.spin.marker import SPIN
from pool_env.sim.levels import LEVELS, level_of
from pool_env.sim.result import SpinShotResult
from pool_env.sim.simulate import simulate_checked_arrays
from pool_env.sim.table import MODELS, SPIN_MODELS
from pool_env.testing.scenes_random import random_layout


def test_every_model_has_one_level_with_its_own_kernels() -> None:
    assert sorted(LEVELS) == sorted(MODELS)
    # Each level compiles its own copy of the shared kernels.
    assert len({lv.kernels.packed_shot for lv in LEVELS.values()}) == len(LEVELS)
    for model in MODELS:
        table = Table(model=model)
        lv = level_of(table)
        assert lv.name == model
        assert table.has_spin == (model in SPIN_MODELS)
        # The parameter array is the table's own, not a copy that could drift from it.
        assert lv.params_of(table) is (table.spin_params if table.has_spin else table.params)


def test_the_interface_runs_a_level_from_python_and_refuses_anything_else() -> None:
    """From plain Python (as with ``NUMBA_DISABLE_JIT=1``) a call runs the marker's level."""
    roll, spin = ROLL, SPIN
    assert level.tail_sizes(roll) == (0, 0)
    assert level.tail_sizes(spin) == (3, 1)  # angular velocities, motion state
    out = np.empty(5)
    level.strike(roll, 2.0, 0.5, 0.0, 0.0, 0.0, Table().params, out)
    np.testing.assert_array_equal(out, [2.0 * np.cos(0.5), 2.0 * np.sin(0.5), 0.0, 0.0, 0.0])
    with pytest.raises(TypeError, match="marker"):
        level.tail_sizes(None)


@pytest.mark.parametrize("model", MODELS)
@pytest.mark.parametrize("seed", range(6))
def test_the_unchecked_entry_equals_simulate_bit_for_bit(model: str, seed: int) -> None:
    table = Table(model=model)
    rng = np.random.default_rng(seed)
    pos = random_layout(table, 6, rng)
    vel = np.zeros_like(pos)
    vel[0] = rng.uniform(-3.0, 3.0, 2)
    ang = rng.uniform(-40.0, 40.0, (6, 3)) if table.has_spin else None
    if ang is not None:
        ang[1:] = 0.0
    a = simulate(table, pos, vel, angular_velocities=ang)
    b = simulate_checked_arrays(table, pos, vel, ang, True)
    assert type(a) is type(b)
    assert a.n_events == b.n_events
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.event_times, b.event_times)
    np.testing.assert_array_equal(a.pocketed, b.pocketed)
    if isinstance(a, SpinShotResult):
        np.testing.assert_array_equal(a.angular_velocities, b.angular_velocities)


@pytest.mark.parametrize("model", MODELS)
def test_the_unchecked_entry_still_refuses_an_invalid_scene(model: str) -> None:
    """The compiled call validates the scene: overlapping balls never run."""
    table = Table(model=model)
    pos = np.array([[1.0, 0.6], [1.0 + table.ball_radius, 0.6]])  # centres R apart
    with pytest.raises(ValueError, match="overlap"):
        simulate_checked_arrays(table, pos, np.zeros((2, 2)), None, False)
