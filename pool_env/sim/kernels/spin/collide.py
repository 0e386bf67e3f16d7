"""Ball-ball impact with friction and spin (compiled): the "frictional inelastic" model, throw.

The model of pooltool 0.6.0's default ``FrictionalInelastic`` (after Alciatore's technical
proofs TP A-5, A-6 and A-14), derived here for two balls of equal radius ``R`` and any masses
``m1, m2`` (moments of inertia ``I_k = (2/5) m_k R^2``). ``n`` is the unit vector from ball 1's
centre to ball 2's; the contact point is ``+R n`` from ball 1 and ``-R n`` from ball 2. Impulses
are instantaneous and act at that one point.

Normal impulse. With the normal velocities ``u_k = v_k . n`` and the approach speed
``c = u1 - u2 > 0``, Newton's restitution ``u2' - u1' = e_b c`` and momentum give the impulse
``J_n = (1 + e_b) mu_r c`` on ball 2 along ``+n`` (on ball 1 along ``-n``), with the reduced
mass ``mu_r = m1 m2 / (m1 + m2)``. It changes no spin (it points through both centres).

Tangential impulse. The contact points' relative velocity, without its normal part, is the
slip ``s = (v1 - v2)_t + R (w1 + w2) x n`` (3-vector: topspin and draw give it a vertical
component, side spin and the cut a horizontal one). A tangential impulse ``T`` on ball 1
(``-T`` on ball 2) changes the velocities by ``T / m1``, ``-T / m2`` and both spins by the
same ``R n x T / I_k``, so the slip changes by ``(7/2)(1/m1 + 1/m2) T = (7/2) T / mu_r``; it
does not touch the normal velocities (the two directions are decoupled). Coulomb friction
over the impact gives ``|T| = mu |J_n|`` against the slip while the contact slides; the slip
keeps its direction as it shrinks and reaches zero (sticking) at ``|T| = (2/7) mu_r |s|``. So

    T = -min(mu |J_n|, (2/7) mu_r |s|) s / |s|,

the sliding result capped at the no-slip result (pooltool tests the cap by whether the slip
reversed, the same thing since the slip only shrinks along its own direction). For equal
masses the cap is pooltool's ``-(1/7) m s``. Friction modes: 0 frictionless (``mu = 0``),
1 a constant ``mu_const``, 2 Alciatore's fit to Marlow's data (TP A-14)
``mu = 9.951e-3 + 0.108 exp(-1.088 |s|)`` of the pre-impact slip speed ``|s|`` in m/s:
pooltool feeds its fit exactly this (``tangent_surface_velocity`` of both balls, the normal
part removed, the vertical part kept), which for a stun cue ball against a ball at rest is
``v sin(cut)``. There the object ball is thrown by ``atan(min(mu, 2 tan(cut) / (7 (1 + e_b))))``
off the line of centres: at most 6.0 deg at 0.2 m/s (at a 35.7 deg cut), 5.2 at 0.5 (31.8),
4.3 at 1 (27.3), 3.3 at 2 (21.7) and 2.4 at 4 m/s (16.1) with ``e_b = 0.95``.

Vertical velocity. The vertical part of ``T`` would lift one ball and press the other into the
cloth; the table's plane keeps both, so it is dropped from the velocities (as pooltool does)
while the spins keep the whole of ``R n x T / I``. Linear momentum in the plane is conserved
exactly, and no energy is added: the normal exchange loses ``(1 - e_b^2) mu_r c^2 / 2``,
friction never does positive work (the slip only shrinks), and dropping a vertical velocity
only removes energy.

Where this differs from pooltool 0.6.0 (documented choice): pooltool's friction impulse per
unit mass is ``mu |v2n' - v1n'| = mu e_b c``, the separation speed, where Coulomb's law with
its own normal impulse ``m (1 + e_b) c / 2`` (equal masses) gives ``mu (1 + e_b) c / 2``.
The two agree at ``e_b = 1``; at pooltool's ``e_b = 0.95`` its sliding friction is
``0.95 / 0.975`` (2.6 %) of Coulomb's (at ``e_b = 0`` it would have none at all). Here it is
Coulomb's. Pooltool also assumes equal masses (its normal exchange is ``(1 -+ e_b)/2``), which
this formula reproduces for ``m1 = m2``. Mode 3 reproduces pooltool's friction impulse
(``mu' = mu 2 e_b / (1 + e_b)`` with Alciatore's mu; for any masses the impulse is then
``2 mu e_b mu_r c``), so that a comparison with pooltool can run on its exact model.
``bench/spin_kernels_pooltool.py`` runs both on 200 seeded impacts: equal to rounding
(4e-15 m/s) at ``e_b = 1``, and at ``e_b = 0.95`` in mode 3 (mode 2 differs there by up to
5e-3 m/s). Balls that are not approaching (``c <= 0``) are left unchanged: the event loop
only calls this for an approach.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.spin.params import (
    CONSTANT_FRICTION,
    FRICTIONLESS,
    POOLTOOL_FRICTION,
)

#: Alciatore's fit ``mu = A + B exp(-C |s|)`` (TP A-14; pooltool's ``AlciatoreBallBallFriction``).
ALCIATORE_A, ALCIATORE_B, ALCIATORE_C = 9.951e-3, 0.108, 1.088


@kernel
def ball_friction(mode, mu_const, slip):
    """The ball-ball friction coefficient for ``mode`` at a relative slip speed ``slip`` (m/s)."""
    if mode == FRICTIONLESS:
        return 0.0
    if mode == CONSTANT_FRICTION:
        return mu_const
    return ALCIATORE_A + ALCIATORE_B * math.exp(-ALCIATORE_C * slip)  # the two fits


@kernel
def ball_ball_spin(
    v1x,
    v1y,
    w1x,
    w1y,
    w1z,
    v2x,
    v2y,
    w2x,
    w2y,
    w2z,
    nx,
    ny,
    m1,
    m2,
    R,
    e_b,
    friction_mode,
    mu_const,
    out,
):
    """Resolve an impact of two spinning balls with friction (see the module docstring).

    Args:
        v1x, v1y, w1x, w1y, w1z: Ball 1's velocity (m/s) and angular velocity (rad/s).
        v2x, v2y, w2x, w2y, w2z: Ball 2's.
        nx, ny: Unit vector from ball 1's centre to ball 2's.
        m1, m2: The masses (kg). R: the common radius (m). e_b: restitution in [0, 1].
        friction_mode: 0 frictionless, 1 constant ``mu_const``, 2 Alciatore's fit, 3 the
            fit with pooltool's impulse ``mu e_b c`` (for comparisons with pooltool).
        mu_const: The constant friction coefficient of mode 1 (>= 0).
        out: float64 array; ``out[0:10]`` receives the new
            ``v1x, v1y, w1x, w1y, w1z, v2x, v2y, w2x, w2y, w2z``.
    """
    out[0], out[1], out[2], out[3], out[4] = v1x, v1y, w1x, w1y, w1z
    out[5], out[6], out[7], out[8], out[9] = v2x, v2y, w2x, w2y, w2z
    dvx, dvy = v1x - v2x, v1y - v2y
    approach = dvx * nx + dvy * ny
    if not approach > 0.0:
        return
    reduced = m1 * m2 / (m1 + m2)
    jn = (1.0 + e_b) * reduced * approach
    # Slip of ball 1's contact point against ball 2's: tangential relative velocity plus
    # R (w1 + w2) x n, with (a, b, c) x (nx, ny, 0) = (-c ny, c nx, a ny - b nx).
    wsx, wsy, wsz = w1x + w2x, w1y + w2y, w1z + w2z
    sx = dvx - approach * nx - R * wsz * ny
    sy = dvy - approach * ny + R * wsz * nx
    sz = R * (wsx * ny - wsy * nx)
    slip = math.sqrt(sx * sx + sy * sy + sz * sz)
    tx = ty = tz = 0.0
    if slip > 0.0:
        mu = ball_friction(friction_mode, mu_const, slip)
        if friction_mode == POOLTOOL_FRICTION:  # its impulse mu e_b c m = mu' J_n, equal masses
            mu *= 2.0 * e_b / (1.0 + e_b)
        jt = min(mu * jn, (2.0 / 7.0) * reduced * slip)
        tx, ty, tz = -jt * sx / slip, -jt * sy / slip, -jt * sz / slip
    # Velocities: normal impulse -jn n and friction T on ball 1, the opposite on ball 2; the
    # vertical part tz is dropped (the cloth holds both balls in the plane).
    out[0] = v1x + (tx - jn * nx) / m1
    out[1] = v1y + (ty - jn * ny) / m1
    out[5] = v2x + (jn * nx - tx) / m2
    out[6] = v2y + (jn * ny - ty) / m2
    # Spins: R n x T / I_k for both balls, n x T = (ny tz, -nx tz, nx ty - ny tx).
    cx, cy, cz = ny * tz, -nx * tz, nx * ty - ny * tx
    k1 = 2.5 / (m1 * R)
    k2 = 2.5 / (m2 * R)
    out[2], out[3], out[4] = w1x + k1 * cx, w1y + k1 * cy, w1z + k1 * cz
    out[7], out[8], out[9] = w2x + k2 * cx, w2y + k2 * cy, w2z + k2 * cz
