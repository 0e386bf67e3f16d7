"""Mathavan's ball-ball model against the limits where it has a closed form, and its laws."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot
from pool_env.sim.kernels.spin.collide import ball_ball_spin
from pool_env.sim.kernels.spin.mathavan import ball_ball_mathavan
from pool_env.sim.kernels.spin.params import ALCIATORE_FRICTION, CONSTANT_FRICTION, FRICTIONLESS

R, M = 0.028575, 0.170097


def mathavan(v1, w1, v2, w2, n, e=0.95, mode=ALCIATORE_FRICTION, mu=0.0, mu_s=0.2, steps=1000,
             m1=M, m2=M):  # fmt: skip
    """The kernel's result as (v1', w1', v2', w2')."""
    out = np.full(10, np.nan)
    ball_ball_mathavan(*v1, *w1, *v2, *w2, *n, m1, m2, R, e, mode, mu, mu_s, steps, out)
    return out[0:2], out[2:5], out[5:7], out[7:10]


def energy(m, v, w):
    return 0.5 * m * float(v @ v) + 0.2 * m * R * R * float(w @ w)


@pytest.mark.parametrize("e", [1.0, 0.95, 0.5, 0.0])
def test_frictionless_impact_restores_e_times_the_approach(e):
    """No friction: Newton's restitution on the line of centres, to one impulse step."""
    n = np.array([math.cos(0.4), math.sin(0.4)])
    v1, v2 = np.array([1.7, 0.9]), np.array([-0.2, 0.1])
    c = float((v1 - v2) @ n)
    a1, _, a2, _ = mathavan(v1, (3.0, -2.0, 40.0), v2, (0, 0, 0), n, e=e, mode=FRICTIONLESS)
    step = (1 + e) * c / 1000
    assert float((a2 - a1) @ n) == pytest.approx(e * c, abs=2 * step)
    t = np.array([-n[1], n[0]])  # no tangential exchange without friction
    assert float(a1 @ t) == pytest.approx(float(v1 @ t), abs=1e-14)
    np.testing.assert_allclose(a1 + a2, v1 + v2, rtol=0, atol=1e-13)  # equal masses


def test_stun_cut_with_constant_sliding_friction_is_coulombs_impulse():
    """A stun cut sliding throughout: Coulomb's impulse, as the closed-form frictional model.

    The tangential impulse is mu times the normal one, as ``ball_ball_spin`` with a constant
    mu gives it, to the integration's step.
    """
    cut = math.radians(30.0)
    n = np.array([math.cos(cut), math.sin(cut)])
    v1 = np.array([2.0, 0.0])
    zero = (0.0, 0.0, 0.0)
    got = mathavan(v1, zero, (0, 0), zero, n, e=0.9, mode=CONSTANT_FRICTION, mu=0.05, steps=4000)
    ref = np.full(10, np.nan)
    ball_ball_spin(*v1, *zero, 0, 0, *zero, *n, M, M, R, 0.9, CONSTANT_FRICTION, 0.05, ref)
    np.testing.assert_allclose(got[2], ref[5:7], rtol=0, atol=2e-3)  # object ball
    np.testing.assert_allclose(got[0], ref[0:2], rtol=0, atol=2e-3)  # cue ball
    np.testing.assert_allclose(got[3], ref[7:10], rtol=0, atol=0.1)  # its side spin (rad/s)
    assert abs(got[3][2]) > 1.0  # friction did spin it


def test_the_result_converges_as_the_steps_shrink():
    """Halving the step changes the result by half as much (first order), toward a limit."""
    args = ((1.5, 0.3), (10.0, -30.0, 20.0), (0.0, 0.0), (0, 0, 0), (math.cos(0.3), math.sin(0.3)))
    a, b, c = (np.concatenate(mathavan(*args, steps=s)) for s in (500, 1000, 2000))
    d1, d2 = np.abs(b - a).max(), np.abs(c - b).max()
    assert 0.3 < d2 / d1 < 0.7


def test_no_energy_is_gained_and_momentum_keeps_without_table_friction():
    rng = np.random.default_rng(11)
    for _ in range(300):
        ang = rng.uniform(0, 2 * math.pi)
        n = np.array([math.cos(ang), math.sin(ang)])
        v1, v2 = rng.normal(0, 1.5, 2), rng.normal(0, 0.5, 2)
        if (v1 - v2) @ n <= 0.05:
            continue
        w1, w2 = rng.normal(0, 60, 3), rng.normal(0, 20, 3)
        m2 = M * float(rng.uniform(0.7, 1.4))
        for mu_s in (0.2, 0.0):
            a1, b1, a2, b2 = mathavan(v1, w1, v2, w2, n, e=float(rng.uniform(0.5, 1)), m2=m2,
                                      mu_s=mu_s, steps=300)  # fmt: skip
            before = energy(M, v1, w1) + energy(m2, v2, w2)
            assert energy(M, a1, b1) + energy(m2, a2, b2) <= before * (1 + 1e-9)
            if mu_s == 0.0:
                np.testing.assert_allclose(M * a1 + m2 * a2, M * v1 + m2 * v2, atol=1e-12)


def test_mirror_symmetry():
    """Reflecting the scene across the x axis reflects the result (spins as axial vectors)."""
    n = (math.cos(0.5), math.sin(0.5))
    a = mathavan((1.2, 0.4), (5.0, -9.0, 30.0), (0.1, 0.0), (1.0, 2.0, -3.0), n)
    b = mathavan((1.2, -0.4), (-5.0, -9.0, -30.0), (0.1, 0.0), (-1.0, 2.0, 3.0), (n[0], -n[1]))
    for (va, wa), (vb, wb) in (((a[0], a[1]), (b[0], b[1])), ((a[2], a[3]), (b[2], b[3]))):
        np.testing.assert_allclose(vb, (va[0], -va[1]), atol=1e-13)
        np.testing.assert_allclose(wb, (-wa[0], wa[1], -wa[2]), atol=1e-10)


def test_a_table_option_that_changes_the_shot():
    """``ball_model="mathavan"`` reaches the kernel: a follow shot's distance changes."""
    pos = np.array([[0.6, 0.635], [1.2, 0.635]])
    runs = [
        shoot(Table(model="spin", pockets="none", ball_model=b), pos, 0.0, 1.0, 0, tip=(0, 0.5))
        for b in ("frictional", "mathavan")
    ]
    assert abs(runs[0].positions[0, 0] - runs[1].positions[0, 0]) > 1e-3
    with pytest.raises(ValueError, match="mathavan_steps must lie in"):
        Table(model="spin", ball_model="mathavan", mathavan_steps=0)
    with pytest.raises(ValueError, match="ball_model must be one of"):
        Table(model="spin", ball_model="stronge")
