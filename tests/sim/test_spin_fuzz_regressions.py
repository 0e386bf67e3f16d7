"""Regressions found by the spin fuzz (``python -m tools.fuzz --model spin``), one per cause."""

from __future__ import annotations

import math

import pytest

from pool_env import Table, shoot
from pool_env.testing.invariants import check_shot


def test_a_near_vertical_cue_cannot_spin_a_ball_past_the_limits() -> None:
    """Fuzz seed 2040 shot 63: ``elevation`` a hair below pi/2 gave R |w| = 1.4e7 m/s.

    The strike's spin grows as ``1 / cos(elevation)``; ``simulate`` refuses a surface speed
    ``R |w|`` beyond ``limits.MAX_SPEED``, and ``shoot`` must too (the shot looped at one
    instant against a rail until the event cap).
    """
    table = Table(model="spin", pockets="none")
    positions = [[1.0, 0.6]]
    steep = 0.5 * math.pi - 1e-6
    with pytest.raises(ValueError, match="surface speed"):
        shoot(table, positions, 0.0, 2.0, tip=(0.3, 0.3), elevation=steep)
    # The same cue at a steep but playable elevation still runs, to rest.
    result = shoot(table, positions, 0.0, 2.0, tip=(0.3, 0.3), elevation=1.2)
    assert check_shot(table, result) == []
