"""Closed forms and checks shared by the spin-level tests."""

from __future__ import annotations

import numpy as np

from pool_env import Table
from pool_env.sim.kernels.spin_loop import SEG_COLS


def kinetic_energy(table: Table, result, t: float, masses=None) -> float:
    """Translational plus rotational kinetic energy of every ball at time ``t``.

    From each ball's last segment row at or before ``t``: velocity ``v0 + acc tau``; the
    spin of a sliding row (``|acc| = mu_slide g``) ``w0 + (5 / 2R) tau (acc_y, -acc_x)``,
    of a rolling row ``(-vy, vx) / R``; ``wz`` falls at ``spin_decel`` to zero. A solid
    ball's moment of inertia is ``(2/5) m R^2``.
    """
    ball, seg_t, state, _ = result.segments
    assert state.shape[1] == SEG_COLS
    n = result.n_balls
    m = np.full(n, table.ball_mass) if masses is None else np.asarray(masses, float)
    r = table.ball_radius
    last = {}
    for row in range(seg_t.shape[0]):
        if seg_t[row] <= t:
            last[int(ball[row])] = row
    energy = 0.0
    for i in range(n):
        s = state[last[i]]
        tau = t - seg_t[last[i]]
        acc = np.hypot(s[7], s[8])
        v = s[2:4] + s[7:9] * tau
        if acc == 0.0:
            wxy = s[4:6]
        elif abs(acc - table.mu_slide * table.g) <= 1e-12 * acc:
            wxy = s[4:6] + 2.5 / r * tau * np.array([s[8], -s[7]])
        else:
            wxy = np.array([-v[1], v[0]]) / r
        wz = np.sign(s[6]) * max(abs(s[6]) - table.spin_decel * tau, 0.0)
        w2 = wxy @ wxy + wz * wz
        energy += 0.5 * m[i] * (v @ v) + 0.2 * m[i] * r * r * w2
    return energy


def violations(table: Table, result, times) -> float:
    """Largest overlap of two balls or excursion past a rail over ``times`` (m)."""
    r = table.ball_radius
    pos, potted = result.positions_at_many(np.asarray(times, dtype=float))
    worst = 0.0
    for frame, pot in zip(pos, potted, strict=True):
        q = frame[~pot]
        if q.size == 0:
            continue
        worst = max(
            worst,
            (r - q[:, 0]).max(),
            (q[:, 0] - (table.length - r)).max(),
            (r - q[:, 1]).max(),
            (q[:, 1] - (table.width - r)).max(),
        )
        if len(q) > 1:
            d = np.hypot(q[:, None, 0] - q[None, :, 0], q[:, None, 1] - q[None, :, 1])
            d[np.diag_indices(len(q))] = np.inf
            worst = max(worst, 2.0 * r - d.min())
    return worst
