"""Ball state and motion between events (compiled).

Each ball's trajectory is anchored at its own last velocity change (``T0``): position and
velocity there, the speed, the unit direction and the absolute stop time. Between events a
moving ball decelerates at ``a = mu_roll * g`` against its velocity (seed: "resistance between
tablecloth and ball")::

    p(t) = p0 + u * (v0 * tau - a * tau^2 / 2),   tau = t - T0 <= v0 / a

and then rests at ``p0 + u * v0^2 / (2 a)``. The seed derives the direction of the
deceleration from ``theta = atan(vy / vx)``, which loses the quadrant (a ball moving in -x
would speed up) and divides by zero for ``vx = 0``; we use the unit vector ``u = v / |v|``.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel

# Columns of the (N, NCOL) ball-state array.
PX, PY, VX, VY, T0, SPD, UX, UY, TSTOP = range(9)
NCOL = 9

# Ball status codes.
REST, MOVING, POTTED = 0, 1, 2


@kernel
def set_anchor(st, status, i, t, x, y, vx, vy, a, v_rest):
    """Anchor ball ``i`` at time ``t`` with position ``(x, y)`` and velocity ``(vx, vy)``.

    A speed below ``v_rest`` counts as rest: such a ball would stop within ``v_rest / a``
    seconds and ``v_rest^2 / (2 a)`` metres anyway.
    """
    spd = math.sqrt(vx * vx + vy * vy)
    st[i, PX] = x
    st[i, PY] = y
    st[i, T0] = t
    if spd < v_rest or spd == 0.0:
        st[i, VX] = 0.0
        st[i, VY] = 0.0
        st[i, SPD] = 0.0
        st[i, UX] = 0.0
        st[i, UY] = 0.0
        st[i, TSTOP] = t
        status[i] = REST
    else:
        st[i, VX] = vx
        st[i, VY] = vy
        st[i, SPD] = spd
        st[i, UX] = vx / spd
        st[i, UY] = vy / spd
        st[i, TSTOP] = t + spd / a
        status[i] = MOVING


@kernel
def rest_point(st, i, a):
    """Where moving ball ``i`` comes to rest if nothing interferes."""
    spd = st[i, SPD]
    s = spd * spd / (2.0 * a)
    return st[i, PX] + st[i, UX] * s, st[i, PY] + st[i, UY] * s


@kernel
def state_at(st, status, i, t, a):
    """Position and velocity ``(x, y, vx, vy)`` of ball ``i`` at absolute time ``t``.

    ``t`` must not precede the ball's anchor. A potted ball stays at its capture point.
    """
    if status[i] != MOVING:
        return st[i, PX], st[i, PY], 0.0, 0.0
    tau = t - st[i, T0]
    if t >= st[i, TSTOP]:
        x, y = rest_point(st, i, a)
        return x, y, 0.0, 0.0
    spd = st[i, SPD]
    s = tau * (spd - 0.5 * a * tau)
    v = spd - a * tau
    return st[i, PX] + st[i, UX] * s, st[i, PY] + st[i, UY] * s, st[i, UX] * v, st[i, UY] * v


@kernel
def arc_time(speed, s, a):
    """Time for a ball at ``speed`` to roll arc length ``s`` (``0 <= s <= v^2 / 2a``).

    Solves ``s = v t - a t^2 / 2`` in the cancellation-free form
    ``t = 2 s / (v + sqrt(v^2 - 2 a s))``.
    """
    disc = speed * speed - 2.0 * a * s
    if disc < 0.0:
        disc = 0.0
    den = speed + math.sqrt(disc)
    if den <= 0.0:
        return 0.0
    return 2.0 * s / den


@kernel
def struck_velocity(speed, angle, out):
    """The roll level's strike: ``out[:2]`` = the velocity of ``speed`` along ``angle``.

    No squirt and no spin on this level: the ball leaves along the aim at the speed asked.
    """
    out[0] = speed * math.cos(angle)
    out[1] = speed * math.sin(angle)
