"""Stronge's compliant frictional impact, the tangential law of a ball on a cushion (compiled).

The model of pooltool 0.6.0's default cushion, ``StrongeCompliantLinear`` and
``StrongeCompliantCircular`` (W. J. Stronge, "Impact Mechanics", 2nd ed., Cambridge 2018,
ch. 5: "collinear" impact with a compliant contact, tangential compliance and Coulomb
friction). Derived here; :mod:`~pool_env.sim.kernels.spin.cushion` applies its result with
the contact geometry, the normal impulse and the spin change it shares with Han 2005.

Contact velocities. At the cushion's contact point (its angle above the equator:
:mod:`~pool_env.sim.kernels.spin.cushion`) the ball's surface velocity relative to the
rigid cushion has a normal part ``v_n`` along the contact normal (pointing into the ball;
``v_n < 0`` approaching) and a tangential part, the slip ``s``. An impulse per unit mass
along the normal changes ``v_n`` by ``beta_n = 1`` times itself; one along the tangent
changes the slip by ``beta_t = 7/2`` times itself (``1/m + R^2/I`` for a solid ball,
``I = (2/5) m R^2``), without coupling to ``v_n``. The tangential impulse is along the
initial slip direction ``t = -s / |s|`` throughout (the impact is collinear: nothing turns
the slip), so everything reduces to the scalars ``v_n(t)`` and ``v_t(t)`` with
``v_t(0) = -|s| <= 0``; ``rho = v_t0 / v_n0 >= 0``.

Compliance. The contact is a normal spring ``k_n`` and a tangential spring ``k_t =
k_n / eta^2``. Normal motion is a half-cycle of ``omega_n = sqrt(beta_n k_n / m)``:
compression ``v_n = v_n0 cos(omega_n t)`` up to ``t_c = pi / (2 omega_n)``; restitution on a
stiffer unloading spring, ``v_n = e v_n0 cos(phi(t))`` with the phase
``phi(t) = omega_n t / e + (pi/2)(1 - 1/e)`` (``pi/2`` at ``t_c``, ``pi`` at
``t_f = (1 + e) t_c``), so ``v_n(t_f) = -e v_n0``: Newton's restitution, the same normal
impulse as Han's. The normal force per unit mass is ``-v_n0 omega_n sin(omega_n t)``, then
``-v_n0 omega_n sin(phi(t))``. While the contact sticks, the tangential spring oscillates at
``omega_t = omega_n sqrt(beta_t / (beta_n eta^2))``; the model's one free parameter is the
ratio ``Omega = omega_t / omega_n`` in ``(1, 2)`` (pooltool's ``omega_ratio``, 1.8 in its
default resolver), so ``eta^2 = beta_t / (beta_n Omega^2)``. Only ``Omega`` matters: with
times in units of ``1 / omega_n`` (below ``omega_n = 1``, ``t_c = pi/2``) the outcome is
independent of ``k_n`` and ``m``.

Three regimes, by ``rho`` (as pooltool's ``stronge_compliant.py`` has them):

* Gross slip, ``rho > mu ((1 + e) beta_t - eta^2 / e)``: the contact slides throughout and
  Coulomb's law gives ``v_t_f = v_t0 - mu beta_t (1 + e) v_n0``, Han's sliding result.
* Initial stick, ``rho < mu eta^2``: the spring holds the contact from the start,
  ``v_t = v_t0 cos(Omega t)``, ``u_t = -(v_t0 / Omega) sin(Omega t)`` (``du_t/dt = -v_t``),
  until the spring force ``Omega^2 u_t / beta_t`` reaches the friction limit ``mu`` times
  the normal force, in the restitution phase: the first root ``t_s`` in ``[t_c, t_f]`` of
  ``rho |sin(Omega t)| = mu eta^2 Omega sin(phi(t))``. It then slides to the end, the
  friction force ``mu`` times the normal force, which integrates to
  ``v_t_f = v_t0 cos(Omega t_s) + mu beta_t e v_n0 (1 + cos(phi(t_s)))``.
* Slip, stick, slip (between the two): Coulomb sliding while the slip shrinks,
  ``v_t = v_t0 - mu beta_t v_n0 (1 - cos t)`` in compression and
  ``v_t0 - mu beta_t v_n0 (1 - e cos(phi(t)))`` in restitution, with the spring's deflection
  following the friction force, ``u_t = -mu eta^2 v_n0 sin(t)`` (``sin(phi(t))`` in
  restitution). The contact sticks where the spring's own motion would take over, at
  ``t_k``: ``cos(t_k) = x = (rho / mu - beta_t) / (eta^2 - beta_t)`` if
  ``rho <= mu beta_t`` (in compression), else ``cos(phi(t_k)) = (rho / mu - beta_t) /
  (eta^2 / e - e beta_t)`` (in restitution). It sticks, ``u_t = u_k cos(Omega (t - t_k)) -
  (v_k / Omega) sin(Omega (t - t_k))``, ``v_t = Omega u_k sin(Omega (t - t_k)) +
  v_k cos(Omega (t - t_k))``, until ``|u_t| = -mu eta^2 v_n0 sin(phi(t))`` again, at the
  first root ``t_s`` after ``max(t_c, t_k)``, and slides to the end:
  ``v_t_f = v_t(t_s) + mu beta_t e v_n0 (1 + cos(phi(t_s)))``.

Each regime is a closed form but for the re-slip time ``t_s``, the root of a sum of sines
of incommensurate frequencies: found by a scan of 16 steps for the first sign change and
Illinois false position to the last bits (the impact's own definition, not a time step of
the motion). pooltool finds the same root with ``scipy.optimize.toms748`` over
``[t_c, t_f]``; ``bench/spin_kernels_pooltool.py`` runs both cushion impacts on 200 seeded
states: equal to 8.4e-14 m/s.

Range. These three regimes, one interval of stick at most, are the whole story only when
``e >= 1 / Omega`` (0.556 at ``Omega = 1.8``; pooltool's ``e_c = 0.85`` and this package's
0.65 are inside). The slip speed of the contact against the spring's own motion is
``|v_n0| (rho - mu beta_t + (mu beta_t e - mu eta^2 / e) cos(phi))`` while it slides in
restitution; with ``e^2 < eta^2 / beta_t = 1 / Omega^2`` it grows there instead of
shrinking, the gross-slip bound above is no longer the least slip that slides throughout
(that would be ``mu beta_t``), and below ``e = 1 / Omega`` a time-stepped integration of
the same compliant contact sticks and slips in other sequences
(``tests/sim/test_stronge.py`` integrates it: inside the range the closed forms agree with
it to its step size; outside, on a grid with ``mu`` up to 0.5, they are off by up to
``1.2 |v_n0|``). pooltool applies
the formulas at any ``e``; ``Table`` refuses Stronge's model below ``e = 1 / Omega``.
"""

