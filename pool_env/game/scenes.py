"""Scenes: where the balls start, and where a re-spotted ball goes.

Configuration (a name and a ball count), never subclasses. Row 0 of a layout is the cue
ball; rows ``1..n`` are the object balls numbered ``1..n``.

Scenes (the ``scene=`` argument of :class:`pool_env.PoolEnv`):

========== =============== ==================================================================
name       object balls    starting state
========== =============== ==================================================================
one_ball   1               cue and object ball uniformly at random on the table
random     ``n_balls``     cue and ``n_balls`` object balls uniformly at random (default 3)
nine_ball  9               the 9-ball diamond on the foot spot; cue in the kitchen (break)
ten_ball   10              the 10-ball triangle on the foot spot; cue in the kitchen (break)
eight_ball 15              the 15-ball triangle on the foot spot; cue in the kitchen (break)
========== =============== ==================================================================

The rack scenes rack the balls as the WPA rules do (``rack_order="random"``, the default):
9-ball the 1 on the apex and the 9 in the centre, 10-ball the 1 on the apex and the 10 in
the middle of the third row, 8-ball the 8 in the centre of the third row and a solid and a
stripe in the back corners, every other ball on a spot drawn at random by each reset from
the table's generator (:func:`pool_env.sim.layouts.shuffled_spots`), after the cue ball's
spot. ``rack_order="fixed"`` racks one order every time
(:func:`pool_env.sim.layouts.rack_nine_ball` and the others) and draws nothing for it.

"Uniformly at random" means centres uniform over ``[R, L - R] x [R, W - R]``, rejected when
inside a pocket's capture circle or closer than ``2R`` to a ball already placed (both with
:data:`CLEARANCE` to spare). The kitchen is the area behind the head string
(``x <= L / 4``), where the cue ball is placed for a break. A scene that cannot fit is
refused when it is planned (at the environment's construction), and a reset never fails:
should random placement fail :data:`RESTARTS` times in a row, the table gets a fixed
layout on a grid, which the plan checked.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.game.checks import is_integer
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.layout import free_points
from pool_env.sim.layouts import break_scene, head_spot, rack_spots
from pool_env.sim.simulate import check_positions
from pool_env.sim.table import Table

#: Scene names and their number of object balls (``None``: set by ``n_balls``).
SCENES: dict[str, int | None] = {
    "one_ball": 1, "random": None, "nine_ball": 9, "ten_ball": 10, "eight_ball": 15,
}  # fmt: skip

#: The orders of a rack scene's balls (``rack_order``): drawn as the rules rack them, or fixed.
RACK_ORDERS: tuple[str, ...] = ("random", "fixed")

#: Object balls of the ``"random"`` scene when ``n_balls`` is not given.
DEFAULT_RANDOM_BALLS = 3

#: Largest ``n_balls`` of the ``"random"`` scene (the 15 numbered balls of a pool set).
MAX_RANDOM_BALLS = 15

#: Extra clearance (m) kept between placed balls and from capture circles, so that a layout
#: never trips the simulator's overlap or in-pocket checks through rounding.
CLEARANCE = 1e-7

#: Failed random draws in a row after which an attempt at a layout starts over.
MAX_TRIES = 4096

#: Attempts at a random layout before the scene's grid layout is used instead.
RESTARTS = 16

#: A scene is a name, a fixed ``(N, 2)`` layout, or a callable ``(table, rng) -> (N, 2)``.
SceneSpec = str | ArrayLike | Callable[[Table, np.random.Generator], ArrayLike]


@dataclass(frozen=True)
class ScenePlan:
    """A scene, parsed and checked once: how each reset lays out a table.

    Attributes:
        spec: The scene as given (a name, a layout or a callable).
        n_objects: Object balls.
        fixed: The layout of a fixed scene (read-only), else ``None``.
        n_new: Balls drawn at random per layout (0: not a random scene).
        placed: ``(M, 2)`` fixed balls of a random layout (a rack), after the drawn ones.
        box: ``(4,)`` where the drawn balls go.
        fallback: ``(n_new, 2)`` drawn balls' grid layout, used when random placement fails.
        rack: The rack (``"nine"``, ``"ten"``, ``"eight"``) whose order each reset draws
            (``rack_order="random"``), or ``None``: ``placed`` keeps its order.
        spots: ``(M, 2)`` the rack's spots in row order (:func:`~pool_env.sim.layouts.rack_spots`)
            when ``rack`` is set, else empty.
    """

    spec: SceneSpec
    n_objects: int
    fixed: NDArray[np.float64] | None
    n_new: int
    placed: NDArray[np.float64]
    box: NDArray[np.float64]
    fallback: NDArray[np.float64]
    rack: str | None
    spots: NDArray[np.float64]


def placement(table: Table) -> NDArray[np.float64]:
    """The placement entries of the kernels' parameter array for ``table`` (others zero).

    Centres inside the rails, :data:`CLEARANCE` from capture circles and ``2R + CLEARANCE``
    apart; the head spot; :data:`MAX_TRIES` and :data:`RESTARTS` (see
    :mod:`pool_env.game.kernels.params`).
    """
    r = table.ball_radius
    params = np.zeros(kp.N_PARAMS)
    params[kp.RADIUS] = r
    params[[kp.X_LOW, kp.X_HIGH, kp.Y_LOW, kp.Y_HIGH]] = (r, table.length - r, r, table.width - r)
    params[kp.REACH] = 2.0 * r + CLEARANCE
    params[kp.CLEARANCE] = CLEARANCE
    params[[kp.SPOT_X, kp.SPOT_Y]] = head_spot(table)
    params[kp.DIAGONAL] = math.hypot(table.length, table.width)
    params[kp.TRIES], params[kp.RESTARTS] = MAX_TRIES, RESTARTS
    return params


def bounds(params: NDArray[np.float64]) -> NDArray[np.float64]:
    """``(x_low, x_high, y_low, y_high)`` allowed for centres."""
    return params[[kp.X_LOW, kp.X_HIGH, kp.Y_LOW, kp.Y_HIGH]].copy()


def n_object_balls(scene: str, n_balls: int | None) -> int:
    """Number of object balls of a named scene.

    Raises:
        ValueError: On an unknown scene, or an ``n_balls`` the scene cannot have.
    """
    if scene not in SCENES:
        raise ValueError(
            f"scene must be one of {sorted(SCENES)}, a layout or a callable, got {scene!r}"
        )
    fixed = SCENES[scene]
    if n_balls is not None and not is_integer(n_balls):
        raise ValueError(f"n_balls must be an integer or None, got {n_balls!r}")
    if fixed is not None:
        if n_balls is not None and n_balls != fixed:
            raise ValueError(f"n_balls={n_balls} does not fit scene {scene!r}, which has {fixed}")
        return fixed
    n = DEFAULT_RANDOM_BALLS if n_balls is None else int(n_balls)
    if not 1 <= n <= MAX_RANDOM_BALLS:
        raise ValueError(
            f"n_balls must lie in [1, {MAX_RANDOM_BALLS}] for scene {scene!r}, got {n}"
        )
    return n


def check_layout(
    table: Table, positions: ArrayLike, n_total: int | None = None
) -> NDArray[np.float64]:
    """Validate a layout: inside the rails, no overlaps, nothing in a pocket.

    Args:
        table: The table.
        positions: ``(N, 2)`` centres, cue first.
        n_total: Required number of rows, if any.

    Returns:
        The layout as a new contiguous float64 array.

    Raises:
        ValueError: Saying what is wrong (the simulator's own checks and messages).
    """
    try:
        pos = np.array(positions, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"a layout must be an (N, 2) array of numbers: {exc}") from None
    if pos.ndim != 2 or pos.shape[1] != 2:
        raise ValueError(f"a layout must have shape (N, 2), cue first, got {pos.shape}")
    if pos.shape[0] < 2:
        raise ValueError(
            f"a layout needs the cue ball and at least one object ball, got {pos.shape[0]} ball(s)"
        )
    if n_total is not None and pos.shape[0] != n_total:
        raise ValueError(f"the layout has {pos.shape[0]} balls, the environment {n_total}")
    return check_positions(table, pos)


def kitchen_box(table: Table) -> tuple[float, float, float, float]:
    """The kitchen, behind the head string: centres with ``x <= L / 4``."""
    r = table.ball_radius
    return (r, table.length / 4.0, r, table.width - r)


def grid_layout(
    table: Table, n: int, box: NDArray[np.float64], placed: NDArray[np.float64]
) -> NDArray[np.float64] | None:
    """``n`` free centres on a triangular grid over ``box`` (rows from its low corner).

    Grid points are ``reach + CLEARANCE`` apart, so every free one can take a ball.

    Returns:
        ``(n, 2)`` centres, or ``None`` when fewer than ``n`` grid points are free.
    """
    params = placement(table)
    reach = float(params[kp.REACH])
    step = reach + CLEARANCE
    x0, x1, y0, y1 = box.tolist()
    rows = int((y1 - y0) / (step * math.sqrt(3.0) / 2.0)) + 1
    cols = int((x1 - x0) / step) + 1
    grid = [
        (x0 + (c + 0.5 * (r % 2)) * step, y0 + r * step * math.sqrt(3.0) / 2.0)
        for r in range(rows)
        for c in range(cols)
    ]
    points = np.array(grid, dtype=np.float64).reshape(-1, 2)
    inside = (points[:, 0] <= x1) & (points[:, 1] <= y1)
    points = np.ascontiguousarray(points[inside])
    ok = free_points(params, table.pockets, points, placed, reach * reach)
    if np.count_nonzero(ok) < n:
        return None
    return np.ascontiguousarray(points[ok][:n])


def plan_scene(
    scene: SceneSpec, table: Table, n_balls: int | None, rack_order: str = "random"
) -> ScenePlan:
    """Parse and check a scene once; every reset then follows the plan.

    Args:
        scene: A name from :data:`SCENES`, a fixed ``(N, 2)`` layout (cue first), or a
            callable ``(table, rng) -> (N, 2)`` (called once here with a fixed seed).
        table: The table.
        n_balls: Requested object balls (``None``: the scene's own count).
        rack_order: ``"random"`` (a rack scene's balls as the rules rack them, drawn at each
            reset) or ``"fixed"`` (:data:`RACK_ORDERS`); other scenes have no rack to order.

    Returns:
        The plan.

    Raises:
        ValueError: Naming the argument: an unknown scene or rack order, a count the scene
            cannot have, a scene that does not fit on the table, or an invalid layout.
    """
    if not isinstance(rack_order, str) or rack_order not in RACK_ORDERS:
        raise ValueError(f"rack_order must be one of {list(RACK_ORDERS)}, got {rack_order!r}")
    empty = np.zeros((0, 2))
    full_table = bounds(placement(table))
    if isinstance(scene, str):
        n = n_object_balls(scene, n_balls)
        rack, spots = None, empty
        if scene in ("one_ball", "random"):
            n_new, placed, box = n + 1, empty, full_table
        else:
            name = scene.removesuffix("_ball")
            layout = break_scene(table, name)
            n_new, placed, box = 1, np.ascontiguousarray(layout[1:]), np.array(kitchen_box(table))
            if rack_order == "random":
                rack, spots = name, rack_spots(table, name)
        fallback = grid_layout(table, n_new, box, placed)
        if fallback is None:
            raise ValueError(
                f"scene={scene!r}, n_balls={n}: cannot lay out the scene: {n_new} balls do "
                f"not fit in x in [{box[0]:.4g}, {box[1]:.4g}], y in [{box[2]:.4g}, "
                f"{box[3]:.4g}] on a {table.length} x {table.width} m table (each needs "
                f"{2 * table.ball_radius + CLEARANCE:.4g} m from the others, its centre out "
                "of the pockets); "
                "use fewer balls, smaller balls or a larger table"
            )
        return ScenePlan(scene, n, None, n_new, placed, box, fallback, rack, spots)
    kind = "callable" if callable(scene) else "layout"
    try:
        given = scene(table, np.random.default_rng(0)) if callable(scene) else scene
        layout = check_layout(table, given)
    except ValueError as exc:
        raise ValueError(f"scene ({kind}): {exc}") from None
    n = layout.shape[0] - 1
    if n_balls is not None and n_balls != n:
        raise ValueError(f"n_balls={n_balls} does not match the scene's {n} object balls")
    fixed = None
    if not callable(scene):
        layout.setflags(write=False)
        fixed = layout
    return ScenePlan(scene, n, fixed, 0, empty, full_table, empty, None, empty)
