"""PRIVATE PLACEHOLDER of spin-resolve's kernels, with their contract signatures.

Replaced by ``spin_collide``, ``spin_cushion`` and ``spin_strike`` when branch ``spinres``
is merged; this module must not survive that merge. Frictionless ball-ball, mirror
cushion (spin kept), and a centre-line strike without squirt.
"""

from __future__ import annotations

import math

from pool_env.sim.kernels._jit import kernel


@kernel
def ball_ball_spin(
    v1x, v1y, w1x, w1y, w1z, v2x, v2y, w2x, w2y, w2z, nx, ny, m1, m2, radius, e_b,
    friction_mode, mu_const, out,
):  # fmt: skip
    """Frictionless: the normal components exchanged with restitution, spins kept."""
    u1 = v1x * nx + v1y * ny
    u2 = v2x * nx + v2y * ny
    total = m1 + m2
    n1 = (m1 * u1 + m2 * u2 + m2 * e_b * (u2 - u1)) / total
    n2 = (m1 * u1 + m2 * u2 + m1 * e_b * (u1 - u2)) / total
    out[0] = v1x + (n1 - u1) * nx
    out[1] = v1y + (n1 - u1) * ny
    out[2] = w1x
    out[3] = w1y
    out[4] = w1z
    out[5] = v2x + (n2 - u2) * nx
    out[6] = v2y + (n2 - u2) * ny
    out[7] = w2x
    out[8] = w2y
    out[9] = w2z


@kernel
def cushion_han(vx, vy, wx, wy, wz, nx, ny, radius, h, e_c, f_c, out):
    """Mirror: the normal velocity into the cushion reflected with ``e_c``, spin kept."""
    vn = vx * nx + vy * ny
    k = (1.0 + e_c) * vn if vn < 0.0 else 0.0
    out[0] = vx - k * nx
    out[1] = vy - k * ny
    out[2] = wx
    out[3] = wy
    out[4] = wz


@kernel
def cue_strike(speed, angle, a, b, elevation, radius, m_ball, m_end, r_tip, out):
    """Impulse along the aim at contact offsets ``(a R, b R)``: ``w = 5 r x v / (2 R^2)``."""
    c, s = math.cos(angle), math.sin(angle)
    k = 2.5 * speed / radius
    out[0] = speed * c
    out[1] = speed * s
    out[2] = -k * b * s
    out[3] = k * b * c
    out[4] = k * a
