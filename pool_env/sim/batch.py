"""Batched simulation: many independent tables in one compiled, parallel call.

The front of :mod:`pool_env.sim.kernels.batch` for vectorized environments and bulk evaluation.
Results equal one :func:`pool_env.shoot` per table, bit for bit.
"""

from __future__ import annotations

import itertools
import os
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.inputs import (
    DEFAULT_MAX_EVENTS,
    as_active,
    as_batch_masses,
    as_batch_points,
    check_max_events,
    check_table,
    kernel_array,
)
from pool_env.sim.kernels import validation
from pool_env.sim.kernels.packing import BatchOutput
from pool_env.sim.levels import level_of
from pool_env.sim.table import Table

#: Batches this large and larger run in parallel by default.
PARALLEL_FROM = 64


def _batch_angular(
    table: Table, value: ArrayLike | None, n_tables: int, n_balls: int
) -> NDArray[np.float64]:
    """``(B, N, 3)`` angular velocities of a batch (zeros for ``None``; spin tables only)."""
    if value is None:
        return np.zeros((n_tables, n_balls, 3))
    if not table.has_spin:
        raise ValueError(
            "angular_velocities need the spin level: use Table(model='spin'); the roll "
            "level has no spin"
        )
    arr = kernel_array("angular_velocities", value, "a (B, N, 3) array")
    if arr.shape != (n_tables, n_balls, 3):
        raise ValueError(
            f"angular_velocities must have shape {(n_tables, n_balls, 3)}, got {arr.shape}"
        )
    return arr


@dataclass(frozen=True, slots=True)
class BatchResult:
    """Final states of ``B`` tables.

    Attributes:
        positions: ``(B, N, 2)`` final positions (inactive balls keep their input rows).
        pocketed: ``(B, N)``: -1 on the table (or inactive), ``k`` captured by pocket ``k``.
        n_events: ``(B,)`` events per table.
        hit_event_cap: ``(B,)`` whether a table reached ``max_events``.
        first_contact: ``(B, 2)`` balls of each table's first ball-ball impact, -1 if none.
        first_hit: ``(B, N)`` the first ball each ball touched, -1 if none (or inactive).
        cushions_after_contact: ``(B, N)`` each ball's cushion impacts after its table's
            first ball-ball impact (see :attr:`pool_env.ShotResult.cushions_after_contact`).
        pocket_order: ``(B, N)`` the order in which each table's balls dropped (0 first),
            -1 on the table (or inactive).
        stopped_by_cap: ``(B, N)`` the balls that were still moving when a table reached
            ``max_events`` and were stopped there (all False on tables under the cap).
        second_hit: ``(B, N)`` the second distinct ball each ball touched, -1 if none (or
            inactive).
        cushions_at_second: ``(B, N)`` each ball's own cushion impacts from the shot's
            start up to its second distinct ball contact, -1 without one (see
            :attr:`pool_env.ShotResult.cushions_at_second`).
    """

    positions: NDArray[np.float64]
    pocketed: NDArray[np.int64]
    n_events: NDArray[np.int64]
    hit_event_cap: NDArray[np.bool_]
    first_contact: NDArray[np.int64]
    first_hit: NDArray[np.int64]
    cushions_after_contact: NDArray[np.int64]
    pocket_order: NDArray[np.int64]
    stopped_by_cap: NDArray[np.bool_]
    second_hit: NDArray[np.int64]
    cushions_at_second: NDArray[np.int64]


def batch_result(out: BatchOutput) -> BatchResult:
    """The :class:`BatchResult` of a kernel's :data:`~pool_env.sim.kernels.packing.BatchOutput`."""
    return BatchResult(
        positions=out.positions,
        pocketed=out.pocketed,
        n_events=out.n_events,
        hit_event_cap=out.capped,
        first_contact=out.first_contact,
        first_hit=out.first_hit,
        cushions_after_contact=out.cushions_after_contact,
        pocket_order=out.pocket_order,
        stopped_by_cap=out.stopped_by_cap,
        second_hit=out.second_hit,
        cushions_at_second=out.cushions_at_second,
    )


