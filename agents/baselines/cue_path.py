"""The cue ball on the spin table in closed form: strike, slide, roll, contact, after contact.

What a player knows of spin, written as the equations of the spin level (docs/physics.md,
"Spin"), never as a simulation: no event loop, no other balls. Notation: ``R`` the radius,
``mu_s g`` the sliding and ``mu_r g`` the rolling deceleration; a ball's *spin velocity* is
``s = (R wy, -R wx)``, the in-plane velocity its spin alone would give it rolling, so the
cloth contact slips at ``u = v - s``.

- The strike (:func:`strike`): the instantaneous-point cue of the simulator
  (:func:`pool_env.sim.formulas.cue_strike`, reused, not re-derived): the ball
  leaves at the aim plus the squirt, ``s = (5/2) b' V`` along the cue (``b'`` the contact
  offset), ``wz`` from the side offset.
- Sliding: ``v`` loses ``mu_s g t`` along the slip's direction ``u_hat`` and ``s`` gains
  ``(5/2) mu_s g t`` along it, so the slip shrinks at ``(7/2) mu_s g`` and the ball rolls at
  ``tau = 2 |u0| / (7 mu_s g)`` with ``v = v0 - (2/7) u0 = (5/7) v0 + (2/7) s0``. That is the
  30-degree rule for a rolling cue ball (``s0`` = its velocity before contact), the tangent
  line for a stun ball (``s0 = 0``), draw coming back and follow going through (``s0``
  against or along the line of centres). The path while sliding is the parabola
  ``r0 + v0 t - (1/2) mu_s g t^2 u_hat``; rolling is straight, ``|v|^2 / (2 mu_r g)`` long.
- The contact (:func:`collide`): the simulator's frictional impact
  (:func:`pool_env.sim.formulas.ball_ball_spin`, reused): the object ball takes
  the normal exchange with ``e_ball`` plus a throw from the contact points' slip.
- After contact (:func:`after_contact`): the slide as a polyline of its parabola, then the
  rolling legs off the cushions of :func:`agents.baselines.trace.roll_trace`, both checked
  for pockets (a cushion met while sliding is taken as the start of rolling).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from agents.baselines.geometry import PocketMouths
from agents.baselines.trace import TRACE_CUSHIONS, Trace, first_entry
from pool_env import Table
from pool_env.sim.formulas import (
    ALCIATORE_FRICTION,
    CONSTANT_FRICTION,
    FRICTIONLESS,
    POOLTOOL_FRICTION,
    ball_ball_spin,
    cue_strike,
    cushion_han,
    squirt_angle,
)

#: Points of the sliding parabola after contact where its polyline turns.
SLIDE_POINTS = 8


@dataclass(frozen=True)
class Motion:
    """A ball's velocity ``(2,)`` (m/s) and angular velocity ``(3,)`` (rad/s)."""

    vel: NDArray[np.float64]
    spin: NDArray[np.float64]

    def spin_velocity(self, radius: float) -> NDArray[np.float64]:
        """``(R wy, -R wx)``: the velocity the spin alone would roll at."""
        return np.array([radius * self.spin[1], -radius * self.spin[0]])


def contact_fraction(table: Table) -> float:
    """The contact offset per unit of the cue's axis offset, ``1 / (1 + r_tip / R)``."""
    return 1.0 / (1.0 + table.cue_tip_radius / table.ball_radius)


def squirt(table: Table, side: float) -> float:
    """How far (rad, counter-clockwise) the ball leaves from the aim for the side offset ``side``.

    The aim that sends the ball along ``heading`` is ``heading - squirt(table, side)``.
    """
    ac = side * contact_fraction(table)
    return float(squirt_angle(ac, table.ball_mass, table.cue_end_mass))


def strike(table: Table, angle: float, speed: float, tip: tuple[float, float]) -> Motion:
    """The cue ball's motion right after a level strike at ``angle`` (aim), ``speed``, ``tip``."""
    out = np.zeros(5)
    r = table.ball_radius
    cue_strike(
        float(speed), float(angle), tip[0], tip[1], 0.0, r, table.ball_mass,
        table.cue_end_mass, table.cue_tip_radius, out,
    )  # fmt: skip
    return Motion(out[0:2].copy(), out[2:5].copy())


def _decay(wz: float, rate: float, time: float) -> float:
    """The vertical-axis spin ``wz`` after ``time`` at the deceleration ``rate``."""
    return math.copysign(max(abs(wz) - rate * time, 0.0), wz)


