"""Snooker's geometry, compiled: spots, re-spotting, the D, and the snookered test.

- A spot is occupied when a ball cannot be placed on it without touching another ball
  (Section 2 Rule 18): another centre nearer than ``2R`` (and the package's placement
  clearance, ``params[REACH]``), as :func:`pool_env.game.kernels.layout.point_free` has it.
- Colours are re-spotted by Section 3 Rule 7 (:func:`respot_colours`).
- The cue ball in hand goes in the D (Section 3 Rule 5): the requested point, or when that
  is covered the free point of a fine grid of the D nearest to it (:func:`place_in_d`).
- The snookered test is Section 2 Rule 17, exactly from the balls' centres
  (:func:`snookered`); with the cue ball in hand it is made from sample points of the D
  (:func:`snookered_in_hand`).
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.game.games.snooker.params import (
    BAULK_X,
    BLACK_X,
    BLUE_X,
    CENTRE_Y,
    D_RADIUS,
    PINK_X,
)
from pool_env.game.games.snooker.rack_state import BLACK, FIRST_COLOUR
from pool_env.game.kernels.layout import point_free
from pool_env.game.kernels.params import CLEARANCE, RADIUS, REACH, X_HIGH, X_LOW
from pool_env.sim.jit import kernel

#: Grid step of the D's placement search, in ball radii.
D_GRID = 0.25

#: The D's sample points for the snookered test of a cue ball in hand: radii ``k / 4`` of
#: the D's (``k = 0 .. 4``) times directions ``pi / 2 + j pi / 8`` (``j = 0 .. 8``).
D_RINGS, D_RAYS = 4, 8


@kernel
def spot_of(params, colour):
    """``(x, y)`` of ``colour``'s spot (16 yellow .. 21 black)."""
    cy, r = params[CENTRE_Y], params[D_RADIUS]
    if colour == FIRST_COLOUR:
        return params[BAULK_X], cy - r
    if colour == FIRST_COLOUR + 1:
        return params[BAULK_X], cy + r
    if colour == FIRST_COLOUR + 2:
        return params[BAULK_X], cy
    if colour == FIRST_COLOUR + 3:
        return params[BLUE_X], cy
    if colour == FIRST_COLOUR + 4:
        return params[PINK_X], cy
    return params[BLACK_X], cy


@kernel
def _others(positions, on_table, skip, out):
    """The centres of the balls on the table but ``skip`` into ``out``; their count."""
    count = 0
    for j in range(on_table.shape[0]):
        if j != skip and on_table[j]:
            out[count] = positions[j]
            count += 1
    return count


@kernel
def free_at(params, pockets, positions, on_table, ball, x, y, others):
    """Whether ``ball`` may stand at ``(x, y)``: the spot is not occupied."""
    count = _others(positions, on_table, ball, others)
    reach = params[REACH]
    return point_free(x, y, params, pockets, others, count, reach * reach)


@kernel
def _scan(params, pockets, others, count, x, y, direction):
    """The first ``x`` from ``x`` on in ``direction`` (+1, -1) where a centre at ``y`` is free.

    Each ball and each padded capture circle blocks an interval of the line; the scan
    jumps past each interval it stands in until none holds it. Returns ``nan`` when it
    leaves the rails.
    """
    reach = params[REACH]
    for _ in range(4 * (count + pockets.shape[0]) + 4):
        moved = False
        for j in range(count):
            dy = y - others[j, 1]
            if abs(dy) < reach:
                half = math.sqrt(reach * reach - dy * dy) * (1.0 + 1e-9) + 1e-12
                if abs(x - others[j, 0]) < half:  # past the end, beyond rounding
                    x = others[j, 0] + direction * (half + 1e-11)
                    moved = True
        for p in range(pockets.shape[0]):
            r = pockets[p, 2] + params[CLEARANCE]
            dy = y - pockets[p, 1]
            if abs(dy) <= r:
                half = math.sqrt(r * r - dy * dy) * (1.0 + 1e-9) + 1e-12
                if abs(x - pockets[p, 0]) <= half:
                    x = pockets[p, 0] + direction * (half + 1e-11)
                    moved = True
        if not (params[X_LOW] <= x <= params[X_HIGH]):
            return math.nan
        if not moved:
            return x
    return math.nan


