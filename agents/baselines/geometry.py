"""Ghost-ball geometry: pocket mouths, the ghost-ball point, cut angles, clear paths, speeds.

Pure functions of the table (read from its public attributes) and a layout; no simulator
calls. Both baselines and the observation features use them, so the geometry exists once.

Frame and terms (``R`` the ball radius): a ball centre lives in the rectangle
``[R, L - R] x [R, W - R]`` (it touches a cushion on its boundary). A pocket's *mouth* is the
segment that a ball centre crosses when it drops, in those centre coordinates; its
*target* is the mouth's midpoint. To send object ball ``B`` along the unit vector ``u``
towards a target, the cue ball must be at the *ghost-ball point* ``G = B - 2 R u`` when they
touch; the *cut angle* is the angle between the cue ball's path (cue to ``G``) and ``u``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env import Table

#: Which object balls a player may aim at: ``(positions, on_table) -> ball indices``.
#: A rules game replaces the default (any object ball on the table) with its own.
LegalTargets = Callable[[NDArray[np.float64], NDArray[np.bool_]], list[int]]

#: Cuts thinner than this need more speed than the cue ball keeps control of, and a contact
#: too thin to trust (85 degrees: the thinnest that pots more on the jaw table than on 80).
MAX_CUT = math.radians(85.0)
#: A path this close to parallel with the mouth does not go in (cos of 85 degrees).
MIN_APPROACH_COS = math.cos(math.radians(85.0))


def any_object_ball(positions: NDArray[np.float64], on_table: NDArray[np.bool_]) -> list[int]:
    """The default legal targets: every object ball on the table (ball 0 is the cue)."""
    return [int(j) for j in on_table.nonzero()[0] if j != 0]


@dataclass(frozen=True)
class PocketMouths:
    """Each pocket as the opening a ball centre crosses, and where the ball drops.

    Two pocket models are read (:func:`pocket_mouths`): capture circles (a ball drops when
    its centre enters the circle) and jaws (it drops when its centre reaches the pocket's
    fall line, behind the mouth between the two cushion points).

    Attributes:
        model: ``"circles"`` or ``"jaws"``.
        targets: ``(K, 2)`` opening midpoints: where a ghost-ball shot aims.
        inward: ``(K, 2)`` unit normals of the openings, pointing into the pocket (zero for
            a pocket that takes a ball from any direction).
        openings: ``(K, 2, 2)`` the opening as a segment in ball-centre coordinates (on the
            lines ``R`` from the cushion noses): a ball centre crossing it enters the pocket.
        widths: ``(K,)`` the mouth's width: between the cushion points (jaws) or the
            opening itself (circles).
        clearance: ``(K,)`` how far a ball centre must pass inside each end of the mouth:
            ``R`` from a cushion point (jaws), 0 for an opening already in centre
            coordinates (circles).
        capture: ``(K, 3)`` capture circles ``(x, y, r)`` (``"circles"``).
        drop_points: ``(K, 2)`` a point of each fall line (``"jaws"``).
        drop_normals: ``(K, 2)`` unit normals of the fall lines towards the table (``"jaws"``).
    """

    model: str
    targets: NDArray[np.float64]
    inward: NDArray[np.float64]
    openings: NDArray[np.float64]
    widths: NDArray[np.float64]
    clearance: NDArray[np.float64]
    capture: NDArray[np.float64]
    drop_points: NDArray[np.float64]
    drop_normals: NDArray[np.float64]

    @property
    def n(self) -> int:
        """Number of pockets."""
        return int(self.targets.shape[0])

    def half_tolerance(self, k: int, u: NDArray[np.float64]) -> float:
        """How far (m) sideways a path along ``u`` may pass the target of pocket ``k`` and drop.

        The mouth seen along the path, ``width cos(approach) / 2``, less the clearance;
        0 when the path runs (nearly) along the mouth or away from the pocket. (On a jaw
        table this gives a side pocket 7.0 cm straight in, 3.3 cm at 45 degrees and nothing
        beyond 63 degrees: the shape of Dr. Dave Alciatore's tolerance curves, a little
        narrower, since it ignores the balls that rattle in off a facing.)
        """
        normal = self.inward[k]
        cos_a = 1.0 if not normal.any() else float(u @ normal)
        if cos_a < MIN_APPROACH_COS:
            return 0.0
        return max(float(self.widths[k]) / 2.0 * cos_a - float(self.clearance[k]), 0.0)

    def travel(self, k: int, start: NDArray[np.float64], u: NDArray[np.float64]) -> float:
        """Distance a ball from ``start`` along ``u`` rolls until it drops in pocket ``k``.

        To the capture circle's edge, or to the fall line; ``inf`` if the ray misses it (or
        it lies behind).
        """
        if self.model == "jaws":
            normal = self.drop_normals[k]
            closing = -float(u @ normal)  # how fast the fall line comes nearer
            height = float((start - self.drop_points[k]) @ normal)
            return height / closing if closing > 0.0 and height >= 0.0 else math.inf
        return _ray_circle(start, u, self.capture[k])

    def entry(self, k: int, start: NDArray[np.float64], u: NDArray[np.float64]) -> float:
        """Distance along the ray from ``start`` to where it enters pocket ``k`` (``inf``: never).

        Circles: the circle's edge. Jaws: the opening, where the ball leaves the rails' reach.
        """
        if self.model != "jaws":
            return _ray_circle(start, u, self.capture[k])
        a, b = self.openings[k]
        seg = b - a
        denom = float(u[0] * seg[1] - u[1] * seg[0])
        if abs(denom) < 1e-15:
            return math.inf
        w = a - start
        t = float(w[0] * seg[1] - w[1] * seg[0]) / denom  # along the ray
        s = float(w[0] * u[1] - w[1] * u[0]) / denom  # along the opening
        return t if t >= -1e-12 and 0.0 <= s <= 1.0 else math.inf


def _ray_circle(start: NDArray[np.float64], u: NDArray[np.float64], circle: NDArray) -> float:
    """Distance along the ray to a circle's edge (0 from inside, ``inf`` when it misses)."""
    cx, cy, r = circle
    w = start - np.array([cx, cy])
    b = float(w @ u)
    c = float(w @ w) - r * r
    disc = b * b - c
    if disc < 0.0 or -b + math.sqrt(disc) < 0.0:
        return math.inf
    return max(-b - math.sqrt(disc), 0.0)


