"""Ball-ball impact of Mathavan et al. (2014): friction at the balls' and the table's contacts.

S. Mathavan, M. R. Jackson and R. M. Parkin, "Numerical simulations of the frictional
collisions of solid balls on a rough surface", Sports Engineering 17 (2014) 227-237; the
model of pooltool 0.6.0's ``FrictionalMathavan`` (not its default, which is the frictional
inelastic model of :mod:`~pool_env.sim.kernels.spin.collide`).

Frame. ``y`` along the line of centres (ball ``i`` to ball ``j``), ``x = y x z`` in the table
plane, ``z`` up. Both balls stand on the cloth: the model keeps point contacts with each
other (at ``+R y`` from ``i``) and with the table (at ``-R z`` from each).

Impulse integration. The normal impulse ``P`` between the balls is the model's clock: it
grows in steps ``dP`` and every other impulse is a Coulomb law in ``dP``.

* The balls' contact slides with ``u_C = (v_i - v_j)_x - R (w_iz + w_jz)`` along ``x`` and
  ``u_Cz = R (w_ix + w_jx)`` along ``z``; friction ``mu_b dP`` against it,
  ``dP_1 = -mu_b dP u_Cx / |u_C|`` along ``x`` and ``dP_2 = -mu_b dP u_Cz / |u_C|`` along
  ``z`` on ball ``i`` (the opposite on ``j``).
* The vertical part ``dP_2`` presses one ball into the cloth (``j`` if ``dP_2 > 0``, else
  ``i``) and adds ``|dP_2|`` to that ball's table reaction, whose friction ``mu_s |dP_2|``
  opposes the ball's table-contact slip ``u_R = (v_x + R w_y, v_y - R w_x)``.
* Each step changes velocities by impulse over mass and spins by ``R`` times the moment
  over ``I = (2/5) m R^2``: for either ball ``dw = (5 / (2 m R)) (dP_2 + dP_Ry, -dP_Rx,
  -dP_1)`` with ``dP_R`` its table friction; the vertical velocities stay zero (the
  table holds both balls).
* Compression ends when the normal relative velocity ``v_jy - v_iy`` turns positive, with
  the work ``W_c`` of the normal force (the sum of ``dP`` times the mean of ``|v_jy - v_iy|``
  over the step); restitution ends at the total work ``(1 + e^2) W_c`` (Stronge's energetic
  restitution: the work returned is ``e^2`` of the work absorbed).

The step is the model's own (Mathavan's eq. 14): ``dP = (1 + e) mu_r |v_jy - v_iy| / N``
with ``N = 1000`` (``Table.mathavan_steps``; ``mu_r`` the reduced mass, ``M / 2`` for
pooltool's equal balls), about ``N`` steps per impact. The step is part of the model's
definition: a smaller one gives another result (converging as ``1 / N``), so an equal-model
check keeps pooltool's. ``mu_b`` is the ball-ball friction of ``Table.ball_friction`` at the
pre-impact slip (Alciatore's fit by default, as pooltool's ``AlciatoreBallBallFriction``;
pooltool's impulse rule ``"pooltool"`` is the frictional model's and does not apply here),
``mu_s`` the ball-cloth sliding friction ``Table.mu_slide``.

Limits (checked in ``tests/sim/test_mathavan.py``): with ``mu_b = 0`` it is the frictionless
impact, ``v_jy - v_iy`` going from ``-c`` to ``e c`` to within one step; equal masses
exchange momentum exactly (every impulse is internal or from the table, and table friction
only acts through ``dP_2``); energy is never gained. A safety cap of ``20 N`` steps ends an
impact that would not (none in the tests).
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.spin.collide import ball_friction

_TINY = 1e-16  # pooltool's threshold for a vanishing slip


@kernel
def _table_friction(ux, uy, mu_s, dp2):
    """A ball's table friction ``(dP_Rx, dP_Ry)`` for an extra reaction ``dp2 >= 0``."""
    mag = math.sqrt(ux * ux + uy * uy)
    if mag == 0.0:
        return 0.0, 0.0
    k = -mu_s * dp2 / mag
    return k * ux, k * uy


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
        mu_s: Ball-cloth sliding friction (>= 0).
        steps: Mathavan's ``N`` (>= 1).
        out: float64 array; ``out[0:10]`` receives the new
            ``v1x, v1y, w1x, w1y, w1z, v2x, v2y, w2x, w2y, w2z``.
    """
    out[0], out[1], out[2], out[3], out[4] = v1x, v1y, w1x, w1y, w1z
    out[5], out[6], out[7], out[8], out[9] = v2x, v2y, w2x, w2y, w2z
    approach = (v1x - v2x) * nx + (v1y - v2y) * ny
    if not approach > 0.0:
        return
    # Local components (x = (ny, -nx), y = n, z up).
    vix, viy = v1x * ny - v1y * nx, v1x * nx + v1y * ny
    vjx, vjy = v2x * ny - v2y * nx, v2x * nx + v2y * ny
    wix, wiy, wiz = w1x * ny - w1y * nx, w1x * nx + w1y * ny, w1z
    wjx, wjy, wjz = w2x * ny - w2y * nx, w2x * nx + w2y * ny, w2z
    # Ball-ball friction from the pre-impact slip: tangential relative velocity + R (w1+w2) x n.
    ucx, ucz = vix - vjx - R * (wiz + wjz), R * (wix + wjx)
    mu_b = ball_friction(friction_mode, mu_const, math.sqrt(ucx * ucx + ucz * ucz))
    reduced = m1 * m2 / (m1 + m2)
    v_rel = vjy - viy
    dp = (1.0 + e_b) * reduced * abs(v_rel) / steps
    ci, cj = 2.5 / (m1 * R), 2.5 / (m2 * R)
    inv1, inv2 = 1.0 / m1, 1.0 / m2  # the loop multiplies: ~1000 steps per impact
    work, work_end, compressed = 0.0, math.inf, False
    for _ in range(20 * int(steps)):
        if not (v_rel < 0.0 or work < work_end):
            break
        uc = math.sqrt(ucx * ucx + ucz * ucz)
        dp1 = dp2 = dpix = dpiy = dpjx = dpjy = 0.0
        if uc >= _TINY:
            scale = -mu_b * dp / uc
            dp1 = scale * ucx
            if abs(ucz) >= _TINY:
                dp2 = scale * ucz
                if dp2 > 0.0:  # ball j pressed into the cloth
                    dpjx, dpjy = _table_friction(vjx + R * wjy, vjy - R * wjx, mu_s, dp2)
                else:  # ball i pressed: its reaction grows by -dp2
                    dpix, dpiy = _table_friction(vix + R * wiy, viy - R * wix, mu_s, -dp2)
        vix += (dp1 + dpix) * inv1
        viy += (dpiy - dp) * inv1
        vjx += (dpjx - dp1) * inv2
        vjy += (dp + dpjy) * inv2
        wix += ci * (dp2 + dpiy)
        wiy -= ci * dpix
        wiz -= ci * dp1
        wjx += cj * (dp2 + dpjy)
        wjy -= cj * dpjx
        wjz -= cj * dp1
        ucx, ucz = vix - vjx - R * (wiz + wjz), R * (wix + wjx)
        before, v_rel = v_rel, vjy - viy
        work += 0.5 * dp * abs(before + v_rel)
        if not compressed and v_rel > 0.0:
            compressed = True
            work_end = (1.0 + e_b * e_b) * work
    # Back to the table frame: a = a_x (ny, -nx) + a_y (nx, ny).
    out[0], out[1] = vix * ny + viy * nx, -vix * nx + viy * ny
    out[2], out[3], out[4] = wix * ny + wiy * nx, -wix * nx + wiy * ny, wiz
    out[5], out[6] = vjx * ny + vjy * nx, -vjx * nx + vjy * ny
    out[7], out[8], out[9] = wjx * ny + wjy * nx, -wjx * nx + wjy * ny, wjz
