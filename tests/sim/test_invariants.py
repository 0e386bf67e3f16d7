"""The invariant checks catch what they claim to (they are used by the fuzz and the tests)."""

from __future__ import annotations

import numpy as np

from pool_env import Table, shoot
from pool_env.testing.invariants import check_energy, check_geometry, check_momentum, check_shot


def _shot():
    table = Table(pockets="none")
    result = shoot(table, [[0.8, 0.6], [1.1, 0.62]], 0.0, 1.0)
    assert check_shot(table, result) == []
    return table, result


def test_energy_gain_is_caught() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    state[-1, 2:4] *= 3.0  # the last re-anchored ball suddenly moves faster
    assert check_energy(result, np.full(2, table.ball_mass))


def test_momentum_loss_is_caught() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    first_impact_rows = result.event_first_segment[0]
    state[first_impact_rows, 2:4] *= 0.5
    assert check_momentum(result, np.full(2, table.ball_mass))


def test_overlap_and_escape_are_caught() -> None:
    table, result = _shot()
    ball, _, state, _ = result.segments
    moved = state.copy()
    state[:] = moved
    state[ball == 1, 0:2] = state[ball == 0, 0:2][0]  # ball 1 sits on ball 0
    assert any("overlap" in p for p in check_geometry(table, result))
    state[:] = moved
    state[ball == 0, 1] = -0.5  # ball 0 below the table
    assert any("outside" in p for p in check_geometry(table, result))
