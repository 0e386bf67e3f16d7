"""Ball-ball impact of Mathavan et al. (2014): friction at the balls' and the table's contacts.

S. Mathavan, M. R. Jackson and R. M. Parkin, "Numerical simulations of the frictional
collisions of solid balls on a rough surface", Sports Engineering 17 (2014) 227-237; the
model of pooltool 0.6.0's ``FrictionalMathavan`` (not its default, which is the frictional
inelastic model of :mod:`~pool_env.sim.kernels.spin.collide`), with three corrections
(below) that keep it from gaining energy.

Frame. ``y`` along the line of centres (ball ``i`` to ball ``j``), ``x = y x z`` in the table
plane, ``z`` up. Both balls stand on the cloth: the model keeps point contacts with each
other (at ``+R y`` from ``i``) and with the table (at ``-R z`` from each).

Impulse integration. The normal impulse ``P`` between the balls is the model's clock: it
grows in steps ``dP`` and every other impulse is a Coulomb law in ``dP``, its direction held
over the step (so within a step every velocity is linear in ``dP``).

* The balls' contact slides with ``u_C = (v_i - v_j)_x - R (w_iz + w_jz)`` along ``x`` and
  ``u_Cz = R (w_ix + w_jx)`` along ``z``; friction ``mu_b dP`` against it,
  ``dP_1 = -mu_b dP u_Cx / |u_C|`` along ``x`` and ``dP_2 = -mu_b dP u_Cz / |u_C|`` along
  ``z`` on ball ``i`` (the opposite on ``j``).
* The vertical part ``dP_2`` presses one ball into the cloth (``j`` if ``dP_2 > 0``, else
  ``i``) and adds ``|dP_2|`` to that ball's table reaction, whose friction ``mu_s |dP_2|``
  opposes the ball's cloth slip ``u_R = (v_x - R w_y, v_y + R w_x)`` (the simulator's slip,
  :mod:`~pool_env.sim.kernels.spin.state`).
* Each step changes velocities by impulse over mass and spins by ``R`` times the moment
  over ``I = (2/5) m R^2``: for either ball ``dw = (5 / (2 m R)) (dP_2 + dP_Ry, -dP_Rx,
  -dP_1)`` with ``dP_R`` its table friction; the vertical velocities stay zero (the
  table holds both balls).
* Compression ends when the normal relative velocity ``v_jy - v_iy`` reaches zero, with
  the work ``W_c`` of the normal force (the sum over the steps of ``dP`` times the mean of
  ``|v_jy - v_iy|``, exact as it is linear within a step); restitution ends at the total work
  ``(1 + e^2) W_c`` (Stronge's energetic restitution: the work returned is ``e^2`` of the
  work absorbed).

The step is the model's own (Mathavan's eq. 14): ``dP = (1 + e) mu_r |v_jy - v_iy| / N``
with ``N = 1000`` (``Table.mathavan_steps``; ``mu_r`` the reduced mass, ``M / 2`` for
pooltool's equal balls), about ``N`` steps per impact. The step is part of the model's
definition: a smaller one gives another result (converging as ``1 / N``). ``mu_b`` is the
ball-ball friction of ``Table.ball_friction`` at the pre-impact slip (Alciatore's fit by
default, as pooltool's ``AlciatoreBallBallFriction``; pooltool's impulse rule
``"pooltool"`` is the frictional model's and does not apply here), ``mu_s`` the ball-cloth
sliding friction ``Table.mu_slide``.

Where it departs from pooltool 0.6.0 (each a source of energy gain there):

* pooltool's table slip is ``(v_x + R w_y, v_y - R w_x)``, the slip of a contact at ``+R z``
  in this frame: its friction can push the ball's real slip up and feed energy in at any
  ``N`` (up to +44% in one impact with ``mu_s = 0.8``, ``mu_b = 0.5``, ``e = 1``; +1.5% at
  the defaults). Here it opposes the cloth contact's own slip.
* pooltool ends each phase on the first step past its end (compression past
  ``v_jy - v_iy = 0``, restitution past ``(1 + e^2) W_c``) and adds that step's work as
  ``dP |mean|`` across the sign change: up to a whole step too much, which at small ``N``
  is most of the impact (a 2 m/s centre hit at ``N = 1`` left at 1.59 J from 0.34 J). Here
  the last step of either phase is the exact part of a step that ends it (both linear or
  quadratic in the step, solved in closed form).
* A Coulomb impulse held over a step in which its slip reverses overshoots and can do
  positive work. Here a step applies the fraction of its friction impulses that stops the
  balls' slip at zero (sticking) and keeps the friction's work non-positive
  (:func:`_friction_scale`).

At ``N = 1000`` the last two change an impact's velocities by at most about 0.1% of the
approach speed, the first by up to about 1.3% (``docs/from_pooltool.md``, issue 49).

Laws (checked in ``tests/sim/test_mathavan.py``): the kinetic energy (translation and
spin) is never gained, for every ``N >= 1`` and ``e`` in ``[0, 1]``: the normal force
returns ``e^2`` of the work it absorbed and every friction step does no positive work; with
``e = 1`` and no friction it is kept to rounding. The momentum in the table plane changes
only by the table's friction (kept exactly with ``mu_s = 0``). With ``mu_b = 0`` it is the
frictionless impact, ``v_jy - v_iy`` going from ``-c`` to ``e c``. Each phase needs at most
a few ``N`` steps when ``mu_s mu_b <= 1`` (``Table`` refuses more with this model: the table's
friction could then stall the normal relative velocity); a safety cap of ``20 N`` steps
stands behind it.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.spin.collide import ball_friction

_TINY = 1e-16  # pooltool's threshold for a vanishing slip


@kernel
def _add(total, carry, x):
    """One step of Neumaier's compensated sum: ``total + carry`` is the sum to ~1 rounding.

    An impact sums up to ``20 N`` increments (``N`` up to 10^6); a plain sum would drift by
    ~``N`` roundings of it, enough to move an elastic impact's energy past rounding.
    """
    t = total + x
    if abs(total) >= abs(x):
        carry += (total - t) + x
    else:
        carry += (x - t) + total
    return t, carry


@kernel
def _table_friction(ux, uy, mu_s, k2):
    """A ball's table friction ``(x, y)`` per unit normal impulse, its reaction up ``k2 >= 0``."""
    mag = math.sqrt(ux * ux + uy * uy)
    if mag == 0.0:
        return 0.0, 0.0
    k = -mu_s * k2 / mag
    return k * ux, k * uy


