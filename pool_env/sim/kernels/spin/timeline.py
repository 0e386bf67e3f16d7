"""Exact positions at any time from a spin shot's trajectory segments (compiled).

Each segment row anchors a ball at its time with ``x, y, vx, vy, wx, wy, wz, ax, ay``
(:data:`~pool_env.sim.kernels.spin.level.SEG_COLS`); every transition is an event that
writes a row, so from its last row at or before ``t`` a ball follows
``p + v tau + acc tau^2 / 2`` exactly: the arithmetic of the loop's ``state_at``.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.timeline import last_rows


@kernel
def spin_positions_at(seg_ball, seg_t, seg_state, seg_potted, n_balls, t):
    """Ball positions at time ``t`` and whether each ball is potted by then."""
    last = last_rows(seg_ball, seg_t, n_balls, t)
    out = np.empty((n_balls, 2), dtype=np.float64)
    potted = np.zeros(n_balls, dtype=np.bool_)
    for i in range(n_balls):
        row = last[i]
        s = seg_state[row]
        tau = t - seg_t[row]
        out[i, 0] = s[0] + tau * (s[2] + 0.5 * s[7] * tau)
        out[i, 1] = s[1] + tau * (s[3] + 0.5 * s[8] * tau)
        potted[i] = seg_potted[row] != 0
    return out, potted


@kernel
def spin_positions_at_many(seg_ball, seg_t, seg_state, seg_potted, n_balls, times):
    """Positions ``(T, N, 2)`` and potted flags ``(T, N)`` at each of ``times``."""
    out = np.empty((times.shape[0], n_balls, 2), dtype=np.float64)
    potted = np.empty((times.shape[0], n_balls), dtype=np.bool_)
    for k in range(times.shape[0]):
        pos, pot = spin_positions_at(seg_ball, seg_t, seg_state, seg_potted, n_balls, times[k])
        out[k] = pos
        potted[k] = pot
    return out, potted