@kernel
def respot_colours(params, pockets, positions, on_table, to_spot, others):
    """Re-spot the colours of ``to_spot`` (Section 3 Rule 7); False if one is left unplaced.

    (c) a colour goes on its own spot when that is not occupied; (d) when several colours
    are to be spotted and their own spots are occupied, the highest-valued goes first, to
    (c) the highest-valued spot available; (e) when every spot is occupied, as near its
    own spot as it can be on the line from it to the nearest part of the top cushion;
    (f) for the pink and black, when that line has no room, as near its own spot as it
    can be on the centre line below it (the same below-the-spot search is used for the
    other colours here: on a real table their line to the top cushion always has room).
    The colours whose own spots are free are spotted first (they take no other spot);
    the rest follow, black first. A colour left unplaced (no room on either line: not a
    layout the rules foresee) stays on the table at its own spot's row, and False tells
    the caller to put it on the free point nearest its spot.
    """
    placed = True
    waiting = np.zeros(BLACK + 1, dtype=np.bool_)
    for colour in range(BLACK, FIRST_COLOUR - 1, -1):  # (c): their own spots first
        if not to_spot[colour]:
            continue
        x, y = spot_of(params, colour)
        if free_at(params, pockets, positions, on_table, colour, x, y, others):
            positions[colour, 0], positions[colour, 1] = x, y
            on_table[colour] = True
        else:
            waiting[colour] = True
    for colour in range(BLACK, FIRST_COLOUR - 1, -1):  # (d): the highest value first
        if not waiting[colour]:
            continue
        done = False
        for spot in range(BLACK, FIRST_COLOUR - 1, -1):  # (c): the highest spot available
            x, y = spot_of(params, spot)
            if free_at(params, pockets, positions, on_table, colour, x, y, others):
                positions[colour, 0], positions[colour, 1] = x, y
                done = True
                break
        if not done:  # (e), then (f)
            count = _others(positions, on_table, colour, others)
            x0, y0 = spot_of(params, colour)
            x = _scan(params, pockets, others, count, x0, y0, 1.0)
            if math.isnan(x):
                x = _scan(params, pockets, others, count, x0, y0, -1.0)
            if math.isnan(x):
                x = x0
                placed = False
            positions[colour, 0], positions[colour, 1] = x, y0
        on_table[colour] = True
    return placed


@kernel
def d_point(params, u, v):
    """The point of the D at ``(u, v)`` in ``[0, 1] x [-1, 1]`` (see ``markings.d_point``)."""
    r = params[D_RADIUS]
    depth = u * r
    half = math.sqrt(max(r * r - depth * depth, 0.0))
    return params[BAULK_X] - depth, params[CENTRE_Y] + v * half


@kernel
def place_in_d(params, pockets, positions, on_table, tx, ty, others):
    """Put the cue ball on the free point of the D nearest ``(tx, ty)``; False if none.

    ``(tx, ty)`` itself when it is in the D and free, else the nearest free point of the
    D's grid (step :data:`D_GRID` R from the middle of the baulk line).
    """
    count = _others(positions, on_table, 0, others)
    reach = params[REACH]
    bx, cy, r = params[BAULK_X], params[CENTRE_Y], params[D_RADIUS]
    inside = tx <= bx and (tx - bx) ** 2 + (ty - cy) ** 2 <= r * r
    if inside and point_free(tx, ty, params, pockets, others, count, reach * reach):
        positions[0, 0], positions[0, 1] = tx, ty
        on_table[0] = True
        return True
    h = D_GRID * params[RADIUS]
    steps = int(r / h)
    best, bx_, by_ = math.inf, 0.0, 0.0
    for i in range(steps + 1):
        x = bx - i * h
        for k in range(-steps, steps + 1):
            y = cy + k * h
            if (x - bx) ** 2 + (y - cy) ** 2 > r * r:
                continue
            d2 = (x - tx) ** 2 + (y - ty) ** 2
            if d2 < best and point_free(x, y, params, pockets, others, count, reach * reach):
                best, bx_, by_ = d2, x, y
    if best == math.inf:
        return False
    positions[0, 0], positions[0, 1] = bx_, by_
    on_table[0] = True
    return True


