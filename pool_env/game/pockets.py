"""The pockets as mouths: the opening a ball centre crosses, and where the ball drops.

Read once per table from its public pocket geometry (capture circles or jaws) into the
rows that :mod:`pool_env.game.kernels.geometry` computes shots with; the public face is
:mod:`pool_env.game.geometry`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels import geometry as kg
from pool_env.sim import Table

#: A path this close to parallel with the mouth does not go in (cos of 85 degrees).
MIN_APPROACH_COS = math.cos(math.radians(85.0))


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

    @property
    def jaws(self) -> bool:
        """Whether the balls drop at fall lines (jaws) rather than in capture circles."""
        return self.model == "jaws"

    @cached_property
    def rows(self) -> NDArray[np.float64]:
        """The ``(K, NM)`` rows the kernels read (:mod:`pool_env.game.kernels.geometry`).

        Built on first use and kept (read-only: the kernels do not write it).
        """
        out = np.zeros((self.n, kg.NM))
        out[:, kg.TX : kg.TY + 1] = self.targets
        out[:, kg.NX : kg.NY + 1] = self.inward
        out[:, kg.AX : kg.BY + 1] = self.openings.reshape(-1, 4)
        out[:, kg.WIDTH], out[:, kg.CLEAR] = self.widths, self.clearance
        out[:, kg.CX : kg.CR + 1] = self.capture
        out[:, kg.PX : kg.PY + 1] = self.drop_points
        out[:, kg.DX : kg.DY + 1] = self.drop_normals
        return out

    def half_tolerance(self, k: int, u: NDArray[np.float64]) -> float:
        """How far (m) sideways a path along ``u`` may pass the target of pocket ``k`` and drop.

        The mouth seen along the path, ``width cos(approach) / 2``, less the clearance;
        0 when the path runs (nearly) along the mouth or away from the pocket. (On a jaw
        table this gives a side pocket 7.0 cm straight in, 3.3 cm at 45 degrees and nothing
        beyond 63 degrees: the shape of Dr. Dave Alciatore's tolerance curves, a little
        narrower, since it ignores the balls that rattle in off a facing.)
        """
        return kg.half_tolerance(self.rows, k, float(u[0]), float(u[1]), MIN_APPROACH_COS)

    def travel(self, k: int, start: NDArray[np.float64], u: NDArray[np.float64]) -> float:
        """Distance a ball from ``start`` along ``u`` rolls until it drops in pocket ``k``.

        To the capture circle's edge, or to the fall line; ``inf`` if the ray misses it (or
        it lies behind).
        """
        return kg.travel(self.rows, self.jaws, k, *_xy(start), *_xy(u))

    def entry(self, k: int, start: NDArray[np.float64], u: NDArray[np.float64]) -> float:
        """Distance along the ray from ``start`` to where it enters pocket ``k`` (``inf``: never).

        Circles: the circle's edge. Jaws: the opening, where the ball leaves the rails' reach.
        """
        return kg.entry(self.rows, self.jaws, k, *_xy(start), *_xy(u))


def _xy(v: NDArray[np.float64]) -> tuple[float, float]:
    """A 2-vector as two floats (the kernels' scalar arguments)."""
    return float(v[0]), float(v[1])


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
    lo, hi, centre = (rad, rad), (table.length - rad, table.width - rad), (cx, cy)
    points: list[tuple[float, float]] = []
    for axis in (0, 1):  # the sides x = const, then y = const
        other = 1 - axis
        for side in (lo[axis], hi[axis]):
            h = r * r - (side - centre[axis]) ** 2
            if h > 0.0:
                for t in (centre[other] - math.sqrt(h), centre[other] + math.sqrt(h)):
                    if lo[other] <= t <= hi[other]:
                        points.append((side, t) if axis == 0 else (t, side))
    unique: list[tuple[float, float]] = []
    for p in points:  # a corner of the rectangle lies on two sides
        if all(math.hypot(p[0] - q[0], p[1] - q[1]) > 1e-12 for q in unique):
            unique.append(p)
    return unique
