"""Where a ball may be placed: the one "is this point free?" test, and random layouts."""

from __future__ import annotations

import numpy as np

from pool_env.game.kernels.params import (
    CLEARANCE,
    REACH,
    RESTARTS,
    TRIES,
    X_HIGH,
    X_LOW,
    Y_HIGH,
    Y_LOW,
)
from pool_env.game.kernels.rng import next_double
from pool_env.sim.jit import kernel


@kernel
def point_free(x, y, params, pockets, balls, count, min_d2):
    """Whether a ball centred at ``(x, y)`` may be placed.

    Args:
        x: Centre, x (m).
        y: Centre, y (m).
        params: The config's numbers (:mod:`pool_env.game.kernels.params`): the allowed
            centres and the clearance.
        pockets: ``(P, 3)`` capture circles ``(x, y, radius)``: the centre must keep out
            of each, with the clearance to spare.
        balls: ``(M, 2)`` centres of balls already on the table; the first ``count`` count.
        min_d2: Smallest squared distance from each of them.

    Returns:
        True when the point is inside the rails, outside every padded capture circle and
        at least ``sqrt(min_d2)`` from each of the ``count`` balls.
    """
    if not (params[X_LOW] <= x <= params[X_HIGH] and params[Y_LOW] <= y <= params[Y_HIGH]):
        return False
    for p in range(pockets.shape[0]):
        dx, dy = x - pockets[p, 0], y - pockets[p, 1]
        r = pockets[p, 2] + params[CLEARANCE]
        if dx * dx + dy * dy <= r * r:
            return False
    for j in range(count):
        dx, dy = x - balls[j, 0], y - balls[j, 1]
        if dx * dx + dy * dy < min_d2:
            return False
    return True


@kernel
def free_points(params, pockets, points, balls, min_d2):
    """:func:`point_free` for each of ``points`` ``(C, 2)`` against all of ``balls``."""
    out = np.empty(points.shape[0], dtype=np.bool_)
    for c in range(points.shape[0]):
        out[c] = point_free(
            points[c, 0], points[c, 1], params, pockets, balls, balls.shape[0], min_d2
        )
    return out


@kernel
def sample_layouts(params, pockets, tables, positions, ptrs, placed, box, fallback):
    """Draw a starting layout for each of ``tables``, uniformly at random by rejection.

    Balls are placed one after another; each draw is uniform over ``box`` and kept when
    :func:`point_free` (clear of the pockets, the fixed balls and those placed before). The
    uniform numbers come in blocks of ``2 (missing + 2)`` draws of the table's generator (as
    numpy's ``rng.random((missing + 2, 2))``, so a typical layout takes one block). After
    ``params[TRIES]`` failed draws in a row the layout starts over; after
    ``params[RESTARTS]`` such attempts the table gets ``fallback``, a layout that always
    fits (checked when the scene was made), so that a reset never fails.

    Args:
        params: The config's numbers (the placement constants, tries and restarts).
        pockets: ``(P, 3)`` capture circles.
        tables: ``(K,)`` tables to lay out.
        positions: ``(B, N, 2)`` written in place: rows ``0..n_new-1`` the drawn balls in
            the order drawn (``n_new`` is ``fallback``'s length), the next rows ``placed``.
        ptrs: ``(B, 3)`` generator addresses per table (:mod:`pool_env.game.kernels.rng`).
        placed: ``(M, 2)`` fixed balls the drawn ones keep clear of (a rack), or empty.
        box: ``(x_low, x_high, y_low, y_high)`` for the drawn centres.
        fallback: ``(n_new, 2)`` the drawn balls' layout when every attempt failed.

    Returns:
        ``(K,)`` booleans: the tables that got ``fallback``.
    """
    n_new, n_fixed = fallback.shape[0], placed.shape[0]
    total = n_fixed + n_new
    x0, x1, y0, y1 = box[0], box[1], box[2], box[3]
    tries, restarts = int(params[TRIES]), int(params[RESTARTS])
    min_d2 = params[REACH] * params[REACH]  # centres 2R + clearance apart
    fell_back = np.zeros(tables.shape[0], dtype=np.bool_)
    balls = np.empty((total, 2))
    draws = np.empty(2 * (n_new + 2))
    for k in range(tables.shape[0]):
        b = tables[k]
        p = ptrs[b]
        count = total + 1  # no attempt made yet
        for _ in range(restarts):
            balls[:n_fixed] = placed
            count, failures = n_fixed, 0
            while count < total and failures < tries:
                m = total - count + 2
                for i in range(2 * m):  # drawn before use, as rng.random((m, 2)) is
                    draws[i] = next_double(p)
                for i in range(m):
                    x = x0 + draws[2 * i] * (x1 - x0)
                    y = y0 + draws[2 * i + 1] * (y1 - y0)
                    if point_free(x, y, params, pockets, balls, count, min_d2):
                        balls[count, 0], balls[count, 1] = x, y
                        count += 1
                        failures = 0
                        if count == total:
                            break
                    else:
                        failures += 1
            if count == total:
                break
        if count == total:
            positions[b, :n_new] = balls[n_fixed:]
        else:
            positions[b, :n_new] = fallback
            fell_back[k] = True
        positions[b, n_new:total] = placed
    return fell_back