def along(table: Table, motion: Motion, dist: float) -> Motion | None:
    """The motion after rolling or sliding ``dist`` (m) straight on; ``None`` if it stops short.

    Straight: the slip is taken along the velocity (exact for a strike on the cue's vertical
    centre line; the squirt of side spin turns the velocity a degree or two off it, whose
    share of the slip is dropped). The spin velocity across the path is kept.
    """
    speed = float(np.hypot(*motion.vel))
    if speed <= 0.0:
        return None
    d = motion.vel / speed
    r = table.ball_radius
    spin_v = motion.spin_velocity(r)
    along_spin = float(spin_v @ d)
    across = spin_v - along_spin * d
    mu_g, a_r = table.mu_slide * table.g, table.deceleration
    slip = speed - along_spin
    sign = math.copysign(1.0, slip)
    tau = 2.0 * abs(slip) / (7.0 * mu_g)
    d_slide = speed * tau - 0.5 * sign * mu_g * tau * tau
    if dist <= d_slide:
        v2 = speed * speed - 2.0 * sign * mu_g * dist
        if v2 < 0.0:
            return None
        v = math.sqrt(v2)
        t = (speed - v) / (sign * mu_g)
        new_along = v - (slip - 3.5 * sign * mu_g * t)
    else:
        v_roll = speed - sign * mu_g * tau
        v2 = v_roll * v_roll - 2.0 * a_r * (dist - d_slide)
        if v2 < 0.0:
            return None
        v = math.sqrt(v2)
        t = tau + (v_roll - v) / a_r
        new_along = v
    sv = across + new_along * d
    wz = _decay(float(motion.spin[2]), table.spin_decel, t)
    return Motion(v * d, np.array([-sv[1] / r, sv[0] / r, wz]))


def launch_speed(table: Table, slip_ratio: float, dist: float, speed_there: float) -> float:
    """The speed a ball needs to be at ``speed_there`` after ``dist`` (m), straight on.

    Args:
        table: The table.
        slip_ratio: The starting slip over the starting speed, ``1 - s / v`` along the path:
            1 for a ball without spin (an object ball after contact, a stun strike),
            ``1 - (5/2) b'`` for a strike at the contact offset ``b'``.
        dist: The distance (m).
        speed_there: The speed wanted there (m/s).

    Sliding is ``v^2 = V^2 - 2 sign mu_s g x`` until ``c1 V^2`` (the slide's length), then
    rolling at ``k V`` with ``k = 1 - (2/7) slip_ratio`` loses ``2 mu_r g`` of ``v^2`` per
    metre; each regime inverts in closed form and the one that holds is returned.
    """
    mu_g, a_r = table.mu_slide * table.g, table.deceleration
    sign = math.copysign(1.0, slip_ratio)
    kappa = 2.0 * abs(slip_ratio) / (7.0 * mu_g)  # slide time per unit of speed
    c1 = kappa - 0.5 * sign * mu_g * kappa * kappa
    sliding2 = speed_there * speed_there + 2.0 * sign * mu_g * dist
    if sliding2 > 0.0 and dist <= c1 * sliding2:
        return math.sqrt(sliding2)
    k = 1.0 - 2.0 / 7.0 * slip_ratio
    return math.sqrt((speed_there * speed_there + 2.0 * a_r * dist) / (k * k + 2.0 * a_r * c1))


def friction_mode(table: Table) -> tuple[int, float]:
    """The ball-ball friction mode and constant of ``table`` (as the simulator reads them)."""
    friction = table.ball_friction
    if isinstance(friction, str):
        return {"alciatore": ALCIATORE_FRICTION, "pooltool": POOLTOOL_FRICTION}[friction], 0.0
    return (CONSTANT_FRICTION if friction > 0.0 else FRICTIONLESS), float(friction)


def collide(table: Table, cue: Motion, normal: NDArray[np.float64]) -> tuple[Motion, Motion]:
    """The cue ball's and the object ball's motion after the cue ball hits it along ``normal``.

    The object ball is at rest; ``normal`` is the unit vector from the cue ball's centre to
    the object ball's at contact.
    """
    out = np.zeros(10)
    mode, mu = friction_mode(table)
    m = table.ball_mass
    ball_ball_spin(
        cue.vel[0], cue.vel[1], cue.spin[0], cue.spin[1], cue.spin[2],
        0.0, 0.0, 0.0, 0.0, 0.0, float(normal[0]), float(normal[1]),
        m, m, table.ball_radius, table.e_ball, mode, mu, out,
    )  # fmt: skip
    return Motion(out[0:2].copy(), out[2:5].copy()), Motion(out[5:7].copy(), out[7:10].copy())


def _to_rail(
    pos: NDArray[np.float64], w: NDArray[np.float64], lo: NDArray[np.float64], hi: NDArray
) -> tuple[int, float]:
    """The rail line (axis) a ray from ``pos`` along unit ``w`` meets first, and how far."""
    best, dist = 0, math.inf
    for axis in range(2):
        if w[axis] > 1e-15:
            d = (hi[axis] - pos[axis]) / w[axis]
        elif w[axis] < -1e-15:
            d = (lo[axis] - pos[axis]) / w[axis]
        else:
            continue
        if d < dist:
            best, dist = axis, d
    return best, max(dist, 0.0)


