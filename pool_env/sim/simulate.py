"""Public entry points: ``simulate`` and ``shoot``. Validate, run the compiled loop, wrap."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.inputs import (
    DEFAULT_MAX_EVENTS,
    TABLE_MASSES,
    as_masses,
    as_points,
    check_angle,
    check_cue,
    check_max_events,
    check_speed,
    check_table,
    raise_invalid,
)
from pool_env.sim.kernels import validation
from pool_env.sim.levels import level_of
from pool_env.sim.result import ShotResult
from pool_env.sim.spin_inputs import as_angular, check_tip
from pool_env.sim.table import Table

__all__ = ["DEFAULT_MAX_EVENTS", "check_positions", "shoot", "simulate", "simulate_checked_arrays"]


def simulate(
    table: Table,
    positions: ArrayLike,
    velocities: ArrayLike,
    masses: ArrayLike | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    record: bool = True,
    angular_velocities: ArrayLike | None = None,
) -> ShotResult:
    """Simulate balls on ``table`` from the given state until everything rests.

    Args:
        table: The table.
        positions: ``(N, 2)`` ball centres (m), inside the rails, not overlapping (up to
            1e-9 m of rounding), not inside a pocket's capture circle.
        velocities: ``(N, 2)`` initial velocities (m/s).
        masses: ``(N,)`` masses (kg); defaults to ``table.ball_mass`` for every ball.
        max_events: Event cap; a shot that reaches it stops every ball where it is, sets
            ``hit_event_cap`` and flags the balls it stopped in ``stopped_by_cap``.
        record: Keep the event list and the trajectories (for ``events`` and
            ``positions_at``). Training loops that only need the final state pass False.
        angular_velocities: ``(N, 3)`` initial angular velocities ``(wx, wy, wz)`` (rad/s)
            on a spin table (``Table(model="spin")``); ``None`` means no spin (a ball given
            a velocity and no spin starts sliding). Must be ``None`` on a roll table.

    Returns:
        The :class:`~pool_env.sim.result.ShotResult` (a
        :class:`~pool_env.sim.result.SpinShotResult` on a spin table).

    Raises:
        ValueError: On malformed, non-finite or out-of-table input, overlapping balls, a
            non-positive mass, a bad ``max_events``, or angular velocities on a roll table
            (or non-finite, or with a surface speed ``R |w|`` beyond the speed limit).
            Inputs are never modified.

    Examples:
        A head-on hit on a table without pockets: the first impact comes when the rolling
        cue ball has closed the gap, ``s = v t - a t^2 / 2``; ball 1 runs to the far rail
        and back into the cue ball, which kept ``(1 - e) / 2`` of its speed.

        >>> import numpy as np
        >>> from pool_env import Table, simulate
        >>> table = Table(pockets="none")
        >>> positions = np.array([[1.0, 0.635], [1.5, 0.635]])
        >>> result = simulate(table, positions, np.array([[1.0, 0.0], [0.0, 0.0]]))
        >>> [event.kind for event in result.events]
        ['ball', 'stop', 'cushion', 'ball', 'stop', 'stop']
        >>> a, gap = table.mu_roll * table.g, 0.5 - 2 * table.ball_radius
        >>> t = (1.0 - (1.0 - 2 * a * gap) ** 0.5) / a
        >>> abs(result.events[0].time - t) < 1e-15
        True
        >>> result.pocketed
        array([-1, -1])
    """
    pos = as_points("positions", positions)
    vel = as_points("velocities", velocities, pos.shape[0])
    table = check_table(table)
    if not table.has_spin and angular_velocities is not None:
        raise ValueError(
            "angular_velocities need the spin level: use Table(model='spin'); the roll "
            "level has no spin"
        )
    ang = as_angular(table, angular_velocities, pos.shape[0])
    mass = as_masses(masses, pos.shape[0])
    max_events = check_max_events(max_events)
    level = level_of(table)
    raw = level.kernels.packed_shot(
        pos, vel, ang, mass, level.params_of(table), table.pocket_geometry, max_events,
        bool(record),  # one compiled version: a bool, never an int
    )  # fmt: skip  # one compiled call: validation, the loop and the result, in one buffer
    if raw[0] != validation.OK:
        level.raise_invalid(raw[0], raw[1], raw[2], table, pos, vel, ang, mass)
    return level.result(raw, pos.shape[0], table.deceleration, bool(record))


def simulate_checked_arrays(
    table: Table,
    positions: NDArray[np.float64],
    velocities: NDArray[np.float64],
    angular_velocities: NDArray[np.float64] | None,
    record: bool,
) -> ShotResult:
    """:func:`simulate` for a caller whose arrays are already the kernel's (the game layer).

    The internal entry point: no Python argument checks (their cost is about a tenth of a
    two-ball shot). The caller guarantees a checked ``table``, C-contiguous float64
    ``(N, 2)`` positions and velocities, ``(N, 3)`` angular velocities or ``None``
    (``None`` on a roll table), the table's ball mass and the default event cap. The scene
    itself is still validated inside the compiled call, as :func:`simulate` does, so a
    state the rules got wrong raises the same ``ValueError`` instead of running.

    Returns:
        What :func:`simulate` returns for the same arguments, bit for bit.
    """
    level = level_of(table)
    n = positions.shape[0]
    ang = np.zeros((n, 3)) if angular_velocities is None else angular_velocities
    record = bool(record)
    raw = level.kernels.packed_shot(
        positions, velocities, ang, TABLE_MASSES, level.params_of(table),
        table.pocket_geometry, DEFAULT_MAX_EVENTS, record,
    )  # fmt: skip
    if raw[0] != validation.OK:
        level.raise_invalid(raw[0], raw[1], raw[2], table, positions, velocities, ang, TABLE_MASSES)
    return level.result(raw, n, table.deceleration, record)


def shoot(
    table: Table,
    positions: ArrayLike,
    angle: float,
    speed: float,
    cue: int = 0,
    masses: ArrayLike | Sequence[float] | None = None,
    max_events: int = DEFAULT_MAX_EVENTS,
    record: bool = True,
    *,
    tip: tuple[float, float] = (0.0, 0.0),
    elevation: float = 0.0,
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
        tip: The cue tip's offset ``(a, b)`` from the ball's centre, in fractions of the
            radius in [-1, 1]: ``a`` side (+ right english, seen from behind the cue),
            ``b`` vertical (+ above centre: follow; - draw). Spin table only.
        elevation: The cue's elevation (radians, in [0, pi/2)). Spin table only. On a spin
            table ``speed`` stays the cue ball's speed in the table plane after the strike
            and ``angle`` the aim of the cue (the ball leaves at the aim less the squirt).

    Returns:
        The :class:`~pool_env.sim.result.ShotResult`.

    Raises:
        ValueError: On a non-finite angle, a negative or non-finite speed, a cue index out
            of range, a tip or elevation out of range, a strike that would spin the ball
            beyond the speed limit (``R |w|`` above ``limits.MAX_SPEED``: a near-vertical
            cue), a non-zero tip or elevation on a roll table (use
            ``Table(model="spin")``), or any problem :func:`simulate` rejects.

    Examples:
        >>> from pool_env import Table, shoot
        >>> result = shoot(Table(), [[0.635, 0.635], [1.27, 0.635]], angle=0.0, speed=2.0)
        >>> result.first_hit  # the cue ball touched ball 1 first, and ball 1 the cue ball
        array([1, 0])
        >>> shoot(Table(), [[0.635, 0.635]], angle=0.0, speed=-1.0)
        Traceback (most recent call last):
        ...
        ValueError: ...speed...
    """
    table = check_table(table)
    pos = as_points("positions", positions)
    angle = check_angle(angle)
    speed = check_speed(speed, table)
    n = pos.shape[0]
    cue = check_cue(cue, n)
    a, b, elevation = check_tip(table, tip, elevation)
    mass = as_masses(masses, n)
    max_events = check_max_events(max_events)
    level = level_of(table)
    raw = level.kernels.packed_strike(
        pos, cue, speed, angle, a, b, elevation, mass, level.params_of(table),
        table.pocket_geometry, max_events, bool(record),
    )  # fmt: skip  # the strike, validation, the loop and the result: one compiled call
    if raw[0] != validation.OK:  # the arrays the message names, rebuilt (rare)
        vel, ang = np.zeros((n, 2)), np.zeros((n, 3))
        vel[cue], ang[cue] = level.strike(table, speed, angle, a, b, elevation)
        level.raise_invalid(raw[0], raw[1], raw[2], table, pos, vel, ang, mass)
    return level.result(raw, n, table.deceleration, bool(record))


def check_positions(table: Table, positions: ArrayLike) -> NDArray[np.float64]:
    """Check that balls at rest at ``positions`` are a state :func:`simulate` accepts.

    Args:
        table: The table.
        positions: ``(N, 2)`` ball centres.

    Returns:
        The positions as a new contiguous float64 array.

    Raises:
        ValueError: As :func:`simulate` would, naming the first ball off the table, inside
            a pocket or overlapping another (nothing is simulated).
    """
    table = check_table(table)
    pos = np.array(as_points("positions", positions))
    vel, mass = np.zeros_like(pos), as_masses(None, pos.shape[0])
    code, i, j = validation.validate(pos, vel, mass, table.params, table.pocket_geometry)
    if code != validation.OK:
        raise_invalid(code, i, j, table, pos, vel, mass)
    return pos
