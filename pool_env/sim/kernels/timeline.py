"""Exact positions at any time from a shot's trajectory segments (compiled)."""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel


@kernel
def last_rows(seg_ball, seg_t, n_balls, t):
    """Each ball's last segment row starting at or before ``t`` (segments chronological).

    The anchor each level's ``positions_at`` moves a ball on from.
    """
    last = np.full(n_balls, -1, dtype=np.int64)
    for row in range(seg_t.shape[0]):
        if seg_t[row] > t:
            break
        last[seg_ball[row]] = row
    return last


@kernel
def positions_at(seg_ball, seg_t, seg_state, seg_potted, n_balls, t, a):
    """Ball positions at time ``t`` and whether each ball is potted by then.

    Segments are chronological (``seg_potted`` nonzero where a ball was captured); the
    last one of each ball starting at or before ``t`` anchors it, and the ball rolls from
    there with deceleration ``a`` until it rests.
    """
    last = last_rows(seg_ball, seg_t, n_balls, t)
    out = np.empty((n_balls, 2), dtype=np.float64)
    potted = np.zeros(n_balls, dtype=np.bool_)
    for i in range(n_balls):
        row = last[i]
        x, y, vx, vy = seg_state[row, 0], seg_state[row, 1], seg_state[row, 2], seg_state[row, 3]
        potted[i] = seg_potted[row] != 0
        spd = math.sqrt(vx * vx + vy * vy)
        if spd > 0.0:
            # Same arithmetic as the event loop's state_at, so the final frame matches.
            if t >= seg_t[row] + spd / a:
                s = spd * spd / (2.0 * a)
            else:
                tau = t - seg_t[row]
                s = tau * (spd - 0.5 * a * tau)
            x += vx / spd * s
            y += vy / spd * s
        out[i, 0] = x
        out[i, 1] = y
    return out, potted


@kernel
def positions_at_many(seg_ball, seg_t, seg_state, seg_potted, n_balls, times, a):
    """Positions ``(T, N, 2)`` and potted flags ``(T, N)`` at each of ``times``."""
    out = np.empty((times.shape[0], n_balls, 2), dtype=np.float64)
    potted = np.empty((times.shape[0], n_balls), dtype=np.bool_)
    for k in range(times.shape[0]):
        pos, pot = positions_at(seg_ball, seg_t, seg_state, seg_potted, n_balls, times[k], a)
        out[k] = pos
        potted[k] = pot
    return out, potted