@kernel
def edge_clear(cx, cy, px, py, sign, positions, blockers, radius):
    """Whether the cue ball at ``(cx, cy)`` can hit one extreme edge of the ball at ``(px, py)``.

    The stroke that just grazes it on side ``sign`` sends the cue ball's centre along the
    tangent from ``(cx, cy)`` to the circle of radius ``2R`` about the ball, up to the
    tangent point (where the two touch); it is obstructed when a ball of ``blockers``
    lies nearer than ``2R`` to that segment (Section 2 Rule 17).
    """
    dx, dy = px - cx, py - cy
    d = math.sqrt(dx * dx + dy * dy)
    two_r = 2.0 * radius
    if d <= two_r:  # touching: nothing can come between
        return True
    t = math.sqrt(d * d - two_r * two_r)
    sin_a, cos_a = two_r / d, t / d
    ux, uy = dx / d, dy / d
    vx = ux * cos_a - sign * uy * sin_a
    vy = sign * ux * sin_a + uy * cos_a
    for j in range(positions.shape[0]):
        if not blockers[j]:
            continue
        qx, qy = positions[j, 0] - cx, positions[j, 1] - cy
        s = min(max(qx * vx + qy * vy, 0.0), t)
        ex, ey = qx - s * vx, qy - s * vy
        if ex * ex + ey * ey < two_r * two_r:
            return False
    return True


@kernel
def snookered(cx, cy, positions, on_table, balls_on, radius):
    """Section 2 Rule 17: no ball on can be struck at both extreme edges from ``(cx, cy)``.

    ``balls_on`` are the incoming striker's balls on; the obstructions are the other
    object balls on the table (a ball on does not snooker another). Cushions and pocket
    jaws do not snooker (they are not balls).
    """
    n = on_table.shape[0]
    blockers = np.zeros(n, dtype=np.bool_)
    for j in range(1, n):
        blockers[j] = on_table[j] and not balls_on[j]
    for j in range(1, n):
        if not balls_on[j]:
            continue
        px, py = positions[j, 0], positions[j, 1]
        if edge_clear(cx, cy, px, py, 1.0, positions, blockers, radius) and edge_clear(
            cx, cy, px, py, -1.0, positions, blockers, radius
        ):
            return False
    return True


@kernel
def snookered_in_hand(params, pockets, positions, on_table, balls_on, others):
    """The snookered test with the cue ball in hand: snookered from every sample of the D.

    The samples are the D's points at radii ``k / 4`` of its radius (``k = 0 .. 4``) and
    directions ``pi / 2 + j pi / 8`` (``j = 0 .. 8``) from the middle of the baulk line,
    those where the cue ball may be placed. (The rule asks for every point of the D; these
    45 stand for them.)
    """
    count = _others(positions, on_table, 0, others)
    reach = params[REACH]
    bx, cy, r = params[BAULK_X], params[CENTRE_Y], params[D_RADIUS]
    for k in range(D_RINGS + 1):
        rho = r * k / D_RINGS
        for j in range(D_RAYS + 1):
            theta = math.pi / 2.0 + j * math.pi / D_RAYS
            x, y = bx + rho * math.cos(theta), cy + rho * math.sin(theta)
            if not point_free(x, y, params, pockets, others, count, reach * reach):
                continue
            if not snookered(x, y, positions, on_table, balls_on, params[RADIUS]):
                return False
    return True
