"""The cue ball alone on the table after contact: rolling legs off the cushions, into a pocket.

A first-order look, as a player takes it, not a simulation: the ball rolls straight, losing
speed at ``mu_roll g`` (``table.deceleration``), comes off a rail with the normal part of its
velocity times ``e_cushion`` and the rest kept, for up to :data:`TRACE_CUSHIONS` cushions.
Other balls are ignored. :func:`cue_ball_scratches` is the roll level's after-contact check
(the tangent line); :mod:`agents.baselines.cue_path` starts the same trace where the spin
level's cue ball ends its slide.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from agents.baselines.geometry import GhostShot, PocketMouths
from pool_env import Table

#: Most cushions followed when tracing the cue ball after contact (on a low-friction table
#: it may run around the table several times before it stops).
TRACE_CUSHIONS = 20


@dataclass(frozen=True)
class Trace:
    """Where a traced ball went.

    Attributes:
        pocket: The pocket it drops into, or -1.
        rest: Where it stops (or enters the pocket), ``(2,)``.
        legs: The straight legs it rolled, ``(start, end)`` pairs.
    """

    pocket: int
    rest: NDArray[np.float64]
    legs: tuple[tuple[NDArray[np.float64], NDArray[np.float64]], ...]


def first_entry(
    mouths: PocketMouths, start: NDArray[np.float64], u: NDArray[np.float64]
) -> tuple[int, float]:
    """The first pocket the ray from ``start`` along ``u`` enters and how far: ``(k, dist)``.

    ``(-1, inf)`` when it enters none.
    """
    best, dist = -1, math.inf
    for k in range(mouths.n):
        d = mouths.entry(k, start, u)
        if d < dist:
            best, dist = k, d
    return best, dist


def roll_trace(
    table: Table, mouths: PocketMouths, start: NDArray[np.float64], vel: NDArray[np.float64]
) -> Trace:
    """Follow a ball rolling from ``start`` at ``vel`` (m/s) until it stops or drops.

    Args:
        table: The table (its size, rolling deceleration and cushion restitution).
        mouths: Its pockets.
        start: ``(2,)`` the ball's centre.
        vel: ``(2,)`` its velocity.

    Returns:
        The :class:`Trace`.
    """
    a, e_rail = table.deceleration, table.e_cushion
    pos = np.array(start, dtype=np.float64)
    vel = np.array(vel, dtype=np.float64)
    r = table.ball_radius
    lo, hi = np.array([r, r]), np.array([table.length - r, table.width - r])
    legs: list[tuple[NDArray[np.float64], NDArray[np.float64]]] = []
    for _ in range(TRACE_CUSHIONS + 1):
        v = float(np.hypot(*vel))
        if v <= 1e-12:
            break
        w = vel / v
        reach = v * v / (2.0 * a)
        to_rail = np.full(2, math.inf)
        for axis in range(2):
            if w[axis] > 1e-15:
                to_rail[axis] = (hi[axis] - pos[axis]) / w[axis]
            elif w[axis] < -1e-15:
                to_rail[axis] = (lo[axis] - pos[axis]) / w[axis]
        axis = int(np.argmin(to_rail))
        leg = min(max(float(to_rail[axis]), 0.0), reach)
        k, entry = first_entry(mouths, pos, w)
        if entry <= leg + 1e-9:
            end = pos + entry * w
            legs.append((pos, end))
            return Trace(k, end, tuple(legs))
        end = pos + leg * w
        legs.append((pos, end))
        if reach <= leg:
            return Trace(-1, end, tuple(legs))
        pos = end
        vel = w * math.sqrt(max(v * v - 2.0 * a * leg, 0.0))
        vel[axis] = -e_rail * vel[axis]
    return Trace(-1, pos, tuple(legs))


def cue_ball_scratches(table: Table, mouths: PocketMouths, shot: GhostShot, speed: float) -> bool:
    """Whether the cue ball, alone on the table after contact, would roll into a pocket.

    The tangent-line rule: at contact the cue ball keeps its velocity across the line of
    centres and ``(1 - e_ball) / 2`` of the part along it; it then rolls as
    :func:`roll_trace` follows it.

    Args:
        table: The table.
        mouths: Its pockets.
        shot: The shot.
        speed: The cue speed it is played at (m/s).
    """
    a, e_ball = table.deceleration, table.e_ball
    d = np.array([math.cos(shot.angle), math.sin(shot.angle)])
    c, s = math.cos(shot.cut), math.sin(shot.cut)
    u = np.array([c * d[0] - s * d[1], s * d[0] + c * d[1]])  # the object ball's direction
    v2_contact = speed * speed - 2.0 * a * shot.cue_distance
    if v2_contact <= 0.0:
        return False
    vel = math.sqrt(v2_contact) * ((d - c * u) + c * (1.0 - e_ball) / 2.0 * u)
    return roll_trace(table, mouths, np.array(shot.ghost), vel).pocket >= 0