@kernel
def _friction_scale(
    ucx, ucz, uc, f1, f2, fix, fiy, fjx, fjy, vix, viy, wix, wiy, vjx, vjy, wjx, wjy, inv1, inv2,
    ci, cj, R, h,
):  # fmt: skip
    """The fraction ``lam`` in ``[0, 1]`` of a step's Coulomb impulses that the step applies.

    A step holds the friction directions of its start; where a slip would reverse within it,
    the full impulses would overshoot and could do positive work. ``lam`` is the largest
    fraction with (1) the balls' slip not reversed along its start direction (it sticks at
    zero, as Coulomb's law wants), and (2) the step's friction impulses doing no positive
    work, the table slips included (they also move with the normal impulse ``h``). Both are
    exact: within a step every velocity is linear in the impulses.

    Args:
        ucx, ucz, uc: The balls' contact slip at the step's start and its norm (> 0).
        f1, f2, fix, fiy, fjx, fjy: The step's friction impulses per unit normal impulse.
        vix ... wjy: The balls' velocities and spins at the step's start (local frame).
        inv1, inv2, ci, cj, R: ``1 / m``, ``5 / (2 m R)`` of either ball; the radius.
        h: The step's normal impulse.
    """
    # Velocity changes per unit of friction (lam h = 1).
    dvix, dviy, dvjx, dvjy = (f1 + fix) * inv1, fiy * inv1, (fjx - f1) * inv2, fjy * inv2
    dwix, dwiy, dwjx, dwjy = ci * (f2 + fiy), -ci * fix, cj * (f2 + fjy), -cj * fjx
    acx = dvix - dvjx + R * (ci + cj) * f1  # d(ucx); the spins z change by -c f1
    acz = R * (dwix + dwjx)
    # The work of the friction impulses lam h F over the step is
    # lam h (2 F.u0 + h F.B + lam h F.A) / 2, with u the slips they act on, A their change
    # per unit friction and B per unit normal impulse (only the table slips' y move).
    fu = f1 * ucx + f2 * ucz
    fu += fix * (vix - R * wiy) + fiy * (viy + R * wix) + fjx * (vjx - R * wjy)
    fu += fjy * (vjy + R * wjx)
    fa = f1 * acx + f2 * acz
    fa += fix * (dvix - R * dwiy) + fiy * (dviy + R * dwix) + fjx * (dvjx - R * dwjy)
    fa += fjy * (dvjy + R * dwjx)
    bracket = 2.0 * fu + h * (fjy * inv2 - fiy * inv1)
    lam = 1.0
    if bracket >= 0.0:
        return 0.0
    if h * fa > -bracket:
        lam = -bracket / (h * fa)
    along = (ucx * acx + ucz * acz) / uc  # the balls' slip rate along its direction
    if along < 0.0 and lam * h * -along > uc:
        lam = uc / (h * -along)
    return lam