from __future__ import annotations

import math

from pool_env.sim.jit import kernel

#: ``beta_t / beta_n`` of a solid ball on a rigid half-space.
BETA = 3.5
_HALF_PI = 0.5 * math.pi
#: Steps of the scan for the first re-slip root (its bracket then refined).
_SCAN = 16


@kernel
def _phase(t, e):
    """The restitution phase ``phi(t) = t / e + (pi/2)(1 - 1/e)`` (``omega_n = 1``)."""
    return t / e + _HALF_PI * (1.0 - 1.0 / e)


@kernel
def _excess(t, k, a, b, c, omega, e):
    """How far the stuck spring's force exceeds the friction limit at ``t`` (``> 0``: slips).

    ``|a cos(omega (t - k)) + b sin(omega (t - k))| - c sin(phi(t))``.
    """
    x = omega * (t - k)
    return abs(a * math.cos(x) + b * math.sin(x)) - c * math.sin(_phase(t, e))


@kernel
def _reslip(lo, hi, k, a, b, c, omega, e):
    """The first time in ``[lo, hi]`` at which :func:`_excess` turns positive (``hi`` if none)."""
    t0 = lo
    f0 = _excess(lo, k, a, b, c, omega, e)
    for step in range(1, _SCAN + 1):
        t1 = lo + (hi - lo) * step / _SCAN
        f1 = _excess(t1, k, a, b, c, omega, e)
        if f0 <= 0.0 < f1:
            # Illinois false position: superlinear, the bracket kept, so the root is this
            # one; it ends when the bracket is a few doubles wide or the step stalls.
            side = 0
            for _ in range(100):
                mid = t1 - f1 * (t1 - t0) / (f1 - f0)
                if not t0 < mid < t1:
                    mid = 0.5 * (t0 + t1)
                    if not t0 < mid < t1:
                        break
                fm = _excess(mid, k, a, b, c, omega, e)
                if fm > 0.0:
                    t1, f1 = mid, fm
                    if side == 1:
                        f0 *= 0.5
                    side = 1
                else:
                    t0, f0 = mid, fm
                    if side == -1:
                        f1 *= 0.5
                    side = -1
                if t1 - t0 <= 4e-16 * t1:
                    break
            return t1
        t0, f0 = t1, f1
    return hi


