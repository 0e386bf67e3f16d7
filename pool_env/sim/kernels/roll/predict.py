"""Event prediction (compiled): a ball's own events and a pair's next impact.

A ball's own events (cushion, pocket, stop, and on a jaw table facing and point contacts)
are computed once, when the ball is re-anchored, in arc length along its straight path:
rails, facings, fall lines, capture circles and points are lines and circles, so each is a
quadratic in ``s`` at most, and ``t`` follows from ``s = v t - a t^2 / 2`` (jaws:
:mod:`pool_env.sim.kernels.jaw_geometry`).

A pair's next impact is computed over the window in which both trajectories are fixed: until
either ball's next cushion or pocket event (a stop does not change a trajectory, it ends a
phase of it). The window is split at the stop times; on each piece the relative motion has a
constant relative acceleration. Degrees are handled explicitly:

* both resting: no event;
* one resting: a ray-circle quadratic in the moving ball's arc length;
* both moving with bitwise-equal directions: ``c = 0``, a quadratic in time;
* otherwise the bracketed quartic of :mod:`pool_env.sim.kernels.roots`.

Before any root is sought, the pair is culled when the capsules swept by the two balls until
their next trajectory change are farther apart than ``2R``.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel, level_method
from pool_env.sim.kernels import level as interface
from pool_env.sim.kernels.jaw_geometry import JAW_COLS, opening_of, predict_pocket, throat_of
from pool_env.sim.kernels.kinds import CUSHION, EV_ARG, EV_END, EV_KIND, EV_T, POCKET, STOP
from pool_env.sim.kernels.params import P_DECEL, P_LENGTH, P_RADIUS, P_WIDTH
from pool_env.sim.kernels.roll.marker import RollLevel
from pool_env.sim.kernels.roll.motion import (
    MOVING,
    POTTED,
    PX,
    PY,
    SPD,
    T0,
    TSTOP,
    UX,
    UY,
    arc_time,
    rest_point,
    state_at,
)
from pool_env.sim.kernels.roots import (
    APPROACH_RTOL,
    INF,
    equal_accel_contact,
    first_contact,
    ray_circle_entry,
)

# Columns of the (N, 4) capsule array: the segment a ball sweeps until its trajectory changes.
CAP_AX, CAP_AY, CAP_BX, CAP_BY = 0, 1, 2, 3

# A pair is culled only when its capsules are this much farther apart than 2R.
CULL_MARGIN = 1e-9


@level_method(interface.predict_own, RollLevel, inline=False)
def predict_own(level, st, status, i, params, pockets, own, caps):
    """Predict ball ``i``'s next own event and the capsule it sweeps until then.

    Writes ``own[i] = (time, kind, arg, end)`` where ``end`` is the time its trajectory next
    changes (a cushion, jaw, point or pocket event; ``inf`` if it rolls to rest), and
    ``caps[i]``. ``pockets`` is the table's ``pocket_geometry``: capture circles, or jaws.
    """
    length, width = params[P_LENGTH], params[P_WIDTH]
    radius, a = params[P_RADIUS], params[P_DECEL]
    x, y = st[i, PX], st[i, PY]
    if status[i] != MOVING:
        own[i, EV_T] = INF
        own[i, EV_KIND] = STOP
        own[i, EV_ARG] = -1
        own[i, EV_END] = INF
        caps[i, CAP_AX] = x
        caps[i, CAP_AY] = y
        caps[i, CAP_BX] = x
        caps[i, CAP_BY] = y
        return
    spd, ux, uy = st[i, SPD], st[i, UX], st[i, UY]
    s_stop = spd * spd / (2.0 * a)
    best_s = s_stop
    best_kind = STOP
    best_arg = -1
    # Rails (ball-centre lines). At or beyond a rail and moving out: hit now (s = 0), so
    # rounding can never carry a ball through a rail; but a normal direction within
    # rounding of zero is no approach (a ball left rolling along the rail by an impact),
    # and it could not carry the ball more than ~1e-12 m past the line. Ties keep the
    # lower rail index. On a jaw table a crossing inside a pocket's opening is no rail
    # hit: it marks that pocket's jaws as reachable instead.
    jaws = pockets.shape[1] == JAW_COLS
    enter_a = -1
    enter_b = -1
    if ux != 0.0:
        rail = 1 if ux > 0.0 else 0
        line = length - radius if ux > 0.0 else radius
        s = (line - x) / ux
        if s > 0.0 or abs(ux) > APPROACH_RTOL:
            s = max(s, 0.0)
            if jaws:
                enter_a = opening_of(pockets, rail, y + uy * s)
            if enter_a < 0 and (s < best_s or (s == best_s and best_kind > CUSHION)):
                best_s, best_kind, best_arg = s, CUSHION, rail
    if uy != 0.0:
        rail = 3 if uy > 0.0 else 2
        line = width - radius if uy > 0.0 else radius
        s = (line - y) / uy
        if s > 0.0 or abs(uy) > APPROACH_RTOL:
            s = max(s, 0.0)
            if jaws:
                enter_b = opening_of(pockets, rail, x + ux * s)
            if enter_b < 0 and (s < best_s or (s == best_s and best_kind > CUSHION)):
                best_s, best_kind, best_arg = s, CUSHION, rail
    if jaws:
        # The pockets whose jaws this path can reach: the throat the ball is in, and those
        # whose openings it crosses.
        here = throat_of(x, y, params, pockets)
        if enter_a == here:
            enter_a = -1
        if enter_b == here or enter_b == enter_a:  # noqa: SIM109 (numba)
            enter_b = -1
        for k in (here, enter_a, enter_b):
            if k >= 0:
                best_s, best_kind, best_arg = predict_pocket(
                    pockets, k, x, y, ux, uy, best_s, best_kind, best_arg
                )
    else:
        for k in range(pockets.shape[0]):
            r = pockets[k, 2]
            s = ray_circle_entry(x, y, ux, uy, pockets[k, 0], pockets[k, 1], r * r, True)
            if s < best_s or (s == best_s and best_kind > POCKET):
                best_s, best_kind, best_arg = s, POCKET, k
    if best_kind == STOP:
        t_event = st[i, TSTOP]
        end = INF
        bx, by = rest_point(st, i, a)
    else:
        t_event = st[i, T0] + arc_time(spd, best_s, a)
        end = t_event
        bx, by = x + ux * best_s, y + uy * best_s
    own[i, EV_T] = t_event
    own[i, EV_KIND] = best_kind
    own[i, EV_ARG] = best_arg
    own[i, EV_END] = end
    caps[i, CAP_AX] = x
    caps[i, CAP_AY] = y
    caps[i, CAP_BX] = bx
    caps[i, CAP_BY] = by


@kernel
def _point_segment_dist2(px, py, ax, ay, bx, by):
    ex = bx - ax
    ey = by - ay
    len2 = ex * ex + ey * ey
    t = 0.0
    if len2 > 0.0:
        t = ((px - ax) * ex + (py - ay) * ey) / len2
        t = min(max(t, 0.0), 1.0)
    dx = ax + t * ex - px
    dy = ay + t * ey - py
    return dx * dx + dy * dy


@kernel
def _cross(ax, ay, bx, by, cx, cy):
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)


@kernel
def capsules_may_meet(caps, i, j, reach):
    """Whether the segments swept by balls ``i`` and ``j`` come within ``reach``."""
    ax, ay, bx, by = caps[i, 0], caps[i, 1], caps[i, 2], caps[i, 3]
    cx, cy, dx, dy = caps[j, 0], caps[j, 1], caps[j, 2], caps[j, 3]
    # Cheap bounding-box rejection first.
    if min(ax, bx) - max(cx, dx) > reach or min(cx, dx) - max(ax, bx) > reach:
        return False
    if min(ay, by) - max(cy, dy) > reach or min(cy, dy) - max(ay, by) > reach:
        return False
    d1 = _cross(ax, ay, bx, by, cx, cy)
    d2 = _cross(ax, ay, bx, by, dx, dy)
    d3 = _cross(cx, cy, dx, dy, ax, ay)
    d4 = _cross(cx, cy, dx, dy, bx, by)
    if ((d1 > 0.0 and d2 < 0.0) or (d1 < 0.0 and d2 > 0.0)) and (
        (d3 > 0.0 and d4 < 0.0) or (d3 < 0.0 and d4 > 0.0)
    ):
        return True  # the segments cross
    r2 = reach * reach
    return (
        _point_segment_dist2(ax, ay, cx, cy, dx, dy) <= r2
        or _point_segment_dist2(bx, by, cx, cy, dx, dy) <= r2
        or _point_segment_dist2(cx, cy, ax, ay, bx, by) <= r2
        or _point_segment_dist2(dx, dy, ax, ay, bx, by) <= r2
    )


@kernel
def _arc_length(st, i, t, a):
    """Arc length moving ball ``i`` has rolled from its anchor to time ``t``."""
    tau = min(t, st[i, TSTOP]) - st[i, T0]
    return tau * (st[i, SPD] - 0.5 * a * tau)


@kernel
def _one_moving(st, status, mover, still, t_a, t_b, radius, a):
    """Impact time in ``[t_a, t_b]`` of moving ball ``mover`` with a ball resting over it."""
    x, y, vx, vy = state_at(st, status, mover, t_a, a)
    qx, qy, _, _ = state_at(st, status, still, t_a, a)
    v = math.sqrt(vx * vx + vy * vy)
    if v == 0.0:
        return INF
    s = ray_circle_entry(x, y, st[mover, UX], st[mover, UY], qx, qy, 4.0 * radius * radius, False)
    if s > _arc_length(st, mover, t_b, a) - _arc_length(st, mover, t_a, a):
        return INF  # also when s is inf
    return t_a + arc_time(v, s, a)


@kernel
def _both_moving(st, status, i, j, t_a, t_b, radius, a):
    """Impact time in ``[t_a, t_b]`` of two balls that both move throughout it."""
    xi, yi, vxi, vyi = state_at(st, status, i, t_a, a)
    xj, yj, vxj, vyj = state_at(st, status, j, t_a, a)
    d0x, d0y = xj - xi, yj - yi
    wx, wy = vxj - vxi, vyj - vyi
    # Half the relative acceleration: each ball decelerates at a along its own direction.
    cx = -0.5 * a * (st[j, UX] - st[i, UX])
    cy = -0.5 * a * (st[j, UY] - st[i, UY])
    four_r2 = 4.0 * radius * radius
    span = t_b - t_a
    scale = math.sqrt(vxi * vxi + vyi * vyi) + math.sqrt(vxj * vxj + vyj * vyj)
    if cx == 0.0 and cy == 0.0:
        # Same direction bit for bit: the gap is a quadratic in time (degree drop).
        tau = equal_accel_contact(d0x, d0y, wx, wy, four_r2, span, scale)
        return t_a + tau if tau < INF else INF
    tau = first_contact(d0x, d0y, wx, wy, cx, cy, four_r2, span, scale, a)
    return t_a + tau if tau < INF else INF


@level_method(interface.predict_pair, RollLevel, inline=False)
def predict_pair(level, st, status, i, j, now, params, own, caps):
    """Time of the next impact between balls ``i`` and ``j`` after ``now`` (``inf`` if none)."""
    if status[i] == POTTED or status[j] == POTTED:
        return INF
    if status[i] != MOVING and status[j] != MOVING:
        return INF
    radius, a = params[P_RADIUS], params[P_DECEL]
    if not capsules_may_meet(caps, i, j, 2.0 * radius + CULL_MARGIN):
        return INF
    t_end = min(own[i, EV_END], own[j, EV_END])
    stop_i = st[i, TSTOP] if status[i] == MOVING else now
    stop_j = st[j, TSTOP] if status[j] == MOVING else now
    first_stop = max(min(stop_i, stop_j), now)
    last_stop = max(stop_i, stop_j)
    # Piece 1: both moving.
    if first_stop > now:
        t_b = min(first_stop, t_end)
        t = _both_moving(st, status, i, j, now, t_b, radius, a)
        if t < INF:
            return t
        if t_b >= t_end:
            return INF
    # Piece 2: one moving, the other at rest.
    t_a = max(first_stop, now)
    if last_stop > t_a:
        mover, still = (i, j) if stop_i > stop_j else (j, i)
        return _one_moving(st, status, mover, still, t_a, min(last_stop, t_end), radius, a)
    return INF
