"""The table's shot geometry, compiled: pocket mouths, ghost-ball shots, clear paths, speeds.

One copy for the agents' baselines and observation features
(:mod:`pool_env.game.geometry` is the public face). A table's pockets are a ``(K, NM)``
float64 array of mouths, one row a pocket, the columns below (built once per table by
:func:`pool_env.game.pockets.pocket_mouths`), plus a flag: jaws (the ball drops at a fall
line) or capture circles (it drops inside the circle).

Frame and terms (``R`` the ball radius): a ball centre lives in ``[R, L - R] x [R, W - R]``.
A mouth's *target* is the midpoint of its opening; to send object ball ``B`` along the unit
vector ``u`` the cue ball must touch it at the *ghost-ball point* ``G = B - 2 R u``; the
*cut* is the angle between the cue ball's path (cue to ``G``) and ``u``.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel

# Columns of a mouth row.
TX, TY = 0, 1  # target: the opening's midpoint
NX, NY = 2, 3  # unit normal of the opening into the pocket (0, 0: open to every direction)
AX, AY, BX, BY = 4, 5, 6, 7  # the opening's ends (ball-centre coordinates)
WIDTH = 8  # the mouth's width
CLEAR = 9  # how far inside each end of the mouth a ball centre must pass
CX, CY, CR = 10, 11, 12  # capture circle
PX, PY = 13, 14  # a point of the fall line (jaws)
DX, DY = 15, 16  # unit normal of the fall line towards the table (jaws)
NM = 17

# Columns of a ghost-shot row (:func:`ghost_shots`).
VALID = 0  # 1.0 for a shot kept, 0.0 otherwise (the other columns are then meaningless)
ANGLE = 1  # cue ball direction (radians from +x), cue to the ghost-ball point
CUT = 2  # signed cut angle (positive: the object ball leaves counter-clockwise of the cue's path)
GX, GY = 3, 4  # the ghost-ball point
CUE_DIST = 5  # cue centre to the ghost-ball point
BALL_DIST = 6  # object ball centre to its aim point
TRAVEL = 7  # how far the object ball rolls until it drops
APPROACH = 8  # cosine of its path against the mouth's normal (1 for an open pocket)
TOLERANCE = 9  # aim error (rad) forgiven, to first order
CLEAR_PATH = 10  # 1.0 when both paths keep 2R from every other ball
AIM_X, AIM_Y = 11, 12  # where the object ball is aimed (the target moved by the offset)
COS_CUT = 13  # cosine of the cut (as computed, not recovered from CUT)
NG = 14


@kernel
def ray_circle(sx, sy, ux, uy, cx, cy, r):
    """Distance along the ray ``s + t u`` to a circle's edge (0 from inside, inf: misses)."""
    wx, wy = sx - cx, sy - cy
    b = wx * ux + wy * uy
    c = (wx * wx + wy * wy) - r * r
    disc = b * b - c
    if disc < 0.0 or -b + math.sqrt(disc) < 0.0:
        return math.inf
    return max(-b - math.sqrt(disc), 0.0)


@kernel
def travel(mouths, jaws, k, sx, sy, ux, uy):
    """How far a ball from ``s`` along ``u`` rolls until it drops in pocket ``k`` (inf: never).

    To the capture circle's edge, or to the fall line (jaws).
    """
    m = mouths[k]
    if jaws:
        closing = -(ux * m[DX] + uy * m[DY])  # how fast the fall line comes nearer
        height = (sx - m[PX]) * m[DX] + (sy - m[PY]) * m[DY]
        if closing > 0.0 and height >= 0.0:
            return height / closing
        return math.inf
    return ray_circle(sx, sy, ux, uy, m[CX], m[CY], m[CR])


@kernel
def entry(mouths, jaws, k, sx, sy, ux, uy):
    """Distance along the ray from ``s`` to where it enters pocket ``k`` (inf: never).

    Circles: the circle's edge. Jaws: the opening, where the ball leaves the rails' reach.
    """
    m = mouths[k]
    if not jaws:
        return ray_circle(sx, sy, ux, uy, m[CX], m[CY], m[CR])
    segx, segy = m[BX] - m[AX], m[BY] - m[AY]
    denom = ux * segy - uy * segx
    if abs(denom) < 1e-15:
        return math.inf
    wx, wy = m[AX] - sx, m[AY] - sy
    t = (wx * segy - wy * segx) / denom  # along the ray
    s = (wx * uy - wy * ux) / denom  # along the opening
    if t >= -1e-12 and 0.0 <= s <= 1.0:
        return t
    return math.inf