def check_threads(threads: object) -> int | None:
    """A positive thread count, or ``None`` (every CPU)."""
    if threads is not None and (
        isinstance(threads, bool) or not isinstance(threads, int | np.integer) or threads < 1
    ):
        raise ValueError(f"threads must be a positive integer or None, got {threads!r}")
    return threads  # type: ignore[return-value]


def simulate_batch(
    table: Table,
    positions: ArrayLike,
    velocities: ArrayLike,
    masses: ArrayLike | None = None,
    active: ArrayLike | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    parallel: bool | None = None,
    angular_velocities: ArrayLike | None = None,
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
        angular_velocities: ``(B, N, 3)`` initial angular velocities on a spin table
            (``Table(model="spin")``; ``None``: no spin); must be ``None`` on a roll table.
            A spin batch gives bit for bit one :func:`pool_env.simulate` per table.

    Returns:
        The :class:`BatchResult`.

    Raises:
        ValueError: On malformed arrays, or naming the first invalid table and its problem
            (as :func:`pool_env.simulate` would); no table is simulated then.
    """
    table = check_table(table)
    pos = as_batch_points("positions", positions)
    vel = as_batch_points("velocities", velocities, pos.shape)
    n_tables, n_balls = pos.shape[:2]
    mass = as_batch_masses(table, masses, n_tables, n_balls)
    on = as_active(active, n_tables, n_balls)
    max_events = check_max_events(max_events)
    if parallel is None:
        parallel = n_tables >= PARALLEL_FROM
    ang = _batch_angular(table, angular_velocities, n_tables, n_balls)
    out = _batch_output(table, pos, vel, ang, mass, on, max_events, parallel)
    raise_batch_error(table, out.error, pos, vel, ang, mass)
    return batch_result(out)


def _batch_output(
    table: Table,
    pos: NDArray[np.float64],
    vel: NDArray[np.float64],
    ang: NDArray[np.float64],
    mass: NDArray[np.float64],
    on: NDArray[np.bool_],
    max_events: int,
    parallel: bool,
) -> BatchOutput:
    """The kernel's output for checked arrays (``ang`` zeros on a roll table); no raise."""
    level = level_of(table)
    run = level.kernels.run_batch_parallel if parallel else level.kernels.run_batch
    return run(pos, vel, ang, mass, on, level.params_of(table), table.pocket_geometry, max_events)


def raise_batch_error(
    table: Table,
    error: NDArray[np.int64],
    pos: NDArray[np.float64],
    vel: NDArray[np.float64],
    ang: NDArray[np.float64],
    mass: NDArray[np.float64],
) -> None:
    """Raise the ``ValueError`` of the first table whose ``error`` row is not ``OK``.

    ``error`` is the kernel's ``(B, 3)`` rows of validation codes and indices (see
    :data:`~pool_env.sim.kernels.packing.BatchOutput`); the message names the table by its
    row and says what :func:`pool_env.simulate` would say of it.
    """
    codes = error[:, 0]
    if (codes == validation.OK).all():
        return
    bad = np.flatnonzero(codes != validation.OK)
    b = int(bad[0])
    code, i, j = (int(v) for v in error[b])
    try:
        level_of(table).raise_invalid(code, i, j, table, pos[b], vel[b], ang[b], mass[b])
    except ValueError as exc:
        raise ValueError(f"table {b}: {exc}") from None


_pool: tuple[int, int, ThreadPoolExecutor] | None = None  # (owner pid, workers, pool)
_pool_lock = threading.Lock()


def _forget_pool_in_child() -> None:
    """A forked child has none of the parent's threads, and maybe a lock held by one."""
    global _pool, _pool_lock
    _pool, _pool_lock = None, threading.Lock()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_pool_in_child)


