"""Pocket geometry: regulation jaws (rails cut at the points, facings, round tips, fall lines).

Frame as in :mod:`pool_env.sim.table`: the cushion noses are the lines ``x = 0``, ``x = L``,
``y = 0`` and ``y = W``. A jaw table's cushions are, for every pocket:

* the rails, which stop at the pocket **points** (where a cushion nose meets the facing);
* a straight **facing** from each point into the pocket at the regulation cut angle to the
  rail (WPA equipment specifications: 142 degrees at corners, 104 at sides);
* a round **tip** at each point: a circle of radius ``tip_radius`` tangent to the nose and
  to the facing (0 gives a sharp point);
* a **fall line** parallel to the mouth (the line between the two points), set back behind
  it by the shelf depth: a ball whose centre reaches it drops.

A ball centre is kept ``R`` from every cushion: the playing region for centres is the
rectangle ``[R, L - R] x [R, W - R]`` plus one **throat** per pocket, bounded by the
facings and tips offset by ``R`` and closed by the fall line. Every offset facing and tip
lies outside the open rectangle (a tip circle touches the offset rail line at the rail's
end), which is what lets the compiled predictor cull a pocket's jaws until a ball's path
leaves the rectangle through that pocket's opening.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.kernels.jaw_geometry import (
    J_BOX,
    J_FACING0,
    J_FACING1,
    J_FNX,
    J_FX,
    J_OPEN0,
    J_OPEN1,
    J_TIP0,
    J_TIP1,
    JAW_COLS,
)

INCH = 0.0254

#: WPA equipment specifications: corner mouth 4.5-4.625 in and side mouth 5-5.125 in, between
#: the points; we take the narrow end of each range.
CORNER_MOUTH = 4.5 * INCH
SIDE_MOUTH = 5.0 * INCH
#: WPA cut angle of the cushion facing to the rail: 142 degrees at corners (135 + 7) and
#: 104 degrees at sides (90 + 14), so each throat narrows inwards.
CORNER_CUT_DEG = 142.0
SIDE_CUT_DEG = 104.0
#: Shelf (mouth line to the edge of the hole) per WPA: corner 1 5/8-1 7/8 in, side 0-3/8 in.
#: The fall line sits at these depths (mid-range).
CORNER_SHELF = 1.75 * INCH
SIDE_SHELF = 0.1875 * INCH
#: Radius of the rounded points. pooltool 0.6 uses ~0.021 m (corner) and ~0.008 m (side);
#: real cushion noses are nearly sharp and the rubber deforms, so we take smaller radii.
CORNER_TIP_RADIUS = 0.005
SIDE_TIP_RADIUS = 0.003

# Columns of one pocket's row in the kernels' jaw array (see :func:`kernel_rows`): the fall
# line (a point, the unit normal to the table); each facing (offset start x, y, inward
# direction, free-side normal, extent); each tip (centre, contact radius); each opening
# (rail index or -1, lo, hi along that rail line).
J_FACING = (J_FACING0, J_FACING1)
J_TIP = (J_TIP0, J_TIP1)
J_OPEN = (J_OPEN0, J_OPEN1)


@dataclass(frozen=True)
class JawSpec:
    """The shape of a jaw table's pockets (every length in metres, angles in degrees).

    The defaults are the WPA regulation figures (see the module constants and their sources).
    """

    corner_mouth: float = CORNER_MOUTH
    side_mouth: float = SIDE_MOUTH
    corner_cut: float = CORNER_CUT_DEG
    side_cut: float = SIDE_CUT_DEG
    corner_shelf: float = CORNER_SHELF
    side_shelf: float = SIDE_SHELF
    corner_tip_radius: float = CORNER_TIP_RADIUS
    side_tip_radius: float = SIDE_TIP_RADIUS

    def __post_init__(self) -> None:
        for name in ("corner_mouth", "side_mouth"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be a positive finite number, got {value!r}")
        for name in ("corner_shelf", "side_shelf", "corner_tip_radius", "side_tip_radius"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name} must be a non-negative finite number, got {value!r}")
        for name in ("corner_cut", "side_cut"):
            value = getattr(self, name)
            if not (90.0 <= value < 180.0):
                raise ValueError(f"{name} must lie in [90, 180) degrees, got {value!r}")


@dataclass(frozen=True, eq=False)
class PocketJaws:
    """One pocket of a jaw table, in table coordinates (read-only arrays).

    Attributes:
        points: ``(2, 2)`` the two points, where each cushion nose meets its facing; the
            mouth is the segment between them.
        rail_ends: ``(2, 2)`` where each straight rail nose ends (the tip's tangent point on
            the nose; equal to ``points`` for sharp points).
        tip_centres: ``(2, 2)`` centres of the round tips (inside the cushion).
        tip_radius: Radius of both tips (0: sharp points).
        facings: ``(2, 2, 2)`` each facing's straight nose as ``(start, end)``: from the tip's
            tangent point into the pocket, past the fall line.
        fall_line: ``(2, 2)`` the fall line's end points, on the two facings.
        fall_normal: ``(2,)`` unit normal of the fall line pointing back to the table: a
            ball is potted when its centre reaches the fall line from that side.
        rails: The rail line of each point (0: ``x = R``, 1: ``x = L - R``, 2: ``y = R``,
            3: ``y = W - R``): the same twice for a side pocket, two rails for a corner.
    """

    points: NDArray[np.float64]
    rail_ends: NDArray[np.float64]
    tip_centres: NDArray[np.float64]
    tip_radius: float
    facings: NDArray[np.float64]
    fall_line: NDArray[np.float64]
    fall_normal: NDArray[np.float64]
    rails: tuple[int, int]


def _frozen(values: object) -> NDArray[np.float64]:
    arr = np.array(values, dtype=np.float64)
    arr.setflags(write=False)
    return arr


def _pocket(
    points: list[tuple[float, float]],
    along: list[tuple[float, float]],
    inward: list[tuple[float, float]],
    rails: tuple[int, int],
    cut_deg: float,
    shelf: float,
    tip_radius: float,
    ball_radius: float,
) -> PocketJaws:
    """One pocket from its two points.

    Args:
        points: The two points.
        along: For each point, the unit direction of its rail away from the pocket.
        inward: For each point, the unit normal of its rail into the table.
        rails: The rail line of each point.
        cut_deg: Angle between the rail and the facing (degrees).
        shelf: Depth of the fall line behind the mouth.
        tip_radius: Radius of the round tips.
        ball_radius: Ball radius (the facings run ``2 R`` past the fall line).
    """
    cut = math.radians(cut_deg)
    half = 0.5 * cut
    p = np.array(points, dtype=np.float64)
    mouth = p[1] - p[0]
    # Normal of the mouth line towards the table: on the side of the rails' inward normals.
    mouth_n = np.array([-mouth[1], mouth[0]]) / float(np.hypot(*mouth))
    if mouth_n @ np.array(inward[0]) < 0.0:
        mouth_n = -mouth_n
    fall_point = 0.5 * (p[0] + p[1]) - shelf * mouth_n
    ends, centres, facings, fall_ends = [], [], [], []
    for k in range(2):
        e = np.array(along[k], dtype=np.float64)
        t = np.array(inward[k], dtype=np.float64)
        d = math.cos(cut) * e - math.sin(cut) * t  # facing direction, into the pocket
        tangent = tip_radius / math.tan(half)  # point to each tangent point
        bisector = (e + d) / float(np.hypot(*(e + d)))
        ends.append(p[k] + tangent * e)
        centres.append(p[k] + tip_radius / math.sin(half) * bisector)
        start = p[k] + tangent * d
        # Where the facing meets the fall line, then 2R further in.
        depth_rate = -float(d @ mouth_n)  # depth gained per metre of facing
        to_fall = float((p[k] - fall_point) @ mouth_n) / depth_rate
        facings.append((start, p[k] + (to_fall + 2.0 * ball_radius / depth_rate) * d))
        fall_ends.append(p[k] + to_fall * d)
    return PocketJaws(
        points=_frozen(p),
        rail_ends=_frozen(ends),
        tip_centres=_frozen(centres),
        tip_radius=float(tip_radius),
        facings=_frozen(facings),
        fall_line=_frozen(fall_ends),
        fall_normal=_frozen(mouth_n),
        rails=rails,
    )


def regulation_jaws(
    length: float, width: float, ball_radius: float, spec: JawSpec
) -> tuple[PocketJaws, ...]:
    """The six pockets of a jaw table, ordered as the capture circles are.

    Order: bottom-left, bottom-middle, bottom-right, top-left, top-middle, top-right.

    Raises:
        ValueError: If the pockets do not fit on the table's rails.
    """
    c = spec.corner_mouth / math.sqrt(2.0)  # corner point to the corner along each rail
    s = 0.5 * spec.side_mouth
    if 2.0 * (c + spec.corner_tip_radius) + 2.0 * s >= length or 2.0 * c >= width:
        raise ValueError(
            f"pockets of mouths {spec.corner_mouth} m (corner) and {spec.side_mouth} m (side) "
            f"do not fit on a {length} x {width} m table"
        )
    L, W, m = length, width, 0.5 * length
    corner = (spec.corner_cut, spec.corner_shelf, spec.corner_tip_radius, ball_radius)
    side = (spec.side_cut, spec.side_shelf, spec.side_tip_radius, ball_radius)
    right, left, up, down = (1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)
    return (
        _pocket([(c, 0.0), (0.0, c)], [right, up], [up, right], (2, 0), *corner),
        _pocket([(m - s, 0.0), (m + s, 0.0)], [left, right], [up, up], (2, 2), *side),
        _pocket([(L - c, 0.0), (L, c)], [left, up], [up, left], (2, 1), *corner),
        _pocket([(c, W), (0.0, W - c)], [right, down], [down, right], (3, 0), *corner),
        _pocket([(m - s, W), (m + s, W)], [left, right], [down, down], (3, 3), *side),
        _pocket([(L - c, W), (L, W - c)], [left, down], [down, left], (3, 1), *corner),
    )


def rail_segments(length: float, width: float, jaws: tuple[PocketJaws, ...]) -> NDArray[np.float64]:
    """The straight cushion noses between the pockets, ``(M, 2, 2)`` of ``(start, end)``.

    Without pockets (or with capture circles) the four full sides.
    """
    L, W = length, width
    if not jaws:
        return _frozen([[(0, 0), (L, 0)], [(L, 0), (L, W)], [(L, W), (0, W)], [(0, W), (0, 0)]])
    bl, bm, br, tl, tm, tr = (j.rail_ends for j in jaws)
    return _frozen(
        [
            (bl[0], bm[0]),
            (bm[1], br[0]),
            (br[1], tr[1]),
            (tr[0], tm[1]),
            (tm[0], tl[0]),
            (tl[1], bl[1]),
        ]
    )


def kernel_rows(jaws: tuple[PocketJaws, ...], ball_radius: float) -> NDArray[np.float64]:
    """The ``(K, JAW_COLS)`` array the compiled kernels read: the jaws offset by ``R``.

    Per pocket: the fall line (a point and its unit normal to the table); each facing as the
    line a ball centre touches (start ``facing start + R n``, inward unit direction ``d``,
    free-side unit normal ``n``, extent length); each tip as its centre and contact radius
    ``tip_radius + R``; each rail opening as (rail index, lo, hi) along the rail line;
    the reach box, the bounding box of the offset facings, the tip circles and the fall
    line's end points (on the facings themselves, so beyond the offset ones): the mouth a
    centre can be in, with every centre position at which the pocket has an event.
    """
    rows = np.zeros((len(jaws), JAW_COLS), dtype=np.float64)
    for k, jaw in enumerate(jaws):
        row = rows[k]
        row[J_FX : J_FX + 2] = jaw.fall_line.mean(axis=0)
        row[J_FNX : J_FNX + 2] = jaw.fall_normal
        for f in range(2):
            start, end = jaw.facings[f]
            span = end - start
            extent = float(np.hypot(*span))
            d = span / extent
            n = np.array([-d[1], d[0]])
            # The free side is the one facing the other point (across the throat).
            if n @ (jaw.points[1 - f] - jaw.points[f]) < 0.0:
                n = -n
            col = J_FACING[f]
            row[col : col + 2] = start + ball_radius * n
            row[col + 2 : col + 4] = d
            row[col + 4 : col + 6] = n
            row[col + 6] = extent
            tip = J_TIP[f]
            row[tip : tip + 2] = jaw.tip_centres[f]
            row[tip + 2] = jaw.tip_radius + ball_radius
        corners = [jaw.fall_line]
        for f in range(2):
            start = row[J_FACING[f] : J_FACING[f] + 2]
            corners.append(
                np.array(
                    [start, start + row[J_FACING[f] + 6] * row[J_FACING[f] + 2 : J_FACING[f] + 4]]
                )
            )
            rho = jaw.tip_radius + ball_radius
            corners.append(np.array([jaw.tip_centres[f] - rho, jaw.tip_centres[f] + rho]))
        every = np.concatenate(corners)
        row[J_BOX : J_BOX + 2] = every.min(axis=0)
        row[J_BOX + 2 : J_BOX + 4] = every.max(axis=0)
        rails = sorted(set(jaw.rails))
        for o in range(2):
            col = J_OPEN[o]
            if o >= len(rails):
                row[col : col + 3] = (-1.0, 0.0, 0.0)
                continue
            rail = rails[o]
            axis = 1 if rail < 2 else 0  # coordinate along the rail line
            if len(rails) == 1:  # side pocket: between its two rail ends
                ends = sorted(float(jaw.rail_ends[f][axis]) for f in range(2))
                lo, hi = ends[0], ends[1]
            else:  # corner: from the rail end of this rail's point outwards past the corner
                f = jaw.rails.index(rail)
                end = float(jaw.rail_ends[f][axis])
                corner_side = float(jaw.points[1 - f][axis]) < end
                lo, hi = (-math.inf, end) if corner_side else (end, math.inf)
            row[col : col + 3] = (float(rail), lo, hi)
    rows.setflags(write=False)
    return rows