@kernel
def approach_cos(mouths, k, ux, uy):
    """Cosine of a path along ``u`` against pocket ``k``'s inward normal (1: open pocket)."""
    nx, ny = mouths[k, NX], mouths[k, NY]
    if nx == 0.0 and ny == 0.0:
        return 1.0
    return ux * nx + uy * ny


@kernel
def half_tolerance(mouths, k, ux, uy, min_approach_cos):
    """How far (m) sideways a path along ``u`` may pass pocket ``k``'s target and drop.

    The mouth seen along the path, ``width cos(approach) / 2``, less the clearance; 0 when
    the approach's cosine is below ``min_approach_cos`` (along the mouth or away from it).
    """
    cos_a = approach_cos(mouths, k, ux, uy)
    if cos_a < min_approach_cos:
        return 0.0
    return max(mouths[k, WIDTH] / 2.0 * cos_a - mouths[k, CLEAR], 0.0)


@kernel
def path_clear(sx, sy, ex, ey, balls, on, skip_a, skip_b, reach):
    """Whether a centre moving from ``s`` to ``e`` keeps more than ``reach`` from each ball.

    ``balls`` is ``(M, 2)``, ``on`` ``(M,)``: the balls on the table are the obstacles,
    except rows ``skip_a`` and ``skip_b`` (the moving balls; -1: none).
    """
    segx, segy = ex - sx, ey - sy
    length2 = segx * segx + segy * segy
    for i in range(balls.shape[0]):
        if i in (skip_a, skip_b) or not on[i]:
            continue
        rx, ry = balls[i, 0] - sx, balls[i, 1] - sy
        t = 0.0
        if length2 > 0.0:
            t = min(max((rx * segx + ry * segy) / length2, 0.0), 1.0)
        if math.hypot(balls[i, 0] - (sx + t * segx), balls[i, 1] - (sy + t * segy)) <= reach:
            return False
    return True


@kernel
def ghost_contact(px, py, ux, uy, cx, cy, radius, box):
    """The ghost-ball point that sends the ball at ``p`` along ``u``, seen from the cue at ``c``.

    Returns:
        ``(on_cloth, gx, gy, dx, dy, d_cue, cos_cut)``: whether the point ``G = p - 2 R u``
        lies in the centre rectangle ``box`` ``(x0, y0, x1, y1)`` (a cushion keeps the cue
        ball from it otherwise), the point, the cue ball's unit heading to it (``u`` when
        the cue ball already sits there), the distance, and the cut's cosine.
    """
    gx, gy = px - 2.0 * radius * ux, py - 2.0 * radius * uy
    on_cloth = box[0] <= gx <= box[2] and box[1] <= gy <= box[3]
    vx, vy = gx - cx, gy - cy
    d_cue = math.hypot(vx, vy)
    dx, dy = ux, uy
    if d_cue >= 1e-12:
        dx, dy = vx / d_cue, vy / d_cue
    cos_cut = min(max(dx * ux + dy * uy, -1.0), 1.0)
    return on_cloth, gx, gy, dx, dy, d_cue, cos_cut


