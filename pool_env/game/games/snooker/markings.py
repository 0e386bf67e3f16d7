"""The snooker table's markings and the game's two scenes (WPBSA Rules, Section 1).

Coordinates are the package's: ``x`` along the table from the baulk cushion (``x = 0``)
to the top cushion (``x = L``), ``y`` across it; looking up the table from the baulk end,
``+y`` is on the left. The markings are WPBSA Section 1 Rule 1(c) on the 12 ft table
(3569 x 1778 mm), scaled with the table's length on a smaller one ("all markings scaled
down"), so that the game plays on any table with pockets:

- the baulk line 737 mm from the face of the baulk cushion, the D a semicircle of radius
  292 mm centred on the middle of the baulk line, on the baulk side;
- the spots: brown on the middle of the baulk line, yellow on the right-hand corner of the
  D and green on the left-hand one (viewed from the baulk end: yellow at ``y = W/2 - r``),
  blue on the centre spot, pink midway between the centre spot and the face of the top
  cushion, black 324 mm from the face of the top cushion.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.table import Table

#: The WPBSA table these distances are given on (Section 1 Rule 1: playing area, mm).
WPBSA_LENGTH = 3.569
BAULK_LINE = 0.737  # from the face of the baulk cushion
D_RADIUS = 0.292
BLACK_FROM_TOP = 0.324

#: The colours' ball numbers, lowest value first: yellow .. black.
YELLOW, GREEN, BROWN, BLUE, PINK, BLACK = range(16, 22)
COLOURS = (YELLOW, GREEN, BROWN, BLUE, PINK, BLACK)
N_REDS = 15
N_BALLS = 22


class Markings(NamedTuple):
    """The markings of one table (m).

    Attributes:
        baulk_x: The baulk line (``x``).
        d_radius: The D's radius.
        centre_y: The table's long centre line (``y``).
        spots: ``(6, 2)`` the colours' spots, yellow .. black.
    """

    baulk_x: float
    d_radius: float
    centre_y: float
    spots: NDArray[np.float64]


def markings(table: Table) -> Markings:
    """The table's markings, WPBSA's scaled by ``table.length / 3.569``."""
    scale = table.length / WPBSA_LENGTH
    baulk, radius, cy = BAULK_LINE * scale, D_RADIUS * scale, table.width / 2.0
    centre = table.length / 2.0
    spots = np.array(
        [
            (baulk, cy - radius),  # yellow: the D's right-hand corner from the baulk end
            (baulk, cy + radius),  # green: its left-hand corner
            (baulk, cy),  # brown: the middle of the baulk line
            (centre, cy),  # blue: the centre spot
            ((centre + table.length) / 2.0, cy),  # pink: midway to the top cushion
            (table.length - BLACK_FROM_TOP * scale, cy),  # black
        ]
    )
    return Markings(baulk, radius, cy, spots)


def d_point(mark: Markings, u: float, v: float) -> tuple[float, float]:
    """The point of the D at ``(u, v)`` in ``[0, 1] x [-1, 1]``: the cue ball in hand.

    ``u`` goes from the baulk line (0) back to the D's rear (1); ``v`` across the chord of
    the D at that depth: the unit square maps onto the whole D (Section 3 Rule 5: the cue
    ball in hand is placed on or within the lines of the D).
    """
    depth = u * mark.d_radius
    half = np.sqrt(max(mark.d_radius**2 - depth**2, 0.0))
    return mark.baulk_x - depth, mark.centre_y + v * half


def frame_layout(table: Table, rng: np.random.Generator | None = None) -> NDArray[np.float64]:
    """The frame's opening layout (Section 3 Rule 2): ``(22, 2)``, the cue ball in the D.

    The 15 reds in an equilateral triangle, its apex as near the pink as it may be without
    touching it (a gap of a ball's radius / 10 here), its base parallel to the top
    cushion; the colours on their spots; the cue ball (in hand: the first stroke places
    it) at the brown's side of the D, on the centre of the D's rear half. ``rng`` is
    not drawn from (the layout is fixed).
    """
    mark = markings(table)
    r = table.ball_radius
    out = np.zeros((N_BALLS, 2))
    out[0] = d_point(mark, 0.5, 0.5)
    out[YELLOW : BLACK + 1] = mark.spots
    pink_x, cy = mark.spots[PINK - YELLOW]
    gap = 2.0 * r * (1.0 + 1e-6)  # touching within rounding would be an overlap
    apex = pink_x + 2.0 * r + r / 10.0
    k = 1
    for row in range(5):
        for col in range(row + 1):
            out[k] = (apex + row * gap * np.sqrt(3.0) / 2.0, cy + (col - row / 2.0) * gap)
            k += 1
    return out


def break_layout(table: Table, rng: np.random.Generator) -> NDArray[np.float64]:
    """The break-building scene: the colours on their spots, the reds spread at random.

    Each red is drawn uniformly over the half of the table above the blue (``x`` between
    the centre spot and the top cushion, inside the rails), at least four ball radii from
    every other ball and from each pocket's capture circle (so no red sits in a jaw or
    touches another ball: each is a ball a player can aim at), redrawn until it is; the
    cue ball is in the D (in hand: the first stroke places it). Drawn from the reset's
    generator, so a seed gives one layout.
    """
    mark = markings(table)
    r = table.ball_radius
    out = np.zeros((N_BALLS, 2))
    out[0] = d_point(mark, 0.5, 0.5)
    out[YELLOW : BLACK + 1] = mark.spots
    low_x, high_x = table.length / 2.0 + 2.0 * r, table.length - 2.0 * r
    low_y, high_y = 2.0 * r, table.width - 2.0 * r
    pockets = table.pockets
    placed = [out[0], *out[YELLOW:]]
    for k in range(1, N_REDS + 1):
        while True:
            p = np.array([rng.uniform(low_x, high_x), rng.uniform(low_y, high_y)])
            if all(np.hypot(*(p - q)) >= 4.0 * r for q in placed) and all(
                np.hypot(*(p - c[:2])) >= c[2] + 4.0 * r for c in pockets
            ):
                break
        out[k] = p
        placed.append(p)
    return out


#: The game's own scenes (``scene=<name>`` on its tables).
SCENES = {"snooker": frame_layout, "snooker_break": break_layout}
