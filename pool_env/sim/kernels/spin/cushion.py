"""Ball-cushion impact with spin (compiled): Han 2005 or Stronge, with the contact height.

Derived here from rigid-body impulses (I. Han, "Dynamics in carom and three cushion
billiards", J. Mech. Sci. Tech. 19, 2005; the model of pooltool 0.6.0's ``Han2005Linear``,
after its fixes of issues #39, #96 and PR #247). Vectors are 3D with ``z`` up; ``n`` is the
cushion's unit normal in the table plane, pointing from the cushion into the table.

Contact. The cushion's nose touches the ball at the height ``h`` above the cloth, on the
ball's side facing the cushion, so the contact point is ``r = R (-cos(theta) n + sin(theta) z)``
from the ball's centre with ``sin(theta) = h / R - 1`` (the contact angle above the equator;
``h = R`` is a contact at the equator, ``theta = 0``). The contact normal ``r / R`` passes
through the centre.

Normal impulse. The approach speed along the contact normal is ``c = v . r / R =
-cos(theta) (v . n)`` (the velocity in the plane; a rotation adds nothing along ``r``).
Newton's restitution ``e_c`` on it gives the impulse ``P_n = (1 + e_c) m c`` on the ball along
``-r / R``: in the plane ``-(1 + e_c) m c cos(theta)`` against the cushion, and a downward part
``-(1 + e_c) m c sin(theta)`` that presses the ball into the cloth. It changes no spin.

Tangential impulse. The contact point's slip is ``s = v + w x r - c r / R`` (tangent to the
ball at the contact; the cushion is at rest). A tangential impulse ``P_t`` changes it by
``P_t / m + (r x P_t / I) x r = (7 / (2 m)) P_t`` (``I = (2/5) m R^2``) and leaves ``c`` as it
is: Han's ``A = 7 / (2 m)`` and ``B = 1 / m``, decoupled. Coulomb friction ``f_c`` against the
slip, with the slip direction fixed while it slides, gives

    P_t = -min(f_c P_n, (2/7) m |s|) s / |s|.

Sliding throughout (Han's eq. 19) when ``(2/7) |s| > f_c (1 + e_c) c``; otherwise the contact
sticks (eq. 18), ``P_t = -(2/7) m s``. That boundary carries the ``mu`` that Han's paper and
pooltool before PR #247 left out. Then ``v' = v + (P_n + P_t) / m`` and
``w' = w + r x P_t / I`` (the normal part adds no torque).

Closed forms in the rail frame (``x`` into the cushion, ``y`` along it, ``z`` up; ``v = (vx, vy)``
with ``vx > 0``, ``w = (wx, wy, wz)``). The slip has the components
``s_y = vy + R (wz cos(theta) - wx sin(theta))`` along the rail and
``s_t = -(vx sin(theta) + R wy)`` along ``t = (-sin(theta), 0, cos(theta))``. Sticking:

    vx' = vx [1 - (1 + e_c) cos^2(theta) - (2/7) sin^2(theta)] - (2/7) R wy sin(theta)
    vy' = (5/7) vy - (2/7) R (wz cos(theta) - wx sin(theta))
    wy' = wy - (5 / (2 R)) p_t,  p_t = (2/7)(vx sin(theta) + R wy)

(Han's eq. 24). Sliding, with ``k = f_c (1 + e_c) vx cos(theta) / |s|``:

    vx' = vx [1 - (1 + e_c) cos^2(theta)] - k sin(theta) (vx sin(theta) + R wy),
    vy' = vy - k s_y

(eq. 25). The rebound speed and angle ``atan(vy' / -vx')`` thus depend on the spin: running
english (``wz`` that lowers ``|s_y|``) leaves more of ``vy`` and widens the rebound angle,
reverse english narrows it; with the contact above the equator (``theta > 0``), incoming
topspin (``wy > 0``) speeds the rebound and draw slows it, and a stun ball leaves with
topspin for its rebound. A head-on stun ball (``vy = 0``, ``w = 0``) sticks when
``tan(theta) <= (7/2) f_c (1 + e_c)`` and rebounds at
``vx [(1 + e_c) cos^2(theta) + (2/7) sin^2(theta) - 1]`` with topspin
``(5/7)(vx / R) sin(theta)``; with ``theta = 0`` that is the textbook ``-e_c vx``, and at
``Table``'s defaults (``e_c = 0.65``, ``f_c = 0.2``, ``h = 1.27 R``) it is ``0.551 vx``
(``0.736 vx`` at pooltool 0.6.0's ``e_c = 0.85``).

Simplifications. The vertical velocity the impulse gives (into the cloth, or up for a
sliding ball with strong draw) is dropped: the model is planar, the cloth takes the downward
part, and the ball stays on the table; the spin keeps the whole torque. The table's own
impulse and friction during the impact are ignored (as by Han and pooltool). ``e_c`` and
``f_c`` are constants (pooltool's state-dependent variants are disabled in its code). None
of this differs from pooltool 0.6.0's ``han2005``: its equations, once its frames are
unrolled, are these. A ball that is not moving into the cushion (``v . n >= 0``) is left
unchanged.

One addition to Han's model. Its in-plane normal velocity after the impact is
``vx [1 - (1 + e_c) cos^2(theta)]`` plus friction's part, at most ``f_c (1 + e_c) vx
cos(theta) sin(theta)`` against the rebound (with draw). When ``(1 + e_c) cos^2(theta) < 1``
(``e_c < 0.08`` at the WPA height ``h = 1.27 R``), or friction outweighs the rest, the ball
would still move into the cushion once its vertical velocity is dropped, and pooltool meets
the same cushion again at once, shrinking that velocity geometrically. Here it is set to zero
instead: the ball slides along the cushion (the limit of those repeats, without their
events). It cannot happen while ``(1 + e_c) cos^2(theta) - 1 > f_c (1 + e_c) cos(theta)
sin(theta)``, as with ``Table``'s defaults (``e_c = 0.65``, ``f_c = 0.2``, ``h = 1.27 R``:
0.530 against 0.086; at pooltool's ``e_c = 0.85``, 0.715 against 0.096).

Energy never increases: the normal part loses ``(1 - e_c^2) m c^2 / 2``, friction removes
``|P_t| (|s| + |s'|) / 2`` of slip energy, and dropping a vertical velocity only removes.

Stronge's compliant model (pooltool 0.6.0's default cushion, ``Table(cushion_model=
"stronge")``) shares all of the above but the tangential impulse: the same contact, normal
impulse, spin change, dropped vertical velocity and the slide along the cushion. Its
tangential law (:mod:`~pool_env.sim.kernels.spin.stronge`) takes the normal contact velocity
``v_n0 = -c`` and ``v_t0 = -|s|`` and returns ``v_t_f``, so ``P_t = -((v_t_f + |s|) /
(7/2)) m s / |s|``: Han's sliding impulse in its gross-slip regime, and in place of Han's
sticking (``v_t_f = 0``) a compliant contact that can leave the slip reversed. pooltool's
own code (``stronge_compliant/model.py``) keeps no more of the 3D impulse than this: it sets
the vertical velocity to zero after the impact, as here.

One geometric difference between pooltool's two models, kept here for equal models: Han's
contact angle is ``sin(theta) = h / R - 1`` (a ball touching the nose), while pooltool's
Stronge takes the normal from the nose line to the ball's centre where its event loop
meets the cushion, ``R`` away in the plane: ``tan(theta) = h / R - 1`` (15.1 degrees at
``h = 1.27 R`` against Han's 15.7). At jaw points this package uses the same angle (pooltool,
whose pockets differ, takes its round cushion's centre).
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.spin.params import HAN_CUSHION, STRONGE_CUSHION
from pool_env.sim.kernels.spin.stronge import BETA, stronge_tangential


@kernel
def cushion_han(vx, vy, wx, wy, wz, nx, ny, R, h, e_c, f_c, out):
    """Resolve a ball meeting a cushion with Han's 2005 model (see the module docstring).

    :func:`cushion_spin` with ``model = HAN_CUSHION`` (the same arguments, less ``model``
    and ``omega``).
    """
    cushion_spin(vx, vy, wx, wy, wz, nx, ny, R, h, e_c, f_c, HAN_CUSHION, 0.0, out)


@kernel
def cushion_spin(vx, vy, wx, wy, wz, nx, ny, R, h, e_c, f_c, model, omega, out):
    """Resolve a ball meeting a cushion with Han's or Stronge's model (module docstring).

    Used for rails, jaw facings and jaw points alike (for a round jaw point, ``n`` is the
    direction from the point's axis to the ball's centre).

    Args:
        vx, vy: The ball's velocity in the table plane (m/s).
        wx, wy, wz: Its angular velocity (rad/s).
        nx, ny: The cushion's unit normal, pointing from the cushion into the table.
        R: The ball radius (m).
        h: The contact height of the cushion's nose above the cloth (m), in ``(0, 2R)``
            (at ``2R`` the contact is on top of the ball and stops nothing).
        e_c: Restitution along the contact normal, in [0, 1].
        f_c: Friction between ball and cushion (>= 0).
        model: ``HAN_CUSHION`` or ``STRONGE_CUSHION`` (:mod:`~pool_env.sim.kernels.spin.params`).
        omega: Stronge's frequency ratio ``omega_t / omega_n`` in ``(1, 2)``, with
            ``e_c >= 1 / omega`` (ignored by Han's model).
        out: float64 array; ``out[0:5]`` receives the new ``vx, vy, wx, wy, wz`` (the
            vertical velocity is dropped).
    """
    out[0], out[1], out[2], out[3], out[4] = vx, vy, wx, wy, wz
    sin_t = h / R - 1.0
    cos_t = math.sqrt(max(0.0, 1.0 - sin_t * sin_t))
    if model == STRONGE_CUSHION:  # normal from the nose line to the centre, R away across
        lift = h - R
        span = math.sqrt(R * R + lift * lift)
        sin_t, cos_t = lift / span, R / span
    approach = -cos_t * (vx * nx + vy * ny)  # c = v . r / R
    if not approach > 0.0:
        return
    # Unit contact direction from the centre: r / R = (-cos n, sin).
    ex, ey, ez = -cos_t * nx, -cos_t * ny, sin_t
    # Slip s = v + w x r - c r / R (per unit R for the w x r part).
    sx = vx + R * (wy * ez - wz * ey) - approach * ex
    sy = vy + R * (wz * ex - wx * ez) - approach * ey
    sz = R * (wx * ey - wy * ex) - approach * ez
    slip = math.sqrt(sx * sx + sy * sy + sz * sz)
    pn = (1.0 + e_c) * approach  # normal impulse per unit mass, along -r / R
    tx = ty = tz = 0.0
    if slip > 0.0:
        if model == STRONGE_CUSHION:  # its v_t_f from v_t0 = -|s|, v_n0 = -c
            pt = (stronge_tangential(-slip, -approach, f_c, e_c, omega) + slip) / BETA
        else:
            pt = min(f_c * pn, (2.0 / 7.0) * slip)
        tx, ty, tz = -pt * sx / slip, -pt * sy / slip, -pt * sz / slip
    vx_new = vx - pn * ex + tx
    vy_new = vy - pn * ey + ty
    # A ball the model leaves moving into the cushion (low e_c, see the docstring) slides
    # along it instead: the loop would otherwise meet the same cushion again at once.
    into = vx_new * nx + vy_new * ny
    if into < 0.0:
        vx_new -= into * nx
        vy_new -= into * ny
    out[0] = vx_new
    out[1] = vy_new
    # w' = w + r x P_t / I = w + (5 / (2 R)) (r / R) x (P_t / m).
    k = 2.5 / R
    out[2] = wx + k * (ey * tz - ez * ty)
    out[3] = wy + k * (ez * tx - ex * tz)
    out[4] = wz + k * (ex * ty - ey * tx)
