"""Batched rollout: ``S`` cue shots from one layout in one compiled call per thread.

The simulator's counterpart of ``mujoco.rollout``, for search and planning: a planner that
weighs candidate shots (or the noise draws of one shot) from the same layout hands them
over as rows of one array and reads back the final positions, the pots and the first
contacts. Shot ``s`` gives bit for bit what ``shoot(table, positions, *shots[s], cue)``
gives; the kernels are :mod:`pool_env.sim.kernels.rollout_kernel`.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.batch import (
    BatchResult,
    available_cpus,
    batch_result,
    check_threads,
    thread_pool,
)
from pool_env.sim.inputs import (
    DEFAULT_MAX_EVENTS,
    as_masses,
    as_points,
    check_cue,
    check_max_events,
    check_table,
    kernel_array,
)
from pool_env.sim.kernels import rollout_kernel
from pool_env.sim.kernels.packing import BatchOutput, allocate_batch
from pool_env.sim.kernels.validation import OK
from pool_env.sim.levels import level_of
from pool_env.sim.spin_inputs import tip_touches_ball
from pool_env.sim.table import Table

__all__ = ["SHOT_COLUMNS", "rollout"]

SHOT_COLUMNS = rollout_kernel.SHOT_COLUMNS

#: Shots per thread below which a rollout stays on the calling thread: a part costs a
#: thread hand-over (tens of microseconds), a two-ball shot about five.
SHOTS_PER_THREAD = 64


def _as_shots(table: Table, shots: ArrayLike) -> NDArray[np.float64]:
    """``(S, SHOT_COLUMNS)`` checked shot rows from ``(S, 2)`` or ``(S, 5)`` input."""
    arr = kernel_array("shots", shots, "an (S, 2) or (S, 5) array")
    if arr.ndim != 2 or arr.shape[1] not in (2, SHOT_COLUMNS):
        raise ValueError(
            "shots must have shape (S, 2) (angle, speed) or (S, 5) (angle, speed, tip a, "
            f"tip b, elevation), got {arr.shape}"
        )
    if arr.shape[1] == 2:
        full = np.zeros((arr.shape[0], SHOT_COLUMNS))
        full[:, :2] = arr
        arr = full
    angle, speed = arr[:, rollout_kernel.SHOT_ANGLE], arr[:, rollout_kernel.SHOT_SPEED]
    a, b = arr[:, rollout_kernel.SHOT_TIP_A], arr[:, rollout_kernel.SHOT_TIP_B]
    elevation = arr[:, rollout_kernel.SHOT_ELEVATION]
    checks = (
        (np.isfinite(angle), "has a non-finite angle"),
        (speed >= 0.0, "needs a non-negative finite speed"),  # NaN fails
        (np.isfinite(speed), "needs a non-negative finite speed"),
        ((np.abs(a) <= 1.0) & (np.abs(b) <= 1.0), "has tip offsets outside [-1, 1]"),
        (tip_touches_ball(table, a, b), "has a tip that meets the ball off its surface"),
        ((elevation >= 0.0) & (elevation < 0.5 * math.pi), "has elevation outside [0, pi/2)"),
    )
    for ok, problem in checks:
        bad = np.flatnonzero(~ok)
        if bad.size:
            s = int(bad[0])
            raise ValueError(f"shot {s} {problem}: {arr[s].tolist()}")
    if not table.has_spin and np.any(arr[:, 2:] != 0.0):
        s = int(np.flatnonzero(np.any(arr[:, 2:] != 0.0, axis=1))[0])
        raise ValueError(
            f"shot {s} puts spin on the ball (a tip offset or elevation): the roll level has "
            "none, use Table(model='spin')"
        )
    return arr


def _as_on(active: ArrayLike | None, n: int, cue: int) -> NDArray[np.intp]:
    """The rows of the balls in play (``active`` ``(N,)`` booleans, default all)."""
    if active is None:
        return np.arange(n)
    on = np.asarray(active)
    if on.dtype.kind not in "biu" or on.shape != (n,):
        raise ValueError(f"active must be {n} booleans, got {on.dtype} of shape {on.shape}")
    if not on[cue]:
        raise ValueError(f"the cue ball {cue} is not active")
    return np.flatnonzero(on)


def _raise_shot(
    table: Table,
    s: int,
    error: NDArray[np.int64],
    positions: NDArray[np.float64],
    shot: NDArray[np.float64],
    cue: int,
    mass: NDArray[np.float64],
) -> None:
    """Raise the ``ValueError`` of shot ``s``'s validation code (indices of the full layout)."""
    code, i, j = (int(v) for v in error)
    vel = np.zeros_like(positions)
    ang = np.zeros((positions.shape[0], 3))
    level = level_of(table)
    try:
        vel[cue], ang[cue] = level.strike(table, shot[1], shot[0], shot[2], shot[3], shot[4])
        level.raise_invalid(code, i, j, table, positions, vel, ang, mass)
    except ValueError as exc:
        raise ValueError(f"shot {s}: {exc}") from None


