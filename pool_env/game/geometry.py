"""The table's geometry for players: where a ball may be, ghost-ball shots, clear paths, speeds.

The public, batched face of the compiled kernels (:mod:`pool_env.game.kernels.geometry`,
:mod:`pool_env.game.kernels.layout`): the agents' baselines and observation features ask
these questions of many layouts or many candidate shots in one call, and the game asks
the same kernels where a ball may be placed. Pockets are read once per table as mouths
(:func:`pocket_mouths`).

A ghost-shot row (``(..., NG)`` float64) has the columns :data:`VALID`, :data:`ANGLE`,
:data:`CUT`, :data:`GX`, :data:`GY`, :data:`CUE_DIST`, :data:`BALL_DIST`, :data:`TRAVEL`,
:data:`APPROACH`, :data:`TOLERANCE`, :data:`CLEAR_PATH`, :data:`AIM_X`, :data:`AIM_Y`,
:data:`COS_CUT`
(:func:`ghost_shots` says what each holds).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.game.kernels import geometry as kg
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.geometry import (
    AIM_X,
    AIM_Y,
    ANGLE,
    APPROACH,
    BALL_DIST,
    CLEAR_PATH,
    COS_CUT,
    CUE_DIST,
    CUT,
    GX,
    GY,
    NG,
    TOLERANCE,
    TRAVEL,
    VALID,
)
from pool_env.game.kernels.layout import free_points
from pool_env.game.pockets import MIN_APPROACH_COS, PocketMouths, pocket_mouths
from pool_env.game.scenes import placement
from pool_env.sim import Table

__all__ = [
    "AIM_X",
    "AIM_Y",
    "ANGLE",
    "APPROACH",
    "BALL_DIST",
    "CLEAR_PATH",
    "COS_CUT",
    "CUE_DIST",
    "CUT",
    "GX",
    "GY",
    "MAX_CUT",
    "MIN_APPROACH_COS",
    "NG",
    "TOLERANCE",
    "TRAVEL",
    "VALID",
    "PocketMouths",
    "cue_speeds",
    "ghost_contact",
    "ghost_shots",
    "path_clear",
    "pocket_mouths",
    "points_free",
]

#: Cuts thinner than this need more speed than the cue ball keeps control of, and a contact
#: too thin to trust (85 degrees: the thinnest that pots more on the jaw table than on 80).
MAX_CUT = math.radians(85.0)


def ghost_shots(
    table: Table,
    mouths: PocketMouths,
    positions: ArrayLike,
    on_table: ArrayLike,
    targets: ArrayLike,
    offset: float = 0.0,
    max_cut: float = MAX_CUT,
    cue: int = 0,
) -> NDArray[np.float64]:
    """Every direct ghost-ball shot of ``B`` layouts on their target balls, every pocket.

    A shot is valid when the mouth is open to the object ball's path (its half-tolerance
    :meth:`PocketMouths.half_tolerance` is positive), the ghost-ball point is where a ball
    centre can be, the cut is below ``max_cut`` and the ball's path reaches the drop;
    whether the paths are clear of the other balls is a column. The *tolerance* ranks the
    shots: a cue direction error ``e`` moves the contact point sideways by
    ``d_cue e / cos(cut)``, which turns the object ball's path by ``d_cue e / (2 R cos(cut))``;
    the ball still drops while it passes the target within the half-width ``h``, so
    ``e_max = 2 R cos(cut) h / (d_cue d_ball)`` (``d_cue`` floored at ``2R``).

    Args:
        table: The table (ball radius and size).
        mouths: Its pockets (:func:`pocket_mouths`).
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on the table.
        targets: ``(B, T)`` object ball indices to aim at (-1: an empty slot).
        offset: Aim point sideways from each target, as a fraction of the mouth's
            half-width seen along the path.
        max_cut: Thinnest cut kept (radians).
        cue: The cue ball's index.

    Returns:
        ``(B, T, K, NG)`` rows: :data:`VALID` (1.0 or 0.0; the rest is meaningful when 1),
        :data:`ANGLE` the cue ball's direction (rad from +x), :data:`CUT` the signed cut
        (positive: the object ball leaves counter-clockwise of the cue's path), the
        ghost-ball point (:data:`GX`, :data:`GY`), :data:`CUE_DIST` cue to ghost point,
        :data:`BALL_DIST` object ball to its aim point, :data:`TRAVEL` how far it rolls
        until it drops, :data:`APPROACH` the cosine of its path against the mouth's
        normal, :data:`TOLERANCE` (rad), :data:`CLEAR_PATH` (1.0: both paths keep ``2R``
        from every other ball), the aim point (``AIM_X``, ``AIM_Y``) and :data:`COS_CUT`.

    Raises:
        ValueError: On shapes that do not fit together or a target that is no ball.
    """
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    on = np.ascontiguousarray(on_table, dtype=np.bool_)
    tgt = np.ascontiguousarray(targets, dtype=np.int64)
    if pos.ndim != 3 or pos.shape[2] != 2 or on.shape != pos.shape[:2]:
        raise ValueError(f"positions (B, N, 2) and on_table (B, N), got {pos.shape}, {on.shape}")
    if tgt.ndim != 2 or tgt.shape[0] != pos.shape[0]:
        raise ValueError(f"targets must be ({pos.shape[0]}, T) ball indices, got {tgt.shape}")
    if tgt.size and (tgt.max() >= pos.shape[1] or tgt.min() < -1):
        raise ValueError(f"targets must be ball indices in 0..{pos.shape[1] - 1} (or -1)")
    r = table.ball_radius
    return kg.ghost_shots(
        mouths.rows, mouths.jaws, pos, on, tgt, int(cue), r, _centre_box(table), float(offset),
        math.cos(max_cut), MIN_APPROACH_COS,
    )  # fmt: skip


def ghost_contact(
    table: Table, ball: ArrayLike, u: ArrayLike, cue: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64], float, float] | None:
    """Where the cue ball must touch ``ball`` to send it along the unit vector ``u``.

    Args:
        table: The table (ball radius and size).
        ball: ``(2,)`` the object ball's centre.
        u: ``(2,)`` unit direction the object ball should leave along.
        cue: ``(2,)`` the cue ball's centre.

    Returns:
        ``(ghost, heading, distance, cos_cut)``: the ghost-ball point ``ball - 2 R u``, the
        cue ball's unit heading to it and the distance, and the cosine of the cut; ``None``
        when the point lies off the cloth (a cushion is in the way).
    """
    box = _centre_box(table)
    args = (np.asarray(v, dtype=np.float64).tolist() for v in (ball, u, cue))
    flat = [x for a in args for x in a]
    on, gx, gy, dx, dy, dist, cos_cut = kg.ghost_contact(*flat, table.ball_radius, box)
    if not on:
        return None
    return np.array([gx, gy]), np.array([dx, dy]), dist, cos_cut


def cue_speeds(table: Table, shots: NDArray[np.float64], arrival: float) -> NDArray[np.float64]:
    """Cue speed (m/s) of each valid shot row at which its object ball drops at ``arrival``.

    Balls roll at the constant deceleration ``a = mu_roll g`` and, being of equal mass, the
    object ball leaves a collision with ``(1 + e_ball) / 2`` of the cue ball's velocity
    along the line of centres: ``v_ball = sqrt(arrival^2 + 2 a travel)``,
    ``v_contact = v_ball / ((1 + e) / 2 cos(cut))``, ``v_cue = sqrt(v_contact^2 + 2 a d_cue)``.

    Args:
        table: The table (deceleration, ball restitution).
        shots: ``(..., NG)`` rows of :func:`ghost_shots`.
        arrival: Speed (m/s) at which the object ball should drop.

    Returns:
        ``shots.shape[:-1]`` speeds, 0 for an invalid row.
    """
    rows = np.ascontiguousarray(shots, dtype=np.float64)
    flat = rows.reshape(-1, NG)
    out = kg.cue_speeds(table.deceleration, table.e_ball, flat, float(arrival))
    return out.reshape(rows.shape[:-1])


def path_clear(start: ArrayLike, end: ArrayLike, balls: ArrayLike, reach: float) -> bool:
    """Whether a ball centre moving from ``start`` to ``end`` stays ``reach`` from every ball.

    Args:
        start: ``(2,)`` where the centre starts.
        end: ``(2,)`` where it stops.
        balls: ``(M, 2)`` centres of the obstacles.
        reach: The least distance (m): strictly more keeps the path clear.
    """
    pts = np.ascontiguousarray(balls, dtype=np.float64).reshape(-1, 2)
    (sx, sy), (ex, ey) = (np.asarray(p, dtype=np.float64).tolist() for p in (start, end))
    on = np.ones(pts.shape[0], dtype=np.bool_)
    return bool(kg.path_clear(sx, sy, ex, ey, pts, on, -1, -1, float(reach)))


def points_free(
    table: Table, points: ArrayLike, balls: ArrayLike, behind_head_string: bool = False
) -> NDArray[np.bool_]:
    """Where a ball may be placed: the game's own test for each of ``points``.

    The test that placing the cue ball in hand, re-spotting and the scenes use
    (:func:`pool_env.game.kernels.layout.point_free`): inside the rails (behind the head
    string, ``x <= L / 4``, if asked), outside every capture circle with its clearance, and
    at least ``2R`` (plus the clearance) from every ball of ``balls``.

    Args:
        table: The table.
        points: ``(C, 2)`` candidate centres.
        balls: ``(M, 2)`` centres of the balls on the table (the one placed excluded).
        behind_head_string: Only the kitchen is free (ball in hand after some fouls).

    Returns:
        ``(C,)`` whether each point is free.
    """
    params = placement(table)
    if behind_head_string:
        params[kp.X_HIGH] = table.length / 4.0
    pts = np.ascontiguousarray(points, dtype=np.float64).reshape(-1, 2)
    occupied = np.ascontiguousarray(balls, dtype=np.float64).reshape(-1, 2)
    reach = float(params[kp.REACH])
    return free_points(params, table.pockets, pts, occupied, reach * reach)


def _centre_box(table: Table) -> NDArray[np.float64]:
    """Where a ball centre can be, ``(x0, y0, x1, y1)``, with 1e-12 of slack for rounding."""
    r = table.ball_radius
    return np.array([r - 1e-12, r - 1e-12, table.length - r + 1e-12, table.width - r + 1e-12])
