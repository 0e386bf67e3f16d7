"""Many independent tables in one compiled call, optionally parallel over tables (``prange``).

Each table runs the very same event loop as a single shot (:func:`loop._shoot`, events not
recorded) on its active balls, so a batch gives bit-for-bit the results of one ``shoot()``
per table.
"""

from __future__ import annotations

import numpy as np
from numba import prange

from pool_env.sim.jit import kernel, parallel_kernel
from pool_env.sim.kernels.loop import _shoot
from pool_env.sim.kernels.packing import (
    BatchOutput,
    allocate_batch,
    batch_fields,
    store_error,
    store_table,
)
from pool_env.sim.kernels.validation import BEHIND_LINE, IN_JAW, IN_POCKET, OK, validate


@kernel
def _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out):
    """Validate and simulate table ``b``, writing into the :data:`BatchOutput` ``out``."""
    index = np.flatnonzero(active[b])
    if index.shape[0] == positions.shape[1]:  # every ball in play: views, no gathers
        pos, vel, mass = positions[b], velocities[b], masses[b]
    else:
        pos = np.ascontiguousarray(positions[b][index])
        vel = np.ascontiguousarray(velocities[b][index])
        mass = np.ascontiguousarray(masses[b][index])
    code, i, j = validate(pos, vel, mass, params, pockets)
    if code != OK:
        pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
        store_error(out, b, index, code, i, j, pocket)
        return
    st, balls, first_i, first_j, n_ev, _, capped, _, _, _ = _shoot(
        pos, vel, mass, params, pockets, max_events, False
    )
    store_table(out, b, index, st, balls, first_i, first_j, n_ev, capped)


@kernel
def run_batch(positions, velocities, masses, active, params, pockets, max_events):
    """Simulate ``B`` tables of up to ``N`` balls each to rest, one after the other.

    Args:
        positions: ``(B, N, 2)`` ball centres.
        velocities: ``(B, N, 2)`` initial velocities.
        masses: ``(B, N)`` masses.
        active: ``(B, N)`` booleans: which balls are on each table (others are ignored and
            keep their row as it is).
        params: The table's flat parameter array.
        pockets: ``Table.pocket_geometry`` (capture circles or jaws).
        max_events: Event cap per table.

    Returns:
        A :data:`~pool_env.sim.kernels.packing.BatchOutput`.
    """
    out = allocate_batch(positions)
    for b in range(positions.shape[0]):
        _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out)
    return out


@kernel
def _one_table_of(b, positions, velocities, masses, active, params, pockets, max_events, fields):
    """:func:`_one_table` writing into the plain tuple of a :data:`BatchOutput`'s fields."""
    out = BatchOutput(*fields)
    _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out)


@parallel_kernel
def run_batch_parallel(positions, velocities, masses, active, params, pockets, max_events):
    """:func:`run_batch` with the tables spread over threads."""
    out = allocate_batch(positions)
    fields = batch_fields(out)
    for b in prange(positions.shape[0]):
        _one_table_of(b, positions, velocities, masses, active, params, pockets, max_events, fields)
    return out
