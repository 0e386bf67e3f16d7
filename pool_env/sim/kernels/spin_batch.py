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
from pool_env.sim.kernels.packing import (
    BatchOutput,
    allocate_batch,
    batch_fields,
    store_error,
    store_table,
)
from pool_env.sim.kernels.spin_loop import shoot_spin, validate_spin_scene
from pool_env.sim.kernels.validation import BEHIND_LINE, IN_JAW, IN_POCKET, OK


@kernel
def _one_table(b, positions, velocities, angular, masses, active, prm, pockets, max_events, out):
    """Validate and simulate spin table ``b``, writing into the ``BatchOutput`` ``out``."""
    index = np.flatnonzero(active[b])
    pos = np.ascontiguousarray(positions[b][index])
    vel = np.ascontiguousarray(velocities[b][index])
    ang = np.ascontiguousarray(angular[b][index])
    mass = np.ascontiguousarray(masses[b][index])
    code, i, j = validate_spin_scene(pos, vel, ang, mass, prm, pockets)
    if code != OK:
        pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
        store_error(out, b, index, code, i, j, pocket)
        return
    st, _, balls, first_i, first_j, n_ev, _, capped, _, _, _ = shoot_spin(
        pos, vel, ang, mass, prm, pockets, max_events, False
    )
    store_table(out, b, index, st, balls, first_i, first_j, n_ev, capped)


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
        A :data:`~pool_env.sim.kernels.packing.BatchOutput`.
    """
    out = allocate_batch(positions)
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
    out = allocate_batch(positions)
    fields = batch_fields(out)
    for b in prange(positions.shape[0]):
        _one_table_of(
            b, positions, velocities, angular, masses, active, prm, pockets, max_events, fields
        )
    return out
