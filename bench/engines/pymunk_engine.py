"""The same model on pymunk (Chipmunk2D), set up as a pool game would use it.

Balls are circles of radius ``R`` and mass ``m`` (moment of a solid disc, zero friction so no
spin is exchanged); the rails are four static zero-radius segments on the cushion noses, so a
ball touches a rail when its centre is ``R`` from it, as in our model. pymunk multiplies the
two shapes' elasticities, so balls get ``sqrt(e_ball)`` and rails ``e_cushion /
sqrt(e_ball)``: ball-ball restitution is ``e_ball`` and ball-rail ``e_cushion``. Rolling
resistance is the usual per-step velocity update: after each ``space.step(dt)`` a moving
ball's speed drops by ``mu_roll g dt`` (and stops instead of reversing). A ball whose centre
is inside a capture circle after a step is potted and removed from the space.

``collision_slop`` defaults to 0.1, a length meant for pixel units; in metres that would let
balls overlap by 10 cm, so we set it to 1e-5 m. Everything else is pymunk's default
(10 solver iterations, no damping, no sleeping).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pymunk
from numpy.typing import NDArray

from pool_env import Table

BALL, RAIL = 1, 2
COLLISION_SLOP = 1e-5  # m


@dataclass
class PymunkResult:
    """Outcome of one pymunk run (fields mirror the fixed-step engine's tuple)."""

    positions: NDArray[np.float64]
    pocketed: NDArray[np.int64]
    steps: int
    capped: bool
    obj_velocity: NDArray[np.float64]
    hits: set[tuple[int, int]] = field(default_factory=set)
    max_overlap: float = 0.0
    max_rail_depth: float = 0.0


def _build(
    table: Table,
    positions: NDArray[np.float64],
    velocities: NDArray[np.float64],
    masses: NDArray[np.float64],
) -> tuple[pymunk.Space, list[pymunk.Body], dict[pymunk.Shape, int]]:
    space = pymunk.Space()
    space.gravity = (0.0, 0.0)
    space.collision_slop = COLLISION_SLOP
    e_ball = math.sqrt(table.e_ball)
    e_rail = table.e_cushion / e_ball if e_ball > 0.0 else 0.0
    length, width, r = table.length, table.width, table.ball_radius
    corners = [(0.0, 0.0), (length, 0.0), (length, width), (0.0, width)]
    for k in range(4):
        rail = pymunk.Segment(space.static_body, corners[k], corners[(k + 1) % 4], 0.0)
        rail.elasticity = min(e_rail, 1.0)
        rail.friction = 0.0
        rail.collision_type = RAIL
        space.add(rail)
    bodies = []
    index: dict[pymunk.Shape, int] = {}
    for i in range(positions.shape[0]):
        m = float(masses[i])
        body = pymunk.Body(m, pymunk.moment_for_circle(m, 0.0, r))
        body.position = (float(positions[i, 0]), float(positions[i, 1]))
        body.velocity = (float(velocities[i, 0]), float(velocities[i, 1]))
        shape = pymunk.Circle(body, r)
        shape.elasticity = e_ball
        shape.friction = 0.0
        shape.collision_type = BALL
        space.add(body, shape)
        bodies.append(body)
        index[shape] = i
    return space, bodies, index


def simulate_pymunk(
    table: Table,
    positions: NDArray[np.float64],
    velocities: NDArray[np.float64],
    masses: NDArray[np.float64] | None = None,
    dt: float = 1e-3,
    obj: int = -1,
    max_time: float = 200.0,
    diagnostics: bool = False,
) -> PymunkResult:
    """Simulate one shot to rest in pymunk with steps of ``dt``.

    Args:
        table: The table (its capture circles are the pockets).
        positions: ``(N, 2)`` centres.
        velocities: ``(N, 2)`` velocities.
        masses: ``(N,)`` masses (default: the table's ball mass).
        dt: Step (s).
        obj: Ball whose velocity after its first ball-ball contact is recorded.
        max_time: Simulated seconds after which the run stops and reports ``capped``.
        diagnostics: Also track the deepest overlaps (slower; off when timing).

    Returns:
        A :class:`PymunkResult`.
    """
    positions = np.asarray(positions, dtype=np.float64)
    n = positions.shape[0]
    masses = np.full(n, table.ball_mass) if masses is None else np.asarray(masses, float)
    space, bodies, index = _build(table, positions, np.asarray(velocities, float), masses)
    res = PymunkResult(
        positions.copy(), np.full(n, -1, dtype=np.int64), 0, False, np.full(2, np.nan)
    )
    pending = [False]  # obj touched a ball in this step; read its velocity after the step

    def begin(arbiter: pymunk.Arbiter, _space: pymunk.Space, _data: object) -> None:
        a, b = (index[s] for s in arbiter.shapes)
        res.hits.add((min(a, b), max(a, b)))
        if obj in (a, b) and np.isnan(res.obj_velocity[0]):
            pending[0] = True

    space.on_collision(BALL, BALL, begin=begin)
    decel_step = table.deceleration * dt
    pockets = table.pockets
    active = list(range(n))
    max_steps = math.ceil(max_time / dt)
    while res.steps < max_steps:
        space.step(dt)
        res.steps += 1
        if pending[0]:
            res.obj_velocity = np.array(bodies[obj].velocity)
            pending[0] = False
        moving = False
        for i in list(active):
            body = bodies[i]
            vx, vy = body.velocity
            speed = math.hypot(vx, vy)
            if speed > decel_step:
                scale = (speed - decel_step) / speed
                body.velocity = (vx * scale, vy * scale)
                moving = True
            elif speed > 0.0:
                body.velocity = (0.0, 0.0)
            x, y = body.position
            for k in range(pockets.shape[0]):
                if (x - pockets[k, 0]) ** 2 + (y - pockets[k, 1]) ** 2 < pockets[k, 2] ** 2:
                    res.pocketed[i] = k
                    res.positions[i] = (x, y)
                    space.remove(body, *body.shapes)
                    active.remove(i)
                    break
        if diagnostics:
            _track_overlaps(res, bodies, active, table)
        if not moving:
            break
    res.capped = res.steps >= max_steps
    for i in active:
        res.positions[i] = tuple(bodies[i].position)
    return res


def _track_overlaps(
    res: PymunkResult, bodies: list[pymunk.Body], active: list[int], table: Table
) -> None:
    r = table.ball_radius
    pts = np.array([tuple(bodies[i].position) for i in active])
    if pts.size == 0:
        return
    depth = np.max(
        np.maximum.reduce(
            [
                r - pts[:, 0],
                pts[:, 0] - (table.length - r),
                r - pts[:, 1],
                pts[:, 1] - (table.width - r),
            ]
        )
    )
    res.max_rail_depth = max(res.max_rail_depth, float(depth))
    if len(active) > 1:
        d = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
        d[np.diag_indices_from(d)] = np.inf
        res.max_overlap = max(res.max_overlap, float(2.0 * r - d.min()))
