"""The spin level's physics at 50 digits (mpmath): motion, transitions, resolutions, strike.

Part of the independent reference :mod:`pool_env.testing.spin_reference`; it imports nothing
from ``pool_env`` and shares no code with ``pool_env.sim``. Every formula is derived here
from the model of pooltool 0.6.0 (facts read from its physics code, not its code):

Frame z up, contact with the cloth at ``-R z``; slip velocity ``u = (vx - R wy, vy + R wx)``.

* Sliding: ``dv/dt = -mu_s g u_hat``, ``dw_xy/dt = (5/2)(mu_s g / R)(-u_hat_y, u_hat_x)``
  (``u_hat`` constant, ``du/dt = -(7/2) mu_s g u_hat``); ends at ``2 |u0| / (7 mu_s g)``.
* Rolling: ``dv/dt = -mu_r g v_hat``, ``w_xy = (-vy, vx) / R``; ends at ``|v0| / (mu_r g)``
  in the spinning state if ``wz != 0`` then, else at rest.
* Vertical spin in every state decays at ``spin_decel`` towards 0 and stays there; only a
  spinning ball's ``wz`` reaching 0 is an event (spinning -> stationary).
* Ball-ball, "frictional inelastic" (pooltool 0.6.0's default model): the normal
  components follow restitution ``e`` (normal impulse ``J_n = (1 + e) m_r |du_n|``,
  ``m_r = m1 m2 / (m1 + m2)``); a tangential impulse against the 3D relative velocity of
  the contact points (its vertical part comes from the spins across the line of centres),
  capped at the no-slip impulse; the vertical velocity it gives is dropped, the spin kept.
  Its size: ``throw="coulomb"`` (the spin level's choice, the default) ``mu J_n``;
  ``throw="pooltool"`` pooltool 0.6.0's ``mu e |du_n| m`` (friction times the *separation*
  speed; ``m = 2 m_r`` for equal masses), 2.6% less at ``e = 0.95``. ``mu`` is Alciatore's
  fit ``0.009951 + 0.108 exp(-1.088 v_rel)`` (pooltool's coefficients) of the pre-impact
  relative surface speed, or a constant (0: frictionless).
* Cushion, Han 2005: contact on the nose at height ``h`` above the cloth, direction
  ``c = cos(theta) d + sin(theta) z`` from the centre with ``sin(theta) = h / R - 1`` and
  ``d`` the horizontal unit vector into the cushion. Normal impulse ``(1 + e) m (v.c)``
  along ``-c`` (a sphere's normal response is ``1/m``); the tangential response of the
  contact point is isotropic, ``7 / (2 m)``, so the no-slip impulse is ``-(2m/7) s`` for
  the contact slip ``s``; friction is ``mu P_n`` against ``s`` unless that exceeds the
  no-slip one (stick). ``v += P_xy / m`` (vertical dropped), ``w += R c x P / I``.
* Cue strike (Alciatore TP A-30, instantaneous point, pooltool's form): with contact
  offsets ``(a, b)`` = tip offsets ``/ (1 + r_tip / R)`` (``a`` > 0 right english) and
  elevation ``theta``, the ball's speed along the cue is ``V = speed / cos(theta)`` (the
  in-plane ``speed`` is the input), ``w = (5 V / (2 R)) (b l + a sin(theta) f + a
  cos(theta) z)`` for aim ``f`` and ``l = z x f``; the velocity is turned by the squirt
  ``atan2((5/2) a sqrt(1-a^2), 1 + m/m_e + (5/2)(1-a^2))`` towards the side opposite the
  english (the spin stays aligned with the aim, as in pooltool).
"""

from __future__ import annotations

from mpmath import mp, mpf

STATIONARY, SPINNING, SLIDING, ROLLING = 0, 1, 2, 3

Vec2 = tuple[mpf, mpf]
Vec3 = tuple[mpf, mpf, mpf]


def cross(p: Vec3, q: Vec3) -> Vec3:
    """3D cross product."""
    return (p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0])


def dot(p: tuple[mpf, ...], q: tuple[mpf, ...]) -> mpf:
    """Dot product of equal-length tuples."""
    return sum((a * b for a, b in zip(p, q, strict=True)), mpf(0))


def norm(p: tuple[mpf, ...]) -> mpf:
    """Euclidean norm."""
    return mp.sqrt(dot(p, p))


def slip(v: Vec2, w: Vec3, r: mpf) -> Vec2:
    """Velocity of the cloth contact point."""
    return (v[0] - r * w[1], v[1] + r * w[0])


def state_of(v: Vec2, w: Vec3, r: mpf) -> int:
    """Motion state of a free ball: sliding unless it rolls (no slip) or stands."""
    if v[0] == 0 and v[1] == 0 and w[0] == 0 and w[1] == 0:
        return SPINNING if w[2] != 0 else STATIONARY
    u = slip(v, w, r)
    return ROLLING if u[0] == 0 and u[1] == 0 else SLIDING


def spin_z(wz: mpf, tau: mpf, decel: mpf) -> mpf:
    """Vertical spin after ``tau``: decays at ``decel`` towards zero and stays there."""
    left = abs(wz) - decel * tau
    return mp.sign(wz) * left if left > 0 else mpf(0)