@kernel
def ball_ball_mathavan(
    v1x, v1y, w1x, w1y, w1z, v2x, v2y, w2x, w2y, w2z, nx, ny, m1, m2, R, e_b,
    friction_mode, mu_const, mu_s, steps, out,
):  # fmt: skip
    """Resolve an impact of two balls on the cloth with Mathavan's model (module docstring).

    Args:
        v1x, v1y, w1x, w1y, w1z: Ball 1's velocity (m/s) and angular velocity (rad/s).
        v2x, v2y, w2x, w2y, w2z: Ball 2's.
        nx, ny: Unit vector from ball 1's centre to ball 2's.
        m1, m2: The masses (kg). R: the common radius (m). e_b: restitution in [0, 1].
        friction_mode, mu_const: The ball-ball friction
            (:func:`~pool_env.sim.kernels.spin.collide.ball_friction`).
        mu_s: Ball-cloth sliding friction (>= 0; ``mu_s mu_b <= 1``).
        steps: Mathavan's ``N`` (>= 1).
        out: float64 array; ``out[0:10]`` receives the new
            ``v1x, v1y, w1x, w1y, w1z, v2x, v2y, w2x, w2y, w2z``.
    """
    out[0], out[1], out[2], out[3], out[4] = v1x, v1y, w1x, w1y, w1z
    out[5], out[6], out[7], out[8], out[9] = v2x, v2y, w2x, w2y, w2z
    approach = (v1x - v2x) * nx + (v1y - v2y) * ny
    if not approach > 0.0:
        return
    # Local components (x = (ny, -nx), y = n, z up): the state at the impact's start.
    vix0, viy0 = v1x * ny - v1y * nx, v1x * nx + v1y * ny
    vjx0, vjy0 = v2x * ny - v2y * nx, v2x * nx + v2y * ny
    wix0, wiy0, wiz0 = w1x * ny - w1y * nx, w1x * nx + w1y * ny, w1z
    wjx0, wjy0, wjz0 = w2x * ny - w2y * nx, w2x * nx + w2y * ny, w2z
    # The changes over the impact, summed from zero with compensation (``_add``; ``c*`` the
    # carries) and added to the start state at each step, not into it: thousands of small
    # steps then round neither a fast ball's velocity nor the sums (a heavy ball's rounding
    # alone would move the energy by ~N eps of it).
    dvix = dviy = dvjx = dvjy = dwix = dwiy = dwiz = dwjx = dwjy = dwjz = 0.0
    cvix = cviy = cvjx = cvjy = cwix = cwiy = cwiz = cwjx = cwjy = cwjz = cwork = 0.0
    # Ball-ball friction from the pre-impact slip: tangential relative velocity + R (w1+w2) x n.
    ucx, ucz = vix0 - vjx0 - R * (wiz0 + wjz0), R * (wix0 + wjx0)
    mu_b = ball_friction(friction_mode, mu_const, math.sqrt(ucx * ucx + ucz * ucz))
    reduced = m1 * m2 / (m1 + m2)
    v_rel0 = vjy0 - viy0
    v_rel = v_rel0
    dp = (1.0 + e_b) * reduced * abs(v_rel) / steps
    ci, cj = 2.5 / (m1 * R), 2.5 / (m2 * R)
    inv1, inv2 = 1.0 / m1, 1.0 / m2  # the loop multiplies: ~1000 steps per impact
    work, work_end, compressed = 0.0, math.inf, False
    for _ in range(20 * int(steps)):
        if compressed and not work + cwork < work_end:
            break
        vix, viy = vix0 + (dvix + cvix), viy0 + (dviy + cviy)
        vjx, vjy = vjx0 + (dvjx + cvjx), vjy0 + (dvjy + cvjy)
        wix, wiy, wiz = wix0 + (dwix + cwix), wiy0 + (dwiy + cwiy), wiz0 + (dwiz + cwiz)
        wjx, wjy, wjz = wjx0 + (dwjx + cwjx), wjy0 + (dwjy + cwjy), wjz0 + (dwjz + cwjz)
        ucx, ucz = vix - vjx - R * (wiz + wjz), R * (wix + wjx)
        # The step's impulses per unit normal impulse, directions from its start.
        uc = math.sqrt(ucx * ucx + ucz * ucz)
        f1 = f2 = fix = fiy = fjx = fjy = 0.0
        lam = 1.0
        if uc >= _TINY:
            f1 = -mu_b * ucx / uc
            if abs(ucz) >= _TINY:
                f2 = -mu_b * ucz / uc
                if f2 > 0.0:  # ball j pressed into the cloth
                    fjx, fjy = _table_friction(vjx - R * wjy, vjy + R * wjx, mu_s, f2)
                else:  # ball i pressed: its reaction grows by -f2
                    fix, fiy = _table_friction(vix - R * wiy, viy + R * wix, mu_s, -f2)
            lam = _friction_scale(
                ucx, ucz, uc, f1, f2, fix, fiy, fjx, fjy, vix, viy, wix, wiy, vjx, vjy, wjx,
                wjy, inv1, inv2, ci, cj, R, dp,
            )  # fmt: skip
        # The normal relative velocity grows at rate `a` per unit normal impulse (> 0 when
        # mu_s mu_b <= 1): the step that ends a phase is cut to end it exactly.
        a = inv1 + inv2 + lam * (fjy * inv2 - fiy * inv1)
        h, last = dp, False
        if not compressed:
            if v_rel + a * h >= 0.0:
                h, last = -v_rel / a, True
        else:
            rest = work_end - (work + cwork)  # the work left: h (v_rel + a h / 2) = rest
            if h * (v_rel + 0.5 * a * h) >= rest:
                disc = math.sqrt(v_rel * v_rel + 2.0 * a * rest)
                h = 2.0 * rest / (v_rel + disc) if v_rel > 0.0 else (disc - v_rel) / a
                last = True
        g = lam * h
        dp1, dp2, dpix, dpiy, dpjx, dpjy = f1 * g, f2 * g, fix * g, fiy * g, fjx * g, fjy * g
        dvix, cvix = _add(dvix, cvix, (dp1 + dpix) * inv1)
        dviy, cviy = _add(dviy, cviy, (dpiy - h) * inv1)
        dvjx, cvjx = _add(dvjx, cvjx, (dpjx - dp1) * inv2)
        dvjy, cvjy = _add(dvjy, cvjy, (h + dpjy) * inv2)
        dwix, cwix = _add(dwix, cwix, ci * (dp2 + dpiy))
        dwiy, cwiy = _add(dwiy, cwiy, -ci * dpix)
        dwiz, cwiz = _add(dwiz, cwiz, -ci * dp1)
        dwjx, cwjx = _add(dwjx, cwjx, cj * (dp2 + dpjy))
        dwjy, cwjy = _add(dwjy, cwjy, -cj * dpjx)
        dwjz, cwjz = _add(dwjz, cwjz, -cj * dp1)
        before, v_rel = v_rel, v_rel0 + ((dvjy + cvjy) - (dviy + cviy))
        work, cwork = _add(work, cwork, 0.5 * h * abs(before + v_rel))  # no sign change in a step
        work_sum = work + cwork
        if last:
            if compressed:
                break
            compressed = True
            work_end = (1.0 + e_b * e_b) * work_sum
    vix, viy = vix0 + (dvix + cvix), viy0 + (dviy + cviy)
    vjx, vjy = vjx0 + (dvjx + cvjx), vjy0 + (dvjy + cvjy)
    wix, wiy, wiz = wix0 + (dwix + cwix), wiy0 + (dwiy + cwiy), wiz0 + (dwiz + cwiz)
    wjx, wjy, wjz = wjx0 + (dwjx + cwjx), wjy0 + (dwjy + cwjy), wjz0 + (dwjz + cwjz)
    # Back to the table frame: a = a_x (ny, -nx) + a_y (nx, ny).
    out[0], out[1] = vix * ny + viy * nx, -vix * nx + viy * ny
    out[2], out[3], out[4] = wix * ny + wiy * nx, -wix * nx + wiy * ny, wiz
    out[5], out[6] = vjx * ny + vjy * nx, -vjx * nx + vjy * ny
    out[7], out[8], out[9] = wjx * ny + wjy * nx, -wjx * nx + wjy * ny, wjz
