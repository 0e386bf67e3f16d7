"""Seeded scene suites: non-chaotic shots (1-3 collisions) and breaks.

Every suite is a pure function of its seed and size, so a rerun measures the same scenes.
Non-chaotic shots are drawn in five families and kept when our simulator counts 1 to 3
collisions (ball-ball plus cushion impacts) before everything rests; this is only a selection
rule (the reference, not our simulator, is what every method is then compared with).

* ``straight``: a straight pot attempt (cue, object ball and pocket in line).
* ``cut``: a cut pot attempt (ghost-ball aim, cut angle 10-65 degrees).
* ``bank``: the object ball sent into a rail (a bank attempt).
* ``combo``: cue -> ball 1 -> ball 2 towards a pocket (two ball-ball impacts).
* ``cushion``: the cue ball played at a random angle with one object ball on the table.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from pool_env import Table, simulate
from pool_env.sim.layouts import break_scene
from tools.shots import Scene

FAMILIES = ("straight", "cut", "bank", "combo", "cushion")
SPEEDS = (0.3, 2.5)  # m/s, cue speed range of the non-chaotic suite
MAX_COLLISIONS = 3


def _unit(angle: float) -> NDArray[np.float64]:
    return np.array([math.cos(angle), math.sin(angle)])


def _free(table: Table, p: NDArray[np.float64], others: list[NDArray[np.float64]]) -> bool:
    """Whether a ball at ``p`` is on the table, clear of pockets, rails and ``others``."""
    r = table.ball_radius
    margin = 0.5 * r
    if not (r + margin <= p[0] <= table.length - r - margin):
        return False
    if not (r + margin <= p[1] <= table.width - r - margin):
        return False
    for x, y, rad in table.pockets:
        if math.hypot(p[0] - x, p[1] - y) < rad + r:
            return False
    return all(np.hypot(*(p - q)) > 2.0 * r + margin for q in others)


def _random_point(rng: np.random.Generator, table: Table) -> NDArray[np.float64]:
    r = table.ball_radius
    return np.array(
        [rng.uniform(2 * r, table.length - 2 * r), rng.uniform(2 * r, table.width - 2 * r)]
    )


def _aim_through(
    rng: np.random.Generator,
    table: Table,
    ball: NDArray[np.float64],
    target: NDArray[np.float64],
    cut: float,
    others: list[NDArray[np.float64]],
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """Place a striker so that it sends ``ball`` towards ``target`` at a ``cut`` angle.

    Returns ``(striker position, unit direction of the striker)`` or None if it does not fit.
    """
    u = target - ball
    u /= np.hypot(*u)
    ghost = ball - 2.0 * table.ball_radius * u
    w = _unit(math.atan2(u[1], u[0]) + cut)
    start = ghost - rng.uniform(0.15, 1.0) * w
    if not _free(table, start, [*others, ball]):
        return None
    return start, w


def _draw(rng: np.random.Generator, table: Table, family: str) -> tuple | None:
    """One candidate ``(positions, cue direction)`` of ``family``, or None."""
    pockets = table.pockets[:, :2]
    if family == "cushion":
        cue, obj = _random_point(rng, table), _random_point(rng, table)
        if not (_free(table, cue, []) and _free(table, obj, [cue])):
            return None
        return np.array([cue, obj]), _unit(rng.uniform(-math.pi, math.pi))
    obj = _random_point(rng, table)
    if not _free(table, obj, []):
        return None
    if family == "bank":
        rail_y = 0.0 if rng.random() < 0.5 else table.width
        target = np.array([rng.uniform(0.2, table.length - 0.2), rail_y])
    else:
        target = pockets[rng.integers(len(pockets))]
    if family == "combo":
        placed = _aim_through(rng, table, obj, target, rng.uniform(-0.3, 0.3), [])
        if placed is None:
            return None
        first = placed[0] + 0.0  # ball 1 sits where its striker would start
        ghost_target = first + placed[1]
        aim = _aim_through(rng, table, first, ghost_target, rng.uniform(-0.5, 0.5), [obj])
        if aim is None:
            return None
        return np.array([aim[0], first, obj]), aim[1]
    cut = 0.0 if family == "straight" else rng.choice([-1, 1]) * rng.uniform(0.17, 1.13)
    aim = _aim_through(rng, table, obj, target, cut, [])
    if aim is None:
        return None
    return np.array([aim[0], obj]), aim[1]


def _collisions(
    table: Table, positions: NDArray[np.float64], velocities: NDArray[np.float64]
) -> int:
    res = simulate(table, positions, velocities)
    return int(np.count_nonzero((res.event_kinds == 1) | (res.event_kinds == 2)))


def shot_suite(n: int, seed: int = 2024, table: Table | None = None) -> list[Scene]:
    """``n`` non-chaotic shots (1-3 collisions), the families in turn.

    Args:
        n: Number of scenes.
        seed: Seed of the generator.
        table: The table (default: ``Table(pockets="circles")``, the pocket model the
            fixed-step and pymunk engines share).

    Returns:
        The scenes, ordered by index.
    """
    table = Table(pockets="circles") if table is None else table
    rng = np.random.default_rng(seed)
    scenes: list[Scene] = []
    while len(scenes) < n:
        family = FAMILIES[len(scenes) % len(FAMILIES)]
        drawn = _draw(rng, table, family)
        if drawn is None:
            continue
        positions, direction = drawn
        velocities = np.zeros_like(positions)
        velocities[0] = rng.uniform(*SPEEDS) * direction
        if not 1 <= _collisions(table, positions, velocities) <= MAX_COLLISIONS:
            continue
        scenes.append(Scene(f"{family}-{len(scenes)}", family, table, positions, velocities, 1))
    return scenes


def break_suite(n: int, seed: int = 7, table: Table | None = None) -> list[Scene]:
    """``n`` breaks, alternating a 9-ball diamond and a 15-ball triangle (touching racks).

    The cue ball starts on the head string up to 15 cm off the centre line and is aimed at
    the apex ball within a normal scatter of 0.5 degrees, at 6-9 m/s.

    Args:
        n: Number of breaks.
        seed: Seed of the generator.
        table: The table (default: ``Table(pockets="circles")``, the pocket model the
            fixed-step and pymunk engines share).

    Returns:
        The scenes (ball 0 is the cue, ball 1 the apex).
    """
    table = Table(pockets="circles") if table is None else table
    rng = np.random.default_rng(seed)
    scenes = []
    for k in range(n):
        rack = "nine" if k % 2 == 0 else "eight"
        positions = break_scene(table, rack)
        positions[0, 1] += rng.uniform(-0.15, 0.15)
        d = positions[1] - positions[0]
        angle = math.atan2(d[1], d[0]) + math.radians(rng.normal(0.0, 0.5))
        velocities = np.zeros_like(positions)
        velocities[0] = rng.uniform(6.0, 9.0) * _unit(angle)
        scenes.append(Scene(f"break-{rack}-{k}", f"break-{rack}", table, positions, velocities, 1))
    return scenes
