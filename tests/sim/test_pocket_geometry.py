"""Capture-circle pockets pinned by the WPA equipment specification, not by ``table.pockets``.

The spec: corner pocket mouth 4.5 - 4.625 in, side pocket mouth 5 - 5.125 in, measured
between the points where the cushion noses end (the model takes the narrow end of each
range). With full-length rails the capture circles are built so that a ball rolling along
a rail (centre ``R`` from the nose) is captured exactly where it reaches the mouth: at
``4.5 in / sqrt(2)`` from a corner along each rail (the corner noses are cut at 45 degrees)
and ``5 in / 2`` from the middle of a long rail. The numbers below come from the spec and
the table's size only; the simulator must capture the ball exactly there.

(The jaw model's geometry, the default from 2026-12, is pinned by its own tests.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot

INCH = 0.0254  # m, exactly
CORNER_MOUTH_SPEC = 4.5 * INCH  # WPA: 4.5 - 4.625 in, narrow end
SIDE_MOUTH_SPEC = 5.0 * INCH  # WPA: 5 - 5.125 in, narrow end
TABLE = Table(pockets="circles")  # capture circles (the jaw geometry: tests/sim/test_jaws.py)
L, W, R = 2.54, 1.27, 0.028575  # the 9-ft table (docs/physics.md defaults)


def test_the_table_is_the_specified_one() -> None:
    assert (TABLE.length, TABLE.width, TABLE.ball_radius) == (L, W, R)


def test_capture_circles_from_the_spec() -> None:
    corner = math.hypot(R, CORNER_MOUTH_SPEC / math.sqrt(2))
    side = math.hypot(2 * R, SIDE_MOUTH_SPEC / 2)
    expected = [
        (0.0, 0.0, corner),
        (L / 2, -R, side),
        (L, 0.0, corner),
        (0.0, W, corner),
        (L / 2, W + R, side),
        (L, W, corner),
    ]
    np.testing.assert_allclose(TABLE.pockets, expected, rtol=0, atol=1e-15)
    # In inches (R = 1.125 in): corner sqrt(1.125^2 + 4.5^2 / 2) = 3.375 in exactly, side
    # sqrt(2.25^2 + 2.5^2) = sqrt(11.3125) in.
    assert corner == pytest.approx(3.375 * INCH, rel=1e-14)
    assert side == pytest.approx(math.sqrt(11.3125) * INCH, rel=1e-14)


# (start, angle, pocket, coordinate that varies, where it is captured): a ball on a rail
# line rolling into each pocket along each of its rails.
_D = CORNER_MOUTH_SPEC / math.sqrt(2)
_S = SIDE_MOUTH_SPEC / 2
RAIL_RUNS = [
    ((0.5, R), math.pi, 0, 0, _D),
    ((R, 0.5), -math.pi / 2, 0, 1, _D),
    ((2.0, R), 0.0, 2, 0, L - _D),
    ((L - R, 0.5), -math.pi / 2, 2, 1, _D),
    ((0.5, W - R), math.pi, 3, 0, _D),
    ((R, 0.7), math.pi / 2, 3, 1, W - _D),
    ((2.0, W - R), 0.0, 5, 0, L - _D),
    ((L - R, 0.7), math.pi / 2, 5, 1, W - _D),
    ((0.5, R), 0.0, 1, 0, L / 2 - _S),
    ((2.0, R), math.pi, 1, 0, L / 2 + _S),
    ((0.5, W - R), 0.0, 4, 0, L / 2 - _S),
    ((2.0, W - R), math.pi, 4, 0, L / 2 + _S),
]


@pytest.mark.parametrize(("start", "angle", "pocket", "axis", "mouth"), RAIL_RUNS)
def test_a_ball_along_a_rail_drops_exactly_at_the_mouth(start, angle, pocket, axis, mouth):
    result = shoot(TABLE, [start], angle, 2.0)
    assert result.pocketed.tolist() == [pocket]
    assert result.positions[0][axis] == pytest.approx(mouth, abs=1e-12)
    assert result.positions[0][1 - axis] == pytest.approx(start[1 - axis], abs=1e-12)


@pytest.mark.parametrize("hair", [1e-6, -1e-6])
def test_the_side_mouth_is_five_inches_wide(hair: float) -> None:
    """A slow ball along the bottom rail stopping a hair before or after the mouth's edge."""
    edge = L / 2 - _S
    start = 1.0
    speed = math.sqrt(2 * TABLE.deceleration * (edge + hair - start))
    result = shoot(TABLE, [(start, R)], 0.0, speed)
    assert (result.pocketed[0] == 1) == (hair > 0)
