"""Many independent tables in one compiled call, optionally parallel over tables (``prange``).

Written once for every model level (the marker ``level`` picks one, as for the loop). Each
table runs the very same event loop as a single shot (:func:`loop.shoot`, events not
recorded) on its active balls, so a batch gives bit-for-bit the results of one ``shoot()``
per table.
"""

from __future__ import annotations

import numpy as np
from numba import prange

from pool_env.sim.jit import kernel, parallel_kernel
from pool_env.sim.kernels.level import check_scene
from pool_env.sim.kernels.loop import shoot
from pool_env.sim.kernels.packing import (
    BatchOutput,
    allocate_batch,
    batch_fields,
    store_error,
    store_table,
)
from pool_env.sim.kernels.validation import BEHIND_LINE, IN_JAW, IN_POCKET, OK


@kernel
def _one_table(
    level, b, positions, velocities, angular, masses, active, prm, pockets, max_events, out
):
    """Validate and simulate table ``b``, writing into the :data:`BatchOutput` ``out``."""
    index = np.flatnonzero(active[b])
    if index.shape[0] == positions.shape[1]:  # every ball in play: views, no gathers
        pos, vel, ang, mass = positions[b], velocities[b], angular[b], masses[b]
    else:
        pos = np.ascontiguousarray(positions[b][index])
        vel = np.ascontiguousarray(velocities[b][index])
        ang = np.ascontiguousarray(angular[b][index])
        mass = np.ascontiguousarray(masses[b][index])
    code, i, j = check_scene(level, pos, vel, ang, mass, prm, pockets)
    if code != OK:
        pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
        store_error(out, b, index, code, i, j, pocket)
        return
    st, _, balls, first_i, first_j, n_ev, _, capped, _, _, _ = shoot(
        level, pos, vel, ang, mass, prm, pockets, max_events, False
    )
    store_table(out, b, index, st, balls, first_i, first_j, n_ev, capped)


@kernel
def run_batch(level, positions, velocities, angular, masses, active, prm, pockets, max_events):
    """Simulate ``B`` tables of up to ``N`` balls each to rest, one after the other.

    Args:
        level: The model level's marker (``ROLL`` or ``SPIN``).
        positions: ``(B, N, 2)`` ball centres.
        velocities: ``(B, N, 2)`` initial velocities.
        angular: ``(B, N, 3)`` initial angular velocities (zeros on a level without spin).
        masses: ``(B, N)`` masses.
        active: ``(B, N)`` booleans: which balls are on each table (others are ignored and
            keep their row as it is).
        prm: The level's flat parameter array (``Table.params``, ``Table.spin_params``).
        pockets: ``Table.pocket_geometry`` (capture circles or jaws).
        max_events: Event cap per table.

    Returns:
        A :data:`~pool_env.sim.kernels.packing.BatchOutput`.
    """
    out = allocate_batch(positions)
    for b in range(positions.shape[0]):
        _one_table(
            level, b, positions, velocities, angular, masses, active, prm, pockets,
            max_events, out,
        )  # fmt: skip
    return out


@kernel
def _one_table_of(
    level, b, positions, velocities, angular, masses, active, prm, pockets, max_events, fields
):
    """:func:`_one_table` writing into the plain tuple of a :data:`BatchOutput`'s fields."""
    out = BatchOutput(*fields)
    _one_table(
        level, b, positions, velocities, angular, masses, active, prm, pockets, max_events, out
    )


@parallel_kernel
def run_batch_parallel(
    level, positions, velocities, angular, masses, active, prm, pockets, max_events
):
    """:func:`run_batch` with the tables spread over threads."""
    out = allocate_batch(positions)
    fields = batch_fields(out)
    for b in prange(positions.shape[0]):
        _one_table_of(
            level, b, positions, velocities, angular, masses, active, prm, pockets,
            max_events, fields,
        )  # fmt: skip
    return out
