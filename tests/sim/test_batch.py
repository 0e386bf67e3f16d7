"""Batched simulation equals one shoot() per table, bit for bit, serial or parallel."""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.batch import simulate_batch
from pool_env.sim.layouts import break_scene
from pool_env.testing.scenes_random import random_layout


def _scenes(table: Table, n_tables: int, n_balls: int, seed: int):
    rng = np.random.default_rng(seed)
    pos = np.array([random_layout(table, n_balls, rng) for _ in range(n_tables)])
    active = rng.random((n_tables, n_balls)) < 0.8
    active[:, 0] = True
    vel = np.zeros_like(pos)
    angle = rng.uniform(-np.pi, np.pi, n_tables)
    speed = rng.uniform(0.5, 10.0, n_tables)
    vel[:, 0] = np.stack([speed * np.cos(angle), speed * np.sin(angle)], axis=1)
    return pos, vel, active, angle, speed


@pytest.mark.parametrize("parallel", [False, True])
@pytest.mark.parametrize("n_balls", [1, 2, 9])
def test_batch_equals_single_shots(table: Table, parallel: bool, n_balls: int) -> None:
    pos, vel, active, angle, speed = _scenes(table, 40, n_balls, seed=n_balls)
    masses = np.random.default_rng(1).uniform(0.15, 0.2, n_balls)
    batch = simulate_batch(table, pos, vel, masses=masses, active=active, parallel=parallel)
    for b in range(len(pos)):
        idx = np.flatnonzero(active[b])
        single = shoot(table, pos[b][idx], angle[b], speed[b], masses=masses[idx], record=False)
        np.testing.assert_array_equal(batch.positions[b][idx], single.positions)
        np.testing.assert_array_equal(batch.pocketed[b][idx], single.pocketed)
        assert batch.n_events[b] == single.n_events
        inactive = ~active[b]
        np.testing.assert_array_equal(batch.positions[b][inactive], pos[b][inactive])
        assert np.all(batch.pocketed[b][inactive] == -1)
        if single.first_contact is None:
            assert batch.first_contact[b].tolist() == [-1, -1]
        else:
            assert batch.first_contact[b].tolist() == idx[list(single.first_contact)].tolist()


def test_batch_of_breaks(table: Table) -> None:
    base = break_scene(table, "eight")
    pos = np.repeat(base[None], 8, axis=0)
    vel = np.zeros_like(pos)
    vel[:, 0, 0] = np.linspace(2.0, 12.0, 8)
    batch = simulate_batch(table, pos, vel, parallel=True)
    for b in range(8):
        single = simulate(table, pos[b], vel[b], record=False)
        np.testing.assert_array_equal(batch.positions[b], single.positions)


def test_batch_errors_name_the_table(table: Table) -> None:
    pos = np.array([[[1.0, 0.6], [1.5, 0.6]], [[1.0, 0.6], [1.0 + 1e-3, 0.6]]])
    with pytest.raises(ValueError, match=r"table 1: balls 0 and 1 overlap"):
        simulate_batch(table, pos, np.zeros_like(pos))
    with pytest.raises(ValueError, match="shape"):
        simulate_batch(table, pos[0], np.zeros_like(pos[0]))
    with pytest.raises(ValueError, match="active"):
        simulate_batch(table, pos, np.zeros_like(pos), active=[True, False])
    # An inactive ball may sit anywhere: it is not on the table.
    active = np.array([[True, True], [True, False]])
    result = simulate_batch(table, pos, np.zeros_like(pos), active=active)
    np.testing.assert_array_equal(result.positions, pos)
