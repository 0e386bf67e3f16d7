"""Where a ball may be placed, at the edges of the rule (:func:`point_free`).

The documented rule (:func:`pool_env.game.scenes.placement`): centres inside the rails, at
least ``CLEARANCE`` outside every capture circle and ``2R + CLEARANCE`` from every other
ball. Random layouts almost never land within a fraction of a micrometre of those edges, so
the rule is pinned here point by point, a quarter of the clearance either side of each edge.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table
from pool_env.game.kernels.layout import point_free
from pool_env.game.scenes import CLEARANCE, placement

TABLE = Table(pockets="circles")
R = TABLE.ball_radius
PARAMS = placement(TABLE)
POCKETS = np.ascontiguousarray(TABLE.pockets)
NO_BALLS = np.zeros((0, 2))
REACH2 = (2 * R + CLEARANCE) ** 2


def _free(p, balls=NO_BALLS) -> bool:
    return bool(point_free(p[0], p[1], PARAMS, POCKETS, balls, balls.shape[0], REACH2))


@pytest.mark.parametrize("k", range(6))
def test_a_centre_keeps_the_clearance_from_every_capture_circle(k: int) -> None:
    """Towards the table's middle from pocket ``k``: in, just short of, and past the margin."""
    x, y, radius = TABLE.pockets[k]
    u = np.array([TABLE.length / 2 - x, TABLE.width / 2 - y])
    u /= np.hypot(*u)
    centre = np.array([x, y])
    assert not _free(centre + (radius - 0.25 * CLEARANCE) * u)
    assert not _free(centre + (radius + 0.75 * CLEARANCE) * u)  # outside, inside the margin
    assert _free(centre + (radius + 1.25 * CLEARANCE) * u)


@pytest.mark.parametrize("angle", [0.0, 1.0, 2.5])
def test_a_centre_keeps_two_radii_and_the_clearance_from_every_ball(angle: float) -> None:
    ball = np.array([[1.2, 0.6]])
    u = np.array([math.cos(angle), math.sin(angle)])
    assert not _free(ball[0] + (2 * R + 0.75 * CLEARANCE) * u, ball)
    assert _free(ball[0] + (2 * R + 1.25 * CLEARANCE) * u, ball)


def test_a_centre_stays_inside_the_rails() -> None:
    assert _free((R, 0.6)) and _free((TABLE.length - R, 0.6))
    assert not _free((R - 1e-12, 0.6)) and not _free((1.2, TABLE.width - R + 1e-12))
