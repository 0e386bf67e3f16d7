"""A fixed-time-step integrator of the same model, written straight from the formulas.

This is what a user would write from the classic formulas (``docs/physics.md``, "The
model") without an event loop: explicit (forward Euler) steps of size ``dt``; a collision
is noticed when two balls overlap (or a ball is past a rail) at the end of a step, and
resolved then. It is compiled
with numba, like the project's simulator, so the comparison is about the method and not the
language.

Per step, in this order:

1. Motion (seed: "resistance between tablecloth and ball"): ``p += v dt``, then the speed
   drops by ``mu_roll g dt`` along ``-v/|v|``; a ball whose speed would reverse stops. The
   seed finds the direction with ``atan(vy / vx)``, which loses the quadrant; we use the
   unit vector (``docs/physics.md``, "The model").
2. Pockets: a ball whose centre is inside a capture circle is potted there.
3. Rails (seed: "bumpers"), by overlap: a ball past a rail line and moving into it has its
   normal velocity multiplied by ``-e_cushion``. No position correction (the seed has none).
4. Ball-ball (seed: "impact between two balls"), by overlap: every pair closer than ``2R``
   and approaching is resolved once, pairs in index order. The seed's printed formulas are
   CORRECTED as ``docs/physics.md`` ("Three mistakes in the classic formulas") says: its
   restitution term has the wrong sign (with ``e = 1`` and
   equal masses the balls would pass through each other), and its rotate-back step swaps
   ``sin(phi + 90)`` and ``cos(phi + 90)``. We use ``ua' = (ma ua + mb ub + mb e (ub - ua)) /
   (ma + mb)`` (and symmetrically ``ub'``) along the line of centres, keeping the tangential
   components, which is the seed's rotation written with vectors.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import NDArray

from pool_env.sim.constants import P_DECEL, P_E_BALL, P_E_CUSHION, P_LENGTH, P_RADIUS, P_WIDTH


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _ball_ball(pos, vel, masses, i, j, e):
    """Resolve an overlapping pair if it approaches; return whether it did."""
    dx = pos[j, 0] - pos[i, 0]
    dy = pos[j, 1] - pos[i, 1]
    d = math.sqrt(dx * dx + dy * dy)
    if d == 0.0:
        return False
    nx, ny = dx / d, dy / d
    ua = vel[i, 0] * nx + vel[i, 1] * ny
    ub = vel[j, 0] * nx + vel[j, 1] * ny
    if ua - ub <= 0.0:  # separating or sliding past: no impact
        return False
    ma, mb = masses[i], masses[j]
    ua_new = (ma * ua + mb * ub + mb * e * (ub - ua)) / (ma + mb)
    ub_new = (ma * ua + mb * ub + ma * e * (ua - ub)) / (ma + mb)
    vel[i, 0] += (ua_new - ua) * nx
    vel[i, 1] += (ua_new - ua) * ny
    vel[j, 0] += (ub_new - ub) * nx
    vel[j, 1] += (ub_new - ub) * ny
    return True


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _rails(pos, vel, i, length, width, r, e):
    """Reflect ball ``i``'s normal velocity on every rail it is past and moving into."""
    # Each axis on its own: a ball in a corner meets both rails, in either order.
    if (pos[i, 0] < r and vel[i, 0] < 0.0) or (pos[i, 0] > length - r and vel[i, 0] > 0.0):
        vel[i, 0] = -e * vel[i, 0]
    if (pos[i, 1] < r and vel[i, 1] < 0.0) or (pos[i, 1] > width - r and vel[i, 1] > 0.0):
        vel[i, 1] = -e * vel[i, 1]


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _move(pos, vel, i, dt, a):
    """One explicit Euler step of ball ``i`` under rolling resistance; True if it moves."""
    vx, vy = vel[i, 0], vel[i, 1]
    speed = math.sqrt(vx * vx + vy * vy)
    if speed == 0.0:
        return False
    pos[i, 0] += vx * dt
    pos[i, 1] += vy * dt
    dv = a * dt
    if speed <= dv:
        vel[i, 0] = 0.0
        vel[i, 1] = 0.0
    else:
        scale = (speed - dv) / speed
        vel[i, 0] = vx * scale
        vel[i, 1] = vy * scale
    return True


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _pot(pos, vel, i, pockets):
    """The pocket whose capture circle holds ball ``i``'s centre, or -1."""
    for k in range(pockets.shape[0]):
        dx = pos[i, 0] - pockets[k, 0]
        dy = pos[i, 1] - pockets[k, 1]
        if dx * dx + dy * dy < pockets[k, 2] * pockets[k, 2]:
            vel[i, 0] = 0.0
            vel[i, 1] = 0.0
            return k
    return -1


