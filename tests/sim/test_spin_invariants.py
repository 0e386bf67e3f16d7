"""The invariant checks on spin-level results catch what they claim to.

Each test corrupts one recorded quantity of a clean spin shot (segments are views into the
result's arrays) and asserts that the named check reports it, and only where the spin
matters (a spin-only energy gain is invisible to the roll level's translational energy).
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import Table, shoot
from pool_env.testing.invariants import (
    check_energy,
    check_momentum,
    check_order,
    check_shot,
)
from pool_env.testing.spin_invariants import check_motion, energy_after_each_event


def _shot():
    """A draw shot into a ball, then rails: sliding, rolling, spinning, impacts."""
    table = Table(model="spin", pockets="none")
    positions = [[0.6, 0.6], [1.2, 0.62]]
    result = shoot(table, positions, 0.03, 2.0, tip=(0.3, -0.4), elevation=0.1)
    assert check_shot(table, result) == []
    kinds = {e.kind for e in result.events}
    assert {"ball", "cushion", "slide_roll"} <= kinds
    return table, result


def _rows(result, sliding: bool):
    """Rows anchored sliding (slip != 0) or rolling, of moving balls."""
    _, _, state, _ = result.segments
    r = Table().ball_radius
    moving = np.hypot(state[:, 2], state[:, 3]) > 0
    rolling = (state[:, 4] == -state[:, 3] / r) & (state[:, 5] == state[:, 2] / r)
    return np.flatnonzero(moving & (~rolling if sliding else rolling))


def test_energy_counts_the_spin() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    m = np.full(2, table.ball_mass)
    energy = energy_after_each_event(table, result, m)
    assert np.all(np.diff(energy) <= 1e-12 * energy[0])
    row = _rows(result, sliding=True)[-1]
    state[row, 6] += 500.0  # side spin out of nowhere: no translational change
    assert check_energy(result, m, table)
    with pytest.raises(ValueError, match="table"):
        check_energy(result, m)


def test_wrong_acceleration_is_caught() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    row = _rows(result, sliding=True)[0]
    state[row, 7:9] *= -1.0  # friction along the slip instead of against it
    assert any("accelerates" in p for p in check_motion(table, result))


def test_missed_transition_is_caught() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    row = _rows(result, sliding=False)[0]
    state[row, 2:6] *= 0.5  # still rolling, but it would stop in half the time
    assert any("past its transition" in p for p in check_motion(table, result))


def test_transition_state_is_checked() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    k = next(i for i, e in enumerate(result.events) if e.kind == "slide_roll")
    state[result.event_first_segment[k], 4] += 1.0  # the "rolling" row still slips
    assert any("slide_roll" in p for p in check_motion(table, result))


def test_momentum_and_order_on_the_spin_level() -> None:
    table, result = _shot()
    _, _, state, _ = result.segments
    k = next(i for i, e in enumerate(result.events) if e.kind == "ball")
    state[result.event_first_segment[k], 2:4] *= 0.5
    assert check_momentum(result, np.full(2, table.ball_mass), table)
    times = result.event_times
    times[[0, 1]] = times[[1, 0]]
    assert check_order(result)
