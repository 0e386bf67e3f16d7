"""Where a ball may go back on the table: ball in hand and re-spotting, deterministic.

A point is *free* for a ball centre when it lies in the playing area ``[R, L - R] x
[R, W - R]`` (behind the head string, ``x <= L / 4``, when the rules ask), at least ``2R``
from every other ball on the table, and outside every pocket's capture circle: the same
tests the simulator's input validation applies.

:func:`nearest_free_point` returns the free point nearest to a requested one. The free
region is a box minus a union of discs, so its nearest point to a target is the target
itself (clamped into the box), a projection of the target on one disc's circle or on one
side of the box, or a corner of the region: two circles' crossing, a circle's crossing
with a side, or a box corner. Every such candidate is generated; the nearest free one wins
(ties go to the first in a fixed order), which makes the answer exact and deterministic.
One exception: a target exactly on a ball's centre has every point of that ball's circle
nearest; only the one on the +x side is a candidate (the answer is then free and
deterministic, but possibly not the nearest).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.table import Table

# Candidates sit this much (relative) outside a disc, so rounding cannot put them inside it.
_SLACK = 1e-9


def _discs(
    table: Table, positions: NDArray[np.float64], on_table: NDArray[np.bool_]
) -> NDArray[np.float64]:
    """``(M, 3)`` forbidden discs ``(x, y, radius)``: the balls (``2R``) and the pockets."""
    balls = positions[on_table]
    ball_discs = np.column_stack([balls, np.full(len(balls), 2.0 * table.ball_radius)])
    return np.vstack([ball_discs, table.pockets]) if table.n_pockets else ball_discs


def _box(table: Table, behind_head_string: bool) -> tuple[float, float, float, float]:
    r = table.ball_radius
    hi_x = table.length / 4.0 if behind_head_string else table.length - r
    return r, hi_x, r, table.width - r


def _is_free(points: NDArray[np.float64], discs: NDArray[np.float64], box) -> NDArray[np.bool_]:
    x0, x1, y0, y1 = box
    inside = (
        (points[:, 0] >= x0) & (points[:, 0] <= x1) & (points[:, 1] >= y0) & (points[:, 1] <= y1)
    )
    if len(discs) == 0:
        return inside
    d2 = ((points[:, None, :] - discs[None, :, :2]) ** 2).sum(axis=2)
    # Strictly outside: the simulator counts a centre on a capture circle as in the pocket.
    return inside & np.all(d2 > discs[None, :, 2] ** 2, axis=1)


def _candidates(
    target: NDArray[np.float64], discs: NDArray[np.float64], box
) -> NDArray[np.float64]:
    x0, x1, y0, y1 = box
    tx, ty = min(max(target[0], x0), x1), min(max(target[1], y0), y1)
    out = [(tx, ty), (x0, y0), (x0, y1), (x1, y0), (x1, y1)]
    out += [(x0, ty), (x1, ty), (tx, y0), (tx, y1)]
    radii = discs[:, 2] * (1.0 + _SLACK)
    for (cx, cy), rad in zip(discs[:, :2], radii, strict=True):
        dx, dy = target[0] - cx, target[1] - cy
        norm = math.hypot(dx, dy)
        ux, uy = (dx / norm, dy / norm) if norm > 0.0 else (1.0, 0.0)
        out.append((cx + rad * ux, cy + rad * uy))
        for x in (x0, x1):  # the circle's crossings with the box's vertical sides
            h = rad * rad - (x - cx) ** 2
            if h >= 0.0:
                out += [(x, cy + math.sqrt(h)), (x, cy - math.sqrt(h))]
        for y in (y0, y1):
            h = rad * rad - (y - cy) ** 2
            if h >= 0.0:
                out += [(cx + math.sqrt(h), y), (cx - math.sqrt(h), y)]
    n = len(discs)
    for a in range(n):
        for b in range(a + 1, n):
            out += _circle_crossings(discs[a, :2], radii[a], discs[b, :2], radii[b])
    return np.array(out, dtype=np.float64)


def _circle_crossings(p, rp: float, q, rq: float) -> list[tuple[float, float]]:
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = math.hypot(dx, dy)
    if d == 0.0 or d > rp + rq or d < abs(rp - rq):
        return []
    along = (rp * rp - rq * rq + d * d) / (2.0 * d)
    h = math.sqrt(max(rp * rp - along * along, 0.0))
    mx, my = p[0] + along * dx / d, p[1] + along * dy / d
    return [(mx - h * dy / d, my + h * dx / d), (mx + h * dy / d, my - h * dx / d)]


def nearest_free_point(
    table: Table,
    positions: ArrayLike,
    on_table: ArrayLike,
    target: ArrayLike,
    behind_head_string: bool = False,
) -> NDArray[np.float64]:
    """The free point nearest to ``target`` for a ball placed among the others.

    Args:
        table: The table.
        positions: ``(N, 2)`` centres of the other balls.
        on_table: ``(N,)`` which of them are on the table (others are ignored; pass False
            for the ball being placed).
        target: The requested ``(x, y)`` (may be off the table, in a pocket or on a ball).
        behind_head_string: Only ``x <= L / 4`` is allowed (after an 8-ball break scratch).

    Returns:
        The ``(2,)`` point: ``target`` itself when it is free.

    Raises:
        ValueError: On malformed input, or when no free point exists.
    """
    pos = np.asarray(positions, dtype=np.float64).reshape(-1, 2)
    on = np.asarray(on_table, dtype=np.bool_).reshape(-1)
    want = np.asarray(target, dtype=np.float64).reshape(-1)
    if on.shape[0] != pos.shape[0] or want.shape != (2,) or not np.all(np.isfinite(want)):
        raise ValueError("need (N, 2) positions, (N,) on_table and a finite (x, y) target")
    discs = _discs(table, pos, on)
    box = _box(table, behind_head_string)
    if _is_free(want[None, :], discs, box)[0]:
        return want.copy()
    points = _candidates(want, discs, box)
    free = np.flatnonzero(_is_free(points, discs, box))
    if free.size == 0:
        raise ValueError("no free point on the table for the ball")
    dist = np.hypot(points[free, 0] - want[0], points[free, 1] - want[1])
    return points[free[int(np.argmin(dist))]].copy()


def respot_point(
    table: Table, positions: ArrayLike, on_table: ArrayLike, spot: ArrayLike
) -> NDArray[np.float64]:
    """Where a re-spotted ball goes: on ``spot``, or as near it as the balls there allow.

    As close to the spot as possible on the long string behind it (towards ``x = L``), else
    in front of it (WPA 9-ball 1.5).

    Args:
        table: The table.
        positions: ``(N, 2)`` centres of the other balls.
        on_table: ``(N,)`` which of them are on the table.
        spot: The spot (the foot spot for the 9 and the 8).

    Returns:
        The ``(2,)`` point.

    Raises:
        ValueError: If the whole long string through ``spot`` is blocked.
    """
    pos = np.asarray(positions, dtype=np.float64).reshape(-1, 2)
    on = np.asarray(on_table, dtype=np.bool_).reshape(-1)
    sx, sy = (float(v) for v in np.asarray(spot, dtype=np.float64).reshape(2))
    discs = _discs(table, pos, on)
    box = _box(table, False)
    xs = [sx]
    for cx, cy, rad in discs:  # where the string leaves each disc
        h = (rad * (1.0 + _SLACK)) ** 2 - (cy - sy) ** 2
        if h >= 0.0:
            xs += [cx + math.sqrt(h), cx - math.sqrt(h)]
    pts = np.array([(x, sy) for x in xs])
    free = _is_free(pts, discs, box)
    behind = [x for x, ok in zip(xs, free, strict=True) if ok and x >= sx]
    if behind:
        return np.array([min(behind), sy])
    ahead = [x for x, ok in zip(xs, free, strict=True) if ok and x < sx]
    if ahead:
        return np.array([max(ahead), sy])
    raise ValueError("no free point on the long string for the re-spotted ball")
