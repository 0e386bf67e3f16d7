"""Position play on the spin table: the tip and speed of a ghost-ball shot, in closed form.

For one ghost-ball shot (:class:`agents.baselines.geometry.GhostShot`) and one cue-tip offset
and object-ball arrival speed, :func:`plan_contact` finds the strike that pots it on the
spin level's physics (:mod:`agents.baselines.cue_path`): the object ball must leave along
the line to the pocket although the contact *throws* it a few degrees off the line of
centres (the ghost point is turned against the throw, a fixed point found in a few
rounds), the cue ball must arrive at that point although it slides before it rolls (the
strike speed from :func:`~agents.baselines.cue_path.launch_speed`), and the cue must be
aimed off by the squirt of side spin. :func:`agents.baselines.cue_path.after_contact` then
says where the cue ball comes to rest and whether it drops.

:class:`PositionScore` ranks the candidates as a player does: the chance to pot this ball
times the chance to pot the next one from where the cue ball stops (each the probability
that an aim error of the execution noise's size stays within the shot's tolerance), with a
shot that leaves no next shot worth only a little. The last ball on the table is scored by
its own pot alone.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from agents.baselines.cue_path import (
    after_contact,
    along,
    collide,
    contact_fraction,
    launch_speed,
    squirt,
    strike,
)
from agents.baselines.geometry import MAX_CUT, GhostShot, PocketMouths, ghost_shots, path_clear
from agents.baselines.trace import Trace
from pool_env import Table
from pool_env.game.geometry import ghost_contact

#: Vertical tip offsets tried, as fractions of the tip limit (+ follow, - draw).
VERTICAL_TIPS = (0.0, 0.5, 1.0, -0.5, -1.0)
#: Side offsets tried with each vertical one, as fractions of the tip limit.
SIDE_TIPS = (0.0, -0.6, 0.6)
#: Speeds (m/s) at which the object ball should reach the pocket: the speed is the other
#: half of position play (how far the cue ball travels).
ARRIVAL_SPEEDS = (0.3, 0.6, 1.0, 1.6)
#: Rounds of the throw's fixed point (the throw changes little with the ghost point).
THROW_ROUNDS = 3
#: Next-shot candidates: ``(positions, on_table, potted ball) -> legal balls after the pot``
#: (empty when nothing is left to shoot at).
NextTargets = Callable[[NDArray[np.float64], NDArray[np.bool_], int], list[int]]


@dataclass(frozen=True)
class Contact:
    """The strike that pots a shot on the spin table, and what the cue ball does after.

    Attributes:
        aim: The cue's aim (radians from +x): the path to the ghost point less the squirt.
        speed: The cue ball's speed after the strike (m/s).
        tip: The cue's axis offset ``(side, vertical)`` in fractions of ``R``.
        ghost: Where the cue ball touches the object ball (turned against the throw).
        object_speed: The object ball's speed leaving the contact (m/s).
        path: The cue ball's path after contact.
    """

    aim: float
    speed: float
    tip: tuple[float, float]
    ghost: NDArray[np.float64]
    object_speed: float
    path: Trace


def plan_contact(
    table: Table,
    mouths: PocketMouths,
    shot: GhostShot,
    positions: NDArray[np.float64],
    tip: tuple[float, float],
    arrival: float,
    throw_rounds: int = THROW_ROUNDS,
) -> Contact | None:
    """The strike that pots ``shot`` with ``tip`` so that the ball drops at ``arrival`` m/s.

    ``throw_rounds=0`` aims at the plain ghost point (no throw correction). ``None`` when
    the throw-corrected contact is out of reach (a cut beyond
    :data:`~agents.baselines.geometry.MAX_CUT`, a ghost point off the table, a cue ball that
    stops short).
    """
    r = table.ball_radius
    cue, ball = positions[0], positions[shot.ball]
    u = (ball - np.array(shot.ghost)) / (2.0 * r)  # the object ball's path to the pocket
    v_object = launch_speed(table, 1.0, shot.travel, arrival)
    slip_ratio = 1.0 - 2.5 * tip[1] * contact_fraction(table)
    normal, scale = u.copy(), 1.0
    for _ in range(throw_rounds + 1):
        contact = ghost_contact(table, ball, normal, cue)
        if contact is None:
            return None
        ghost, heading, dist, cos_cut = contact
        if cos_cut < math.cos(MAX_CUT):
            return None
        v_contact = scale * v_object / ((1.0 + table.e_ball) / 2.0 * cos_cut)
        speed = launch_speed(table, slip_ratio, dist, v_contact)
        aim = math.atan2(heading[1], heading[0]) - squirt(table, tip[0])
        arriving = along(table, strike(table, aim, speed, tip), dist)
        if arriving is None:
            return None
        cue_after, obj = collide(table, arriving, normal)
        obj_speed = float(np.hypot(*obj.vel))
        if obj_speed <= 0.0:
            return None
        obj_dir = obj.vel / obj_speed
        throw = math.atan2(normal[0] * obj_dir[1] - normal[1] * obj_dir[0], normal @ obj_dir)
        c, s = math.cos(-throw), math.sin(-throw)
        normal = np.array([c * u[0] - s * u[1], s * u[0] + c * u[1]])
        scale *= v_object / obj_speed
    path = after_contact(table, mouths, ghost, cue_after)
    return Contact(aim, speed, tip, ghost, obj_speed, path)


def pot_chance(tolerance: float, sigma: float) -> float:
    """The chance that a Gaussian aim error of ``sigma`` (rad) stays within ``tolerance``."""
    return math.erf(tolerance / (sigma * math.sqrt(2.0)))


#: What a shot that leaves no next shot is worth, against one that leaves a sure one.
NO_NEXT_SHOT = 0.1


class PositionScore:
    """The value of leaving the cue ball at a point: the next shot's chance to pot.

    Args:
        table: The table.
        mouths: Its pockets.
        sigma: The aim error (rad) the chances are taken at.
        next_targets: The legal balls after a pot (see :data:`NextTargets`).
    """

    def __init__(
        self,
        table: Table,
        mouths: PocketMouths,
        sigma: float,
        next_targets: NextTargets,
    ) -> None:
        self.table, self.mouths = table, mouths
        self.sigma = sigma
        self.next_targets = next_targets

    def score(
        self,
        shot: GhostShot,
        contact: Contact,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
    ) -> float:
        """This pot's chance times the next one's (or this pot's alone if nothing is left)."""
        p_now = pot_chance(shot.tolerance, self.sigma)
        after = on_table.copy()
        after[shot.ball] = False
        targets = self.next_targets(positions, after, shot.ball)
        if not targets:
            return p_now
        p_next = self.next_chance(contact, positions, after, targets)
        return p_now * (NO_NEXT_SHOT + (1.0 - NO_NEXT_SHOT) * p_next)

    def next_chance(
        self,
        contact: Contact,
        positions: NDArray[np.float64],
        after: NDArray[np.bool_],
        targets: list[int],
    ) -> float:
        """The best next shot's chance from where the cue ball rests.

        Halved when the cue ball's path runs into another ball: its resting point is then
        a guess.
        """
        r = self.table.ball_radius
        rest = contact.path.rest
        others = positions[1:][after[1:]]
        if others.shape[0] and np.min(np.hypot(*(others - rest).T)) < 2.0 * r:
            return 0.0
        moved = positions.copy()
        moved[0] = rest
        best = 0.0
        for nxt in ghost_shots(self.table, self.mouths, moved, after, targets):
            if nxt.clear and nxt.tolerance > best:
                best = nxt.tolerance
        chance = pot_chance(best, self.sigma)
        if others.shape[0] and not all(
            path_clear(a, b, others, 2.0 * r) for a, b in contact.path.legs
        ):
            chance *= 0.5
        return chance


#: Contact offsets (fractions of ``2R`` across the object ball) of :func:`traced_pots`.
TRACE_OFFSETS = tuple(float(x) for x in np.linspace(-0.95, 0.95, 39))
#: Strike speeds (fractions of the top speed) of :func:`traced_pots`.
TRACE_SPEEDS = (0.35, 0.55, 0.75, 1.0)


@dataclass(frozen=True)
class TracedPot:
    """A centre-ball strike whose object ball, traced off the cushions, drops.

    Attributes:
        ball: The object ball.
        aim: The cue's aim (rad).
        speed: The strike speed (m/s).
        pocket: Where the object ball drops.
        margin: How many neighbouring strikes (one offset step either side) also pot.
    """

    ball: int
    aim: float
    speed: float
    pocket: int
    margin: int


def traced_pots(
    table: Table,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    targets: list[int],
    top_speed: float,
) -> list[TracedPot]:
    """Strikes that pot by a bank or a carom off the rails, found forward in closed form.

    For when no direct ghost-ball shot is playable: a fan of centre-ball strikes at each
    target (:data:`TRACE_OFFSETS` x :data:`TRACE_SPEEDS`) is followed through the contact
    (:func:`~agents.baselines.cue_path.collide`) and both balls off the cushions
    (:func:`~agents.baselines.cue_path.after_contact`); a strike counts when the object
    ball drops, the cue ball does not, and the cue ball's way to the contact and the object
    ball's legs are clear of the other balls. Sorted by margin, most first.
    """
    cue = positions[0]
    found: list[TracedPot] = []
    for b in targets:
        ball = positions[b]
        to_ball = ball - cue
        dist = float(np.hypot(*to_ball))
        base = math.atan2(to_ball[1], to_ball[0])
        others = np.array(
            [positions[j] for j in range(1, positions.shape[0]) if on_table[j] and j != b]
        ).reshape(-1, 2)
        for fraction in TRACE_SPEEDS:
            speed = fraction * top_speed
            pots: list[tuple[float, int] | None] = []
            for offset in TRACE_OFFSETS:
                pots.append(_traced(table, mouths, cue, ball, dist, base, offset, speed, others))
            for i, hit in enumerate(pots):
                if hit is None:
                    continue
                margin = sum(
                    1 for j in (i - 1, i + 1) if 0 <= j < len(pots) and pots[j] is not None
                )
                found.append(TracedPot(b, hit[0], speed, hit[1], margin))
    return sorted(found, key=lambda p: -p.margin)


def _traced(
    table: Table,
    mouths: PocketMouths,
    cue: NDArray[np.float64],
    ball: NDArray[np.float64],
    dist: float,
    base: float,
    offset: float,
    speed: float,
    others: NDArray[np.float64],
) -> tuple[float, int] | None:
    """``(aim, pocket)`` of one strike of :func:`traced_pots` if it pots cleanly, else None."""
    r = table.ball_radius
    side = offset * 2.0 * r
    if abs(side) >= dist:
        return None
    aim = base + math.asin(side / dist)
    heading = np.array([math.cos(aim), math.sin(aim)])
    along_path = float(heading @ (ball - cue))
    travel = along_path - math.sqrt(max(4.0 * r * r - side * side, 0.0))
    if travel <= 0.0:
        return None
    contact = cue + travel * heading
    if others.shape[0] and not path_clear(cue, contact, others, 2.0 * r):
        return None
    arriving = along(table, strike(table, aim, speed, (0.0, 0.0)), travel)
    if arriving is None:
        return None
    cue_after, obj = collide(table, arriving, (ball - contact) / (2.0 * r))
    obj_path = after_contact(table, mouths, ball, obj)
    if obj_path.pocket < 0 or after_contact(table, mouths, contact, cue_after).pocket >= 0:
        return None
    if others.shape[0] and not all(path_clear(p, q, others, 2.0 * r) for p, q in obj_path.legs):
        return None
    return aim, obj_path.pocket
