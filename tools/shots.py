"""A shot to check and what an engine reports of it: the records the checkers and benchmarks share.

:class:`Scene` is one shot (a table, the balls' initial state, the ball whose direction is
measured); :class:`Outcome` is what an engine reports of it, in this project's frame and
units. The checkers (:mod:`tools.hard_cases`, :mod:`tools.chaos`) describe their cases with
them, and the benchmarks (``bench/``: the seeded suites of ``bench/scenes.py``, the engines'
runners, the error measures of ``bench/errors.py``) run and compare them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from pool_env import Table


@dataclass(frozen=True, eq=False)
class Scene:
    """One shot: a table, the initial state, and the ball whose direction is measured.

    Attributes:
        name: Unique label (family and index).
        family: Suite family.
        table: The table.
        positions: ``(N, 2)`` centres.
        velocities: ``(N, 2)`` initial velocities.
        obj: Object ball: its direction after its first ball-ball impact is compared.
        masses: ``(N,)`` masses, or None for the table's ball mass.
    """

    name: str
    family: str
    table: Table
    positions: NDArray[np.float64]
    velocities: NDArray[np.float64]
    obj: int = 1
    masses: NDArray[np.float64] | None = None

    @property
    def n_balls(self) -> int:
        """Number of balls."""
        return int(self.positions.shape[0])

    def mass_array(self) -> NDArray[np.float64]:
        """``(N,)`` masses (the table's ball mass if none were given)."""
        if self.masses is None:
            return np.full(self.n_balls, self.table.ball_mass)
        return np.asarray(self.masses, dtype=np.float64)


@dataclass
class Outcome:
    """What every engine reports about one shot, in our frame and units.

    Attributes:
        positions: ``(N, 2)`` final centres; a potted ball keeps its capture point.
        pocketed: ``(N,)`` pocket index per ball, -1 on the table.
        obj_velocity: The object ball's velocity right after its first ball-ball impact
            (NaN if it was never hit).
        pairs: Pairs ``(i, j)``, ``i < j``, that collided at least once.
        capped: The run hit its step or event cap.
        error: Why there is no outcome (crash, hang), else None.
    """

    positions: NDArray[np.float64]
    pocketed: NDArray[np.int64]
    obj_velocity: NDArray[np.float64]
    pairs: set[tuple[int, int]] = field(default_factory=set)
    capped: bool = False
    error: str | None = None
