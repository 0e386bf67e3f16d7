"""Many independent spin tables in one compiled call (the spin level's batch).

The sibling of :mod:`pool_env.sim.kernels.batch` (whose roll-level code it leaves as it
is): each table runs the spin loop's :func:`~pool_env.sim.kernels.spin_loop.shoot_spin`
without recording, on its active balls, so a batch gives bit-for-bit the results of one
``simulate()`` per table. Results are written into the roll batch's
:data:`~pool_env.sim.kernels.batch.BatchOutput`.
"""

from __future__ import annotations

import numpy as np
from numba import prange

from pool_env.sim.jit import kernel, parallel_kernel
from pool_env.sim.kernels.batch import BatchOutput, _allocate, _fields
from pool_env.sim.kernels.loop import (
    BALL_CUSHIONS,
    BALL_FIRST_HIT,
    BALL_POCKET,
    BALL_POCKET_ORDER,
    BALL_STOPPED,
    BEHIND_LINE,
    IN_JAW,
    IN_POCKET,
    OK,
    validate,
)
from pool_env.sim.kernels.params import P_RADIUS
from pool_env.sim.kernels.spin_loop import shoot_spin, validate_spins
from pool_env.sim.kernels.spin_state import PX, PY


@kernel
def _one_table(b, positions, velocities, angular, masses, active, prm, pockets, max_events, out):
    """Validate and simulate spin table ``b``, writing into the ``BatchOutput`` ``out``."""
    index = np.flatnonzero(active[b])
    pos = np.ascontiguousarray(positions[b][index])
    vel = np.ascontiguousarray(velocities[b][index])
    ang = np.ascontiguousarray(angular[b][index])
    mass = np.ascontiguousarray(masses[b][index])
    code, i, j = validate(pos, vel, mass, prm, pockets)
    if code == OK:
        code, i, j = validate_spins(ang, prm[P_RADIUS])
    if code != OK:
        out.error[b, 0] = code
        out.error[b, 1] = index[i] if i >= 0 else -1
        pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
        out.error[b, 2] = index[j] if j >= 0 and not pocket else j
        return
    st, _, balls, first_i, first_j, n_ev, _, capped, _, _, _ = shoot_spin(
        pos, vel, ang, mass, prm, pockets, max_events, False
    )
    for k in range(index.shape[0]):
        ball = index[k]
        out.positions[b, ball, 0] = st[k, PX]
        out.positions[b, ball, 1] = st[k, PY]
        out.pocketed[b, ball] = balls[BALL_POCKET, k]
        out.pocket_order[b, ball] = balls[BALL_POCKET_ORDER, k]
        hit = balls[BALL_FIRST_HIT, k]
        out.first_hit[b, ball] = index[hit] if hit >= 0 else -1
        out.cushions_after_contact[b, ball] = balls[BALL_CUSHIONS, k]
        out.stopped_by_cap[b, ball] = balls[BALL_STOPPED, k] != 0
    out.n_events[b] = n_ev
    out.capped[b] = capped
    if first_i >= 0:
        out.first_contact[b, 0] = index[first_i]
        out.first_contact[b, 1] = index[first_j]


@kernel
def run_spin_batch(positions, velocities, angular, masses, active, prm, pockets, max_events):
    """Simulate ``B`` spin tables to rest, one after the other.

    Args:
        positions, velocities: ``(B, N, 2)``.
        angular: ``(B, N, 3)`` angular velocities.
        masses: ``(B, N)``.
        active: ``(B, N)`` booleans: the balls on each table.
        prm: ``Table.spin_params``.
        pockets: ``Table.pocket_geometry``.
        max_events: Event cap per table.

    Returns:
        A :data:`~pool_env.sim.kernels.batch.BatchOutput`.
    """
    out = _allocate(positions)
    for b in range(positions.shape[0]):
        _one_table(b, positions, velocities, angular, masses, active, prm, pockets, max_events, out)
    return out


@kernel
def _one_table_of(
    b, positions, velocities, angular, masses, active, prm, pockets, max_events, fields
):
    out = BatchOutput(*fields)
    _one_table(b, positions, velocities, angular, masses, active, prm, pockets, max_events, out)


@parallel_kernel
def run_spin_batch_parallel(
    positions, velocities, angular, masses, active, prm, pockets, max_events
):
    """:func:`run_spin_batch` with the tables spread over threads."""
    out = _allocate(positions)
    fields = _fields(out)
    for b in prange(positions.shape[0]):
        _one_table_of(
            b, positions, velocities, angular, masses, active, prm, pockets, max_events, fields
        )
    return out
