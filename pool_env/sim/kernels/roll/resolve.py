"""Impact resolution (compiled): ball-ball and ball-cushion.

Ball-ball (seed: "impact between two balls"). The seed rotates the frame so the line of
impact is horizontal, applies momentum conservation and restitution along it, and rotates
back. Its printed formulas have two misprints that we do not reproduce:

1. The restitution term has the wrong sign. The seed prints
   ``v_fa = (ma v_ia + mb v_ib - mb e (v_ib - v_ia)) / (ma + mb)``; with ``e = 1`` and equal
   masses that gives ``v_fa = v_ia``: the balls pass through each other. Solving its own two
   equations (momentum, and separation speed = ``e`` x approach speed) gives
   ``ua' = (ma ua + mb ub + mb e (ub - ua)) / (ma + mb)`` and symmetrically for ``ub'``.
2. Its rotate-back step uses ``sin(phi + 90)`` for x and ``cos(phi + 90)`` for y, swapped:
   with ``phi = 0`` it adds the tangential component to x. We never rotate: the normal
   component along ``n = (pb - pa) / |pb - pa|`` is replaced and the tangential part of the
   velocity is kept as it is, which is the correct rotation written in vectors.

It also finds angles with ``atan(vy / vx)``, which loses the quadrant; vectors avoid that.

Cushions (seed: "bumpers"): ``v_n -> -e_cushion v_n`` on the rail's normal component.

Zeno rules (documented in the package README):

* An impact that repeats within ``ZENO_WINDOW`` with a normal approach speed below
  ``V_ZENO`` is perfectly inelastic along the normal (``e = 0``).
* Two balls stick, leaving with their common centre-of-mass velocity together with every
  ball touching them (momentum conserved, energy lost), when an inelastic impact leaves
  them touching with their relative deceleration pressing them together (they would
  re-collide endlessly); when an inelastic impact repeats within ``ZENO_WINDOW`` (a
  cascade through a cluster of touching balls); or when any impact repeats
  ``ZENO_REPEATS`` times in a row that closely (a ball wedged between a ball and a rail,
  inelastic collapse).
* A lump pressed into a rail that one of its balls touches meets that rail as one body
  (:func:`lump_off_rail`): its normal velocity ``v_n`` into the rail becomes
  ``-e_cushion v_n`` (0 if slower than ``V_ZENO``), its tangential velocity is kept. The
  rail's impulse ``-(1 + e_cushion) M v_n`` along its normal is the only momentum that
  changes (``M`` the lump's mass) and the kinetic energy drops by exactly
  ``(1 - e_cushion^2) M v_n^2 / 2``. Reflecting only the ball at the rail instead leaves a
  heavy ball driving a light one into the rail losing ``~2 m / M`` of its speed per cycle,
  thousands of events at one instant.
* A ball slower than ``V_REST`` after an impact is at rest (it would stop within 1e-8 s and
  5e-18 m anyway).
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.contact import (
    CONTACT_TOL,
    V_REST,
    V_ZENO,
    ZENO_REPEATS,
    lump_off_rails,
)
from pool_env.sim.kernels.params import P_DECEL, P_E_BALL, P_E_CUSHION, P_LENGTH, P_RADIUS, P_WIDTH
from pool_env.sim.kernels.roll.motion import POTTED, set_anchor, state_at


@kernel
def _pressed_together(dx, dy, vxi, vyi, vxj, vyj, a):
    """Whether touching balls with no normal relative speed would be pushed into each other.

    With ``d = pj - pi`` and ``w = vj - vi`` and ``d.w = 0``, the squared gap curves as
    ``D''/2 = |w|^2 + 2 d.c`` with ``c`` half the relative deceleration: negative means the
    balls come straight back together.
    """
    si = math.sqrt(vxi * vxi + vyi * vyi)
    sj = math.sqrt(vxj * vxj + vyj * vyj)
    cx = 0.0
    cy = 0.0
    if sj > 0.0:
        cx -= 0.5 * a * vxj / sj
        cy -= 0.5 * a * vyj / sj
    if si > 0.0:
        cx += 0.5 * a * vxi / si
        cy += 0.5 * a * vyi / si
    wx, wy = vxj - vxi, vyj - vyi
    return wx * wx + wy * wy + 2.0 * (dx * cx + dy * cy) <= 0.0


@kernel
def ball_ball(st, status, masses, i, j, t, params, repeats):
    """Resolve an impact between balls ``i`` and ``j`` at time ``t`` and re-anchor both.

    ``repeats`` counts this pair's impacts in a row, each within ``ZENO_WINDOW`` of the
    last (1 for an isolated impact).

    Returns:
        Whether the pair must stick (see :func:`stick_cluster`).
    """
    a, e = params[P_DECEL], params[P_E_BALL]
    xi, yi, vxi, vyi = state_at(st, status, i, t, a)
    xj, yj, vxj, vyj = state_at(st, status, j, t, a)
    dx, dy = xj - xi, yj - yi
    dist = math.sqrt(dx * dx + dy * dy)
    if dist == 0.0:  # coincident centres cannot pass validation; keep the state unchanged
        set_anchor(st, status, i, t, xi, yi, vxi, vyi, a, V_REST)
        set_anchor(st, status, j, t, xj, yj, vxj, vyj, a, V_REST)
        return False
    nx, ny = dx / dist, dy / dist
    ui = vxi * nx + vyi * ny
    uj = vxj * nx + vyj * ny
    mi, mj = masses[i], masses[j]
    # A repeated impact slower than V_ZENO, and a contact found by the predictor's
    # compression test (approach within rounding of zero), are perfectly inelastic: the
    # normal components become their common centre-of-mass value, which never adds energy.
    # An isolated slow impact keeps e: the model is exact wherever no cascade needs ending.
    approach = ui - uj
    e_eff = e if approach >= V_ZENO or (approach > 0.0 and repeats < 2) else 0.0
    total = mi + mj
    ui_new = (mi * ui + mj * uj + mj * e_eff * (uj - ui)) / total
    uj_new = (mi * ui + mj * uj + mi * e_eff * (ui - uj)) / total
    vxi += (ui_new - ui) * nx
    vyi += (ui_new - ui) * ny
    vxj += (uj_new - uj) * nx
    vyj += (uj_new - uj) * ny
    set_anchor(st, status, i, t, xi, yi, vxi, vyi, a, V_REST)
    set_anchor(st, status, j, t, xj, yj, vxj, vyj, a, V_REST)
    # Sticking ends inelastic cascades: with e = 0, sequential impulses through a cluster of
    # touching balls converge only geometrically, and slowly, towards common normal speeds.
    return repeats >= ZENO_REPEATS or (
        e_eff == 0.0 and (repeats >= 2 or _pressed_together(dx, dy, vxi, vyi, vxj, vyj, a))
    )


@kernel
def stick_cluster(st, status, masses, i, t, params, changed):
    """Give ball ``i`` and every ball touching it, transitively, their common velocity.

    Touching means centres within ``2R + CONTACT_TOL`` (of each other, or of a rail line).
    The cluster leaves as one lump with its centre-of-mass velocity, then meets every rail
    one of its balls touches as one body (:func:`lump_off_rails`): momentum is conserved
    but for the rails' impulses along their normals, and kinetic energy can only drop.

    Returns:
        How many balls changed; their indices are written to ``changed``.
    """
    a, radius = params[P_DECEL], params[P_RADIUS]
    n = st.shape[0]
    reach2 = (2.0 * radius + CONTACT_TOL) ** 2
    xs = np.empty(n)
    ys = np.empty(n)
    in_cluster = np.zeros(n, dtype=np.bool_)
    for k in range(n):
        xs[k], ys[k], _, _ = state_at(st, status, k, t, a)
    in_cluster[i] = True
    changed[0] = i
    size = 1
    head = 0
    while head < size:  # breadth-first over the contact graph
        k = changed[head]
        head += 1
        for m in range(n):
            if in_cluster[m] or status[m] == POTTED:
                continue
            dx, dy = xs[m] - xs[k], ys[m] - ys[k]
            if dx * dx + dy * dy <= reach2:
                in_cluster[m] = True
                changed[size] = m
                size += 1
    px = 0.0
    py = 0.0
    total = 0.0
    for c in range(size):
        k = changed[c]
        _, _, vx, vy = state_at(st, status, k, t, a)
        px += masses[k] * vx
        py += masses[k] * vy
        total += masses[k]
    vx, vy = px / total, py / total
    # The rails the lump touches, as unit normals into the table (rail order).
    length, width = params[P_LENGTH], params[P_WIDTH]
    left = right = bottom = top = False
    for c in range(size):  # at a rail line (a ball past one is in a pocket's throat)
        k = changed[c]
        left |= abs(xs[k] - radius) <= CONTACT_TOL
        right |= abs(xs[k] - (length - radius)) <= CONTACT_TOL
        bottom |= abs(ys[k] - radius) <= CONTACT_TOL
        top |= abs(ys[k] - (width - radius)) <= CONTACT_TOL
    normals = np.zeros((4, 2))
    count = 0
    rails = ((left, 1.0, 0.0), (right, -1.0, 0.0), (bottom, 0.0, 1.0), (top, 0.0, -1.0))
    for touched, nx, ny in rails:
        if touched:
            normals[count, 0] = nx
            normals[count, 1] = ny
            count += 1
    vx, vy = lump_off_rails(vx, vy, normals, count, params[P_E_CUSHION])
    for c in range(size):
        k = changed[c]
        set_anchor(st, status, k, t, xs[k], ys[k], vx, vy, a, V_REST)
    return size


@kernel
def cushion(st, status, i, rail, t, params):
    """Resolve ball ``i`` hitting rail ``rail`` (0: x=R, 1: x=L-R, 2: y=R, 3: y=W-R)."""
    a, e = params[P_DECEL], params[P_E_CUSHION]
    x, y, vx, vy = state_at(st, status, i, t, a)
    # Only a velocity into the rail is reflected, so a repeated or stale hit is harmless.
    if rail < 2:
        into = vx > 0.0 if rail == 1 else vx < 0.0
        if into:
            vx = -e * vx
    else:
        into = vy > 0.0 if rail == 3 else vy < 0.0
        if into:
            vy = -e * vy
    set_anchor(st, status, i, t, x, y, vx, vy, a, V_REST)
