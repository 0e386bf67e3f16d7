"""Impacts with pocket jaws on the roll level (compiled): facings and points, and lumps.

The jaws' geometry (facings, points, fall lines, where a centre lies) is the shared
:mod:`~pool_env.sim.kernels.jaw_geometry`; what is here re-anchors balls that move by the roll
level's law.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.contact import lump_off_contacts, slide, wedged
from pool_env.sim.kernels.jaw_geometry import J_FACING0, J_TIP0, jaw_normal, opening_of, throat_of
from pool_env.sim.kernels.params import (
    P_DECEL,
    P_E_CUSHION,
    P_E_JAW,
    P_LENGTH,
    P_RADIUS,
    P_WIDTH,
)
from pool_env.sim.kernels.roll.motion import set_anchor, state_at


@kernel
def jaw_impact(st, status, i, kind, arg, t, params, pockets, v_rest):
    """Resolve ball ``i`` hitting facing or point ``arg`` at time ``t`` and re-anchor it.

    The normal component is reflected with restitution ``e_jaw`` (``params[P_E_JAW]``); only a
    velocity into the jaw is reflected, so a stale or repeated hit changes nothing.
    """
    a, e = params[P_DECEL], params[P_E_JAW]
    x, y, vx, vy = state_at(st, status, i, t, a)
    nx, ny = jaw_normal(pockets, kind, arg, x, y)
    vn = vx * nx + vy * ny
    if vn < 0.0:
        vx -= (1.0 + e) * vn * nx
        vy -= (1.0 + e) * vn * ny
    set_anchor(st, status, i, t, x, y, vx, vy, a, v_rest)


@kernel
def unpress_lump(st, status, changed, size, t, params, pockets, v_zeno, contact_tol, v_rest):
    """A stuck lump of balls meets the jaws and rails it touches as one body.

    The jaw counterpart of the rail rule of :func:`pool_env.sim.kernels.roll.resolve.stick_cluster`
    (which has just given the ``size`` balls in ``changed`` one common velocity and met the
    rails with it). A lump wedged between contacts (it cannot slide along any one of them
    without pressing into another) stops. Otherwise it meets every facing, point and rail
    that one of its balls touches (within ``contact_tol``) as one body
    (:func:`~pool_env.sim.kernels.contact.lump_off_contacts`: the normal velocity ``v_n``
    into it becomes ``-e v_n``, ``e_jaw`` for jaws and ``e_cushion`` for rails, 0 below
    ``V_ZENO``); reflecting only the ball at the jaw instead leaves a heavy ball driving a
    light one into a point re-sticking to it forever at one instant. A component slower
    than ``v_zeno`` still pressing into a contact after that is removed, as the cushion's
    impulse would. Only the contacts' impulses along their normals change the momentum,
    and the kinetic energy never rises.
    """
    a, radius = params[P_DECEL], params[P_RADIUS]
    length, width = params[P_LENGTH], params[P_WIDTH]
    _, _, vx, vy = state_at(st, status, changed[0], t, a)
    # The normals of every contact of the lump (at most a few per ball).
    normals = np.zeros((4 * size + 4, 2))
    es = np.full(4 * size + 4, params[P_E_CUSHION])  # each contact's restitution
    count = 0
    for c in range(size):
        k = changed[c]
        x, y, _, _ = state_at(st, status, k, t, a)
        # A rail is touched at its line, outside the pocket openings (a ball in a throat,
        # past the rail line, touches no rail there).
        if abs(x - radius) <= contact_tol and opening_of(pockets, 0, y) < 0:
            normals[count] = (1.0, 0.0)
            count += 1
        if abs(x - (length - radius)) <= contact_tol and opening_of(pockets, 1, y) < 0:
            normals[count] = (-1.0, 0.0)
            count += 1
        if abs(y - radius) <= contact_tol and opening_of(pockets, 2, x) < 0:
            normals[count] = (0.0, 1.0)
            count += 1
        if abs(y - (width - radius)) <= contact_tol and opening_of(pockets, 3, x) < 0:
            normals[count] = (0.0, -1.0)
            count += 1
        p = throat_of(x, y, params, pockets)
        if p < 0:
            continue
        row = pockets[p]
        for side in range(2):
            col = J_FACING0 + 7 * side
            delta = (x - row[col]) * row[col + 4] + (y - row[col + 1]) * row[col + 5]
            along = (x - row[col]) * row[col + 2] + (y - row[col + 1]) * row[col + 3]
            if delta <= contact_tol and 0.0 <= along <= row[col + 6]:
                normals[count] = (row[col + 4], row[col + 5])
                es[count] = params[P_E_JAW]
                count += 1
            tip = J_TIP0 + 3 * side
            dx, dy = x - row[tip], y - row[tip + 1]
            dist = math.sqrt(dx * dx + dy * dy)
            if dist > 0.0 and dist <= row[tip + 2] + contact_tol:
                normals[count] = (dx / dist, dy / dist)
                es[count] = params[P_E_JAW]
                count += 1
            if count > normals.shape[0] - 3:
                break
    # Wedged: pressing into contacts (at any speed) so that it cannot slide along any one
    # of them without pressing into another (two balls jammed across a narrowing throat).
    # Sequential impulses would shed that motion only geometrically, over thousands of
    # events at one instant; the jam stops the lump, the cushions taking its momentum.
    if wedged(normals, count, vx, vy, math.inf, v_rest) or wedged(
        normals, count, vx, vy, v_zeno, v_rest
    ):
        vx, vy = 0.0, 0.0
    else:
        vx, vy = lump_off_contacts(vx, vy, normals, es, count)
        vx, vy = slide(normals, count, vx, vy, v_zeno, v_rest)
    for c in range(size):
        k = changed[c]
        x, y, _, _ = state_at(st, status, k, t, a)
        set_anchor(st, status, k, t, x, y, vx, vy, a, v_rest)
