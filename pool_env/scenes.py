"""Scenes: where the balls start. Configuration (a name and a ball count), never subclasses.

Every function here is pure: a table, arrays and a ``numpy.random.Generator`` in, arrays out.
Row 0 of a layout is the cue ball; rows ``1..n`` are the object balls numbered ``1..n``.

Scenes (the ``scene=`` argument of :class:`pool_env.env.PoolEnv`):

========== =============== ==================================================================
name       object balls    starting state
========== =============== ==================================================================
one_ball   1               cue and object ball uniformly at random on the table
random     ``n_balls``     cue and ``n_balls`` object balls uniformly at random (default 3)
nine_ball  9               the 9-ball diamond on the foot spot; cue in the kitchen (break)
eight_ball 15              the 15-ball triangle on the foot spot; cue in the kitchen (break)
========== =============== ==================================================================

"Uniformly at random" means centres uniform over ``[R, L - R] x [R, W - R]``, rejected when
inside a pocket's capture circle or closer than ``2R`` to a ball already placed. The kitchen
is the area behind the head string (``x <= L / 4``), where the cue ball is placed for a break.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.layouts import break_scene, head_spot
from pool_env.sim.simulate import shoot
from pool_env.sim.table import Table

#: Scene names and their number of object balls (``None``: set by ``n_balls``).
SCENES: dict[str, int | None] = {"one_ball": 1, "random": None, "nine_ball": 9, "eight_ball": 15}

#: Object balls of the ``"random"`` scene when ``n_balls`` is not given.
DEFAULT_RANDOM_BALLS = 3

#: Largest ``n_balls`` of the ``"random"`` scene (the 15 numbered balls of a pool set).
MAX_RANDOM_BALLS = 15

#: Extra clearance (m) kept between sampled balls and from capture circles, so that a layout
#: never trips the simulator's overlap or in-pocket checks through rounding.
CLEARANCE = 1e-7

#: A scene is a name, a fixed ``(N, 2)`` layout, or a callable ``(table, rng) -> (N, 2)``.
SceneSpec = str | ArrayLike | Callable[[Table, np.random.Generator], ArrayLike]

_MAX_TRIES = 4096  # failed draws in a row before a layout is declared impossible


def n_object_balls(scene: str, n_balls: int | None) -> int:
    """Number of object balls of a named scene.

    Args:
        scene: A name from :data:`SCENES`.
        n_balls: Requested object balls, or ``None`` for the scene's default.

    Returns:
        The number of object balls.

    Raises:
        ValueError: On an unknown scene, or an ``n_balls`` the scene cannot have.
    """
    if scene not in SCENES:
        raise ValueError(
            f"scene must be one of {sorted(SCENES)}, a layout or a callable, got {scene!r}"
        )
    fixed = SCENES[scene]
    if n_balls is not None and (
        isinstance(n_balls, bool) or not isinstance(n_balls, int | np.integer)
    ):
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
    pos = np.array(positions, dtype=np.float64)
    if pos.ndim != 2 or pos.shape[1] != 2 or pos.shape[0] < 2:
        raise ValueError(
            f"a layout must have shape (N, 2) with N >= 2 (cue first), got {pos.shape}"
        )
    if n_total is not None and pos.shape[0] != n_total:
        raise ValueError(f"the layout has {pos.shape[0]} balls, the environment {n_total}")
    shoot(table, pos, 0.0, 0.0, record=False)  # raises the simulator's ValueError, if any
    return pos


def sample_uniform(
    table: Table,
    n: int,
    rng: np.random.Generator,
    box: tuple[float, float, float, float] | None = None,
    placed: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """Place ``n`` balls uniformly at random, one after another, by rejection.

    Scalar Python on purpose: a layout of a few balls is a handful of checks, and numpy
    would spend more on calling overhead than on arithmetic (a ``OneBall`` reset is on the
    hot path of training, since every episode is one shot).

    Args:
        table: The table.
        n: Number of balls to place.
        rng: The source of randomness.
        box: ``(x_low, x_high, y_low, y_high)`` for the centres; the whole table by default.
        placed: ``(M, 2)`` balls already on the table that the new ones must not overlap.

    Returns:
        ``(n, 2)`` centres.

    Raises:
        ValueError: If some ball finds no free place in 4,096 tries (the scene does not fit).
    """
    r = table.ball_radius
    x0, x1, y0, y1 = box if box is not None else (r, table.length - r, r, table.width - r)
    pockets = _capture_circles(table)
    min_d2 = (2.0 * r + CLEARANCE) ** 2
    balls = [] if placed is None else [(x, y) for x, y in np.asarray(placed).tolist()]
    n_fixed = len(balls)
    failures = 0
    while len(balls) < n_fixed + n:
        # Draw a few spare points per call: most layouts need a single call.
        for u, v in rng.random((n_fixed + n - len(balls) + 2, 2)).tolist():
            x, y = x0 + u * (x1 - x0), y0 + v * (y1 - y0)
            if _clear(x, y, pockets, balls, min_d2):
                balls.append((x, y))
                failures = 0
                if len(balls) == n_fixed + n:
                    break
            else:
                failures += 1
        if failures >= _MAX_TRIES:
            raise ValueError(
                f"cannot lay out the scene: no free place for ball {len(balls)} of "
                f"{n_fixed + n} after {_MAX_TRIES} random tries in x in [{x0:.4g}, {x1:.4g}], "
                f"y in [{y0:.4g}, {y1:.4g}] on a {table.length} x {table.width} m table; "
                "use fewer balls, smaller balls or a larger table"
            )
    return np.array(balls[n_fixed:], dtype=np.float64).reshape(n, 2)


@functools.lru_cache(maxsize=64)
def _capture_circles(table: Table) -> list[tuple[float, float, float]]:
    """``(x, y, (radius + clearance)^2)`` of each pocket, as floats (tables are immutable)."""
    return [(px, py, (pr + CLEARANCE) ** 2) for px, py, pr in table.pockets.tolist()]


def _clear(
    x: float,
    y: float,
    pockets: list[tuple[float, float, float]],
    balls: list[tuple[float, float]],
    min_d2: float,
) -> bool:
    """Whether ``(x, y)`` is outside every (squared) capture circle and ``2R`` from each ball."""
    # Plain loops with early exits: about twice as fast as all() over generators here.
    for px, py, pr2 in pockets:
        if (x - px) ** 2 + (y - py) ** 2 <= pr2:
            return False
    for bx, by in balls:  # noqa: SIM110
        if (x - bx) ** 2 + (y - by) ** 2 < min_d2:
            return False
    return True


def kitchen_box(table: Table) -> tuple[float, float, float, float]:
    """The kitchen, behind the head string: centres with ``x <= L / 4``."""
    r = table.ball_radius
    return (r, table.length / 4.0, r, table.width - r)


def sample_scene(
    scene: str, table: Table, n_objects: int, rng: np.random.Generator
) -> NDArray[np.float64]:
    """Draw the starting layout of a named scene.

    Args:
        scene: A name from :data:`SCENES`.
        table: The table.
        n_objects: Number of object balls (see :func:`n_object_balls`).
        rng: The source of randomness.

    Returns:
        ``(1 + n_objects, 2)`` centres, cue first.

    Raises:
        ValueError: If the scene does not fit on the table, or on an unknown name.
    """
    if scene in ("one_ball", "random"):
        return sample_uniform(table, 1 + n_objects, rng)
    if scene in ("nine_ball", "eight_ball"):
        layout = break_scene(table, "nine" if scene == "nine_ball" else "eight")
        layout[0] = sample_uniform(table, 1, rng, kitchen_box(table), placed=layout[1:])[0]
        return layout
    raise ValueError(f"unknown scene {scene!r}")


def free_spot(
    table: Table,
    positions: NDArray[np.float64],
    occupied: NDArray[np.bool_],
    target: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """The free point nearest to ``target`` (the head spot by default) for a re-spotted ball.

    A point is free when it lies inside the rails, outside every capture circle and at least
    ``2R`` from every occupied ball. The nearest free point is the target itself, the radial
    projection of the target onto the ``2R`` circle of one ball, or an intersection of two
    such circles; these candidates are checked exactly. A ring search around the target is
    the fallback for the rare case that the rails or a pocket cut all of them off.

    Args:
        table: The table.
        positions: ``(N, 2)`` centres.
        occupied: ``(N,)`` which rows are balls on the table (the ball to place excluded).
        target: The preferred point.

    Returns:
        The ``(2,)`` free point.

    Raises:
        ValueError: If the table has no free point at all.
    """
    target = head_spot(table) if target is None else np.array(target, dtype=np.float64)
    balls = positions[occupied]
    reach = 2.0 * table.ball_radius + CLEARANCE
    tx, ty = target.tolist()
    r = table.ball_radius
    inside = r <= tx <= table.length - r and r <= ty <= table.width - r
    if inside and _clear(tx, ty, _capture_circles(table), balls.tolist(), reach * reach):
        return target  # the usual case, without building candidates
    cands = [target[None, :]]
    if balls.shape[0]:
        d = target - balls
        norm = np.hypot(d[:, 0], d[:, 1])
        unit = np.where(norm[:, None] > 0.0, d / np.maximum(norm, 1e-300)[:, None], [1.0, 0.0])
        cands.append(balls + reach * unit)
        i, j = np.triu_indices(balls.shape[0], 1)
        sep = balls[j] - balls[i]
        dist = np.hypot(sep[:, 0], sep[:, 1])
        near = (dist > 0.0) & (dist < 2.0 * reach)
        if np.any(near):
            a, s, dist = balls[i[near]], sep[near], dist[near]
            mid = a + 0.5 * s
            h = np.sqrt(np.maximum(reach * reach - 0.25 * dist * dist, 0.0)) * 1.000001
            perp = np.stack([-s[:, 1], s[:, 0]], axis=1) / dist[:, None]
            cands += [mid + h[:, None] * perp, mid - h[:, None] * perp]
    cand = np.concatenate(cands)
    ok = _free(table, cand, balls, reach)
    if np.any(ok):
        dist = np.hypot(*(cand[ok] - target).T)
        return cand[ok][int(np.argmin(dist))].copy()
    step = table.ball_radius / 4.0
    for ring in range(1, int(math.hypot(table.length, table.width) / step) + 1):
        k = max(8, int(2.0 * math.pi * ring))
        phi = np.linspace(0.0, 2.0 * math.pi, k, endpoint=False)
        cand = target + ring * step * np.stack([np.cos(phi), np.sin(phi)], axis=1)
        ok = _free(table, cand, balls, reach)
        if np.any(ok):
            return cand[int(np.argmax(ok))].copy()
    raise ValueError("no free point on the table to re-spot the ball")


def _free(
    table: Table, cand: NDArray[np.float64], balls: NDArray[np.float64], reach: float
) -> NDArray[np.bool_]:
    """Which candidate points are inside the rails, out of the pockets and clear of the balls."""
    r = table.ball_radius
    x, y = cand[:, 0], cand[:, 1]
    ok = (x >= r) & (x <= table.length - r) & (y >= r) & (y <= table.width - r)
    for px, py, pr in table.pockets:
        ok &= (x - px) ** 2 + (y - py) ** 2 > (pr + CLEARANCE) ** 2
    for bx, by in balls:
        ok &= (x - bx) ** 2 + (y - by) ** 2 >= (reach - CLEARANCE / 2.0) ** 2
    return ok


class SceneSampler:
    """A picklable sampler ``rng -> (N, 2)`` for one scene on one table.

    Args:
        scene: A name from :data:`SCENES`, a fixed ``(N, 2)`` layout (cue first), or a
            callable ``(table, rng) -> (N, 2)``.
        table: The table.
        n_objects: Number of object balls.
    """

    def __init__(self, scene: SceneSpec, table: Table, n_objects: int) -> None:
        self.scene = scene
        self.table = table
        self.n_objects = n_objects

    def __call__(self, rng: np.random.Generator) -> NDArray[np.float64]:
        """Draw a layout (a fresh array: a fixed layout is copied)."""
        scene = self.scene
        if isinstance(scene, str):
            return sample_scene(scene, self.table, self.n_objects, rng)
        if callable(scene):
            return check_layout(self.table, scene(self.table, rng), self.n_objects + 1)
        return np.array(scene, dtype=np.float64)


def make_sampler(scene: SceneSpec, table: Table, n_balls: int | None) -> tuple[SceneSampler, int]:
    """Turn a scene specification into a sampler and its number of object balls.

    A named scene is laid out once here (with a fixed seed), so that a scene that does not
    fit fails when the environment is made, not at its first reset.

    Args:
        scene: A name from :data:`SCENES`, a fixed ``(N, 2)`` layout (cue first), or a
            callable ``(table, rng) -> (N, 2)``.
        table: The table.
        n_balls: Requested object balls (``None``: the scene's own count).

    Returns:
        ``(sampler, n_objects)``.

    Raises:
        ValueError: Naming the argument: an unknown scene, a count the scene cannot have, a
            scene that does not fit, or an invalid layout.
    """
    if isinstance(scene, str):
        n = n_object_balls(scene, n_balls)
        try:
            sample_scene(scene, table, n, np.random.default_rng(0))
        except ValueError as exc:
            raise ValueError(f"scene={scene!r}, n_balls={n}: {exc}") from None
        return SceneSampler(scene, table, n), n
    try:
        if callable(scene):
            n = check_layout(table, scene(table, np.random.default_rng(0))).shape[0] - 1
        else:
            scene = check_layout(table, scene)
            scene.setflags(write=False)
            n = scene.shape[0] - 1
    except ValueError as exc:
        kind = "callable" if callable(scene) else "layout"
        raise ValueError(f"scene ({kind}): {exc}") from None
    if n_balls is not None and n_balls != n:
        raise ValueError(f"n_balls={n_balls} does not match the scene's {n} object balls")
    return SceneSampler(scene, table, n), n
