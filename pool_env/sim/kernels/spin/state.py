"""Ball state of the spin level (compiled): motion states, anchors and motion between events.

Motion states (the one enumeration of the spin level; the resolution kernels and the
reference import it): ``STATIONARY``, ``SPINNING`` (in place, about the vertical axis),
``SLIDING``, ``ROLLING``, ``POTTED``.

Frame and conventions (pooltool 0.6.0's equations of motion, ``docs/sources.md``): z up,
angular velocity ``w = (wx, wy, wz)`` (rad/s), the cloth contact at ``-R z``, its slip
velocity ``u = (vx - R wy, vy + R wx)``. Every state has a constant acceleration ``acc``, so
each ball's position is quadratic in the time since its anchor ``tau = t - T0``::

    p(tau) = p0 + v0 tau + acc tau^2 / 2,          v(tau) = v0 + acc tau

* sliding: ``acc = -mu_slide g u0 / |u0|`` (the slip keeps its direction and shrinks at
  ``(7/2) mu_slide g``), ``w_xy(tau) = w0_xy + (5 / 2R) tau (acc_y, -acc_x)``; it rolls at
  ``tau_s = 2 |u0| / (7 mu_slide g)``;
* rolling: ``acc = -mu_roll g v0 / |v0|``, ``w_xy = (-vy / R, vx / R)``; it stops at
  ``tau_r = |v0| / (mu_roll g)``, and spins on if ``wz`` is left then;
* spinning: at rest, ``wz`` falls at ``spin_decel``; it stops at ``|wz0| / spin_decel``;
* in every state ``wz(tau) = sign(wz0) max(|wz0| - spin_decel tau, 0)``.

Each anchor stores the state at ``T0`` and the time ``TEND`` of its next transition (a
closed form above; ``inf`` for a ball at rest or potted). The loop treats each transition
as an event and re-anchors there, so a formula is never used past its ``TEND``.

Simplifications (documented, as pooltool 0.6.0 has them): the vertical-axis spin does not
couple to the motion of the centre (no swerve: the cue is level in the plane's motion, see
the strike kernel for elevation); rolling resistance acts only in the rolling state; a
ball whose speed and contact-point surface speed are both below ``V_REST`` = 1e-9 m/s is at
rest (its spin ``wz`` below ``V_REST / R`` as well); a slip below ``ROLL_RTOL`` (1e-12) of
the ball's speed scale ``|v| + R |w_xy|`` is rounding and the ball rolls.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.params import P_DECEL, P_RADIUS
from pool_env.sim.kernels.spin.params import S_SLIDE_DECEL, S_SPIN_DECEL

#: Motion states (the contract's enumeration).
STATIONARY, SPINNING, SLIDING, ROLLING, POTTED = 0, 1, 2, 3, 4
#: Their names, by code.
STATE_NAMES = ("stationary", "spinning", "sliding", "rolling", "potted")

# Columns of the (N, SCOL) ball-state array: position, velocity, angular velocity at the
# anchor time T0, the constant acceleration of the current state, the time of the next
# transition.
PX, PY, VX, VY, WX, WY, WZ, T0, AX, AY, TEND = range(11)
SCOL = 11

V_REST = 1e-9  # m/s
ROLL_RTOL = 1e-12
INF = math.inf

# How set_anchor treats the slip: classify it, or force rolling (at a slide-roll transition,
# where the slip is zero in exact arithmetic and rounding only).
CLASSIFY, FORCE_ROLL = 0, 1


@kernel
def moving(state):
    """Whether a ball in motion state ``state`` moves (slides or rolls)."""
    return SLIDING <= state <= ROLLING  # the two codes are adjacent


@kernel
def set_anchor(st, ms, i, t, x, y, vx, vy, wx, wy, wz, prm, mode):
    """Anchor ball ``i`` at time ``t`` with the given state; set its motion state.

    Args:
        st, ms: The ball-state array and the motion states.
        i: The ball.
        t: Anchor time.
        x, y, vx, vy, wx, wy, wz: Position, velocity, angular velocity.
        prm: ``Table.spin_params``.
        mode: ``CLASSIFY``, or ``FORCE_ROLL`` at a slide-roll transition.
    """
    radius = prm[P_RADIUS]
    spd = math.sqrt(vx * vx + vy * vy)
    ux = vx - radius * wy
    uy = vy + radius * wx
    slip = math.sqrt(ux * ux + uy * uy)
    scale = spd + radius * math.sqrt(wx * wx + wy * wy)
    if abs(wz) * radius < V_REST:
        wz = 0.0
    st[i, PX] = x
    st[i, PY] = y
    st[i, T0] = t
    st[i, WZ] = wz
    st[i, AX] = 0.0
    st[i, AY] = 0.0
    rolls = mode == FORCE_ROLL or slip <= ROLL_RTOL * scale
    if scale < V_REST or (rolls and spd < V_REST):
        st[i, VX] = 0.0
        st[i, VY] = 0.0
        st[i, WX] = 0.0
        st[i, WY] = 0.0
        if wz != 0.0:
            ms[i] = SPINNING
            st[i, TEND] = t + abs(wz) / prm[S_SPIN_DECEL]
        else:
            ms[i] = STATIONARY
            st[i, TEND] = INF
        return
    st[i, VX] = vx
    st[i, VY] = vy
    if rolls:
        ms[i] = ROLLING
        st[i, WX] = -vy / radius
        st[i, WY] = vx / radius
        a = prm[P_DECEL]
        st[i, AX] = -a * vx / spd
        st[i, AY] = -a * vy / spd
        st[i, TEND] = t + spd / a
    else:
        ms[i] = SLIDING
        st[i, WX] = wx
        st[i, WY] = wy
        a = prm[S_SLIDE_DECEL]
        st[i, AX] = -a * ux / slip
        st[i, AY] = -a * uy / slip
        st[i, TEND] = t + slip / (3.5 * a)


@kernel
def set_potted(st, ms, i, t, x, y):
    """Ball ``i`` captured at ``(x, y)`` at time ``t``: it stays there, still."""
    for c in range(SCOL):
        st[i, c] = 0.0
    st[i, PX] = x
    st[i, PY] = y
    st[i, T0] = t
    st[i, TEND] = INF
    ms[i] = POTTED


@kernel
def spin_z(wz0, tau, spin_decel):
    """``wz`` after ``tau`` seconds: it falls at ``spin_decel`` to zero and stays there."""
    left = abs(wz0) - spin_decel * tau
    if left <= 0.0:
        return 0.0
    return left if wz0 > 0.0 else -left


@kernel
def state_at(st, ms, i, t, prm):
    """``(x, y, vx, vy, wx, wy, wz)`` of ball ``i`` at absolute time ``t`` (``T0 <= t``).

    ``t`` is clamped to the anchor's ``TEND``: the loop re-anchors there.
    """
    tau = min(t, st[i, TEND]) - st[i, T0]
    wz = spin_z(st[i, WZ], tau, prm[S_SPIN_DECEL])
    state = ms[i]
    if not moving(state):
        return st[i, PX], st[i, PY], 0.0, 0.0, 0.0, 0.0, wz
    ax, ay = st[i, AX], st[i, AY]
    x = st[i, PX] + tau * (st[i, VX] + 0.5 * ax * tau)
    y = st[i, PY] + tau * (st[i, VY] + 0.5 * ay * tau)
    vx = st[i, VX] + ax * tau
    vy = st[i, VY] + ay * tau
    radius = prm[P_RADIUS]
    if state == ROLLING:
        return x, y, vx, vy, -vy / radius, vx / radius, wz
    k = 2.5 / radius * tau
    return x, y, vx, vy, st[i, WX] + k * ay, st[i, WY] - k * ax, wz


@kernel
def rest_point(st, i):
    """Where rolling ball ``i`` stops: ``p0 + v0 |v0| / (2 mu_roll g)`` along its path.

    Written from the speed (not from ``p(TEND)``) so that the rest point carries no rounding
    of the stop time.
    """
    vx, vy = st[i, VX], st[i, VY]
    a = math.sqrt(st[i, AX] * st[i, AX] + st[i, AY] * st[i, AY])
    k = math.sqrt(vx * vx + vy * vy) / (2.0 * a)
    return st[i, PX] + vx * k, st[i, PY] + vy * k
