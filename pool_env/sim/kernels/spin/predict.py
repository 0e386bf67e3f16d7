"""Event prediction of the spin level (compiled): a ball's own events and a pair's impact.

Every ball moves with a constant acceleration between its anchor and its next transition
(:mod:`~pool_env.sim.kernels.spin.state`), so each question is a polynomial in the time
``tau`` since the anchor, answered exactly (no time stepping):

* a straight rail: the signed penetration ``g(tau) = g0 + g1 tau + g2 tau^2`` of the ball
  centre past the rail line is a quadratic; the event is its first root where the ball
  moves into the rail (``g' > 0``), found from the stable quadratic formula; a ball at or
  past the line moving into it hits now (the contact rule of the roll level);
* a capture circle: the squared distance to its centre less its squared radius is a
  quartic, solved by the bracketed :func:`~pool_env.sim.kernels.roots.first_contact`
  (a start inside captures now, in any direction); pocket jaws (facings, points, fall
  lines): :mod:`~pool_env.sim.kernels.spin.jaw_events` (on a jaw table a rail crossing inside a
  pocket's opening is no rail hit);
* a pair of balls: the squared gap is a quartic in any mix of states
  (:func:`~pool_env.sim.kernels.roots.first_contact`), with the explicit degree drops: both
  still, no event; bitwise-equal accelerations (two balls rolling or sliding the same way),
  the quadratic :func:`~pool_env.sim.kernels.roots.equal_accel_contact`;
* a transition: its closed-form time ``TEND``.

A ball's own event (rail, pocket or transition) ends its piece of motion; a pair is
predicted over the window up to the earlier own event of its two balls, and re-predicted
whenever either ball is re-anchored (an impact or a transition): that is how a prediction
covers a piecewise path. Pairs are culled first by the bounding boxes of the two pieces,
pockets by reach: a capture circle or a pocket's jaws whose box the piece's bounding box
misses is not solved for (exact: :func:`~pool_env.sim.kernels.jaw_geometry.box_meets`).

A ball at a rail or facing with no normal speed whose slip presses it in is an impact now
(the loop's pressed-cushion rule then sets it rolling along the cushion).
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel, level_method
from pool_env.sim.kernels import level as interface
from pool_env.sim.kernels.jaw_geometry import JAW_COLS, REACH_MARGIN, opening_of
from pool_env.sim.kernels.kinds import (
    CUSHION,
    EV_ARG,
    EV_KIND,
    EV_T,
    POCKET,
    ROLL_SPIN,
    SLIDE_ROLL,
    SPIN_STOP,
    STOP,
)
from pool_env.sim.kernels.params import P_LENGTH, P_RADIUS, P_WIDTH
from pool_env.sim.kernels.roots import (
    APPROACH_RTOL,
    INF,
    equal_accel_contact,
    first_contact,
    quadratic_roots,
)
from pool_env.sim.kernels.spin.jaw_events import predict_jaws
from pool_env.sim.kernels.spin.marker import SpinLevel
from pool_env.sim.kernels.spin.params import S_SLIDE_DECEL, S_SPIN_DECEL
from pool_env.sim.kernels.spin.state import (
    AX,
    AY,
    POTTED,
    PX,
    PY,
    SLIDING,
    SPINNING,
    T0,
    TEND,
    VX,
    VY,
    WZ,
    moving,
    state_at,
)

# Columns of the (N, 4) bounding-box array of each ball's current piece.
B_XMIN, B_YMIN, B_XMAX, B_YMAX = 0, 1, 2, 3
CULL_MARGIN = 1e-9


@kernel
def first_rise(g0, g1, g2, span, tol, curv_tol):
    """First ``tau`` in ``[0, span]`` where ``g0 + g1 tau + g2 tau^2`` reaches 0 rising.

    ``g`` is a ball's penetration past a rail line. At ``tau = 0`` the contact rule: at or
    past the line (``g0 >= 0``) and moving in faster than ``tol``, an impact now; moving
    in slower is rounding (a ball just reflected or rolling along the rail): no event,
    unless the ball is pressed in, its acceleration into the rail beyond rounding
    (``g2 > curv_tol``, a sliding ball's slip driving it into the rail): an impact now.
    """
    if g0 >= 0.0 and (g1 > tol or (g1 >= -tol and g2 > curv_tol)):
        return 0.0
    r1, r2 = quadratic_roots(g2, g1, g0)
    for r in (r1, r2):
        if r > 0.0 and r <= span and g1 + 2.0 * g2 * r > tol:
            return r
    return INF


@kernel
def _extent(p0, v0, a, span):
    """Min and max of ``p0 + v0 tau + a tau^2 / 2`` over ``[0, span]`` (``span`` finite)."""
    end = p0 + span * (v0 + 0.5 * a * span)
    lo = min(p0, end)
    hi = max(p0, end)
    if a != 0.0:
        turn = -v0 / a
        if 0.0 < turn < span:
            mid = p0 + turn * (v0 + 0.5 * a * turn)
            lo = min(lo, mid)
            hi = max(hi, mid)
    return lo, hi


@kernel
def _transition(st, ms, i, prm):
    """Kind of ball ``i``'s next transition (its time is ``st[i, TEND]``)."""
    state = ms[i]
    if state == SLIDING:
        return SLIDE_ROLL
    if state == SPINNING:
        return SPIN_STOP
    # Rolling: it spins on if wz outlasts the roll.
    if abs(st[i, WZ]) > prm[S_SPIN_DECEL] * (st[i, TEND] - st[i, T0]):
        return ROLL_SPIN
    return STOP


@level_method(interface.predict_own, SpinLevel, inline=False)
def predict_own(level, st, ms, i, prm, pockets, own, boxes):
    """Ball ``i``'s next own event (rail, pocket or transition) and its piece's box.

    Writes ``own[i] = (time, kind, arg, time)`` (the last column, the end of the piece,
    equals the event time: every own event re-anchors the ball) and ``boxes[i]``.
    """
    x, y = st[i, PX], st[i, PY]
    t_end = st[i, TEND]
    best_t = t_end
    best_kind = STOP
    best_arg = -1
    if t_end < INF:
        best_kind = _transition(st, ms, i, prm)
    span = t_end - st[i, T0]
    xl, xh, yl, yh = x, x, y, y
    if moving(ms[i]):
        radius, length, width = prm[P_RADIUS], prm[P_LENGTH], prm[P_WIDTH]
        t0 = st[i, T0]
        vx, vy, ax, ay = st[i, VX], st[i, VY], st[i, AX], st[i, AY]
        # Speed scale of the piece: its speed now plus the most it can change over the piece.
        scale = math.sqrt(vx * vx + vy * vy) + math.sqrt(ax * ax + ay * ay) * span
        tol = APPROACH_RTOL * scale
        curv_tol = APPROACH_RTOL * prm[S_SLIDE_DECEL]
        jaws = pockets.shape[1] == JAW_COLS
        lines = (radius - x, x - (length - radius), radius - y, y - (width - radius))
        for rail in range(4):
            sign = -1.0 if rail % 2 == 0 else 1.0
            v, a = (vx, ax) if rail < 2 else (vy, ay)
            tau = first_rise(lines[rail], sign * v, 0.5 * sign * a, span, tol, curv_tol)
            t = t0 + tau
            if tau < INF and (t < best_t or (t == best_t and best_kind > CUSHION)):
                # On a jaw table a crossing inside a pocket's opening is no rail hit.
                if jaws:
                    if rail < 2:
                        coord = y + tau * (vy + 0.5 * ay * tau)
                    else:
                        coord = x + tau * (vx + 0.5 * ax * tau)
                    if opening_of(pockets, rail, coord) >= 0:
                        continue
                best_t, best_kind, best_arg = t, CUSHION, rail
        if jaws:
            xl, xh = _extent(x, vx, ax, span)
            yl, yh = _extent(y, vy, ay, span)
            if xl < radius or xh > length - radius or yl < radius or yh > width - radius:
                best = (best_t, best_kind, best_arg)
                best_t, best_kind, best_arg = predict_jaws(
                    pockets, prm, x, y, vx, vy, ax, ay, span, tol, curv_tol, scale,
                    prm[S_SLIDE_DECEL], t0, best, (xl, yl, xh, yh),
                )  # fmt: skip
        else:
            # Culling by reach: a capture needs the centre within r of the pocket's centre,
            # so a circle whose box the piece's box misses has no root to look for.
            xl, xh = _extent(x, vx, ax, span)
            yl, yh = _extent(y, vy, ay, span)
            for k in range(pockets.shape[0]):
                qx, qy, r = pockets[k, 0], pockets[k, 1], pockets[k, 2]
                reach = r + REACH_MARGIN
                if xh < qx - reach or xl > qx + reach or yh < qy - reach or yl > qy + reach:
                    continue
                dx, dy = qx - x, qy - y
                if dx * dx + dy * dy <= r * r:
                    tau = 0.0
                else:
                    tau = first_contact(
                        dx, dy, -vx, -vy, -0.5 * ax, -0.5 * ay, r * r, span, scale, 0.0
                    )
                t = t0 + tau
                if tau < INF and (t < best_t or (t == best_t and best_kind > POCKET)):
                    best_t, best_kind, best_arg = t, POCKET, k
        piece = best_t - st[i, T0]
        xl, xh = _extent(x, vx, ax, piece)
        yl, yh = _extent(y, vy, ay, piece)
    own[i, EV_T] = best_t
    own[i, EV_KIND] = best_kind
    own[i, EV_ARG] = best_arg
    own[i, 3] = best_t
    boxes[i, B_XMIN] = xl
    boxes[i, B_YMIN] = yl
    boxes[i, B_XMAX] = xh
    boxes[i, B_YMAX] = yh


@level_method(interface.predict_pair, SpinLevel, inline=False)
def predict_pair(level, st, ms, i, j, now, prm, own, boxes):
    """Time of the next impact of balls ``i`` and ``j`` after ``now`` (``inf`` if none).

    The window ends at the earlier own event of the two (the end of either piece).
    """
    if not (moving(ms[i]) or moving(ms[j])):
        return INF  # both still (at rest, spinning in place or potted): no event
    reach = 2.0 * prm[P_RADIUS] + CULL_MARGIN
    if (
        boxes[i, B_XMIN] - boxes[j, B_XMAX] > reach
        or boxes[j, B_XMIN] - boxes[i, B_XMAX] > reach
        or boxes[i, B_YMIN] - boxes[j, B_YMAX] > reach
        or boxes[j, B_YMIN] - boxes[i, B_YMAX] > reach
    ):
        return INF
    if ms[i] == POTTED or ms[j] == POTTED:
        return INF
    span = min(own[i, EV_T], own[j, EV_T]) - now
    if span < 0.0:
        return INF
    xi, yi, vxi, vyi, _, _, _ = state_at(st, ms, i, now, prm)
    xj, yj, vxj, vyj, _, _, _ = state_at(st, ms, j, now, prm)
    d0x, d0y = xj - xi, yj - yi
    wx, wy = vxj - vxi, vyj - vyi
    ai = moving(ms[i])
    aj = moving(ms[j])
    cx = 0.5 * ((st[j, AX] if aj else 0.0) - (st[i, AX] if ai else 0.0))
    cy = 0.5 * ((st[j, AY] if aj else 0.0) - (st[i, AY] if ai else 0.0))
    four_r2 = 4.0 * prm[P_RADIUS] * prm[P_RADIUS]
    scale = math.sqrt(vxi * vxi + vyi * vyi) + math.sqrt(vxj * vxj + vyj * vyj)
    if cx == 0.0 and cy == 0.0:
        tau = equal_accel_contact(d0x, d0y, wx, wy, four_r2, span, scale)
    else:
        tau = first_contact(d0x, d0y, wx, wy, cx, cy, four_r2, span, scale, prm[S_SLIDE_DECEL])
    return now + tau if tau < INF else INF