#: Inward normal of each rail line of :attr:`PocketJaws.rails` (x = R, x = L - R, y = R,
#: y = W - R).
_RAIL_INWARD = np.array([(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)])


def pocket_mouths(table: Table) -> PocketMouths:
    """The pockets of ``table`` as mouths, from its public pocket geometry.

    A jaw table (``table.pocket_model == "jaws"``) lists for each pocket in ``table.jaws``
    its two cushion points and its fall line: the opening runs between the points moved
    ``R`` into the table along their rails' normals, the mouth between the points, and the
    ball drops at the fall line. Otherwise the pockets are capture circles
    (``table.pockets``, rows ``(x, y, r)``): a circle that reaches into the table cuts the
    boundary of the ball-centre rectangle in two points, and the chord between them is the
    opening (a ball centre crossing it is inside the circle without having touched a
    cushion). A circle wholly inside the table takes a ball from any direction: its target
    is its centre and its width its diameter.
    """
    if getattr(table, "pocket_model", "circles") == "jaws":
        return _jaw_mouths(table)
    pockets = np.asarray(table.pockets, dtype=np.float64).reshape(-1, 3)
    k = pockets.shape[0]
    targets, inward, widths = np.empty((k, 2)), np.zeros((k, 2)), np.empty(k)
    openings = np.empty((k, 2, 2))
    centre = np.array([table.length, table.width]) / 2.0
    for p, (cx, cy, r) in enumerate(pockets.tolist()):
        ends = _circle_on_centre_box(cx, cy, r, table)
        if len(ends) == 2:
            a, b = np.array(ends[0]), np.array(ends[1])
            openings[p] = (a, b)
            targets[p] = (a + b) / 2.0
            widths[p] = float(np.hypot(*(b - a)))
            along = (b - a) / widths[p]
            normal = np.array([-along[1], along[0]])
            if normal @ (targets[p] - centre) < 0.0:
                normal = -normal  # into the pocket: away from the table's centre
            inward[p] = normal
        else:
            targets[p] = (cx, cy)
            openings[p] = ((cx, cy), (cx, cy))
            widths[p] = 2.0 * r
    none = np.zeros((k, 2))
    return PocketMouths(
        "circles", targets, inward, openings, widths, np.zeros(k), pockets.copy(), none, none
    )


