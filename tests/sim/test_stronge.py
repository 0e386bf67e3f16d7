"""Stronge's compliant cushion: its limits, an independent integration of its model, energy.

The kernel :func:`~pool_env.sim.kernels.spin.stronge.stronge_tangential` is checked against
a time-stepped integration of the compliant contact the module docstring derives it from
(:func:`integrate`: a tangential spring with a Coulomb slider, loaded by the normal
half-cycles), and the whole cushion impact (``cushion_spin``) against Han's model where the
two must agree.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table
from pool_env.sim.kernels.spin.cushion import cushion_spin
from pool_env.sim.kernels.spin.params import HAN_CUSHION, STRONGE_CUSHION
from pool_env.sim.kernels.spin.stronge import BETA, stronge_tangential

R = 0.028575
OMEGA = 1.8  # pooltool's default resolver


def bounce(v, w, model, n=(-1.0, 0.0), h=R, e=0.85, f=0.2, omega=OMEGA):
    """``cushion_spin``'s result as (v', w') for a rail at +x (normal -x) by default."""
    out = np.full(5, np.nan)
    cushion_spin(*v, *w, *n, R, h, e, f, model, omega, out)
    return out[0:2], out[2:5]


def integrate(v_t0, v_n0, mu, e, omega, steps=400_000):
    """The compliant contact integrated in time (``omega_n = 1``), independently of the kernel.

    Normal force per unit mass ``-v_n0 sin(t)`` in compression and ``-v_n0 sin(phi(t))`` in
    restitution; the tangential spring's deflection ``u`` moves with ``du/dt = -v_t`` while
    its force ``omega^2 u`` (as a rate of ``v_t``) is within ``mu beta_t`` times the normal
    force, and is held at that bound while the contact slides; ``dv_t/dt = omega^2 u``.
    """
    t_f = (1.0 + e) * math.pi / 2
    dt = t_f / steps
    u, v = 0.0, v_t0
    for k in range(steps):
        t = (k + 0.5) * dt
        phase = t if t <= math.pi / 2 else t / e + (math.pi / 2) * (1 - 1 / e)
        bound = mu * BETA * (-v_n0) * math.sin(phase) / omega**2
        u = min(bound, max(-bound, u - v * dt))
        v += omega**2 * u * dt
    return v


def thresholds(mu, e, omega=OMEGA):
    """The initial-stick and gross-slip bounds of ``rho = v_t0 / v_n0``."""
    eta2 = BETA / omega**2
    return mu * eta2, mu * ((1 + e) * BETA - eta2 / e)


@pytest.mark.parametrize("where", [0.3, 0.8, 1.2, 2.0, 3.5, 4.5])
def test_each_regime_matches_the_integrated_compliant_contact(where):
    """Initial stick (0.3, 0.8 of its bound), slip-stick-slip, gross slip (past its bound)."""
    mu, e, v_n0 = 0.2, 0.85, -1.0
    stick, gross = thresholds(mu, e)
    rho = where * stick if where < 1 else stick + (gross - stick) * (where - 1.0) / 2.5
    expected = integrate(-rho, v_n0, mu, e, OMEGA)
    assert stronge_tangential(-rho, v_n0, mu, e, OMEGA) == pytest.approx(expected, abs=2e-4)


def test_the_closed_forms_match_the_integration_across_the_models_range():
    """Random friction, restitution in ``[1 / Omega, 1]``, frequency ratio and slip."""
    rng = np.random.default_rng(3)
    for _ in range(12):
        omega = float(rng.uniform(1.05, 1.95))
        e = float(rng.uniform(1.0 / omega, 1.0))
        mu = float(rng.uniform(0.05, 0.6))
        rho = float(rng.uniform(0.0, 1.1)) * thresholds(mu, e, omega)[1]
        expected = integrate(-rho, -1.0, mu, e, omega, steps=100_000)
        assert stronge_tangential(-rho, -1.0, mu, e, omega) == pytest.approx(expected, abs=1e-3)


def test_outside_its_range_the_closed_forms_leave_the_integrated_contact():
    """Below ``e = 1 / Omega`` (why ``Table`` refuses it there): off by far more than a step."""
    mu, e, omega = 0.5, 0.45, 1.3
    rho = 0.5  # past pooltool's gross-slip bound (0.235), below mu beta_t (1.75)
    expected = integrate(-rho, -1.0, mu, e, omega, steps=100_000)
    assert abs(stronge_tangential(-rho, -1.0, mu, e, omega) - expected) > 0.1