def rollout(
    table: Table,
    positions: ArrayLike,
    shots: ArrayLike,
    cue: int = 0,
    masses: ArrayLike | None = None,
    active: ArrayLike | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    threads: int | None = None,
) -> BatchResult:
    """Play ``S`` cue shots from one layout; return each one's final state.

    Each shot strikes ball ``cue`` (the others at rest) and runs to rest, unrecorded, as
    :func:`pool_env.shoot` would: row ``s`` of every result equals ``shoot(table,
    positions, angle, speed, cue, masses, tip=(a, b), elevation=e)`` with the row's values,
    bit for bit. Execution noise is the caller's: add the draws to the rows.

    Args:
        table: The table (either level).
        positions: ``(N, 2)`` ball centres, the layout every shot starts from.
        shots: ``(S, 5)`` rows ``(angle, speed, tip a, tip b, elevation)`` as
            :func:`pool_env.shoot` takes them, or ``(S, 2)`` rows ``(angle, speed)`` (a
            centre hit). The tip and elevation must be zero on a roll table.
        cue: The struck ball.
        masses: ``(N,)`` masses; default ``table.ball_mass``.
        active: ``(N,)`` booleans, the balls on the table (default all); the others are
            left out of every shot and keep their rows (the cue ball must be active).
        max_events: The event cap of each shot.
        threads: Threads to split the shots over (default: :func:`available_cpus`); the
            result does not depend on it.

    Returns:
        A :class:`~pool_env.sim.batch.BatchResult` of ``S`` rows, fresh arrays: final
        ``positions``, ``pocketed``, ``first_contact``, ``first_hit``, ... of each shot.

    Raises:
        ValueError: On malformed input, or naming the first shot the simulator refuses and
            why (as :func:`pool_env.shoot` would: a layout it rejects, a speed or a spin
            beyond the limits); no result is returned then.

    Examples:
        >>> import numpy as np
        >>> from pool_env import Table
        >>> from pool_env.sim import rollout
        >>> layout = np.array([[0.635, 0.635], [1.27, 0.635]])
        >>> out = rollout(Table(), layout, [[0.0, 2.0], [np.pi / 2, 0.2]])
        >>> out.first_contact.tolist()  # straight at ball 1; slowly away from it
        [[0, 1], [-1, -1]]
    """
    table = check_table(table)
    pos_all = as_points("positions", positions)
    n = pos_all.shape[0]
    cue = check_cue(cue, n)
    rows = _as_shots(table, shots)
    mass_all = as_masses(masses, n)
    index = _as_on(active, n, cue)
    max_events = check_max_events(max_events)
    threads = check_threads(threads)
    pos = np.ascontiguousarray(pos_all[index])
    mass = np.ascontiguousarray(mass_all[index]) if mass_all.shape[0] else mass_all
    compact_cue = int(np.searchsorted(index, cue))
    n_shots = rows.shape[0]
    # Every shot starts from the layout: inactive balls keep their rows.
    fields = tuple(allocate_batch(np.repeat(pos_all[None], n_shots, axis=0)))
    level = level_of(table)
    run, prm, pockets = level.kernels.run_shots, level.params_of(table), table.pocket_geometry

    def part(lo: int, hi: int) -> None:
        run(pos, mass, index, compact_cue, rows, prm, pockets, max_events, lo, hi, fields)

    parts = max(1, min(threads or available_cpus(), n_shots // SHOTS_PER_THREAD))
    edges = np.linspace(0, n_shots, parts + 1).astype(np.int64).tolist()
    bounds = list(itertools.pairwise(edges))
    if parts > 1:
        # The calling thread takes the last part itself; the kernel releases the GIL.
        futures = [thread_pool(parts - 1).submit(part, lo, hi) for lo, hi in bounds[:-1]]
        part(*bounds[-1])
        for f in futures:
            f.result()
    else:
        part(0, n_shots)
    out = BatchOutput(*fields)
    bad = np.flatnonzero(out.error[:, 0] != OK)
    if bad.size:
        s = int(bad[0])
        _raise_shot(table, s, out.error[s], pos_all, rows[s], cue, mass_all)
    return batch_result(out)