@kernel
def stronge_tangential(v_t0, v_n0, mu, e, omega):
    """Stronge's final tangential contact velocity (see the module docstring).

    Args:
        v_t0: Initial tangential contact velocity along the fixed tangent, ``<= 0`` (``-|s|``).
        v_n0: Initial normal contact velocity, ``< 0`` (approaching).
        mu: Coulomb friction between ball and cushion (>= 0).
        e: Restitution, in ``[1 / omega, 1]`` (the model's range).
        omega: The frequency ratio ``omega_t / omega_n``, in ``(1, 2)``.

    Returns:
        ``v_t_f``; the tangential impulse per unit mass is ``(v_t_f - v_t0) / beta_t``.
    """
    if not mu > 0.0:
        return v_t0
    eta2 = BETA / (omega * omega)
    rho = v_t0 / v_n0
    t_c = _HALF_PI
    t_f = (1.0 + e) * t_c
    if rho > mu * ((1.0 + e) * BETA - eta2 / e):  # gross slip
        return v_t0 - mu * v_n0 * BETA * (1.0 + e)
    if rho < mu * eta2:  # initial stick; slips again in restitution
        t_s = t_f
        if rho > 0.0:
            t_s = _reslip(t_c, t_f, 0.0, 0.0, rho, mu * eta2 * omega, omega, e)
        slide = mu * v_n0 * BETA * e * (1.0 + math.cos(_phase(t_s, e)))
        return v_t0 * math.cos(omega * t_s) + slide
    # slip, stick at t_k (deflection u_k, velocity v_k), slip again at t_s
    if rho <= mu * BETA:
        x = min(1.0, max(-1.0, (rho / mu - BETA) / (eta2 - BETA)))
        t_k = math.acos(x)
        u_k = -mu * v_n0 * eta2 * math.sin(t_k)
        v_k = v_t0 - mu * BETA * v_n0 * (1.0 - math.cos(t_k))
    else:
        x = min(1.0, max(-1.0, (rho / mu - BETA) / (eta2 / e - e * BETA)))
        t_k = (math.acos(x) - _HALF_PI * (1.0 - 1.0 / e)) * e
        u_k = -mu * v_n0 * eta2 * math.sin(_phase(t_k, e))
        v_k = v_t0 - mu * BETA * v_n0 * (1.0 - e * math.cos(_phase(t_k, e)))
    # |u_t| against the limit, both divided by -mu v_n0 > 0
    scale = -1.0 / (mu * v_n0)
    t_s = _reslip(max(t_c, t_k), t_f, t_k, u_k * scale, -v_k / omega * scale, eta2, omega, e)
    x = omega * (t_s - t_k)
    v_s = omega * u_k * math.sin(x) + v_k * math.cos(x)
    return v_s + BETA * mu * v_n0 * e * (1.0 + math.cos(_phase(t_s, e)))
