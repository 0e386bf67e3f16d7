"""Ghost-ball geometry for the baselines: the game's compiled geometry, one shot at a time.

The geometry itself (pocket mouths, the ghost-ball point, clear paths, speeds) is the
game's, compiled and batched (:mod:`pool_env.game.geometry`); this module gives the
planners its shots of one layout as :class:`GhostShot` records, and names the targets a
player may aim at. See :mod:`pool_env.game.geometry` for the frame and the terms.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env import Table
from pool_env.game import formulas
from pool_env.game import geometry as geo
from pool_env.game.geometry import (
    MAX_CUT,
    MIN_APPROACH_COS,
    PocketMouths,
    path_clear,
    pocket_mouths,
)

__all__ = [
    "MAX_CUT",
    "MIN_APPROACH_COS",
    "GhostShot",
    "LegalTargets",
    "PocketMouths",
    "any_object_ball",
    "cue_speed",
    "ghost_shots",
    "path_clear",
    "pocket_mouths",
]

#: Which object balls a player may aim at: ``(positions, on_table) -> ball indices``.
#: A rules game replaces the default (any object ball on the table) with its own.
LegalTargets = Callable[[NDArray[np.float64], NDArray[np.bool_]], list[int]]


def any_object_ball(positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> list[int]:
    """The default legal targets: every object ball on the table (ball 0 is the cue)."""
    return [int(j) for j in on_table.nonzero()[0] if j != 0]


@dataclass(frozen=True)
class GhostShot:
    """One direct shot: object ball ``ball`` into pocket ``pocket`` via the ghost-ball point.

    Attributes:
        ball: Object ball index.
        pocket: Pocket index.
        angle: Direction of the cue ball (radians from +x), cue to the ghost-ball point.
        cut: Signed cut angle (radians; positive when the object ball leaves
            counter-clockwise of the cue ball's path).
        ghost: The ghost-ball point ``(x, y)``.
        cue_distance: Cue ball centre to the ghost-ball point (m).
        ball_distance: Object ball centre to the pocket target (m).
        travel: Distance the object ball rolls until it drops (m).
        approach_cos: Cosine of the angle between its path and the mouth's normal.
        tolerance: Aim error (radians of cue direction) the shot forgives, to first order.
        clear: Whether both paths are free of the other balls.
    """

    ball: int
    pocket: int
    angle: float
    cut: float
    ghost: tuple[float, float]
    cue_distance: float
    ball_distance: float
    travel: float
    approach_cos: float
    tolerance: float
    clear: bool


def ghost_shots(
    table: Table,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    targets: list[int],
    offset: float = 0.0,
    max_cut: float = MAX_CUT,
    cue: int = 0,
) -> list[GhostShot]:
    """Every direct ghost-ball shot on ``targets`` whose cut is below ``max_cut``.

    The valid rows of :func:`pool_env.game.geometry.ghost_shots` for one layout (which says
    when a shot is kept and how its tolerance ranks it).

    Args:
        table: The table (ball radius and size).
        mouths: Its pockets (:func:`pocket_mouths`).
        positions: ``(N, 2)`` ball centres, cue first.
        on_table: ``(N,)`` which balls are on the table.
        targets: The object balls one may aim at.
        offset: Aim point sideways from each target, as a fraction of the mouth's
            half-width seen along the path (the search agent varies it).
        max_cut: Thinnest cut kept (radians).
        cue: The cue ball's index.

    Returns:
        The shots, in the order ball, pocket.
    """
    rows = geo.ghost_shots(
        table, mouths, positions[None], on_table[None], [list(targets)], offset, max_cut, cue
    )[0]
    shots = []
    for t, b in enumerate(targets):
        for k in range(mouths.n):
            row = rows[t, k].tolist()
            if row[geo.VALID] == 0.0:
                continue
            shots.append(
                GhostShot(
                    ball=int(b),
                    pocket=k,
                    angle=row[geo.ANGLE],
                    cut=row[geo.CUT],
                    ghost=(row[geo.GX], row[geo.GY]),
                    cue_distance=row[geo.CUE_DIST],
                    ball_distance=row[geo.BALL_DIST],
                    travel=row[geo.TRAVEL],
                    approach_cos=row[geo.APPROACH],
                    tolerance=row[geo.TOLERANCE],
                    clear=row[geo.CLEAR_PATH] > 0.0,
                )
            )
    return shots


def cue_speed(table: Table, shot: GhostShot, arrival_speed: float) -> float:
    """Cue speed (m/s) at which the object ball drops at ``arrival_speed``.

    The game's rule (:func:`pool_env.game.geometry.cue_speeds`): the rolling deceleration
    over the object ball's travel and the cue ball's distance, and the collision's
    ``(1 + e) / 2 cos(cut)`` between them.
    """
    return formulas.cue_speed(
        table.deceleration, table.e_ball, shot.travel, shot.cut, shot.cue_distance, arrival_speed
    )
