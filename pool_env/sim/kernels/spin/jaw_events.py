"""Jaw events on the spin level (compiled): a curved path meeting facings, points, fall lines.

The jaw rows of :mod:`pool_env.sim.kernels.jaw_geometry` (every piece already offset by ``R``, so
the ball *centre* touches it) against a ball whose position is quadratic in time
``p(tau) = p0 + v tau + acc tau^2 / 2``:

* a **facing** (a finite line of unit normal ``n`` into the free side): the signed distance
  ``delta(tau) = (p(tau) - A) . n`` is a quadratic; the event is its first root where the
  ball moves into the facing (``delta' < 0`` beyond rounding) with the contact inside the
  facing's extent (``0 <= (p - A) . d <= extent``); at or past the facing and moving in,
  an impact now (the contact rule);
* a **point** (a tip circle of radius ``rho``): the squared distance less ``rho^2`` is a
  quartic, the bracketed :func:`~pool_env.sim.kernels.roots.first_contact`;
* the **fall line**: a quadratic half-plane crossing inside the pocket's own throat; on or
  behind it, potted now.

Culling: every offset facing and tip lies outside the open rectangle of the rail lines, so
a piece of motion whose bounding box stays inside it needs no jaw at all; otherwise every
pocket is checked (a simplification of the roll level's opening-based culling, which
relies on straight paths).
"""

from __future__ import annotations

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.jaw_geometry import (
    J_FACING0,
    J_FNX,
    J_FNY,
    J_FX,
    J_FY,
    J_TIP0,
    box_meets,
    throat_of,
)
from pool_env.sim.kernels.kinds import JAW, POCKET, POINT
from pool_env.sim.kernels.roots import INF, first_contact, quadratic_roots


@kernel
def _facing_time(row, col, x, y, vx, vy, ax, ay, span, tol, curv_tol):
    """First ``tau`` in ``[0, span]`` of a contact with the facing at ``row[col:]``."""
    fx, fy = row[col], row[col + 1]
    dx, dy = row[col + 2], row[col + 3]
    nx, ny = row[col + 4], row[col + 5]
    extent = row[col + 6]
    # Penetration g = -delta: g0 + g1 tau + g2 tau^2.
    g0 = -((x - fx) * nx + (y - fy) * ny)
    g1 = -(vx * nx + vy * ny)
    g2 = -0.5 * (ax * nx + ay * ny)
    cand = [INF, INF, INF]
    if g0 >= 0.0 and (g1 > tol or (g1 >= -tol and g2 > curv_tol)):
        cand[0] = 0.0  # the contact rule, and a ball pressed in by its slip
    r1, r2 = quadratic_roots(g2, g1, g0)
    for m, r in enumerate((r1, r2)):
        if r > 0.0 and r <= span and g1 + 2.0 * g2 * r > tol:
            cand[m + 1] = r
    for tau in cand:
        if tau < INF:
            px = x + tau * (vx + 0.5 * ax * tau)
            py = y + tau * (vy + 0.5 * ay * tau)
            along = (px - fx) * dx + (py - fy) * dy
            if 0.0 <= along <= extent:
                return tau
    return INF


@kernel
def predict_jaws(
    pockets, prm, x, y, vx, vy, ax, ay, span, tol, curv_tol, scale, accel, t0, best, box
):
    """Fold every pocket's fall line, facings and points into ``best = (t, kind, arg)``.

    A pocket whose reach box the piece's bounding box ``box = (xl, yl, xh, yh)`` misses has
    no event on the piece (:func:`~pool_env.sim.kernels.jaw_geometry.box_meets`) and is skipped:
    culling by reach, exact.

    Ties at equal times keep the lower kind (a fall before a jaw contact, a facing before a
    point where they meet at a tip's tangent point).

    Returns:
        The updated ``(t, kind, arg)``; ``kind`` ``POCKET`` (``arg = k``), ``JAW`` or
        ``POINT`` (``arg = 2 k + side``).
    """
    best_t, best_kind, best_arg = best
    xl, yl, xh, yh = box
    for k in range(pockets.shape[0]):
        row = pockets[k]
        if not box_meets(row, xl, yl, xh, yh):
            continue
        fall0 = (x - row[J_FX]) * row[J_FNX] + (y - row[J_FY]) * row[J_FNY]
        if fall0 <= 0.0:
            tau = 0.0
        else:
            g1 = -(vx * row[J_FNX] + vy * row[J_FNY])
            g2 = -0.5 * (ax * row[J_FNX] + ay * row[J_FNY])
            tau = INF
            r1, r2 = quadratic_roots(g2, g1, -fall0)
            for r in (r1, r2):
                if tau == INF and r > 0.0 and r <= span and g1 + 2.0 * g2 * r > 0.0:
                    tau = r
        if tau < INF:
            # A fall line counts in its own pocket's throat only: the line extended
            # crosses the other pockets' throats (a side pocket's, a corner's).
            px = x + tau * (vx + 0.5 * ax * tau)
            py = y + tau * (vy + 0.5 * ay * tau)
            if throat_of(px, py, prm, pockets) != k:
                tau = INF
        t = t0 + tau
        if tau < INF and (t < best_t or (t == best_t and best_kind > 0)):
            best_t, best_kind, best_arg = t, POCKET, k
        for side in range(2):
            tau = _facing_time(row, J_FACING0 + 7 * side, x, y, vx, vy, ax, ay, span, tol, curv_tol)
            t = t0 + tau
            if tau < INF and (t < best_t or (t == best_t and best_kind > JAW)):
                best_t, best_kind, best_arg = t, JAW, 2 * k + side
        for side in range(2):
            col = J_TIP0 + 3 * side
            rho = row[col + 2]
            tau = first_contact(
                row[col] - x, row[col + 1] - y, -vx, -vy, -0.5 * ax, -0.5 * ay, rho * rho,
                span, scale, accel,
            )  # fmt: skip
            t = t0 + tau
            if tau < INF and (t < best_t or (t == best_t and best_kind > POINT)):
                best_t, best_kind, best_arg = t, POINT, 2 * k + side
    return best_t, best_kind, best_arg