class Piece:
    """A ball's motion from an anchor: constant acceleration until its next transition.

    Attributes:
        t0: Anchor time.
        p: Position at ``t0``.
        v: Velocity at ``t0``.
        w: Angular velocity at ``t0``.
        state: Motion state.
        acc: Constant acceleration (zero when not translating).
        w_rate: ``d(wx, wy)/dt`` while sliding (zero otherwise).
        duration: Time to the next transition (``None``: never).
    """

    def __init__(self, t0: mpf, p: Vec2, v: Vec2, w: Vec3, state: int, prm: dict) -> None:
        self.t0, self.p, self.v, self.w, self.state = t0, p, v, w, state
        r, zero = prm["R"], mpf(0)
        self.acc: Vec2 = (zero, zero)
        self.w_rate: Vec2 = (zero, zero)
        if state == SLIDING:
            u = slip(v, w, r)
            mu_g = prm["mu_slide"] * prm["g"]
            un = norm(u)
            uh = (u[0] / un, u[1] / un)
            self.acc = (-mu_g * uh[0], -mu_g * uh[1])
            k = mpf(5) / 2 * mu_g / r
            self.w_rate = (-k * uh[1], k * uh[0])
            self.duration: mpf | None = 2 * un / (7 * mu_g)
        elif state == ROLLING:
            mu_g = prm["mu_roll"] * prm["g"]
            s = norm(v)
            self.acc = (-mu_g * v[0] / s, -mu_g * v[1] / s)
            self.duration = s / mu_g
        elif state == SPINNING:
            self.duration = abs(w[2]) / prm["spin_decel"]
        else:
            self.duration = None

    def at(self, t: mpf, prm: dict) -> tuple[Vec2, Vec2, Vec3]:
        """Position, velocity and angular velocity at ``t`` (within this piece)."""
        tau = t - self.t0
        p, v, a = self.p, self.v, self.acc
        pos = (p[0] + v[0] * tau + a[0] * tau * tau / 2, p[1] + v[1] * tau + a[1] * tau * tau / 2)
        vel = (v[0] + a[0] * tau, v[1] + a[1] * tau)
        wz = spin_z(self.w[2], tau, prm["spin_decel"])
        if self.state == ROLLING:
            r = prm["R"]
            w = (-vel[1] / r, vel[0] / r, wz)
        elif self.state == SLIDING:
            w = (self.w[0] + self.w_rate[0] * tau, self.w[1] + self.w_rate[1] * tau, wz)
        else:
            w = (mpf(0), mpf(0), wz)
        return pos, vel, w


def alciatore(v_rel: mpf) -> mpf:
    """Alciatore's fit of ball-ball friction against relative surface speed (TP A-14)."""
    return mpf("0.009951") + mpf("0.108") * mp.exp(mpf("-1.088") * v_rel)


def ball_ball(
    v1: Vec2, w1: Vec3, v2: Vec2, w2: Vec3, n2: Vec2, m1: mpf, m2: mpf, prm: dict
) -> tuple[Vec2, Vec3, Vec2, Vec3]:
    """Frictional inelastic ball-ball impact (see the module docstring).

    Args:
        v1: Ball 1's velocity.
        w1: Ball 1's angular velocity.
        v2: Ball 2's velocity.
        w2: Ball 2's angular velocity.
        n2: Unit vector from ball 1's centre to ball 2's.
        m1: Ball 1's mass.
        m2: Ball 2's mass.
        prm: Parameters (``R``, ``e_ball``, ``ball_friction``, ``throw``).

    Returns:
        New ``(v1, w1, v2, w2)``.
    """
    r, e = prm["R"], prm["e_ball"]
    n: Vec3 = (n2[0], n2[1], mpf(0))
    du = dot(v1, n2) - dot(v2, n2)  # approach speed along the line of centres
    m_red = m1 * m2 / (m1 + m2)
    jn = (1 + e) * m_red * du  # normal impulse on ball 2 (along +n)
    dv: list[mpf] = [-jn / m1 * n[0], -jn / m1 * n[1], mpf(0)]  # on ball 1
    dv2: list[mpf] = [jn / m2 * n[0], jn / m2 * n[1], mpf(0)]
    dw1: Vec3 = (mpf(0), mpf(0), mpf(0))
    dw2: Vec3 = dw1
    # Relative velocity of the contact points (1's at +R n, 2's at -R n), tangential part.
    vt = (v1[0] - v2[0] - du * n[0], v1[1] - v2[1] - du * n[1], mpf(0))
    wsum = (w1[0] + w2[0], w1[1] + w2[1], w1[2] + w2[2])
    spin = cross(wsum, n)
    rel = (vt[0] + r * spin[0], vt[1] + r * spin[1], vt[2] + r * spin[2])
    rel_speed = norm(rel)
    friction = prm["ball_friction"]
    mu = alciatore(rel_speed) if friction == "alciatore" else mpf(friction)
    if mu > 0 and rel_speed > 0:
        # Contact-point response to a tangential impulse J on 1 (-J on 2): (7/2)(1/m1+1/m2) J.
        k = mpf(7) / 2 * (1 / m1 + 1 / m2)
        # Coulomb: mu J_n; pooltool 0.6.0: mu * (separation speed) * m.
        j_slip = mu * e * du * 2 * m_red if prm["throw"] == "pooltool" else mu * jn
        j = min(j_slip, rel_speed / k)  # capped at the no-slip impulse
        jt = tuple(-j * c / rel_speed for c in rel)  # on ball 1, against the slip
        dv = [dv[k_] + jt[k_] / m1 for k_ in range(3)]
        dv2 = [dv2[k_] - jt[k_] / m2 for k_ in range(3)]
        arm1 = cross(n, jt)  # R n x J / I1 and (-R n) x (-J) / I2
        dw1 = tuple(c * r / (mpf(2) / 5 * m1 * r * r) for c in arm1)  # type: ignore[assignment]
        dw2 = tuple(c * r / (mpf(2) / 5 * m2 * r * r) for c in arm1)  # type: ignore[assignment]
    # Vertical velocity changes are dropped (2D), the spins kept.
    return (
        (v1[0] + dv[0], v1[1] + dv[1]),
        (w1[0] + dw1[0], w1[1] + dw1[1], w1[2] + dw1[2]),
        (v2[0] + dv2[0], v2[1] + dv2[1]),
        (w2[0] + dw2[0], w2[1] + dw2[1], w2[2] + dw2[2]),
    )


