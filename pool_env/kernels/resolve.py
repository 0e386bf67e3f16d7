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

* An impact whose normal approach speed is below ``V_ZENO`` is perfectly inelastic along the
  normal (``e = 0``).
* Two balls stick, leaving with their common centre-of-mass velocity (momentum conserved,
  energy lost), when an inelastic impact leaves them touching with their relative
  deceleration pressing them together (they would re-collide endlessly); when an inelastic
  impact repeats within ``ZENO_WINDOW`` (a cascade through a cluster of touching balls);
  or when any impact repeats ``ZENO_REPEATS`` times in a row that closely (a ball wedged
  between a ball and a rail, inelastic collapse).
* A ball slower than ``V_REST`` after an impact is at rest (it would stop within 1e-8 s and
  5e-18 m anyway).
"""

from __future__ import annotations

import math

from pool_env.kernels._jit import kernel
from pool_env.kernels.motion import set_anchor, state_at

V_ZENO = 1e-6  # m/s
V_REST = 1e-9  # m/s
# Impacts of one pair closer together than this are one contact repeating (a cascade of
# sequential impulses through touching balls, or a ball wedged against a rail).
ZENO_WINDOW = 1e-9  # s
# A pair that repeats this often within ZENO_WINDOW of each impact sticks, whatever its e.
ZENO_REPEATS = 16


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
    """
    a, e = params[3], params[4]
    xi, yi, vxi, vyi = state_at(st, status, i, t, a)
    xj, yj, vxj, vyj = state_at(st, status, j, t, a)
    dx, dy = xj - xi, yj - yi
    dist = math.sqrt(dx * dx + dy * dy)
    if dist == 0.0:  # coincident centres cannot pass validation; keep the state unchanged
        set_anchor(st, status, i, t, xi, yi, vxi, vyi, a, V_REST)
        set_anchor(st, status, j, t, xj, yj, vxj, vyj, a, V_REST)
        return
    nx, ny = dx / dist, dy / dist
    ui = vxi * nx + vyi * ny
    uj = vxj * nx + vyj * ny
    mi, mj = masses[i], masses[j]
    # Below V_ZENO (which includes a rounding-level approach at a touching contact found
    # by the compression test of the predictor) the impact is perfectly inelastic: the normal
    # components become their common centre-of-mass value, which never adds energy.
    approach = ui - uj
    e_eff = e if approach >= V_ZENO else 0.0
    total = mi + mj
    ui_new = (mi * ui + mj * uj + mj * e_eff * (uj - ui)) / total
    uj_new = (mi * ui + mj * uj + mi * e_eff * (ui - uj)) / total
    vxi += (ui_new - ui) * nx
    vyi += (ui_new - ui) * ny
    vxj += (uj_new - uj) * nx
    vyj += (uj_new - uj) * ny
    # Sticking ends inelastic cascades: with e = 0, sequential impulses through a cluster of
    # touching balls converge only geometrically, and slowly, towards common normal speeds.
    if repeats >= ZENO_REPEATS or (
        e_eff == 0.0 and (repeats >= 2 or _pressed_together(dx, dy, vxi, vyi, vxj, vyj, a))
    ):
        vx = (mi * vxi + mj * vxj) / total
        vy = (mi * vyi + mj * vyj) / total
        vxi, vyi, vxj, vyj = vx, vy, vx, vy
    set_anchor(st, status, i, t, xi, yi, vxi, vyi, a, V_REST)
    set_anchor(st, status, j, t, xj, yj, vxj, vyj, a, V_REST)


@kernel
def cushion(st, status, i, rail, t, params):
    """Resolve ball ``i`` hitting rail ``rail`` (0: x=R, 1: x=L-R, 2: y=R, 3: y=W-R)."""
    a, e = params[3], params[5]
    x, y, vx, vy = state_at(st, status, i, t, a)
    # Only a velocity into the rail is reflected, so a repeated or stale hit is harmless.
    if rail < 2:
        into = vx > 0.0 if rail == 1 else vx < 0.0
        if into:
            vx = -e * vx if abs(vx) >= V_ZENO else 0.0
    else:
        into = vy > 0.0 if rail == 3 else vy < 0.0
        if into:
            vy = -e * vy if abs(vy) >= V_ZENO else 0.0
    set_anchor(st, status, i, t, x, y, vx, vy, a, V_REST)

