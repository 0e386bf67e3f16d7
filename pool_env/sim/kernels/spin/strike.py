"""The cue strike (compiled): instantaneous point impact, tip offset, elevation and squirt.

The model of pooltool 0.6.0's ``InstantaneousPoint`` (Alciatore, TP A-30 and A-31), written
with the ball's speed after the strike as the input, as this project's API has it.

Tip offset to contact point. ``(a, b)`` is the offset of the cue's axis from the ball's
centre, in fractions of ``R``, seen from behind the cue: ``a`` to the right, ``b`` up (in the
plane perpendicular to the cue). The tip is a sphere of radius ``r_tip``; at contact its
centre lies ``R + r_tip`` from the ball's centre, and the contact point on the line between
the two centres, so its offset from the axis through the ball's centre is
``(a', b') = (a, b) / (1 + r_tip / R)`` (1.37 for a 10.6 mm tip on a 57.15 mm ball). Note:
pooltool's physics takes its ``(a, b)`` as this contact offset ``(a', b')`` already (its
``tip_contact_offset`` scaling is applied by its GUI, not by ``InstantaneousPoint``); see
:func:`pool_env.sim.cue.from_pooltool`. The contact point is
``Q = R (a' s + b' u - c' d)``, ``c' = sqrt(1 - a'^2 - b'^2)``, with the cue's direction
``d = cos(e) f - sin(e) z`` (aim ``f`` in the plane, elevation ``e``), its right
``s = f x z`` and its up ``u = sin(e) f + cos(e) z``.

Impulse and spin. The tip's impulse ``J`` acts along the cue's axis ``d`` (no tip friction:
the point model). The ball leaves along ``d`` at ``V = J / m`` and spins at
``w = Q x J / I = (5 V / (2 R)) (a' (sin(e) f + cos(e) z) + b' (z x f))``, since
``s x d = sin(e) f + cos(e) z`` and ``u x d = z x f`` (``c'`` drops out). So ``b'`` gives
topspin (``b' > 0``) or draw about ``z x f``; ``a'`` gives side spin about ``z`` (right
english ``a' > 0`` spins counter-clockwise seen from above) and, with elevation, spin about
the aim line, which curves the path (masse). A centre-line hit (``a = 0``, ``e = 0``) leaves
rolling (``w R = V``) exactly when ``b' = 2/5``.

Elevation, 2D. The impulse's vertical part ``-V sin(e)`` drives the ball into the cloth; the
model is planar, so it is dropped and the spin kept (pooltool 0.6.0 does the same). The
in-plane speed ``V cos(e)`` is the input ``speed``, so ``V = speed / cos(e)``: the spin for a
given speed grows as the cue rises. (The cue's speed for that ball speed, an elastic tip:
``V = 2 V0 / (1 + m / M + (5/2)(a'^2 + b'^2))``, is :func:`pool_env.sim.cue.from_pooltool`'s.)

Squirt (TP A-31). Side english deflects the ball away from the side of the english, by

    alpha = atan[(5/2) a' sqrt(1 - a'^2) / (1 + m_ball / m_end + (5/2)(1 - a'^2))]

with ``m_end`` the cue's effective end mass: 1.2 deg at ``a' = 0.3``, 1.9 at 0.5 and 2.2 at
0.7 for ``m_end = m_ball / 30``. Measured clockwise (towards right english), the ball leaves
at ``angle - alpha``. As in pooltool, only the velocity turns: the spin stays the one the
impulse along the cue's axis gives (TP A-31 models only the deflection), and elevation does
not change the squirt.

Safe range (not enforced: the caller decides). Real tips miscue beyond a contact offset of
about half a radius (``sqrt(a'^2 + b'^2) > 0.5``, an axis offset of about 0.69 for the default
tip); the formulas stay finite for any ``|a|, |b| <= 1`` and elevation below ``pi / 2`` (the
spin grows as ``1 / cos(e)``). ``c'`` needs ``a'^2 + b'^2 <= 1``, which always holds for
``a^2 + b^2 <= 1``; the formulas here never use ``c'``.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel


@kernel
def squirt_angle(a_contact, m_ball, m_end):
    """The squirt angle (rad) of TP A-31 for the contact offset ``a_contact`` (sign of ``a``)."""
    rest = 1.0 - a_contact * a_contact
    return math.atan2(
        2.5 * a_contact * math.sqrt(max(0.0, rest)), 1.0 + m_ball / m_end + 2.5 * rest
    )


@kernel
def cue_strike(speed, angle, a, b, elevation, R, m_ball, m_end, r_tip, out):
    """The cue ball's velocity and spin after a strike (see the module docstring).

    Args:
        speed: The cue ball's speed in the table plane after the strike (m/s).
        angle: The cue's aim in the table plane (rad).
        a: Side offset of the cue's axis, fraction of ``R`` (+ = right english).
        b: Vertical offset of the cue's axis, fraction of ``R`` (+ = above centre).
        elevation: The cue's elevation (rad), in ``[0, pi / 2)``.
        R: The ball radius (m). m_ball: its mass (kg).
        m_end: The cue's end mass for squirt (kg).
        r_tip: The cue tip's radius (m).
        out: float64 array; ``out[0:5]`` receives ``vx, vy, wx, wy, wz``.
    """
    scale = 1.0 / (1.0 + r_tip / R)
    ac = a * scale
    bc = b * scale
    cos_e, sin_e = math.cos(elevation), math.sin(elevation)
    fx, fy = math.cos(angle), math.sin(angle)
    spin = 2.5 * (speed / cos_e) / R  # (5/2) V / R with V the speed along the cue
    # w = spin (a' sin(e) f + b' (z x f) + a' cos(e) z), z x f = (-fy, fx).
    out[2] = spin * (ac * sin_e * fx - bc * fy)
    out[3] = spin * (ac * sin_e * fy + bc * fx)
    out[4] = spin * ac * cos_e
    # Right english squirts the ball left: counter-clockwise from the aim.
    heading = angle + squirt_angle(ac, m_ball, m_end)
    out[0] = speed * math.cos(heading)
    out[1] = speed * math.sin(heading)
