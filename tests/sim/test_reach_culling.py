"""Culling by reach (issue 30, item 1): a pocket out of a piece's reach has no event on it.

The spin level tests a pocket's jaws only when the bounding box of a ball's current piece
meets the pocket's reach box (``J_BOX`` of its jaw row). The culling is exact, so the
prediction with it must equal the prediction without it, bit for bit, on any piece: these
tests draw pieces aimed at and around the pockets (curving, fast, slow, starting in a
throat) and compare. The same-shot A/B over 100,000 fuzz shots (``bench.sim_ab``) checks
whole shots.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table
from pool_env.sim.kernels.jaw_geometry import J_BOX, J_FACING0, J_FACING1, J_TIP0, J_TIP1, box_meets
from pool_env.sim.kernels.roots import APPROACH_RTOL
from pool_env.sim.kernels.spin.jaw_events import predict_jaws
from pool_env.sim.kernels.spin.params import S_SLIDE_DECEL
from pool_env.sim.kernels.spin.predict import _extent
from pool_env.sim.pockets import J_FX

TABLE = Table(model="spin")
PRM, POCKETS = TABLE.spin_params, TABLE.pocket_geometry
EVERYWHERE = (-math.inf, -math.inf, math.inf, math.inf)


def test_the_reach_box_holds_every_piece_of_its_pocket() -> None:
    """Facing segments, tip circles and the fall line's centre lie inside the box."""
    for row in POCKETS:
        lo, hi = row[J_BOX : J_BOX + 2], row[J_BOX + 2 : J_BOX + 4]
        for col in (J_FACING0, J_FACING1):
            start, d, extent = row[col : col + 2], row[col + 2 : col + 4], row[col + 6]
            for p in (start, start + extent * d):
                assert np.all(lo <= p) and np.all(p <= hi)
        for col in (J_TIP0, J_TIP1):
            c, rho = row[col : col + 2], row[col + 2]
            assert np.all(lo <= c - rho) and np.all(c + rho <= hi)
        fall = row[J_FX : J_FX + 2]
        assert np.all(lo <= fall) and np.all(fall <= hi)


def test_a_box_far_from_every_pocket_meets_none() -> None:
    centre = (TABLE.length / 2, TABLE.width / 2)
    box = (centre[0] - 0.1, centre[1] - 0.1, centre[0] + 0.1, centre[1] + 0.1)
    assert not any(box_meets(row, *box) for row in POCKETS)
    assert all(box_meets(row, *EVERYWHERE) for row in POCKETS)


def _pieces(rng: np.random.Generator, n: int):
    """Pieces ``(x, y, vx, vy, ax, ay, span)`` aimed at, past and around the pockets."""
    radius = TABLE.ball_radius
    for _ in range(n):
        row = POCKETS[rng.integers(len(POCKETS))]
        mouth = 0.5 * (row[J_BOX : J_BOX + 2] + row[J_BOX + 2 : J_BOX + 4])
        if rng.random() < 0.15:  # starting in a throat, between the facings
            start = mouth + rng.normal(0.0, 0.01, 2)
        else:
            start = rng.uniform((radius, radius), (TABLE.length - radius, TABLE.width - radius))
        target = mouth + rng.normal(0.0, 0.08, 2)
        speed = rng.choice([0.05, 0.5, 2.0, 6.0]) * rng.uniform(0.5, 1.5)
        heading = target - start
        heading /= max(np.hypot(*heading), 1e-12)
        v = speed * heading
        a = rng.normal(0.0, 2.0, 2) if rng.random() < 0.7 else -0.7 * heading
        span = rng.uniform(0.01, 3.0)
        yield (*start, *v, *a, span)


@pytest.mark.parametrize("seed", range(4))
def test_culled_and_full_predictions_agree_bit_for_bit(seed: int) -> None:
    rng = np.random.default_rng(seed)
    accel = PRM[S_SLIDE_DECEL]
    met = culled = 0
    for x, y, vx, vy, ax, ay, span in _pieces(rng, 3000):
        scale = math.hypot(vx, vy) + math.hypot(ax, ay) * span
        tol = APPROACH_RTOL * scale
        curv_tol = APPROACH_RTOL * accel
        xl, xh = _extent(x, vx, ax, span)
        yl, yh = _extent(y, vy, ay, span)
        best = (1e9, 3, -1)
        args = (POCKETS, PRM, x, y, vx, vy, ax, ay, span, tol, curv_tol, scale, accel, 0.0)
        full = predict_jaws(*args, best, EVERYWHERE)
        cut = predict_jaws(*args, best, (xl, yl, xh, yh))
        assert cut == full, (x, y, vx, vy, ax, ay, span)
        met += full[0] < 1e9
        culled += sum(not box_meets(row, xl, yl, xh, yh) for row in POCKETS)
    # The draw reaches the jaws often and culls most pockets: the comparison has teeth.
    assert met > 300
    assert culled > 3 * 3000
