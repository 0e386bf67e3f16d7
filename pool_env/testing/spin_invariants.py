"""Invariant checks of the spin level on a recorded shot (tests and the fuzz's spin mode).

The geometry and termination checks of :mod:`pool_env.testing.invariants` hold as they
are (they read only positions); this module adds the spin level's energy, which counts
rotation: a solid ball's kinetic energy is ``m |v|^2 / 2 + (1/5) m R^2 |w|^2``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from pool_env.sim.result import SpinShotResult
from pool_env.sim.table import Table

ENERGY_RTOL = 1e-12


def kinetic_energy(table: Table, result: SpinShotResult, t: float, masses=None) -> float:
    """Translational plus rotational kinetic energy of every ball at time ``t``.

    From each ball's last segment row at or before ``t``: velocity ``v0 + acc tau``; the
    spin of a sliding row (``|acc| = mu_slide g``) ``w0 + (5 / 2R) tau (acc_y, -acc_x)``,
    of a rolling row ``(-vy, vx) / R``; ``wz`` falls at ``spin_decel`` to zero. Written
    from the equations of motion, not from the kernels' code.
    """
    ball, seg_t, state, _ = result.segments
    n = result.n_balls
    m = np.full(n, table.ball_mass) if masses is None else np.asarray(masses, float)
    r = table.ball_radius
    last: dict[int, int] = {}
    for row in range(seg_t.shape[0]):
        if seg_t[row] <= t:
            last[int(ball[row])] = row
    energy = 0.0
    for i in range(n):
        s = state[last[i]]
        tau = t - seg_t[last[i]]
        acc = float(np.hypot(s[7], s[8]))
        v = s[2:4] + s[7:9] * tau
        if acc == 0.0:
            wxy = s[4:6]
        elif abs(acc - table.mu_slide * table.g) <= 1e-12 * acc:
            wxy = s[4:6] + 2.5 / r * tau * np.array([s[8], -s[7]])
        else:
            wxy = np.array([-v[1], v[0]]) / r
        wz = np.sign(s[6]) * max(abs(s[6]) - table.spin_decel * tau, 0.0)
        energy += 0.5 * m[i] * float(v @ v) + 0.2 * m[i] * r * r * float(wxy @ wxy + wz * wz)
    return energy


def check_spin_energy(
    table: Table, result: SpinShotResult, masses: ArrayLike | None = None
) -> list[str]:
    """E: the kinetic energy (with rotation) after each event never exceeds the one before."""
    times = np.unique(np.concatenate([[0.0], result.event_times, [result.duration]]))
    energy = [kinetic_energy(table, result, t, masses) for t in times]
    rises = [
        f"E: energy rose from {a!r} to {b!r} at t={t}"
        for a, b, t in zip(energy, energy[1:], times[1:], strict=False)
        if b > a * (1 + ENERGY_RTOL) + 1e-300
    ]
    return rises[:5]
