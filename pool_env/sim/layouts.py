"""Standard ball layouts: spots, the 9-ball diamond, the 10-ball and 8-ball triangles.

Touching balls: rack neighbours are placed ``2R + gap`` apart (``gap = 0`` by default, so a
rack touches as a real, tightly racked one does, up to rounding of the last bit). The
simulator accepts overlaps up to 1e-9 m from such rounding, and resolves the simultaneous
contacts of a break by its documented sequential rule (see ``pool_env.sim.kernels.loop``). A
positive ``gap`` separates the balls, so every impact of the break has its own instant.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.table import Table


def head_spot(table: Table) -> NDArray[np.float64]:
    """The head spot: a quarter of the length from the ``x = 0`` end, on the centre line."""
    return np.array([table.length / 4.0, table.width / 2.0])


def foot_spot(table: Table) -> NDArray[np.float64]:
    """The foot spot (apex of the rack): three quarters of the length, on the centre line."""
    return np.array([3.0 * table.length / 4.0, table.width / 2.0])


def _triangle_rows(table: Table, row_sizes: tuple[int, ...], gap: float) -> NDArray[np.float64]:
    """Centres of a rack with the given row sizes, apex on the foot spot, opening to +x."""
    if not (math.isfinite(gap) and gap >= 0.0):
        raise ValueError(f"gap must be a non-negative finite number, got {gap!r}")
    pitch = 2.0 * table.ball_radius + gap
    row_step = pitch * math.sqrt(3.0) / 2.0
    apex = foot_spot(table)
    points = []
    for row, size in enumerate(row_sizes):
        # Row offsets are symmetric about the centre line; a diamond's later rows shrink.
        for k in range(size):
            points.append((apex[0] + row * row_step, apex[1] + (k - (size - 1) / 2.0) * pitch))
    out = np.array(points, dtype=np.float64)
    r = table.ball_radius
    if out[:, 0].max() > table.length - r or np.any(np.abs(out[:, 1] - apex[1]) > apex[1] - r):
        raise ValueError(f"the rack does not fit on a {table.length} x {table.width} m table")
    return out


def rack_nine_ball(table: Table, gap: float = 0.0) -> NDArray[np.float64]:
    """The 9-ball diamond (rows 1-2-3-2-1), apex on the foot spot.

    Row ``i`` of a diamond sits where row ``i`` of a triangle would, so its rows of 2 after
    the middle row lie between the middle row's balls.

    Args:
        table: The table.
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(9, 2)`` centres for balls 1..9: the 1 at the apex, the 9 in the centre, the rest
        in a fixed order (2, 3 on the second row; 4, 5 flanking the 9; 6, 7; 8 at the back).
    """
    pts = _triangle_rows(table, (1, 2, 3, 2, 1), gap)
    # Triangle order: apex, row2 (2), row3 (3), row4 (2), row5 (1). Put the 9 in the middle.
    order = [0, 1, 2, 3, 5, 6, 7, 8, 4]
    return pts[order]


def rack_eight_ball(table: Table, gap: float = 0.0) -> NDArray[np.float64]:
    """The 8-ball triangle (rows 1-2-3-4-5), apex on the foot spot.

    Args:
        table: The table.
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(15, 2)`` centres for balls 1..15: the 1 at the apex, the 8 in the centre of the
        third row, the others in row order.
    """
    pts = _triangle_rows(table, (1, 2, 3, 4, 5), gap)
    # Row-major index 4 is the middle of the third row: swap it with index 7 (ball 8).
    order = list(range(15))
    order[4], order[7] = order[7], order[4]
    return pts[order]


def rack_ten_ball(table: Table, gap: float = 0.0) -> NDArray[np.float64]:
    """The 10-ball triangle (rows 1-2-3-4), apex on the foot spot (WPA 10-ball rule 2).

    Args:
        table: The table.
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(10, 2)`` centres for balls 1..10: the 1 at the apex, the 10 in the middle of the
        third row, the others in row order (2, 3 on the second row; 4, 5 flanking the 10;
        6-9 at the back).
    """
    pts = _triangle_rows(table, (1, 2, 3, 4), gap)
    # Row-major index 4 is the middle of the third row: it takes ball 10 (index 9).
    order = [0, 1, 2, 3, 5, 6, 7, 8, 9, 4]
    return pts[order]


#: The racks of :func:`break_scene`, by name.
RACKS = {"nine": rack_nine_ball, "ten": rack_ten_ball, "eight": rack_eight_ball}


def break_scene(table: Table, rack: str = "nine", gap: float = 0.0) -> NDArray[np.float64]:
    """A break: the cue ball (row 0) on the head spot, then the rack's balls.

    Args:
        table: The table.
        rack: ``"nine"`` (9-ball diamond), ``"ten"`` (10-ball triangle) or ``"eight"``
            (15-ball triangle).
        gap: Extra distance between neighbouring rack balls (m).

    Returns:
        ``(10, 2)``, ``(11, 2)`` or ``(16, 2)`` centres.

    Raises:
        ValueError: On an unknown rack name or a rack that does not fit.
    """
    if rack not in RACKS:
        raise ValueError(f"unknown rack {rack!r}: use one of {list(RACKS)}")
    return np.vstack([head_spot(table)[None, :], RACKS[rack](table, gap)])
