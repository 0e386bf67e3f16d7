"""The free point nearest a target: where a ball goes when its own point is covered.

:func:`free_spot` is the one placement search of the package: a scratched cue ball whose
head spot is covered, a re-spotted ball whose foot spot is covered, and a cue ball in hand
placed on an occupied or forbidden point all go here, deterministically.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels import params as kp
from pool_env.game.kernels.layout import free_points, point_free
from pool_env.game.scenes import CLEARANCE, placement
from pool_env.sim.layouts import head_spot
from pool_env.sim.table import Table


def free_spot(
    table: Table,
    positions: NDArray[np.float64],
    occupied: NDArray[np.bool_],
    target: NDArray[np.float64] | None = None,
    behind_head_string: bool = False,
) -> NDArray[np.float64]:
    """The free point nearest to ``target`` (the head spot by default) for a placed ball.

    The one placement search of the package: a scratched cue ball whose head spot is
    covered, a re-spotted 9 (or 8) whose foot spot is covered, and a cue ball in hand
    placed on an occupied or forbidden point all go here, deterministically.

    A point is free when :func:`pool_env.game.kernels.layout.point_free` says so: inside
    the rails (and behind the head string, ``x <= L / 4``, when ``behind_head_string``),
    outside every capture circle and at least ``2R`` from every occupied ball. The free
    region is a box (the rails, the head string) minus discs (the balls' ``2R + clearance``
    circles, the capture circles padded by twice the clearance), so its nearest point to the
    target is the target itself, the nearest point of one edge (the projection onto a line
    or radially onto a circle), or a corner where two edges meet (line-line, line-circle,
    circle-circle): every one of these candidates is checked, and the nearest free one is
    the answer (exact up to rounding and the clearance). A ring search around the target
    remains as a fallback should rounding reject every candidate.

    Args:
        table: The table.
        positions: ``(N, 2)`` centres.
        occupied: ``(N,)`` which rows are balls on the table (the ball to place excluded).
        target: The preferred point (anywhere, even off the table).
        behind_head_string: Only centres with ``x <= L / 4`` are free (ball in hand after a
            scratch on an 8-ball break).

    Returns:
        The ``(2,)`` free point.

    Raises:
        ValueError: If the table has no free point at all.
    """
    params, pockets = placement(table), table.pockets
    if behind_head_string:
        params[kp.X_HIGH] = table.length / 4.0
    target = head_spot(table) if target is None else np.array(target, dtype=np.float64)
    balls = np.ascontiguousarray(positions[occupied], dtype=np.float64)
    reach = float(params[kp.REACH])
    tx, ty = target.tolist()
    if point_free(tx, ty, params, pockets, balls, balls.shape[0], reach * reach):
        return target
    box = params[[kp.X_LOW, kp.X_HIGH, kp.Y_LOW, kp.Y_HIGH]]
    centres = np.concatenate([balls, pockets[:, :2]])
    radii = np.concatenate(
        [np.full(balls.shape[0], reach), pockets[:, 2] + 2.0 * CLEARANCE]
    )  # out of a capture circle with the clearance to spare
    cands = [target[None, :], *_edge_candidates(target, box, centres, radii)]
    # Candidates lie on a 2R circle up to rounding: half the clearance absorbs it.
    min_d2 = (reach - CLEARANCE / 2.0) ** 2
    cand = np.ascontiguousarray(np.concatenate(cands))
    ok = free_points(params, pockets, cand, balls, min_d2)
    if np.any(ok):
        dist = np.hypot(*(cand[ok] - target).T)
        return cand[ok][int(np.argmin(dist))].copy()
    step = table.ball_radius / 4.0
    for ring in range(1, int(math.hypot(table.length, table.width) / step) + 1):
        k = max(8, int(2.0 * math.pi * ring))
        phi = np.linspace(0.0, 2.0 * math.pi, k, endpoint=False)
        cand = target + ring * step * np.stack([np.cos(phi), np.sin(phi)], axis=1)
        ok = free_points(params, pockets, np.ascontiguousarray(cand), balls, min_d2)
        if np.any(ok):
            return cand[int(np.argmax(ok))].copy()
    raise ValueError("no free point on the table to re-spot the ball")


def _edge_candidates(
    target: NDArray[np.float64],
    box: NDArray[np.float64],
    centres: NDArray[np.float64],
    radii: NDArray[np.float64],
) -> list[NDArray[np.float64]]:
    """The points where the nearest free point to ``target`` can lie, short of the target.

    The allowed region is the box ``(x_low, x_high, y_low, y_high)`` minus the discs
    ``(centres, radii)``. Its nearest point to the target lies on one edge (then it is the
    target's projection onto that line or circle) or where two edges meet.

    Returns:
        ``(k, 2)`` arrays: projections onto the four lines and the circles, the box's
        corners, line-circle and circle-circle intersections.
    """
    tx, ty = target.tolist()
    x_low, x_high, y_low, y_high = box.tolist()
    out = [
        np.array([[x_low, ty], [x_high, ty], [tx, y_low], [tx, y_high]]),
        np.array([[x_low, y_low], [x_low, y_high], [x_high, y_low], [x_high, y_high]]),
    ]
    if centres.shape[0] == 0:
        return out
    d = target - centres
    norm = np.hypot(d[:, 0], d[:, 1])
    unit = np.where(norm[:, None] > 0.0, d / np.maximum(norm, 1e-300)[:, None], [1.0, 0.0])
    out.append(centres + radii[:, None] * unit)  # radially onto each circle
    for axis, values in ((0, (x_low, x_high)), (1, (y_low, y_high))):
        for value in values:  # each circle meets the line coordinate[axis] = value
            off = value - centres[:, axis]
            meets = np.abs(off) <= radii
            half = np.sqrt(np.maximum(radii[meets] ** 2 - off[meets] ** 2, 0.0))
            along = centres[meets, 1 - axis]
            for sign in (-1.0, 1.0):
                pts = np.empty((half.shape[0], 2))
                pts[:, axis], pts[:, 1 - axis] = value, along + sign * half
                out.append(pts)
    i, j = np.triu_indices(centres.shape[0], 1)
    sep = centres[j] - centres[i]
    dist = np.hypot(sep[:, 0], sep[:, 1])
    ri, rj = radii[i], radii[j]
    meet = (dist > 0.0) & (dist <= ri + rj) & (dist >= np.abs(ri - rj))
    if np.any(meet):
        a, s, dist, ri, rj = centres[i[meet]], sep[meet], dist[meet], ri[meet], rj[meet]
        along = (ri * ri - rj * rj + dist * dist) / (2.0 * dist)
        # lifted 1e-6 (relative) off both circles, so that rounding cannot put it inside
        h = np.sqrt(np.maximum(ri * ri - along * along, 0.0)) * 1.000001
        mid = a + (along / dist)[:, None] * s
        perp = np.stack([-s[:, 1], s[:, 0]], axis=1) / dist[:, None]
        out += [mid + h[:, None] * perp, mid - h[:, None] * perp]
    return out
