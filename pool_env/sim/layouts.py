"""Standard ball layouts: spots, the 9-ball diamond, the 10-ball and 8-ball triangles.

Touching balls: rack neighbours are placed ``2R + gap`` apart (``gap = 0`` by default, so a
rack touches as a real, tightly racked one does, up to rounding of the last bit). The
simulator accepts overlaps up to 1e-9 m from such rounding, and resolves the simultaneous
contacts of a break by its documented sequential rule (see ``pool_env.sim.kernels.loop``). A
positive ``gap`` separates the balls, so every impact of the break has its own instant.

A rack is its spots (:func:`rack_spots`) and an order of the balls on them: the fixed order
of :func:`rack_nine_ball`, :func:`rack_ten_ball` and :func:`rack_eight_ball`, or an order
drawn as the rules rack the balls (:func:`shuffled_spots`: the balls the rules place on
their spots, the others at random), which the environments' rack scenes use by default.
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


#: Row sizes of each rack, apex first: the 9-ball diamond, the 10-ball and 8-ball triangles.
RACK_ROWS: dict[str, tuple[int, ...]] = {
    "nine": (1, 2, 3, 2, 1),
    "ten": (1, 2, 3, 4),
    "eight": (1, 2, 3, 4, 5),
}

#: The fixed order of each rack: the spot (index into :func:`rack_spots`) of ball 1, 2, ...
#: 9-ball: the 1 at the apex, the 9 in the centre (spot 4), 2-8 in row order around it;
#: 10-ball: the 1 at the apex, the 10 in the middle of the third row (spot 4), 2-9 in row
#: order; 8-ball: the 1 at the apex, the 8 in the centre of the third row (spot 4, where the
#: 5 would be: the 5 takes the 8's spot 7), the others in row order.
FIXED_SPOTS: dict[str, tuple[int, ...]] = {
    "nine": (0, 1, 2, 3, 5, 6, 7, 8, 4),
    "ten": (0, 1, 2, 3, 5, 6, 7, 8, 9, 4),
    "eight": (0, 1, 2, 3, 7, 5, 6, 4, 8, 9, 10, 11, 12, 13, 14),
}

#: The balls each game's rules rack on a given spot, ``{ball: spot}`` (the WPA rules'
#: "racking the balls"): 9-ball the 1 on the apex (the foot spot) and the 9 in the centre
#: of the diamond; 10-ball the 1 on the apex and the 10 in the middle of the third row;
#: 8-ball the 8 in the centre of the third row (and a solid and a stripe in the back
#: corners, :data:`EIGHT_CORNERS`). The other balls go anywhere.
PINNED: dict[str, dict[int, int]] = {
    "nine": {1: 0, 9: 4},
    "ten": {1: 0, 10: 4},
    "eight": {8: 4},
}

#: The two back corners of the 8-ball triangle (spots of :func:`rack_spots`): the rules put
#: a solid (1-7) in one and a stripe (9-15) in the other.
EIGHT_CORNERS = (10, 14)


def rack_spots(table: Table, rack: str, gap: float = 0.0) -> NDArray[np.float64]:
    """The spots of a rack in row order, apex on the foot spot, the rack opening to +x.

    Row ``i`` of a diamond sits where row ``i`` of a triangle would, so its rows of 2 after
    the middle row lie between the middle row's balls. Within a row the spots run from low
    to high ``y``.

    Args:
        table: The table.
        rack: ``"nine"``, ``"ten"`` or ``"eight"`` (:data:`RACK_ROWS`).
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(n, 2)`` centres: the apex first, then each row.

    Raises:
        ValueError: On an unknown rack, a bad gap or a rack that does not fit on the table.
    """
    if rack not in RACK_ROWS:
        raise ValueError(f"unknown rack {rack!r}: use one of {list(RACK_ROWS)}")
    if not (math.isfinite(gap) and gap >= 0.0):
        raise ValueError(f"gap must be a non-negative finite number, got {gap!r}")
    pitch = 2.0 * table.ball_radius + gap
    row_step = pitch * math.sqrt(3.0) / 2.0
    apex = foot_spot(table)
    points = []
    for row, size in enumerate(RACK_ROWS[rack]):
        # Row offsets are symmetric about the centre line; a diamond's later rows shrink.
        for k in range(size):
            points.append((apex[0] + row * row_step, apex[1] + (k - (size - 1) / 2.0) * pitch))
    out = np.array(points, dtype=np.float64)
    r = table.ball_radius
    if out[:, 0].max() > table.length - r or np.any(np.abs(out[:, 1] - apex[1]) > apex[1] - r):
        raise ValueError(f"the rack does not fit on a {table.length} x {table.width} m table")
    return out


def shuffled_spots(rack: str, rng: np.random.Generator) -> NDArray[np.intp]:
    """A rack as the rules rack it: the spot of each ball 1, 2, ..., the free ones at random.

    The balls of :data:`PINNED` take their spots; in 8-ball a solid and a stripe, each
    uniform over its group, take the back corners (:data:`EIGHT_CORNERS`), which one takes
    which at random; the other balls take the other spots in a uniformly random order. Every
    rack the rules allow is equally likely. Draws, in this order: (8-ball) the solid, the
    stripe and the corner of the solid (``rng.integers``), then the order
    (``rng.permutation``).

    Args:
        rack: ``"nine"``, ``"ten"`` or ``"eight"``.
        rng: The generator drawn from.

    Returns:
        ``(n,)`` the spot (index into :func:`rack_spots`) of ball ``1 + i`` at ``i``.
    """
    pinned = dict(PINNED[rack])
    if rack == "eight":
        solid, stripe = int(rng.integers(1, 8)), int(rng.integers(9, 16))
        first = int(rng.integers(2))  # which corner the solid takes
        pinned[solid], pinned[stripe] = EIGHT_CORNERS[first], EIGHT_CORNERS[1 - first]
    n = sum(RACK_ROWS[rack])
    taken = set(pinned.values())
    free_balls = [ball for ball in range(1, n + 1) if ball not in pinned]
    free_spots = np.array([spot for spot in range(n) if spot not in taken], dtype=np.intp)
    out = np.empty(n, dtype=np.intp)
    for ball, spot in pinned.items():
        out[ball - 1] = spot
    out[np.array(free_balls) - 1] = rng.permutation(free_spots)
    return out


def rack_nine_ball(table: Table, gap: float = 0.0) -> NDArray[np.float64]:
    """The 9-ball diamond (rows 1-2-3-2-1) in its fixed order, apex on the foot spot.

    Args:
        table: The table.
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(9, 2)`` centres for balls 1..9: the 1 at the apex, the 9 in the centre, the rest
        in a fixed order (2, 3 on the second row; 4, 5 flanking the 9; 6, 7; 8 at the back).
        The environments' rack scenes draw the order (:func:`shuffled_spots`).
    """
    return rack_spots(table, "nine", gap)[list(FIXED_SPOTS["nine"])]


def rack_eight_ball(table: Table, gap: float = 0.0) -> NDArray[np.float64]:
    """The 8-ball triangle (rows 1-2-3-4-5) in its fixed order, apex on the foot spot.

    Args:
        table: The table.
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(15, 2)`` centres for balls 1..15: the 1 at the apex, the 8 in the centre of the
        third row, the others in row order (the back corners take two stripes, 11 and 15;
        the environments' rack scenes draw the order as the rules rack it,
        :func:`shuffled_spots`).
    """
    return rack_spots(table, "eight", gap)[list(FIXED_SPOTS["eight"])]


def rack_ten_ball(table: Table, gap: float = 0.0) -> NDArray[np.float64]:
    """The 10-ball triangle (rows 1-2-3-4) in its fixed order, apex on the foot spot.

    WPA 10-ball rule 2 racks the 1 on the foot spot and the 10 in the middle of the third row.

    Args:
        table: The table.
        gap: Extra distance between neighbouring balls (m), 0 for a touching rack.

    Returns:
        ``(10, 2)`` centres for balls 1..10: the 1 at the apex, the 10 in the middle of the
        third row, the others in row order (2, 3 on the second row; 4, 5 flanking the 10;
        6-9 at the back). The environments' rack scenes draw the order
        (:func:`shuffled_spots`).
    """
    return rack_spots(table, "ten", gap)[list(FIXED_SPOTS["ten"])]


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
