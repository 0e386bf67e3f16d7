"""Batched simulation: many independent tables in one compiled, parallel call.

The front of :mod:`pool_env.kernels.batch` for vectorized environments and bulk evaluation.
Results equal one :func:`pool_env.shoot` per table, bit for bit.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.kernels import batch as _batch
from pool_env.kernels import loop
from pool_env.simulate import DEFAULT_MAX_EVENTS, _raise_invalid
from pool_env.table import Table

#: Batches this large and larger run in parallel by default.
PARALLEL_FROM = 64


@dataclass(frozen=True, slots=True)
class BatchResult:
    """Final states of ``B`` tables.

    Attributes:
        positions: ``(B, N, 2)`` final positions (inactive balls keep their input rows).
        pocketed: ``(B, N)``: -1 on the table (or inactive), ``k`` captured by pocket ``k``.
        n_events: ``(B,)`` events per table.
        hit_event_cap: ``(B,)`` whether a table reached ``max_events``.
        first_contact: ``(B, 2)`` balls of each table's first ball-ball impact, -1 if none.
    """

    positions: NDArray[np.float64]
    pocketed: NDArray[np.int64]
    n_events: NDArray[np.int64]
    hit_event_cap: NDArray[np.bool_]
    first_contact: NDArray[np.int64]


def simulate_batch(
    table: Table,
    positions: ArrayLike,
    velocities: ArrayLike,
    masses: ArrayLike | None = None,
    active: ArrayLike | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    parallel: bool | None = None,
) -> BatchResult:
    """Simulate ``B`` tables, each from its own state, until everything rests.

    Args:
        table: The table (shared by all).
        positions: ``(B, N, 2)`` ball centres.
        velocities: ``(B, N, 2)`` initial velocities.
        masses: ``(N,)`` or ``(B, N)`` masses; default ``table.ball_mass``.
        active: ``(B, N)`` booleans, which balls are on each table; default all.
        max_events: Event cap per table.
        parallel: Spread the tables over numba's threads; ``None`` does so from
            :data:`PARALLEL_FROM` tables on, where it pays for the threads' start-up.

    Returns:
        The :class:`BatchResult`.

    Raises:
        ValueError: On malformed arrays, or naming the first invalid table and its problem
            (as :func:`pool_env.simulate` would); no table is simulated then.
    """
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    vel = np.ascontiguousarray(velocities, dtype=np.float64)
    if pos.ndim != 3 or pos.shape[2] != 2:
        raise ValueError(f"positions must have shape (B, N, 2), got {pos.shape}")
    if vel.shape != pos.shape:
        raise ValueError(f"velocities must have shape {pos.shape}, got {vel.shape}")
    n_tables, n_balls = pos.shape[:2]
    if masses is None:
        mass = np.full((n_tables, n_balls), table.ball_mass)
    else:
        mass = np.ascontiguousarray(
            np.broadcast_to(np.asarray(masses, np.float64), (n_tables, n_balls))
        )
    on = np.ones((n_tables, n_balls), np.bool_) if active is None else np.asarray(active, np.bool_)
    if on.shape != (n_tables, n_balls):
        raise ValueError(f"active must have shape {(n_tables, n_balls)}, got {on.shape}")
    if parallel is None:
        parallel = n_tables >= PARALLEL_FROM
    run = _batch.run_batch_parallel if parallel else _batch.run_batch
    final, pocketed, n_events, capped, first, error = run(
        pos, vel, mass, np.ascontiguousarray(on), table.params, table.pockets, int(max_events)
    )
    bad = np.flatnonzero(error[:, 0] != loop.OK)
    if bad.size:
        b = int(bad[0])
        try:
            _raise_invalid(int(error[b, 0]), int(error[b, 1]), int(error[b, 2]), pos[b], table)
        except ValueError as exc:
            raise ValueError(f"table {b}: {exc}") from None
    return BatchResult(final, pocketed, n_events, capped, first)
