"""Root finding for event times (compiled).

We never compute the four complex roots of a quartic and filter by imaginary part (the
pooltool trap: a dropped degree turns into phantom roots at t = 0). The question asked is
"when does the gap first close while the balls approach", answered by bracketing:

* the squared gap ``D(t) = |d(t)|^2 - (2R)^2`` with ``d(t) = d0 + w t + c t^2`` is a quartic;
* ``D''/2 = 6|c|^2 t^2 + 6 (w.c) t + |w|^2 + 2 d0.c`` is a quadratic, solved in closed form;
* between its roots ``D'`` is monotone, so each root of ``D'`` (a closest or farthest
  approach) is bracketed and polished;
* between those, ``D`` is monotone: the first decreasing piece on which ``D`` reaches 0 holds
  the event, found by safeguarded Newton.

``D`` is always evaluated from the vector form, never from expanded coefficients, so a tiny
leading coefficient (two balls moving almost the same way) costs no accuracy.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel

INF = math.inf

# Touching balls whose normal approach speed is below this fraction of their speed scale
# count as not approaching: that is rounding left by an inelastic impact, not motion.
APPROACH_RTOL = 1e-12


@kernel
def quadratic_roots(qa, qb, qc):
    """Real roots ``(r1, r2)``, ``r1 <= r2``, of ``qa t^2 + qb t + qc``; NaN where absent.

    Uses the cancellation-free pair ``q = -(b + sign(b) sqrt(disc)) / 2``, ``r = q / a`` and
    ``c / q``, so a vanishing leading coefficient degrades gracefully to the linear root.
    """
    nan = math.nan
    if qa == 0.0:
        if qb == 0.0:
            return nan, nan
        r = -qc / qb
        return r, nan
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return nan, nan
    sq = math.sqrt(disc)
    q = -0.5 * (qb + sq) if qb >= 0.0 else -0.5 * (qb - sq)
    if q == 0.0:  # qb == 0 and qc == 0
        return 0.0, 0.0
    r1 = q / qa
    r2 = qc / q
    if r1 > r2:
        r1, r2 = r2, r1
    return r1, r2


@kernel
def gap_terms(t, d0x, d0y, wx, wy, cx, cy, four_r2):
    """``(D, D', D''/2)`` of the squared gap at time ``t`` (see module docstring)."""
    dx = d0x + t * (wx + t * cx)
    dy = d0y + t * (wy + t * cy)
    ex = wx + 2.0 * t * cx
    ey = wy + 2.0 * t * cy
    gap = dx * dx + dy * dy - four_r2
    dgap = 2.0 * (dx * ex + dy * ey)
    half_curv = ex * ex + ey * ey + 2.0 * (dx * cx + dy * cy)
    return gap, dgap, half_curv


@kernel
def _polish(mode, lo, hi, f_lo, d0x, d0y, wx, wy, cx, cy, four_r2):
    """Root of ``D`` (mode 0) or ``D'`` (mode 1) in ``[lo, hi]`` where it changes sign.

    Safeguarded Newton: a Newton step that leaves the bracket is replaced by bisection.
    """
    x = 0.5 * (lo + hi)
    for _ in range(200):
        gap, dgap, half_curv = gap_terms(x, d0x, d0y, wx, wy, cx, cy, four_r2)
        if mode == 0:
            f, df = gap, dgap
        else:
            f, df = dgap, 2.0 * half_curv
        if f == 0.0:
            return x
        if (f > 0.0) == (f_lo > 0.0):
            lo = x
        else:
            hi = x
        xn = x - f / df if df != 0.0 else lo - 1.0
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        if xn == x or hi - lo <= 4.4e-16 * max(abs(lo), abs(hi)) + 1e-300:
            return xn
        x = xn
    return x


@kernel
def first_contact(d0x, d0y, wx, wy, cx, cy, four_r2, t_end, speed_scale, accel):
    """First ``t`` in ``[0, t_end]`` where the gap closes while the balls approach.

    Args:
        d0x, d0y: Relative position ``pj - pi`` at ``t = 0``.
        wx, wy: Relative velocity at ``t = 0``.
        cx, cy: Half the relative acceleration (constant over the window).
        four_r2: ``(2R)^2``.
        t_end: End of the window in which this motion is valid.
        speed_scale: Sum of the two speeds, for the approach tolerance at contact.
        accel: The rolling deceleration, the scale of the rounding in ``c``.

    Returns:
        The event time, or ``inf`` when none.

    The contact rule: touching or overlapping (``D <= 0``) and approaching means collide
    now; separating means no event now.
    """
    # Critical points of D' (roots of D''), then of D (roots of D'), inside (0, t_end).
    c2 = cx * cx + cy * cy
    wc = wx * cx + wy * cy
    r1, r2 = quadratic_roots(6.0 * c2, 6.0 * wc, wx * wx + wy * wy + 2.0 * (d0x * cx + d0y * cy))
    knots = [0.0, 0.0, 0.0, 0.0]  # at most 2 inflection points + end (and the start)
    nk = 1
    for r in (r1, r2):
        if r > 0.0 and r < t_end:
            knots[nk] = r
            nk += 1
    knots[nk] = t_end
    nk += 1
    crit = [0.0, 0.0, 0.0, 0.0, 0.0]  # the start, at most 3 critical points, the end
    nc = 1
    _, p_lo, _ = gap_terms(0.0, d0x, d0y, wx, wy, cx, cy, four_r2)
    for k in range(nk - 1):
        _, p_hi, _ = gap_terms(knots[k + 1], d0x, d0y, wx, wy, cx, cy, four_r2)
        if (p_lo < 0.0 and p_hi > 0.0) or (p_lo > 0.0 and p_hi < 0.0):
            crit[nc] = _polish(1, knots[k], knots[k + 1], p_lo, d0x, d0y, wx, wy, cx, cy, four_r2)
            nc += 1
        p_lo = p_hi
    crit[nc] = t_end
    nc += 1

    # Contact rule at t = 0. A closing rate within rounding of zero (|D'| <= tol) is not an
    # approach: such a pair was just resolved, and firing again would repeat it forever.
    dist0 = math.sqrt(d0x * d0x + d0y * d0y)
    tol = APPROACH_RTOL * 2.0 * dist0 * speed_scale
    g0, dg0, hc0 = gap_terms(0.0, d0x, d0y, wx, wy, cx, cy, four_r2)
    if g0 <= 0.0:
        # Pressed together (D' ~ 0 and D'' < 0) counts only beyond the rounding of D'':
        # c comes from two unit vectors, each rounded, so its noise scales with accel.
        curv_tol = APPROACH_RTOL * (wx * wx + wy * wy + 2.0 * dist0 * accel)
        if dg0 < -tol or (dg0 <= tol and hc0 < -curv_tol):
            return 0.0
        first_piece = 1  # separating (or rounding-level): the first monotone piece holds no event
    else:
        first_piece = 0

    for k in range(first_piece, nc - 1):
        a = crit[k]
        b = crit[k + 1]
        if b <= a:
            continue
        g_a, _, _ = gap_terms(a, d0x, d0y, wx, wy, cx, cy, four_r2)
        g_b, _, _ = gap_terms(b, d0x, d0y, wx, wy, cx, cy, four_r2)
        _, dg_mid, _ = gap_terms(0.5 * (a + b), d0x, d0y, wx, wy, cx, cy, four_r2)
        if dg_mid >= -tol:
            continue  # separating, or closing at a rate within rounding of zero
        if g_a <= 0.0:
            return a  # approach starts while touching (a is a farthest-approach point)
        if g_b <= 0.0:
            return _polish(0, a, b, g_a, d0x, d0y, wx, wy, cx, cy, four_r2)
    return INF


@kernel
def equal_accel_contact(d0x, d0y, wx, wy, four_r2, span, scale):
    """First ``t`` in ``[0, span]`` where the gap closes, for equal accelerations (``c = 0``).

    The degree drop of :func:`first_contact`: the relative motion is uniform, the squared
    gap a quadratic in time. Same contact rule: touching and approaching is an impact now.

    Args:
        d0x, d0y: Relative position at ``t = 0``.
        wx, wy: Relative velocity.
        four_r2: The squared contact distance.
        span: End of the window.
        scale: Sum of the two speeds, for the approach tolerance.

    Returns:
        The event time, or ``inf``.
    """
    g0 = d0x * d0x + d0y * d0y - four_r2
    dw = d0x * wx + d0y * wy
    tol = APPROACH_RTOL * math.sqrt(d0x * d0x + d0y * d0y) * scale
    if dw >= -tol:
        return INF  # separating, or closing within rounding of zero
    if g0 <= 0.0:
        return 0.0
    w2 = wx * wx + wy * wy
    disc = dw * dw - w2 * g0
    if disc < 0.0:
        return INF
    tau = g0 / (-dw + math.sqrt(disc))
    return tau if tau <= span else INF


@kernel
def ray_circle_entry(px, py, ux, uy, qx, qy, radius2, capture_inside):
    """Arc length ``s >= 0`` at which the ray ``p + u s`` (``|u| = 1``) enters a circle.

    Args:
        px, py: Start of the ray.
        ux, uy: Unit direction.
        qx, qy: Circle centre.
        radius2: Squared circle radius.
        capture_inside: If true (pockets), a start inside the circle is an entry at 0 in
            any direction. If false (a resting ball), a start inside counts only while moving
            towards the centre (the contact rule), beyond rounding.

    Returns:
        The arc length, 0 for an immediate event, or ``inf`` when the ray never enters.
    """
    dx = px - qx
    dy = py - qy
    b = ux * dx + uy * dy
    cc = dx * dx + dy * dy - radius2
    if cc <= 0.0:
        if capture_inside:
            return 0.0
        # Touching a resting ball: approaching (beyond rounding) means collide now.
        if b < -APPROACH_RTOL * math.sqrt(dx * dx + dy * dy):
            return 0.0
        return INF
    if b >= 0.0 or (not capture_inside and b >= -APPROACH_RTOL * math.sqrt(dx * dx + dy * dy)):
        return INF  # moving away, tangent, or (a ball) closing within rounding of zero
    # b^2 - cc, written as radius^2 minus the squared distance of the centre from the line:
    # the difference form cancels the rounding of |d|^2 (~1e-16 |d|^2) against the small
    # discriminant of a grazing contact, which put a ball 3 km away 1e-8 m into its target.
    cross = ux * dy - uy * dx
    disc = radius2 - cross * cross
    if disc < 0.0:
        return INF
    return cc / (-b + math.sqrt(disc))
