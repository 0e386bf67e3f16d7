"""Kernels of the batched environment: the per-table work around a batch of shots.

Each mirrors, table by table and operation by operation, what the single environment does
in Python (:mod:`pool_env.scenes`, :class:`pool_env.env.PoolEnv`), so that a batch gives
bit for bit the same layouts, shots and outcomes. Random numbers come from each table's
own generator through :mod:`pool_env.game.kernels.rng`.

Squares that the Python code writes as ``d ** 2`` are, near a decision threshold, computed
here as ``d ** two`` with ``two`` read from an array: CPython's ``**`` calls the C library's
``pow``, which differs from ``d * d`` in the last bit for about one value in a thousand, and
LLVM turns a constant exponent into ``d * d``; a run-time exponent keeps the library call
and the same bits.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.game.kernels.rng import next_double, standard_normal
from pool_env.sim.kernels._jit import kernel


@kernel
def _square_distance(dx, dy, threshold, two):
    """``dx ** 2 + dy ** 2`` as Python computes it, wherever it matters against ``threshold``.

    ``pow`` and ``d * d`` differ by at most an ulp, so the fast product decides unless the
    sum lies within rounding of the threshold; only then is the slow ``pow`` called.
    """
    q = dx * dx + dy * dy
    if abs(q - threshold) <= 1e-12 * threshold:
        q = dx**two + dy**two
    return q


@kernel
def _clear(x, y, circles, balls, n_balls, min_d2, two):
    """``scenes._clear``: outside every (squared) capture circle and clear of the balls."""
    for p in range(circles.shape[0]):
        r2 = circles[p, 2]
        if _square_distance(x - circles[p, 0], y - circles[p, 1], r2, two) <= r2:
            return False
    for j in range(n_balls):
        if _square_distance(x - balls[j, 0], y - balls[j, 1], min_d2, two) < min_d2:
            return False
    return True


@kernel
def sample_layouts(tables, positions, ptrs, n_new, placed, box, circles, min_d2, powers, tries):
    """Draw a starting layout for each table in ``tables``, as ``scenes.sample_uniform``.

    New balls are placed one after another by rejection, from batches of
    ``2 * (missing + 2)`` uniform draws (numpy's ``rng.random((missing + 2, 2))``, row by
    row); the unused draws of a batch are spent, as numpy spends them.

    Args:
        tables: ``(K,)`` tables to lay out.
        positions: ``(B, N, 2)`` written in place: rows ``0..n_new-1`` the new balls in
            the order drawn, the rows after them ``placed``.
        ptrs: ``(B, 3)`` generator addresses per table (:mod:`pool_env.game.kernels.rng`).
        n_new: Balls to draw.
        placed: ``(M, 2)`` fixed balls the new ones must keep clear of (a rack), or empty.
        box: ``(x_low, x_high, y_low, y_high)`` for the new centres.
        circles: ``(P, 3)`` capture circles ``(x, y, (radius + clearance)^2)``.
        min_d2: Smallest squared distance between centres.
        powers: ``(1,)`` holding 2.0 (see the module docstring).
        tries: Failed draws in a row after which a layout is impossible.

    Returns:
        ``(K,)``: -1 for a table laid out, else the number of balls placed when it failed.
    """
    two = powers[0]
    n_fixed = placed.shape[0]
    total = n_fixed + n_new
    x0, x1, y0, y1 = box[0], box[1], box[2], box[3]
    failed = np.full(tables.shape[0], -1, dtype=np.int64)
    balls = np.empty((total, 2))
    draws = np.empty(2 * (n_new + 2))
    for k in range(tables.shape[0]):
        b = tables[k]
        p = ptrs[b]
        balls[:n_fixed] = placed
        count, failures = n_fixed, 0
        while count < total:
            m = total - count + 2
            for i in range(2 * m):  # drawn before use, as rng.random((m, 2)) is
                draws[i] = next_double(p)
            for i in range(m):
                x = x0 + draws[2 * i] * (x1 - x0)
                y = y0 + draws[2 * i + 1] * (y1 - y0)
                if _clear(x, y, circles, balls, count, min_d2, two):
                    balls[count, 0], balls[count, 1] = x, y
                    count += 1
                    failures = 0
                    if count == total:
                        break
                else:
                    failures += 1
            if failures >= tries:
                failed[k] = count
                break
        if failed[k] < 0:
            positions[b, :n_new] = balls[n_fixed:]
            positions[b, n_new:total] = balls[:n_fixed]
    return failed


@kernel
def add_noise(tables, angles, speeds, ptrs, sigma_angle, sigma_speed):
    """Execution noise in place, as ``PoolEnv.step`` draws it: angle first, then speed."""
    for k in range(tables.shape[0]):
        p = ptrs[tables[k]]
        angles[k] = angles[k] + sigma_angle * standard_normal(p)
        s = speeds[k] + sigma_speed * standard_normal(p)
        speeds[k] = s if s > 0.0 else 0.0  # Python's max(0.0, s), -0.0 included


@kernel
def cue_velocities(angles, speeds, n_balls, cue):
    """``(K, N, 2)`` initial velocities: the cue ball struck as ``shoot()`` does."""
    out = np.zeros((angles.shape[0], n_balls, 2))
    for k in range(angles.shape[0]):
        out[k, cue, 0] = speeds[k] * math.cos(angles[k])
        out[k, cue, 1] = speeds[k] * math.sin(angles[k])
    return out


@kernel
def settle(
    tables, positions, on_table, n_left, final, pocketed, first, spot, circles, reach2, bounds,
    powers,
):  # fmt: skip
    """Apply a batch of shots to the tables' state, as ``PoolEnv.step`` does one.

    Potted balls leave the table (keeping their capture point); a potted cue ball goes
    back to ``spot`` when that point is free, exactly as ``scenes.free_spot``'s first test.

    Args:
        tables: ``(K,)`` tables that shot; row ``k`` of the results is table ``tables[k]``.
        positions: ``(B, N, 2)`` state, updated in place.
        on_table: ``(B, N)`` state, updated in place.
        n_left: ``(B,)`` object balls on each table, updated in place.
        final: ``(K, N, 2)`` simulated final positions (off-table rows unchanged).
        pocketed: ``(K, N)`` pocket per ball, -1 for none.
        first: ``(K, 2)`` balls of the first ball-ball impact, -1 for none.
        spot: ``(2,)`` where a potted cue ball goes (the head spot).
        circles: ``(P, 3)`` capture circles with squared, padded radii.
        reach2: Squared distance a re-spotted ball keeps from the others.
        bounds: ``(4,)`` ``(x_low, x_high, y_low, y_high)`` allowed for centres.
        powers: ``(1,)`` holding 2.0.

    Returns:
        ``(n_potted, potted_bits, scratch, first_ball, spot_taken)``, each ``(K,)``:
        object balls potted, bit ``j - 1`` set for each potted object ball ``j``, whether
        the cue ball was potted, the first ball the cue ball hit (-1 for none), and tables
        whose cue ball needs the full nearest-free-point search (its spot is taken; the
        cue is then marked on the table but not yet moved).
    """
    n_shots, n_balls = pocketed.shape
    two = powers[0]
    n_potted = np.zeros(n_shots, dtype=np.int64)
    bits = np.zeros(n_shots, dtype=np.int64)
    scratch = np.zeros(n_shots, dtype=np.bool_)
    first_ball = np.full(n_shots, -1, dtype=np.int64)
    spot_taken = np.zeros(n_shots, dtype=np.bool_)
    others = np.empty((n_balls, 2))
    tx, ty = spot[0], spot[1]
    inside = bounds[0] <= tx <= bounds[1] and bounds[2] <= ty <= bounds[3]
    for k in range(n_shots):
        b = tables[k]
        positions[b] = final[k]
        for j in range(1, n_balls):
            if pocketed[k, j] >= 0:
                on_table[b, j] = False
                n_potted[k] += 1
                if j <= 62:
                    bits[k] |= np.int64(1) << (j - 1)
        n_left[b] -= n_potted[k]
        if first[k, 0] >= 0:
            first_ball[k] = first[k, 1] if first[k, 0] == 0 else first[k, 0]
        if pocketed[k, 0] >= 0:
            scratch[k] = True
            count = 0
            for j in range(1, n_balls):
                if on_table[b, j]:
                    others[count] = positions[b, j]
                    count += 1
            if inside and _clear(tx, ty, circles, others, count, reach2, two):
                positions[b, 0, 0], positions[b, 0, 1] = tx, ty
            else:
                spot_taken[k] = True
    return n_potted, bits, scratch, first_ball, spot_taken
