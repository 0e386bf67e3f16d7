"""The one place that picks a table's model level, for the Python side of the simulator.

A model level (:mod:`pool_env.sim.kernels.level`) is a compiled strategy of the one event
loop; this module maps ``Table.model`` to what the Python entry points need of it: the
compiled entry points, the parameter array, the result type, and the messages of
a refused scene. :func:`pool_env.simulate`, :func:`pool_env.shoot`, the batch and the
rollout call :func:`level_of` and nothing else asks which level a table has. A third level
is one more entry in :data:`LEVELS` (and its kernel package).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.inputs import raise_invalid
from pool_env.sim.kernels import entries
from pool_env.sim.kernels.roll import level as roll_level
from pool_env.sim.kernels.roll.motion import struck_velocity
from pool_env.sim.kernels.spin import level as spin_level
from pool_env.sim.result import ShotResult, SpinShotResult
from pool_env.sim.spin_inputs import raise_spin_invalid, strike
from pool_env.sim.table import Table


def _raise_roll_invalid(
    code: int,
    i: int,
    j: int,
    table: Table,
    pos: NDArray[np.float64],
    vel: NDArray[np.float64],
    ang: NDArray[np.float64],
    mass: NDArray[np.float64],
) -> None:
    raise_invalid(code, i, j, table, pos, vel, mass)


def _roll_strike(
    table: Table, speed: float, angle: float, a: float, b: float, elevation: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    velocity = np.empty(2)
    struck_velocity(speed, angle, velocity)  # the roll level's compiled strike itself
    return velocity, np.zeros(3)


@dataclass(frozen=True)
class Level:
    """What the Python entry points need of one model level.

    Attributes:
        name: ``Table.model`` of its tables.
        kernels: Its entry points, the shared kernels for this level
            (:data:`~pool_env.sim.kernels.entries.Entries`).
        params_of: The flat parameter array its kernels read, from a table.
        result: The result type of one shot.
        raise_invalid: Raises the ``ValueError`` of a validation code ``(code, i, j,
            table, positions, velocities, angular, masses)``.
        strike: The struck ball's ``(velocity (2,), angular velocity (3,))`` from
            ``(table, speed, angle, a, b, elevation)``, for messages.
    """

    name: str
    kernels: entries.Entries
    params_of: Callable[[Table], NDArray[np.float64]]
    result: type[ShotResult]
    raise_invalid: Callable[..., None]
    strike: Callable[..., tuple[NDArray[np.float64], NDArray[np.float64]]]


#: Every model level, by ``Table.model``.
LEVELS: dict[str, Level] = {
    "roll": Level(
        "roll",
        roll_level.ENTRIES,
        lambda t: t.params,
        ShotResult,
        _raise_roll_invalid,
        _roll_strike,
    ),
    "spin": Level(
        "spin",
        spin_level.ENTRIES,
        lambda t: t.spin_params,
        SpinShotResult,
        raise_spin_invalid,
        strike,
    ),
}


def level_of(table: Table) -> Level:
    """The model level of ``table`` (a checked :class:`~pool_env.sim.table.Table`)."""
    return LEVELS[table.model]