def available_cpus() -> int:
    """CPUs this process may run on (its affinity mask where the OS has one)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def thread_pool(workers: int) -> ThreadPoolExecutor:
    """The process's shared pool, with at least ``workers`` threads.

    A caller that needs more threads gets a new, larger pool; the old one is never shut
    down (another thread may be submitting to it at that moment): it is only dropped, and
    its idle threads end once nothing refers to it.
    """
    global _pool
    with _pool_lock:
        if _pool is None or _pool[0] != os.getpid() or _pool[1] < workers:
            pool = ThreadPoolExecutor(workers, thread_name_prefix="pool_env")
            _pool = (os.getpid(), workers, pool)
        return _pool[2]


def simulate_batch_threads(
    table: Table,
    positions: ArrayLike,
    velocities: ArrayLike,
    active: ArrayLike,
    threads: int | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    angular_velocities: ArrayLike | None = None,
) -> BatchResult:
    """:func:`simulate_batch` split into one serial batch per thread, results joined.

    The serial kernel releases the GIL, so Python threads run the parts side by side. Unlike
    numba's ``prange`` (whose default OpenMP layer spin-waits), idle threads sleep: on a
    machine shared with other busy processes this stays faster than one thread, where the
    ``prange`` path was measured 2-3 times slower. Results equal the serial call bit for bit.

    Args:
        table: The table.
        positions: ``(B, N, 2)`` ball centres.
        velocities: ``(B, N, 2)`` initial velocities.
        active: ``(B, N)`` which balls are on each table.
        threads: Parts to split into, a positive integer (default: :func:`available_cpus`).
        max_events: Event cap per table.
        angular_velocities: ``(B, N, 3)`` on a spin table, as for :func:`simulate_batch`.

    Returns:
        The joined :class:`BatchResult`.

    Raises:
        ValueError: As :func:`simulate_batch`, naming the table by its index in the batch.
    """
    table = check_table(table)
    positions = as_batch_points("positions", positions)
    velocities = as_batch_points("velocities", velocities, positions.shape)
    n = positions.shape[0]
    ang = _batch_angular(table, angular_velocities, n, positions.shape[1])
    active = as_active(active, n, positions.shape[1])
    max_events = check_max_events(max_events)
    threads = check_threads(threads)
    if min(threads or available_cpus(), n) <= 1:
        return simulate_batch(
            table, positions, velocities, active=active, max_events=max_events,
            angular_velocities=None if angular_velocities is None else ang,
        )  # fmt: skip
    return run_batch_arrays(table, positions, velocities, ang, active, threads, max_events)


def run_batch_arrays(
    table: Table,
    positions: NDArray[np.float64],
    velocities: NDArray[np.float64],
    angular: NDArray[np.float64] | None,
    active: NDArray[np.bool_],
    threads: int | None = 1,
    max_events: int = DEFAULT_MAX_EVENTS,
) -> BatchResult:
    """The batch of arrays its caller vouches for: no argument checked again.

    For the game layer's step, whose state holds the kernels' arrays already (C-ordered
    float64 ``(B, N, 2)``, boolean ``(B, N)``, a checked table): each scene is still
    validated inside the compiled call, so a bad one raises as :func:`simulate_batch`
    does. ``angular`` is ``(B, N, 3)`` on a spin table, ``None`` for no spin; ``threads``
    splits the batch as :func:`simulate_batch_threads` does (``None``: every CPU; one
    part runs serially).
    """
    n, n_balls = positions.shape[:2]
    ang = np.zeros((n, n_balls, 3)) if angular is None else angular
    mass = np.full((n, n_balls), table.ball_mass)
    parts = min(threads or available_cpus(), n)
    if parts <= 1:
        out = _batch_output(table, positions, velocities, ang, mass, active, max_events, False)
        raise_batch_error(table, out.error, positions, velocities, ang, mass)
        return batch_result(out)
    edges = [n * i // parts for i in range(parts + 1)]  # each table alone: any split is exact

    def part(lo: int, hi: int) -> BatchOutput:
        return _batch_output(
            table, positions[lo:hi], velocities[lo:hi], ang[lo:hi],
            mass[lo:hi], active[lo:hi], max_events, False,
        )  # fmt: skip

    bounds = list(itertools.pairwise(edges))
    # The calling thread takes the last part itself instead of sleeping until the others end.
    pool = thread_pool(parts - 1)
    futures = [pool.submit(part, lo, hi) for lo, hi in bounds[:-1]]
    last = part(*bounds[-1])
    outs = [f.result() for f in futures] + [last]
    out = BatchOutput(*(np.concatenate([o[k] for o in outs]) for k in range(len(last))))
    raise_batch_error(table, out.error, positions, velocities, ang, mass)
    return batch_result(out)