def test_gross_slip_is_coulomb_sliding_and_han_sliding():
    """Past the gross-slip bound the impulse is mu (1 + e) |v_n0|, as Han's sliding branch."""
    mu, e = 0.2, 0.85
    _, gross = thresholds(mu, e)
    v_n0 = -0.7
    v_t0 = 1.01 * gross * v_n0
    assert stronge_tangential(v_t0, v_n0, mu, e, OMEGA) == pytest.approx(
        v_t0 - mu * BETA * (1 + e) * v_n0, rel=1e-15
    )
    # A ball with strong running side spin at the equator (h = R) slides on both models.
    v, w = (1.0, 0.5), (0.0, 0.0, 60.0)
    vs, ws = bounce(v, w, STRONGE_CUSHION)
    vh, wh = bounce(v, w, HAN_CUSHION)
    np.testing.assert_allclose(vs, vh, rtol=0, atol=1e-14)
    np.testing.assert_allclose(ws, wh, rtol=0, atol=1e-12)


def test_head_on_and_frictionless_rebound_by_restitution_alone():
    """No slip (or no friction): the contact normal's velocity is reversed times e, no spin."""
    for f in (0.2, 0.0):
        v, w = bounce((1.3, 0.0), (0.0, 0.0, 0.0), STRONGE_CUSHION, e=0.85, f=f)
        np.testing.assert_allclose(v, (-0.85 * 1.3, 0.0), rtol=0, atol=1e-15)
        np.testing.assert_allclose(w, 0.0, atol=1e-13)
    v, w = bounce((1.3, 0.4), (0.0, 0.0, 5.0), STRONGE_CUSHION, f=0.0)
    np.testing.assert_allclose(v, (-0.85 * 1.3, 0.4), rtol=0, atol=1e-15)
    np.testing.assert_allclose(w, (0.0, 0.0, 5.0), rtol=0, atol=1e-15)


def test_the_regimes_join_without_jumps():
    """The three closed forms agree where the regimes meet (each bound approached both ways)."""
    for mu, e, omega in ((0.2, 0.85, 1.8), (0.5, 0.8, 1.3), (0.1, 0.95, 1.95)):
        for bound in thresholds(mu, e, omega):
            below = stronge_tangential(-bound * (1 - 1e-9), -1.0, mu, e, omega)
            above = stronge_tangential(-bound * (1 + 1e-9), -1.0, mu, e, omega)
            assert abs(below - above) < 1e-6


def test_a_compliant_stick_leaves_part_of_the_slip_unlike_han():
    """Han's rigid stick ends the slip; the spring returns part of it (same direction here)."""
    mu, e = 0.2, 0.85
    stick, _ = thresholds(mu, e)
    v_t0 = -0.5 * stick
    v_tf = stronge_tangential(v_t0, -1.0, mu, e, OMEGA)
    assert v_t0 < v_tf < -0.2 * abs(v_t0)  # Han: exactly 0


def test_no_energy_is_gained_over_random_impacts():
    """Kinetic plus rotational energy never grows, across restitutions, ratios and heights."""
    rng = np.random.default_rng(5)
    for _ in range(3000):
        omega = float(rng.uniform(1.05, 1.95))
        e = float(rng.uniform(1.0 / omega, 1.0))
        v = rng.normal(0.0, 1.5, 2)
        v[0] = abs(v[0]) + 1e-3  # into the rail at +x
        w = rng.normal(0.0, 80.0, 3)
        h = float(rng.uniform(R, 1.6 * R))
        f = float(rng.uniform(0.0, 0.6))
        v2, w2 = bounce(v, w, STRONGE_CUSHION, h=h, e=e, f=f, omega=omega)
        before = v @ v + 0.4 * R * R * (w @ w)
        after = v2 @ v2 + 0.4 * R * R * (w2 @ w2)
        assert after <= before * (1 + 1e-12)


def test_mirror_symmetry():
    """Reflecting the approach along the rail reflects the rebound (and flips the spins)."""
    v, w = (1.1, 0.37), (3.0, -7.0, 21.0)
    va, wa = bounce(v, w, STRONGE_CUSHION, h=1.27 * R)
    vb, wb = bounce((v[0], -v[1]), (-w[0], w[1], -w[2]), STRONGE_CUSHION, h=1.27 * R)
    np.testing.assert_allclose(vb, (va[0], -va[1]), rtol=0, atol=1e-14)
    np.testing.assert_allclose(wb, (-wa[0], wa[1], -wa[2]), rtol=0, atol=1e-12)


def test_table_refuses_restitution_below_the_models_range():
    with pytest.raises(ValueError, match="cushion_omega_ratio"):
        Table(model="spin", cushion_model="stronge", cushion_omega_ratio=2.0)
    with pytest.raises(ValueError, match="e_cushion >= 1 / cushion_omega_ratio"):
        Table(model="spin", cushion_model="stronge", e_cushion=0.5)
    with pytest.raises(ValueError, match="e_jaw >= 1 / cushion_omega_ratio"):
        Table(model="spin", cushion_model="stronge", e_jaw=0.5)
    with pytest.raises(ValueError, match="cushion_model must be one of"):
        Table(model="spin", cushion_model="mathavan")
    assert Table(model="spin", cushion_model="han", e_cushion=0.1).e_cushion == 0.1