def cushion_han(v: Vec2, w: Vec3, nrm: Vec2, m: mpf, prm: dict) -> tuple[Vec2, Vec3]:
    """Han 2005 cushion impact (see the module docstring).

    Args:
        v: Velocity (moving into the cushion).
        w: Angular velocity.
        nrm: Unit normal from the cushion into the table.
        m: Ball mass.
        prm: Parameters (``R``, ``e_cushion``, ``cushion_friction``, ``cushion_height``).

    Returns:
        New ``(v, w)``.
    """
    r, e, mu = prm["R"], prm["e_cushion"], prm["cushion_friction"]
    sin_t = prm["cushion_height"] / r - 1
    cos_t = mp.sqrt(1 - sin_t * sin_t)
    c: Vec3 = (-nrm[0] * cos_t, -nrm[1] * cos_t, sin_t)  # centre -> contact, unit
    v3: Vec3 = (v[0], v[1], mpf(0))
    rot = cross(w, c)
    vc = tuple(v3[k] + r * rot[k] for k in range(3))
    vn = dot(v3, c)  # > 0: into the cushion
    s = tuple(vc[k] - vn * c[k] for k in range(3))
    s_norm = norm(s)
    p_n = (1 + e) * m * vn
    stick = 2 * m / 7 * s_norm
    jt = stick if stick <= mu * p_n else mu * p_n
    pt = tuple(-jt * s[k] / s_norm for k in range(3)) if s_norm > 0 else (mpf(0),) * 3
    imp = tuple(-p_n * c[k] + pt[k] for k in range(3))
    arm = cross(c, imp)
    i_m = mpf(2) / 5 * m * r * r
    return (
        (v[0] + imp[0] / m, v[1] + imp[1] / m),
        (w[0] + r * arm[0] / i_m, w[1] + r * arm[1] / i_m, w[2] + r * arm[2] / i_m),
    )


def squirt_angle(a: mpf, m_ball: mpf, m_end: mpf) -> mpf:
    """Squirt angle (TP A-31) for contact side offset ``a``; > 0 turns left (right english)."""
    rest = 1 - a * a
    return mp.atan2(mpf(5) / 2 * a * mp.sqrt(rest), 1 + m_ball / m_end + mpf(5) / 2 * rest)


def cue_strike(
    speed: mpf,
    angle: mpf,
    tip: tuple[mpf, mpf],
    elevation: mpf,
    prm: dict,
    m_ball: mpf,
) -> tuple[Vec2, Vec3]:
    """Velocity and spin after an instantaneous-point strike (see the module docstring).

    Args:
        speed: The ball's in-plane speed after the strike.
        angle: The cue's aim (radians).
        tip: Side (+ right english) and vertical (+ above centre) tip offsets, fractions of R.
        elevation: Cue elevation (radians).
        prm: Parameters (``R``, ``cue_tip_radius``, ``cue_end_mass``).
        m_ball: The struck ball's mass.

    Returns:
        ``(v, w)``.
    """
    r = prm["R"]
    scale = 1 + prm["cue_tip_radius"] / r
    a, b = tip[0] / scale, tip[1] / scale
    big_v = speed / mp.cos(elevation)
    k = mpf(5) * big_v / (2 * r)
    f = (mp.cos(angle), mp.sin(angle))
    left = (-f[1], f[0])
    s_e, c_e = mp.sin(elevation), mp.cos(elevation)
    w = (k * (b * left[0] + a * s_e * f[0]), k * (b * left[1] + a * s_e * f[1]), k * a * c_e)
    heading = angle + squirt_angle(a, m_ball, prm["cue_end_mass"])
    return (speed * mp.cos(heading), speed * mp.sin(heading)), w