def _rail(table: Table, motion: Motion, axis: int) -> Motion:
    """The motion after meeting the rail across ``axis`` (Han 2005, the simulator's kernel)."""
    normal = np.zeros(2)
    normal[axis] = -math.copysign(1.0, float(motion.vel[axis]))  # from the rail into the table
    out = np.zeros(5)
    v, w = motion.vel, motion.spin
    cushion_han(
        v[0], v[1], w[0], w[1], w[2], normal[0], normal[1], table.ball_radius,
        table.cushion_height, table.e_cushion, table.cushion_friction, out,
    )  # fmt: skip
    return Motion(out[0:2].copy(), out[2:5].copy())


def _slid(table: Table, motion: Motion, u_hat: NDArray[np.float64], t: float) -> Motion:
    """The motion after sliding for ``t`` with the slip along ``u_hat``."""
    mu_g, r = table.mu_slide * table.g, table.ball_radius
    spin_v = motion.spin_velocity(r) + 2.5 * mu_g * t * u_hat
    wz = _decay(float(motion.spin[2]), table.spin_decel, t)
    return Motion(motion.vel - mu_g * t * u_hat, np.array([-spin_v[1] / r, spin_v[0] / r, wz]))


def _rolled(table: Table, motion: Motion, dist: float) -> Motion:
    """The motion of a rolling ball after ``dist`` (m) straight on."""
    v = float(np.hypot(*motion.vel))
    w = motion.vel / v
    v_new = math.sqrt(max(v * v - 2.0 * table.deceleration * dist, 0.0))
    t = (v - v_new) / table.deceleration
    r = table.ball_radius
    wz = _decay(float(motion.spin[2]), table.spin_decel, t)
    return Motion(v_new * w, np.array([-v_new * w[1] / r, v_new * w[0] / r, wz]))


def after_contact(
    table: Table, mouths: PocketMouths, start: NDArray[np.float64], motion: Motion
) -> Trace:
    """Where the cue ball goes from ``start`` with ``motion``, off the cushions, until it stops.

    Each phase in closed form: a slide (the parabola as a polyline of
    :data:`SLIDE_POINTS` legs) until the slip is gone, then a straight roll. A rail is
    resolved by the simulator's cushion law (Han 2005,
    :func:`pool_env.sim.formulas.cushion_han`): a rolling ball leaves it
    sliding and bends. Other balls and the jaws' facings are ignored (a path reaching a
    pocket's opening drops). Up to :data:`agents.baselines.trace.TRACE_CUSHIONS` cushions.

    Args:
        table: The table.
        mouths: Its pockets.
        start: ``(2,)`` the cue ball's centre at contact.
        motion: Its motion right after contact.

    Returns:
        The :class:`~agents.baselines.trace.Trace` of the whole path.
    """
    r = table.ball_radius
    mu_g, a_r = table.mu_slide * table.g, table.deceleration
    lo, hi = np.array([r, r]), np.array([table.length - r, table.width - r])
    pos = np.array(start, dtype=np.float64)
    legs: list[tuple[NDArray[np.float64], NDArray[np.float64]]] = []
    for _ in range(TRACE_CUSHIONS + 1):
        slip = motion.vel - motion.spin_velocity(r)
        slip_speed = float(np.hypot(*slip))
        hit = -1
        if slip_speed > 1e-9:
            u_hat = slip / slip_speed
            tau = 2.0 * slip_speed / (7.0 * mu_g)
            times = np.linspace(0.0, tau, SLIDE_POINTS + 1)
            v0 = motion.vel
            points = pos + np.outer(times, v0) - 0.5 * mu_g * np.outer(times * times, u_hat)
            for i in range(SLIDE_POINTS):
                p, seg = points[i], points[i + 1] - points[i]
                length = float(np.hypot(*seg))
                if length <= 1e-12:
                    continue
                w = seg / length
                axis, to_rail = _to_rail(p, w, lo, hi)
                reach = min(to_rail, length)
                k, entry = first_entry(mouths, p, w)
                if entry <= reach + 1e-9:
                    end = p + entry * w
                    return Trace(k, end, (*legs, (p, end)))
                end = p + reach * w
                legs.append((p, end))
                if to_rail < length:
                    t = times[i] + (times[i + 1] - times[i]) * to_rail / length
                    pos, hit = end, axis
                    motion = _slid(table, motion, u_hat, t)
                    break
            else:
                pos = points[-1]
                motion = _slid(table, motion, u_hat, tau)
        if hit < 0:  # rolling: straight to a rail or to rest
            v = float(np.hypot(*motion.vel))
            if v <= 1e-12:
                return Trace(-1, pos, tuple(legs))
            w = motion.vel / v
            axis, to_rail = _to_rail(pos, w, lo, hi)
            stop = v * v / (2.0 * a_r)
            reach = min(to_rail, stop)
            k, entry = first_entry(mouths, pos, w)
            if entry <= reach + 1e-9:
                end = pos + entry * w
                return Trace(k, end, (*legs, (pos, end)))
            end = pos + reach * w
            legs.append((pos, end))
            if stop <= to_rail:
                return Trace(-1, end, tuple(legs))
            pos, hit = end, axis
            motion = _rolled(table, motion, reach)
        motion = _rail(table, motion, hit)
    return Trace(-1, pos, tuple(legs))
