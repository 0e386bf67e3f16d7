"""Public entry points: ``simulate`` and ``shoot``. Validate, run the compiled loop, wrap."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.kernels import loop
from pool_env.sim.result import ShotResult
from pool_env.sim.table import Table

#: Default event cap. A 16-ball break has a few hundred events; pooltool's FastFiz
#: ancestor used 5,000. A shot that reaches the cap is reported, never hangs.
DEFAULT_MAX_EVENTS = 10_000


def _as_points(name: str, value: ArrayLike, n: int | None) -> NDArray[np.float64]:
    try:
        arr = np.ascontiguousarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be an (N, 2) array of numbers: {exc}") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (N, 2), got {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ValueError(f"{name} has {arr.shape[0]} rows for {n} balls")
    return arr


# Masses left to the kernels: every ball weighs the table's ball_mass.
_TABLE_MASSES = np.empty(0, dtype=np.float64)
_TABLE_MASSES.setflags(write=False)


def _as_masses(masses: ArrayLike | None, n: int) -> NDArray[np.float64]:
    if masses is None:
        return _TABLE_MASSES
    try:
        arr = np.ascontiguousarray(masses, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"masses must be a sequence of N numbers: {exc}") from None
    if arr.shape != (n,):
        raise ValueError(f"masses must have shape ({n},), got {arr.shape}")
    return arr


def _raise_invalid(code: int, i: int, j: int, positions: NDArray[np.float64], table: Table) -> None:
    if code == loop.BAD_POSITION:
        raise ValueError(f"ball {i} has a non-finite position {positions[i].tolist()}")
    if code == loop.BAD_VELOCITY:
        raise ValueError(f"ball {i} has a non-finite velocity")
    if code == loop.BAD_MASS:
        raise ValueError(f"ball {i} has a mass that is not a positive finite number")
    if code == loop.OFF_TABLE:
        r = table.ball_radius
        throats = " or in a pocket's throat" if table.pocket_model == "jaws" else ""
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is off the table: centres must lie in "
            f"[{r}, {table.length - r}] x [{r}, {table.width - r}]{throats}"
        )
    if code == loop.IN_JAW:
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is inside a jaw (facing or point) of pocket {j}"
        )
    if code == loop.BEHIND_LINE:
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is on or behind pocket {j}'s fall line"
        )
    if code == loop.IN_POCKET:
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is inside pocket {j}'s capture circle"
        )
    if code == loop.OVERLAP:
        d = float(np.hypot(*(positions[j] - positions[i])))
        raise ValueError(
            f"balls {i} and {j} overlap: centres {d:.12g} m apart, less than 2R = "
            f"{2 * table.ball_radius} m"
        )


def simulate(
    table: Table,
    positions: ArrayLike,
    velocities: ArrayLike,
    masses: ArrayLike | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    record: bool = True,
) -> ShotResult:
    """Simulate balls on ``table`` from the given state until everything rests.

    Args:
        table: The table.
        positions: ``(N, 2)`` ball centres (m), inside the rails, not overlapping (up to
            1e-9 m of rounding), not inside a pocket's capture circle.
        velocities: ``(N, 2)`` initial velocities (m/s).
        masses: ``(N,)`` masses (kg); defaults to ``table.ball_mass`` for every ball.
        max_events: Event cap; a shot that reaches it stops every ball where it is and
            sets ``hit_event_cap``.
        record: Keep the event list and the trajectories (for ``events`` and
            ``positions_at``). Training loops that only need the final state pass False.

    Returns:
        The :class:`~pool_env.sim.result.ShotResult`.

    Raises:
        ValueError: On malformed, non-finite or out-of-table input, overlapping balls, a
            non-positive mass, or a bad ``max_events``. Inputs are never modified.
    """
    pos = _as_points("positions", positions, None)
    return _run(
        table, pos, _as_points("velocities", velocities, pos.shape[0]), masses, max_events, record
    )


def _run(
    table: Table,
    pos: NDArray[np.float64],
    vel: NDArray[np.float64],
    masses: ArrayLike | None,
    max_events: int,
    record: bool,
) -> ShotResult:
    """:func:`simulate` once ``pos`` and ``vel`` are float64 arrays of matching shapes."""
    if not isinstance(table, Table):
        raise ValueError(f"table must be a pool_env.Table, got {type(table).__name__}")
    n = pos.shape[0]
    mass = _as_masses(masses, n)
    if type(max_events) is not int and (
        isinstance(max_events, bool) or not isinstance(max_events, np.integer)
    ):
        raise ValueError(f"max_events must be a non-negative integer, got {max_events!r}")
    if max_events < 0:
        raise ValueError(f"max_events must be a non-negative integer, got {max_events!r}")
    if not record:  # one compiled call: validation and the loop, final state only
        final = np.empty((n, 2))
        balls = np.empty((loop.N_BALL_ROWS, n), dtype=np.int64)
        meta = np.empty(loop.N_META, dtype=np.int64)
        duration = loop.shoot_final(
            pos, vel, mass, table.params, table.pocket_geometry, int(max_events), final, balls, meta
        )
        if meta[loop.META_CODE] != loop.OK:
            code, i, j = meta[loop.META_CODE : loop.META_J + 1].tolist()
            _raise_invalid(code, i, j, pos, table)
        return ShotResult.unrecorded(final, balls, meta, duration, table.deceleration)
    code, i, j = loop.validate(pos, vel, mass, table.params, table.pocket_geometry)
    if code != loop.OK:
        _raise_invalid(code, i, j, pos, table)
    raw = loop.run_shot(pos, vel, mass, table.params, table.pocket_geometry, int(max_events), True)
    return ShotResult(raw, table.deceleration, True)


def shoot(
    table: Table,
    positions: ArrayLike,
    angle: float,
    speed: float,
    cue: int = 0,
    masses: ArrayLike | Sequence[float] | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    record: bool = True,
) -> ShotResult:
    """Strike ball ``cue`` at ``speed`` (m/s) along ``angle`` (radians from +x); others rest.

    Args:
        table: The table.
        positions: ``(N, 2)`` ball centres (see :func:`simulate`).
        angle: Direction of the shot, radians counter-clockwise from the +x axis.
        speed: Cue ball speed (m/s), non-negative.
        cue: Index of the struck ball.
        masses: Optional per-ball masses.
        max_events: Event cap.
        record: Keep events and trajectories (see :func:`simulate`).

    Returns:
        The :class:`~pool_env.sim.result.ShotResult`.

    Raises:
        ValueError: On a non-finite angle, a negative or non-finite speed, a cue index out
            of range, or any problem :func:`simulate` rejects.
    """
    pos = _as_points("positions", positions, None)
    angle = float(angle)
    speed = float(speed)
    if angle - angle != 0.0:  # inf or NaN
        raise ValueError(f"angle must be finite, got {angle!r}")
    if not (math.isfinite(speed) and speed >= 0.0):
        raise ValueError(f"speed must be a non-negative finite number, got {speed!r}")
    n = pos.shape[0]
    if (type(cue) is not int and not isinstance(cue, np.integer)) or not (0 <= cue < n):
        raise ValueError(f"cue must be a ball index in [0, {n}), got {cue!r}")
    vel = np.zeros((n, 2))
    vel[cue] = (speed * math.cos(angle), speed * math.sin(angle))
    return _run(table, pos, vel, masses, max_events, record)
