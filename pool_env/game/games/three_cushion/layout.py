"""The UMB starting position and the frozen cue ball (balls in contact).

Ball columns: 0 white (player 0's cue ball), 1 yellow (player 1's), 2 red. The starting
position (UMB World Rules of Carom Billiard, art. 23 "Starting position, cue-ball", with
the spots of art. 13): the red on the top spot, the opponent's ball on the head spot, the
striker's ball on the starting line (the head string) beside it. The offset beside it is
pooltool 0.6's (``layouts._get_three_cushion_rack``: 0.1825 m across the table from the
head spot); UMB lets the striker choose the side: here the side of the higher ``y``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.table import Table

#: The starting ball's offset from the head spot along the head string (m).
STARTING_OFFSET = 0.1825
#: A cue ball within this gap (m) of another ball is frozen to it (touching, to rounding).
FROZEN_GAP = 1e-6
RED = 2


def starting_layout(table: Table, striker: int = 0) -> NDArray[np.float64]:
    """``(3, 2)`` the starting position with ``striker``'s cue ball (0 or 1) to play."""
    head = (table.length / 4.0, table.width / 2.0)
    layout = np.empty((3, 2))
    layout[RED] = (3.0 * table.length / 4.0, table.width / 2.0)  # the top spot
    layout[1 - striker] = head
    layout[striker] = (head[0], head[1] + STARTING_OFFSET)
    return layout


def break_scene(table: Table, rng: np.random.Generator) -> NDArray[np.float64]:
    """The game's scene ``"three_cushion"``: the starting position, white to break."""
    return starting_layout(table, 0)


def frozen(
    positions: NDArray[np.float64], cue: NDArray[np.int64], radius: float
) -> NDArray[np.bool_]:
    """``(K,)`` whether each table's cue ball ``cue[k]`` touches another ball."""
    rows = np.arange(positions.shape[0])
    gap = np.linalg.norm(positions - positions[rows, cue][:, None, :], axis=2) - 2.0 * radius
    gap[rows, cue] = np.inf
    return np.any(gap <= FROZEN_GAP, axis=1)
