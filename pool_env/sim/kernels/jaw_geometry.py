"""Pocket jaw geometry, shared by the levels (compiled): facings, points, fall lines, events.

The jaw array (``Table.pocket_geometry`` of a jaw table, one row per pocket, columns in
:mod:`pool_env.sim.pockets`) holds every cushion piece already offset by ``R``, so each is
a curve the ball *centre* touches:

* a **facing** is a finite straight line: along a straight path the signed distance to it
  is linear in arc length, ``delta(s) = delta0 + (u . n) s``; the contact must lie inside
  the facing's extent (else the tip or nothing is hit);
* a **point** (tip) is a circle of radius ``tip_radius + R``: a quadratic in arc length,
  solved as a ray-circle entry;
* the **fall line** is a half-plane: linear; a ball whose centre reaches it is potted.

Contact rule, as for rails and balls: touching or a hair beyond while approaching is an
impact now; separating (or a normal speed within rounding of zero) is none. Impacts reflect
the normal component with restitution ``e_jaw``.

Culling: every offset facing and tip lies outside the open rectangle of the rail lines, so
a pocket's jaws matter only once a path leaves the rectangle through that pocket's opening
(found from the rail-line crossing the predictor computes anyway) or while a ball is in
its throat. A path that is not straight (the spin level) is culled by reach instead: a
pocket whose reach box (``J_BOX``) the piece's bounding box does not meet has no event on
it (:func:`box_meets`). A table without jaws never reaches this module.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.kinds import JAW, POCKET, POINT
from pool_env.sim.kernels.params import (
    P_LENGTH,
    P_RADIUS,
    P_WIDTH,
)
from pool_env.sim.kernels.roots import APPROACH_RTOL, INF, ray_circle_entry

# Columns of a jaw row (mirrors pool_env.sim.pockets, which builds the rows).
J_FX, J_FY, J_FNX, J_FNY = 0, 1, 2, 3
J_FACING0, J_FACING1 = 4, 11
J_TIP0, J_TIP1 = 18, 21
J_OPEN0, J_OPEN1 = 24, 27
# The pocket's reach box (x min, y min, x max, y max): the bounding box of its offset facings,
# tip circles and fall line, which holds every centre position at which the pocket has an
# event (see pool_env.sim.pockets.kernel_rows).
J_BOX = 30
JAW_COLS = 34

# Results of locate().
LOC_FREE, LOC_OUTSIDE, LOC_CIRCLE, LOC_JAW, LOC_FALL = 0, 1, 2, 3, 4


@kernel
def opening_of(pockets, rail, coord):
    """The pocket whose opening on rail line ``rail`` contains ``coord`` (-1: solid rail)."""
    for k in range(pockets.shape[0]):
        for col in (J_OPEN0, J_OPEN1):
            if pockets[k, col] == rail and pockets[k, col + 1] < coord < pockets[k, col + 2]:
                return k
    return -1


@kernel
def throat_of(x, y, params, pockets):
    """The pocket whose opening a centre on or beyond a rail line lies in (-1 if none)."""
    length, width, radius = params[P_LENGTH], params[P_WIDTH], params[P_RADIUS]
    if x <= radius:
        k = opening_of(pockets, 0, y)
        if k >= 0:
            return k
    if x >= length - radius:
        k = opening_of(pockets, 1, y)
        if k >= 0:
            return k
    if y <= radius:
        k = opening_of(pockets, 2, x)
        if k >= 0:
            return k
    if y >= width - radius:
        k = opening_of(pockets, 3, x)
        if k >= 0:
            return k
    return -1


@kernel
def _facing_entry(row, col, x, y, ux, uy):
    """Arc length at which the ray ``(x, y) + u s`` meets a facing (``inf`` if never)."""
    ax, ay = row[col], row[col + 1]
    dx, dy = row[col + 2], row[col + 3]
    nx, ny = row[col + 4], row[col + 5]
    extent = row[col + 6]
    delta = (x - ax) * nx + (y - ay) * ny
    un = ux * nx + uy * ny
    if un >= 0.0:
        return INF  # moving away from the facing or along it
    if delta <= 0.0:
        # Touching or a hair beyond: approaching beyond rounding collides now.
        if un >= -APPROACH_RTOL:
            return INF
        s = 0.0
    else:
        s = delta / -un
    along = (x + ux * s - ax) * dx + (y + uy * s - ay) * dy
    if along < 0.0 or along > extent:
        return INF  # the contact would lie beyond the facing: its tip (or nothing)
    return s


@kernel
def _fall_entry(row, x, y, ux, uy):
    """Arc length at which the ray reaches the fall line (0 if on or behind it)."""
    delta = (x - row[J_FX]) * row[J_FNX] + (y - row[J_FY]) * row[J_FNY]
    if delta <= 0.0:
        return 0.0
    un = ux * row[J_FNX] + uy * row[J_FNY]
    if un >= 0.0:
        return INF
    return delta / -un


@kernel
def predict_pocket(pockets, k, x, y, ux, uy, best_s, best_kind, best_arg):
    """Fold pocket ``k``'s fall line, facings and points into the best own event so far.

    Ties at equal arc length keep the lower kind (a fall before a jaw contact, a facing
    before a point where they meet at a tip's tangent point).

    Returns:
        The updated ``(s, kind, arg)``; ``kind`` :data:`POCKET` (``arg = k``), :data:`JAW` or
        :data:`POINT` (``arg = 2 k + side``), or the input.
    """
    row = pockets[k]
    s = _fall_entry(row, x, y, ux, uy)
    if s <= best_s:
        best_s, best_kind, best_arg = s, POCKET, k
    for side in range(2):
        s = _facing_entry(row, J_FACING0 + 7 * side, x, y, ux, uy)
        if s < best_s or (s == best_s and best_kind > JAW):
            best_s, best_kind, best_arg = s, JAW, 2 * k + side
    for side in range(2):
        col = J_TIP0 + 3 * side
        rho = row[col + 2]
        s = ray_circle_entry(x, y, ux, uy, row[col], row[col + 1], rho * rho, False)
        if s < best_s or (s == best_s and best_kind > POINT):
            best_s, best_kind, best_arg = s, POINT, 2 * k + side
    return best_s, best_kind, best_arg


@kernel
def jaw_normal(pockets, kind, arg, x, y):
    """Unit normal (to the free side) of facing or point ``arg`` at a centre ``(x, y)``."""
    k, side = arg // 2, arg % 2
    if kind == JAW:
        col = J_FACING0 + 7 * side
        return pockets[k, col + 4], pockets[k, col + 5]
    col = J_TIP0 + 3 * side
    nx, ny = x - pockets[k, col], y - pockets[k, col + 1]
    norm = math.sqrt(nx * nx + ny * ny)
    if norm == 0.0:  # cannot happen for a centre R + tip radius away; keep a valid normal
        return 0.0, 0.0
    return nx / norm, ny / norm


@kernel
def _free_of_point(row, side, x, y, tol):
    """Whether a centre is clear (up to ``tol``) of one point: its tip and its facing."""
    tip = J_TIP0 + 3 * side
    col = J_FACING0 + 7 * side
    cx, cy, rho = row[tip], row[tip + 1], row[tip + 2]
    dx, dy = row[col + 2], row[col + 3]
    # In the tip's normal cone (before the facing starts, beyond the rail's end) the tip
    # decides; elsewhere along the throat the facing does.
    along = (x - row[col]) * dx + (y - row[col + 1]) * dy
    if along <= 0.0:
        return (x - cx) ** 2 + (y - cy) ** 2 >= (rho - tol) ** 2
    delta = (x - row[col]) * row[col + 4] + (y - row[col + 1]) * row[col + 5]
    return delta >= -tol


@kernel
def locate(x, y, params, pockets, tol):
    """Where a ball centre lies: ``(code, pocket)``.

    ``LOC_FREE`` inside the playing region (up to ``tol``); ``LOC_OUTSIDE`` beyond the
    rails; ``LOC_CIRCLE`` inside capture circle ``pocket``; ``LOC_JAW`` inside a facing or
    point of pocket ``pocket``; ``LOC_FALL`` on or behind its fall line.
    """
    length, width, radius = params[P_LENGTH], params[P_WIDTH], params[P_RADIUS]
    jaws = pockets.shape[1] == JAW_COLS
    inside = (
        radius - tol <= x <= length - radius + tol and radius - tol <= y <= width - radius + tol
    )
    if not jaws:
        if not inside:
            return LOC_OUTSIDE, -1
        for k in range(pockets.shape[0]):
            dx = x - pockets[k, 0]
            dy = y - pockets[k, 1]
            if dx * dx + dy * dy <= pockets[k, 2] * pockets[k, 2]:
                return LOC_CIRCLE, k
        return LOC_FREE, -1
    if inside:
        return LOC_FREE, -1  # every jaw lies outside the rectangle of the rail lines
    # Beyond a rail line by more than tol: only a pocket's throat can hold the centre.
    k = -1
    if x < radius - tol:
        k = opening_of(pockets, 0, y)
    if k < 0 and x > length - radius + tol:
        k = opening_of(pockets, 1, y)
    if k < 0 and y < radius - tol:
        k = opening_of(pockets, 2, x)
    if k < 0 and y > width - radius + tol:
        k = opening_of(pockets, 3, x)
    if k < 0:
        return LOC_OUTSIDE, -1
    row = pockets[k]
    if (x - row[J_FX]) * row[J_FNX] + (y - row[J_FY]) * row[J_FNY] <= 0.0:
        return LOC_FALL, k
    if not (_free_of_point(row, 0, x, y, tol) and _free_of_point(row, 1, x, y, tol)):
        return LOC_JAW, k
    return LOC_FREE, -1


@kernel
def locate_many(xs, ys, params, pockets, tol):
    """:func:`locate` for arrays of centres: ``(codes, pockets)``."""
    codes = np.empty(xs.shape[0], dtype=np.int64)
    where = np.empty(xs.shape[0], dtype=np.int64)
    for p in range(xs.shape[0]):
        codes[p], where[p] = locate(xs[p], ys[p], params, pockets, tol)
    return codes, where


#: Slack of the reach test (m): far above the rounding of a centre computed on a piece
#: (1e-15 m), far below any distance that separates a pocket from a path that reaches it.
REACH_MARGIN = 1e-6


@kernel
def box_meets(row, xl, yl, xh, yh):
    """Whether the box ``[xl, xh] x [yl, yh]`` meets pocket ``row``'s reach box.

    The reach box bounds the pocket's offset facings, tip circles and fall line, and so the
    closed mouth they and the rail-line opening enclose: a centre can meet a facing, a
    point or the fall line (inside the pocket's throat) only at a position inside the
    mouth's boundary or, beyond it, after crossing that boundary, which is itself an event
    of the pocket at a position inside the box. A path whose box misses the reach box
    (by more than :data:`REACH_MARGIN`) therefore has no event of this pocket: the test is
    exact, not a heuristic.
    """
    return not (
        xh < row[J_BOX] - REACH_MARGIN
        or xl > row[J_BOX + 2] + REACH_MARGIN
        or yh < row[J_BOX + 1] - REACH_MARGIN
        or yl > row[J_BOX + 3] + REACH_MARGIN
    )