def _jaw_mouths(table: Table) -> PocketMouths:
    """:class:`PocketMouths` of a jaw table, from its ``jaws`` (points, rails, fall lines)."""
    r = table.ball_radius
    jaws = table.jaws
    k = len(jaws)
    targets, inward, widths = np.empty((k, 2)), np.empty((k, 2)), np.empty(k)
    openings, drop_points, drop_normals = np.empty((k, 2, 2)), np.empty((k, 2)), np.empty((k, 2))
    for p, jaw in enumerate(jaws):
        points = np.asarray(jaw.points, dtype=np.float64)
        for end in range(2):
            openings[p, end] = points[end] + r * _RAIL_INWARD[jaw.rails[end]]
        targets[p] = openings[p].mean(axis=0)
        widths[p] = float(np.hypot(*(points[1] - points[0])))
        drop_normals[p] = np.asarray(jaw.fall_normal, dtype=np.float64)
        drop_points[p] = np.asarray(jaw.fall_line, dtype=np.float64).mean(axis=0)
        inward[p] = -drop_normals[p]
    return PocketMouths(
        "jaws",
        targets,
        inward,
        openings,
        widths,
        np.full(k, r),
        np.asarray(table.pockets, dtype=np.float64).reshape(-1, 3).copy(),
        drop_points,
        drop_normals,
    )