@kernel
def ghost_shot(out, mouths, jaws, k, balls, on, cue, b, radius, box, offset, cos_max_cut, mac):
    """Fill ``out`` (``NG``) with the ghost-ball shot of ball ``b`` into pocket ``k``.

    ``balls`` is ``(N, 2)`` and ``on`` ``(N,)`` which of them are on the table; ``box`` the centre
    rectangle ``(x0, y0, x1, y1)``; ``offset`` moves the aim point sideways by that
    fraction of the half-tolerance; ``mac`` is the least approach cosine. ``out[VALID]`` is
    0 when the mouth is closed to the ball's path, the ghost point is off the cloth, the cut
    is thinner than ``cos_max_cut`` allows or the path never drops.
    """
    out[:] = 0.0
    px, py = balls[b, 0], balls[b, 1]
    cx, cy = balls[cue, 0], balls[cue, 1]
    tx, ty = mouths[k, TX] - px, mouths[k, TY] - py
    norm = math.hypot(tx, ty)
    sx, sy = tx / norm, ty / norm
    half = half_tolerance(mouths, k, sx, sy, mac)
    if half <= 0.0:
        return
    aimx = mouths[k, TX] + offset * half * -sy
    aimy = mouths[k, TY] + offset * half * sx
    ux, uy = aimx - px, aimy - py
    d_ball = math.hypot(ux, uy)
    ux, uy = ux / d_ball, uy / d_ball
    on_cloth, gx, gy, dx, dy, d_cue, cos_cut = ghost_contact(px, py, ux, uy, cx, cy, radius, box)
    if not on_cloth or cos_cut < cos_max_cut:
        return  # a cushion keeps the cue ball from the ghost point, or the cut is too thin
    rolled = travel(mouths, jaws, k, px, py, ux, uy)
    if not math.isfinite(rolled):
        return
    reach = 2.0 * radius
    clear = path_clear(cx, cy, gx, gy, balls, on, cue, b, reach) and path_clear(
        px, py, aimx, aimy, balls, on, cue, b, reach
    )
    out[VALID] = 1.0
    out[ANGLE] = math.atan2(dy, dx)
    out[CUT] = math.atan2(dx * uy - dy * ux, cos_cut)
    out[GX], out[GY] = gx, gy
    out[CUE_DIST], out[BALL_DIST], out[TRAVEL] = d_cue, d_ball, rolled
    out[APPROACH] = approach_cos(mouths, k, ux, uy)
    out[TOLERANCE] = 2.0 * radius * cos_cut * half / (max(d_cue, reach) * d_ball)
    out[CLEAR_PATH] = 1.0 if clear else 0.0
    out[AIM_X], out[AIM_Y] = aimx, aimy
    out[COS_CUT] = cos_cut


@kernel
def ghost_shots(mouths, jaws, positions, on, targets, cue, radius, box, offset, cos_max_cut, mac):
    """:func:`ghost_shot` for ``B`` layouts, ``T`` target balls each, every pocket.

    Args:
        mouths: ``(K, NM)`` the table's mouths; ``jaws`` their pocket model.
        positions: ``(B, N, 2)`` centres; ``on`` ``(B, N)`` which balls are on the table.
        targets: ``(B, T)`` object ball indices (-1: no target in that slot).
        cue: The cue ball's index.
        radius: Ball radius; ``box`` the centre rectangle ``(x0, y0, x1, y1)``.
        offset: Aim point offset (fraction of the half-tolerance).
        cos_max_cut: Cosine of the thinnest cut kept; ``mac`` the least approach cosine.

    Returns:
        ``(B, T, K, NG)`` shot rows (``VALID`` 0 for an empty slot).
    """
    nb, nt, nk = positions.shape[0], targets.shape[1], mouths.shape[0]
    out = np.zeros((nb, nt, nk, NG))
    for i in range(nb):
        for t in range(nt):
            b = targets[i, t]
            if b < 0:
                continue
            for k in range(nk):
                ghost_shot(
                    out[i, t, k], mouths, jaws, k, positions[i], on[i], cue, b, radius, box,
                    offset, cos_max_cut, mac,
                )  # fmt: skip
    return out


@kernel
def cue_speed(deceleration, e_ball, rolled, cut, cue_distance, arrival):
    """Cue speed (m/s) at which the object ball drops at ``arrival`` (m/s).

    Balls roll at the constant deceleration ``a``; being of equal mass, the object ball
    leaves with ``(1 + e) / 2 cos(cut)`` of the cue ball's speed. Backwards:
    ``v_ball = sqrt(arrival^2 + 2 a rolled)``, ``v_contact = v_ball / ((1 + e) / 2 cos(cut))``,
    ``v_cue = sqrt(v_contact^2 + 2 a cue_distance)``.
    """
    v_ball = math.sqrt(arrival * arrival + 2.0 * deceleration * rolled)
    v_contact = v_ball / ((1.0 + e_ball) / 2.0 * math.cos(cut))
    return math.sqrt(v_contact * v_contact + 2.0 * deceleration * cue_distance)


@kernel
def cue_speeds(deceleration, e_ball, shots, arrival):
    """:func:`cue_speed` of every valid row of ``(..., NG)`` shots flattened to ``(S, NG)``."""
    out = np.zeros(shots.shape[0])
    for s in range(shots.shape[0]):
        if shots[s, VALID] > 0.0:
            out[s] = cue_speed(
                deceleration, e_ball, shots[s, TRAVEL], shots[s, CUT], shots[s, CUE_DIST], arrival
            )
    return out
