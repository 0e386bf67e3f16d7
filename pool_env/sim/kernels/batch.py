"""Many independent tables in one compiled call, optionally parallel over tables (``prange``).

Each table runs the very same event loop as a single shot (:func:`loop.run_shot`, events not
recorded) on its active balls, so a batch gives bit-for-bit the results of one ``shoot()``
per table.
"""

from __future__ import annotations

import numpy as np
from numba import prange

from pool_env.sim.kernels._jit import kernel, parallel_kernel
from pool_env.sim.kernels.loop import IN_POCKET, OK, run_shot, validate


@kernel
def _allocate(positions):
    n_tables, n_balls = positions.shape[0], positions.shape[1]
    final = positions.copy()
    pocketed = np.full((n_tables, n_balls), -1, dtype=np.int64)
    n_events = np.zeros(n_tables, dtype=np.int64)
    capped = np.zeros(n_tables, dtype=np.bool_)
    first = np.full((n_tables, 2), -1, dtype=np.int64)
    error = np.zeros((n_tables, 3), dtype=np.int64)
    return final, pocketed, n_events, capped, first, error


@kernel
def _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out):
    """Validate and simulate table ``b``, writing into the output arrays ``out``."""
    final, pocketed, n_events, capped, first, error = out
    index = np.flatnonzero(active[b])
    if index.shape[0] == positions.shape[1]:  # every ball in play: views, no gathers
        pos, vel, mass = positions[b], velocities[b], masses[b]
    else:
        pos = np.ascontiguousarray(positions[b][index])
        vel = np.ascontiguousarray(velocities[b][index])
        mass = np.ascontiguousarray(masses[b][index])
    code, i, j = validate(pos, vel, mass, params, pockets)
    if code != OK:
        error[b, 0] = code
        error[b, 1] = index[i] if i >= 0 else -1
        error[b, 2] = index[j] if j >= 0 and code != IN_POCKET else j  # a pocket index stays
        return
    shot = run_shot(pos, vel, mass, params, pockets, max_events, False)
    for k in range(index.shape[0]):
        final[b, index[k], 0] = shot[0][k, 0]
        final[b, index[k], 1] = shot[0][k, 1]
        pocketed[b, index[k]] = shot[1][k]
    n_events[b] = shot[2]
    capped[b] = shot[4]
    if shot[5] >= 0:
        first[b, 0] = index[shot[5]]
        first[b, 1] = index[shot[6]]


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
        pockets: ``(K, 3)`` capture circles.
        max_events: Event cap per table.

    Returns:
        ``(final (B, N, 2), pocketed (B, N), n_events (B,), capped (B,), first_contact
        (B, 2), error (B, 3))``: ``first_contact`` holds the ball indices of each table's
        first ball-ball impact (-1 if none); ``error`` is a validation code and its ball
        indices per table, ``(0, -1, -1)`` when the table was valid (an invalid table is
        not simulated).
    """
    out = _allocate(positions)
    for b in range(positions.shape[0]):
        _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out)
    return out


@parallel_kernel
def run_batch_parallel(positions, velocities, masses, active, params, pockets, max_events):
    """:func:`run_batch` with the tables spread over threads."""
    out = _allocate(positions)
    for b in prange(positions.shape[0]):
        _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out)
    return out
