"""Contacts of either level (compiled): the tolerances, and lumps of touching balls.

Both model levels resolve impacts that repeat at one instant with the same rules and the
same tolerances (the Zeno rules of :mod:`~pool_env.sim.kernels.roll.resolve`), and meet a
rail with a lump of balls as one body. What is here works on velocities alone, so it is
written once, below both levels.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel

V_ZENO = 1e-6  # m/s
V_REST = 1e-9  # m/s
# Impacts of one pair closer together than this are one contact repeating (a cascade of
# sequential impulses through touching balls, or a ball wedged against a rail).
ZENO_WINDOW = 1e-6  # s
# A pair that repeats this often within ZENO_WINDOW of each impact sticks, whatever its e.
ZENO_REPEATS = 16
# Balls whose centres are within 2R + CONTACT_TOL touch, for sticking clusters.
CONTACT_TOL = 1e-9  # m


@kernel
def lump_off_rail(vx, vy, nx, ny, e):
    """Velocity of a lump of balls after it meets, as one body, a rail it touches.

    Args:
        vx, vy: The lump's common velocity.
        nx, ny: The rail's unit normal, pointing from the rail into the table (any
            direction: axis-aligned rails and angled pocket facings alike).
        e: The rail's restitution.

    Returns:
        ``(vx, vy, hit)``: a normal velocity into the rail ``v_n = v.n < 0`` becomes
        ``-e v_n``, or 0 when slower than ``V_ZENO`` (a contact repeating at rounding
        speed is inelastic, as for balls); the tangential part is kept. ``hit`` says
        whether the lump was moving into the rail.
    """
    vn = vx * nx + vy * ny
    if not vn < 0.0:
        return vx, vy, False
    k = 1.0 + e if -vn >= V_ZENO else 1.0
    return vx - k * vn * nx, vy - k * vn * ny, True


# Passes over a lump's rails before a lump still pressed into one is jammed (at rest).
LUMP_PASSES = 8


@kernel
def lump_off_contacts(vx, vy, normals, es, count):
    """:func:`lump_off_rail` against every contact a lump touches (``normals[:count]``).

    Contact ``r`` (a rail, a jaw facing or a jaw point) has restitution ``es[r]``. Each pass
    meets every contact in turn; orthogonal rails (a corner) settle in one pass whatever
    their order. A lump still pressed into a contact after ``LUMP_PASSES`` passes (wedged
    between contacts that keep turning it into each other) stops: energy only drops.
    """
    for _ in range(LUMP_PASSES):
        pressed = False
        for r in range(count):
            vx, vy, hit = lump_off_rail(vx, vy, normals[r, 0], normals[r, 1], es[r])
            pressed |= hit
        if not pressed:
            return vx, vy
    for r in range(count):
        if vx * normals[r, 0] + vy * normals[r, 1] < 0.0:
            return 0.0, 0.0
    return vx, vy


@kernel
def lump_off_rails(vx, vy, normals, count, e):
    """:func:`lump_off_contacts` against rails that all have restitution ``e``."""
    return lump_off_contacts(vx, vy, normals, np.full(max(count, 1), e), count)


@kernel
def press_out(nx, ny, vx, vy, v_zeno):
    """Drop a velocity component into a surface of normal ``n`` if slower than ``v_zeno``."""
    vn = vx * nx + vy * ny
    if vn < 0.0 and -vn < v_zeno:
        return vx - vn * nx, vy - vn * ny, True
    return vx, vy, False


@kernel
def slide(normals, count, vx, vy, v_below, v_rest):
    """The nearest velocity free of the contacts pressed slower than ``v_below``.

    It drops one such component (the input comes back if none is pressed or none can go).
    """
    best_x, best_y, best_drop = vx, vy, math.inf
    for m in range(count):
        vn = vx * normals[m, 0] + vy * normals[m, 1]
        if not (vn < 0.0 and -vn < v_below):
            continue
        wx, wy = vx - vn * normals[m, 0], vy - vn * normals[m, 1]
        feasible = True
        for q in range(count):
            vq = vx * normals[q, 0] + vy * normals[q, 1]
            if vq < 0.0 and -vq < v_below and wx * normals[q, 0] + wy * normals[q, 1] < -v_rest:
                feasible = False
        if feasible and -vn < best_drop:
            best_x, best_y, best_drop = wx, wy, -vn
    return best_x, best_y


@kernel
def wedged(normals, count, vx, vy, v_below, v_rest):
    """Whether contacts pressed slower than ``v_below`` leave no single one to slide along."""
    pressed = 0
    for m in range(count):
        vn = vx * normals[m, 0] + vy * normals[m, 1]
        if vn < 0.0 and -vn < v_below:
            pressed += 1
    if pressed < 2:
        return False
    wx, wy = slide(normals, count, vx, vy, v_below, v_rest)
    return wx == vx and wy == vy
