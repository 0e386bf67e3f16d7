"""Many independent tables in one compiled call, optionally parallel over tables (``prange``).

Each table runs the very same event loop as a single shot (:func:`loop.run_shot`, events not
recorded) on its active balls, so a batch gives bit-for-bit the results of one ``shoot()``
per table.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import prange

from pool_env.sim.jit import kernel, parallel_kernel
from pool_env.sim.kernels.loop import BEHIND_LINE, IN_JAW, IN_POCKET, OK, run_shot, validate

#: What :func:`run_batch` returns, by name; ball indices count all ``N`` balls of a table.
#:
#: * ``positions`` ``(B, N, 2)``, ``pocketed``, ``pocket_order``, ``first_hit``,
#:   ``cushions_after_contact`` ``(B, N)``: as the fields of that name of
#:   :data:`~pool_env.sim.kernels.loop.ShotOutput`, per table (an inactive ball keeps its
#:   input position, -1 and 0).
#: * ``n_events`` ``(B,)``, ``capped`` ``(B,)``.
#: * ``first_contact`` ``(B, 2)``: each table's first ball-ball impact, -1 if none.
#: * ``error`` ``(B, 3)``: a validation code and its ball indices (a pocket index for
#:   ``IN_POCKET``), ``(OK, -1, -1)`` when the table was valid (an invalid table is not
#:   simulated).
BatchOutput = namedtuple(
    "BatchOutput",
    [
        "positions",
        "pocketed",
        "pocket_order",
        "first_hit",
        "cushions_after_contact",
        "n_events",
        "capped",
        "first_contact",
        "error",
        "stopped_by_cap",
    ],
)


@kernel
def _allocate(positions):
    n_tables, n_balls = positions.shape[0], positions.shape[1]
    return BatchOutput(
        positions.copy(),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.full((n_tables, n_balls), -1, dtype=np.int64),
        np.zeros((n_tables, n_balls), dtype=np.int64),
        np.zeros(n_tables, dtype=np.int64),
        np.zeros(n_tables, dtype=np.bool_),
        np.full((n_tables, 2), -1, dtype=np.int64),
        np.zeros((n_tables, 3), dtype=np.int64),
        np.zeros((n_tables, n_balls), dtype=np.bool_),
    )


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
        out.error[b, 0] = code
        out.error[b, 1] = index[i] if i >= 0 else -1
        pocket = (code == IN_POCKET) | (code == IN_JAW) | (code == BEHIND_LINE)
        out.error[b, 2] = index[j] if j >= 0 and not pocket else j  # a pocket index stays
        return
    shot = run_shot(pos, vel, mass, params, pockets, max_events, False)
    for k in range(index.shape[0]):
        ball = index[k]
        out.positions[b, ball, 0] = shot.positions[k, 0]
        out.positions[b, ball, 1] = shot.positions[k, 1]
        out.pocketed[b, ball] = shot.pocketed[k]
        out.pocket_order[b, ball] = shot.pocket_order[k]
        hit = shot.first_hit[k]
        out.first_hit[b, ball] = index[hit] if hit >= 0 else -1
        out.cushions_after_contact[b, ball] = shot.cushions_after_contact[k]
        out.stopped_by_cap[b, ball] = shot.stopped_by_cap[k] != 0
    out.n_events[b] = shot.n_events
    out.capped[b] = shot.capped
    if shot.first_i >= 0:
        out.first_contact[b, 0] = index[shot.first_i]
        out.first_contact[b, 1] = index[shot.first_j]


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
        A :data:`BatchOutput`.
    """
    out = _allocate(positions)
    for b in range(positions.shape[0]):
        _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out)
    return out


@kernel
def _fields(out):
    """``out`` as a plain tuple: numba's ``prange`` cannot hand a named tuple to its threads."""
    return (out[0], out[1], out[2], out[3], out[4], out[5], out[6], out[7], out[8], out[9])


@kernel
def _one_table_of(b, positions, velocities, masses, active, params, pockets, max_events, fields):
    """:func:`_one_table` writing into the plain tuple of a :data:`BatchOutput`'s fields."""
    out = BatchOutput(*fields)
    _one_table(b, positions, velocities, masses, active, params, pockets, max_events, out)


@parallel_kernel
def run_batch_parallel(positions, velocities, masses, active, params, pockets, max_events):
    """:func:`run_batch` with the tables spread over threads."""
    out = _allocate(positions)
    fields = _fields(out)
    for b in prange(positions.shape[0]):
        _one_table_of(b, positions, velocities, masses, active, params, pockets, max_events, fields)
    return out