def _circle_on_centre_box(
    cx: float, cy: float, r: float, table: Table
) -> list[tuple[float, float]]:
    """Where a circle crosses the boundary of the ball-centre rectangle (distinct points)."""
    rad = table.ball_radius
    x0, x1, y0, y1 = rad, table.length - rad, rad, table.width - rad
    points: list[tuple[float, float]] = []
    for x in (x0, x1):  # vertical sides
        h = r * r - (x - cx) ** 2
        if h > 0.0:
            for y in (cy - math.sqrt(h), cy + math.sqrt(h)):
                if y0 <= y <= y1:
                    points.append((x, y))
    for y in (y0, y1):  # horizontal sides
        h = r * r - (y - cy) ** 2
        if h > 0.0:
            for x in (cx - math.sqrt(h), cx + math.sqrt(h)):
                if x0 <= x <= x1:
                    points.append((x, y))
    unique: list[tuple[float, float]] = []
    for p in points:  # a corner of the rectangle lies on two sides
        if all(math.hypot(p[0] - q[0], p[1] - q[1]) > 1e-12 for q in unique):
            unique.append(p)
    return unique


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

    A shot is kept when the ghost-ball point is where a ball centre can be and the mouth
    is open to the object ball's path (see :meth:`PocketMouths.half_tolerance`); whether
    the paths are clear of other balls is recorded in :attr:`GhostShot.clear`.

    The *tolerance* ranks the shots: a cue direction error ``e`` moves the contact point
    sideways by ``d_cue e / cos(cut)``, which turns the object ball's path by
    ``d_cue e / (2 R cos(cut))``; the ball still drops while it passes the target within
    the mouth's half-width ``h``, so ``e_max = 2 R cos(cut) h / (d_cue d_ball)`` (``d_cue``
    is floored at ``2R``, where the first-order picture stops).

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
    r = table.ball_radius
    lo = np.array([r, r]) - 1e-12
    hi = np.array([table.length - r, table.width - r]) + 1e-12
    cue_pos = positions[cue]
    shots = []
    for b in targets:
        ball = positions[b]
        others = np.array(
            [positions[j] for j in range(positions.shape[0]) if on_table[j] and j not in (cue, b)]
        ).reshape(-1, 2)
        for k in range(mouths.n):
            to_target = mouths.targets[k] - ball
            straight = to_target / np.hypot(*to_target)
            half = mouths.half_tolerance(k, straight)
            if half <= 0.0:
                continue
            target = mouths.targets[k] + offset * half * np.array([-straight[1], straight[0]])
            u = target - ball
            d_ball = float(np.hypot(*u))
            u /= d_ball
            ghost = ball - 2.0 * r * u
            if np.any(ghost < lo) or np.any(ghost > hi):
                continue  # the cue ball cannot get there: a cushion is in the way
            v = ghost - cue_pos
            d_cue = float(np.hypot(*v))
            d = u if d_cue < 1e-12 else v / d_cue
            cos_cut = float(np.clip(d @ u, -1.0, 1.0))
            if cos_cut < math.cos(max_cut):
                continue
            cut = math.atan2(d[0] * u[1] - d[1] * u[0], cos_cut)
            travel = mouths.travel(k, ball, u)
            if not math.isfinite(travel):
                continue
            clear = path_clear(cue_pos, ghost, others, 2.0 * r) and path_clear(
                ball, target, others, 2.0 * r
            )
            tolerance = 2.0 * r * cos_cut * half / (max(d_cue, 2.0 * r) * d_ball)
            shots.append(
                GhostShot(
                    ball=b,
                    pocket=k,
                    angle=math.atan2(d[1], d[0]),
                    cut=cut,
                    ghost=(float(ghost[0]), float(ghost[1])),
                    cue_distance=d_cue,
                    ball_distance=d_ball,
                    travel=travel,
                    approach_cos=float(u @ mouths.inward[k]) if mouths.inward[k].any() else 1.0,
                    tolerance=tolerance,
                    clear=clear,
                )
            )
    return shots


def cue_speed(table: Table, shot: GhostShot, arrival_speed: float) -> float:
    """Cue speed (m/s) at which the object ball drops at ``arrival_speed``.

    Balls roll at the constant deceleration ``a = mu_roll g`` and, being of equal mass, the
    object ball leaves a collision with ``(1 + e_ball) / 2`` of the cue ball's velocity
    along the line of centres, i.e. ``(1 + e) / 2 cos(cut)`` of its speed. Backwards:
    ``v_ball = sqrt(v_arrive^2 + 2 a travel)``, ``v_contact = v_ball / ((1 + e) / 2
    cos(cut))``, ``v_cue = sqrt(v_contact^2 + 2 a d_cue)``.
    """
    a, e = table.deceleration, table.e_ball
    v_ball = math.sqrt(arrival_speed**2 + 2.0 * a * shot.travel)
    v_contact = v_ball / ((1.0 + e) / 2.0 * math.cos(shot.cut))
    return math.sqrt(v_contact**2 + 2.0 * a * shot.cue_distance)


def path_clear(
    start: NDArray[np.float64], end: NDArray[np.float64], balls: NDArray[np.float64], reach: float
) -> bool:
    """Whether a ball centre moving from ``start`` to ``end`` stays ``reach`` from every ball."""
    if balls.shape[0] == 0:
        return True
    seg = end - start
    length2 = float(seg @ seg)
    rel = balls - start
    t = np.clip(rel @ seg / length2, 0.0, 1.0) if length2 > 0.0 else np.zeros(len(balls))
    closest = start + t[:, None] * seg
    gap = np.hypot(*(balls - closest).T)
    return bool(np.all(gap > reach))