@numba.njit(cache=True, nogil=True, error_model="numpy")
def run_fixed_step(positions, velocities, masses, params, pockets, dt, max_steps, obj):
    """Simulate one shot to rest with fixed steps of ``dt`` seconds.

    Args:
        positions: ``(N, 2)`` ball centres (m).
        velocities: ``(N, 2)`` initial velocities (m/s).
        masses: ``(N,)`` masses (kg).
        params: The table's flat parameter array (``Table.params``).
        pockets: ``(K, 3)`` capture circles.
        dt: Step (s).
        max_steps: Step cap; reaching it reports ``capped``.
        obj: Ball whose velocity right after its first ball-ball impact is recorded
            (-1: none).

    Returns:
        ``(positions, pocketed, steps, capped, obj_velocity, hits, max_overlap,
        max_rail_depth)``: final centres (a potted ball keeps its capture point), pocket
        per ball (-1 on the table), steps taken, whether the cap was hit, the object ball's
        velocity after its first impact (NaN if none), an ``(N, N)`` matrix of pairs that
        collided at least once, and the deepest ball-ball overlap and rail penetration seen
        at any step end (m).
    """
    length, width, r = params[P_LENGTH], params[P_WIDTH], params[P_RADIUS]
    a, e_ball, e_cushion = params[P_DECEL], params[P_E_BALL], params[P_E_CUSHION]
    n = positions.shape[0]
    pos = positions.copy()
    vel = velocities.copy()
    pocketed = np.full(n, -1, dtype=np.int64)
    moving = np.zeros(n, dtype=np.bool_)
    hits = np.zeros((n, n), dtype=np.bool_)
    obj_vel = np.full(2, np.nan)
    obj_hit = False
    max_overlap = 0.0
    max_rail = 0.0
    two_r2 = 4.0 * r * r
    steps = 0
    while steps < max_steps:
        any_moving = False
        for i in range(n):
            moving[i] = pocketed[i] < 0 and _move(pos, vel, i, dt, a)
            any_moving = any_moving or moving[i]
        if not any_moving:
            break
        steps += 1
        for i in range(n):
            if not moving[i]:
                continue
            pocketed[i] = _pot(pos, vel, i, pockets)
            if pocketed[i] < 0:
                _rails(pos, vel, i, length, width, r, e_cushion)
                depth = max(
                    r - pos[i, 0], pos[i, 0] - (length - r), r - pos[i, 1], pos[i, 1] - (width - r)
                )
                max_rail = max(max_rail, depth)
        for i in range(n):
            if pocketed[i] >= 0:
                continue
            for j in range(i + 1, n):
                if pocketed[j] >= 0 or not (moving[i] or moving[j]):
                    continue
                dx = pos[j, 0] - pos[i, 0]
                dy = pos[j, 1] - pos[i, 1]
                d2 = dx * dx + dy * dy
                if d2 >= two_r2:
                    continue
                max_overlap = max(max_overlap, 2.0 * r - math.sqrt(d2))
                if _ball_ball(pos, vel, masses, i, j, e_ball):
                    hits[i, j] = True
                    hits[j, i] = True
                    if not obj_hit and (i == obj or j == obj):
                        obj_hit = True
                        obj_vel[0] = vel[obj, 0]
                        obj_vel[1] = vel[obj, 1]
    capped = steps >= max_steps
    return pos, pocketed, steps, capped, obj_vel, hits, max_overlap, max_rail


def simulate_fixed_step(
    params: NDArray[np.float64],
    pockets: NDArray[np.float64],
    positions: NDArray[np.float64],
    velocities: NDArray[np.float64],
    masses: NDArray[np.float64],
    dt: float,
    obj: int = -1,
    max_time: float = 200.0,
) -> tuple:
    """Call :func:`run_fixed_step` with a step cap of ``max_time / dt``.

    Args:
        params: ``Table.params``.
        pockets: ``Table.pockets``.
        positions: ``(N, 2)`` centres.
        velocities: ``(N, 2)`` velocities.
        masses: ``(N,)`` masses.
        dt: Step (s).
        obj: Ball whose post-impact velocity to record.
        max_time: Simulated seconds after which the run is stopped and reported capped.

    Returns:
        The tuple of :func:`run_fixed_step`.
    """
    return run_fixed_step(
        np.ascontiguousarray(positions, dtype=np.float64),
        np.ascontiguousarray(velocities, dtype=np.float64),
        np.ascontiguousarray(masses, dtype=np.float64),
        params,
        pockets,
        float(dt),
        math.ceil(max_time / dt),
        int(obj),
    )
