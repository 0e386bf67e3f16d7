"""Mathavan's ball-ball model against the limits where it has a closed form, and its laws."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from pool_env import Table, shoot
from pool_env.sim.kernels.spin.collide import ALCIATORE_A, ALCIATORE_B, ball_ball_spin
from pool_env.sim.kernels.spin.mathavan import ball_ball_mathavan
from pool_env.sim.kernels.spin.params import (
    ALCIATORE_FRICTION,
    CONSTANT_FRICTION,
    FRICTIONLESS,
    POOLTOOL_FRICTION,
)

R, M = 0.028575, 0.170097


def mathavan(v1, w1, v2, w2, n, e=0.95, mode=ALCIATORE_FRICTION, mu=0.0, mu_s=0.2, steps=1000,
             m1=M, m2=M):  # fmt: skip
    """The kernel's result as (v1', w1', v2', w2')."""
    out = np.full(10, np.nan)
    ball_ball_mathavan(*v1, *w1, *v2, *w2, *n, m1, m2, R, e, mode, mu, mu_s, steps, out)
    return out[0:2], out[2:5], out[5:7], out[7:10]


def energy(m, v, w):
    return 0.5 * m * float(v @ v) + 0.2 * m * R * R * float(w @ w)


@pytest.mark.parametrize("steps", [1, 2, 7, 1000])
@pytest.mark.parametrize("e", [1.0, 0.95, 0.5, 0.0])
def test_frictionless_impact_restores_e_times_the_approach(e, steps):
    """No friction: Newton's restitution on the line of centres, exactly at any step count.

    The last step of each phase is the exact part of a step that ends it (pooltool's
    integration overshoots by up to a step: a 2 m/s hit at ``N = 1`` left at 3.9 m/s).
    """
    n = np.array([math.cos(0.4), math.sin(0.4)])
    v1, v2 = np.array([1.7, 0.9]), np.array([-0.2, 0.1])
    c = float((v1 - v2) @ n)
    a1, _, a2, _ = mathavan(v1, (3.0, -2.0, 40.0), v2, (0, 0, 0), n, e=e, mode=FRICTIONLESS,
                            steps=steps)  # fmt: skip
    assert float((a2 - a1) @ n) == pytest.approx(e * c, rel=1e-12, abs=1e-14)
    t = np.array([-n[1], n[0]])  # no tangential exchange without friction
    assert float(a1 @ t) == pytest.approx(float(v1 @ t), abs=1e-14)
    np.testing.assert_allclose(a1 + a2, v1 + v2, rtol=0, atol=1e-13)  # equal masses


@pytest.mark.parametrize("steps", [1, 2, 10])
def test_a_centre_hit_at_few_steps_gains_nothing(steps):
    """The issue's shot: a 2 m/s centre hit on a resting ball, ``N = 1``: 0.05 and 1.95 m/s."""
    a1, b1, a2, b2 = mathavan((2.0, 0.0), (0, 0, 0), (0, 0), (0, 0, 0), (1.0, 0.0), steps=steps)
    np.testing.assert_allclose([a1[0], a2[0]], [0.05, 1.95], rtol=1e-12)
    assert energy(M, a1, b1) + energy(M, a2, b2) <= energy(M, np.array([2.0, 0.0]), np.zeros(3))


def test_the_cloth_friction_opposes_the_cloth_slip():
    """The pressed ball's cloth friction slows its own slip ``(v_x - R w_y, v_y + R w_x)``.

    Ball i rolls into j (its top spin drags the balls' contact down: j is pressed, and its
    cloth friction acts). j slides sideways (``+x`` in the impact's frame, its slip
    ``v_x - R w_y`` positive); the model's cloth friction on j must point to ``-x``, so j's
    sideways speed drops and its spin ``w_y`` grows (pooltool's slip ``v_x + R w_y`` is
    zero here: it applies none).
    """
    speed, side = 1.5, 0.4
    n = np.array([0.0, 1.0])  # local x = +x of the table, y = n
    v1, w1 = np.array([0.0, speed]), (-speed / R, 0.0, 0.0)  # rolling along n
    v2, w2 = np.array([side, 0.0]), (0.0, -side / R, 0.0)  # pooltool's slip: side - side = 0
    _, _, a2, b2 = mathavan(v1, w1, v2, w2, n, e=1.0, mode=CONSTANT_FRICTION, mu=0.1, mu_s=0.5)
    frictionless_table = mathavan(v1, w1, v2, w2, n, e=1.0, mode=CONSTANT_FRICTION, mu=0.1,
                                  mu_s=0.0)  # fmt: skip
    assert a2[0] < frictionless_table[2][0] - 1e-3  # slowed sideways
    assert b2[1] > frictionless_table[3][1] + 1e-3 / R  # its spin w_y turned toward rolling


@pytest.mark.parametrize("steps", [1000, 64391, 300000])
def test_an_elastic_impact_keeps_its_energy_to_rounding_at_any_step_count(steps):
    """Elastic, frictionless: the energy to ~1 rounding, whatever the steps and masses.

    The fuzz's case (issue 49): a 15 kg ball on a 1.9 g one at 2.3 m/s, 64,391 steps. Summed
    step by step into the heavy ball's velocity, the roundings moved the energy by 1.2e-12
    of it; the impact's changes are summed from zero, compensated.
    """
    rng = np.random.default_rng(steps)
    m1, m2 = 15.23, 0.0019
    for _ in range(5):
        ang = rng.uniform(0, 2 * math.pi)
        n = np.array([math.cos(ang), math.sin(ang)])
        v1, w1, w2 = 2.29 * n + rng.normal(0, 0.3, 2), rng.normal(0, 30, 3), rng.normal(0, 30, 3)
        out = np.full(10, np.nan)
        ball_ball_mathavan(*v1, *w1, 0, 0, *w2, *n, m1, m2, R, 1.0, FRICTIONLESS, 0.0, 0.2,
                           steps, out)  # fmt: skip
        before = energy(m1, v1, w1) + energy(m2, np.zeros(2), w2)
        after = energy(m1, out[0:2], out[2:5]) + energy(m2, out[5:7], out[7:10])
        assert after == pytest.approx(before, rel=1e-14)


def _impact(draw):
    """A random approaching pair (velocities, spins, normal) of equal or unequal masses."""
    floats = st.floats(-3.0, 3.0)
    ang = draw(st.floats(0.0, 2 * math.pi))
    n = np.array([math.cos(ang), math.sin(ang)])
    v1 = np.array([draw(floats), draw(floats)])
    v2 = np.array([draw(floats), draw(floats)])
    spins = st.floats(-150.0, 150.0)
    w1 = np.array([draw(spins) for _ in range(3)])
    w2 = np.array([draw(spins) for _ in range(3)])
    return v1, w1, v2, w2, n


@st.composite
def impacts(draw):
    """An impact of the model with random parameters over its accepted ranges."""
    v1, w1, v2, w2, n = _impact(draw)
    if (v1 - v2) @ n < 1e-3:  # an approach (the kernel leaves a separating pair alone)
        v1 = v1 + (1e-3 - (v1 - v2) @ n + draw(st.floats(0.0, 3.0))) * n
    mode = draw(st.sampled_from([FRICTIONLESS, CONSTANT_FRICTION, ALCIATORE_FRICTION,
                                 POOLTOOL_FRICTION]))  # fmt: skip
    mu = draw(st.floats(0.0, 1.0)) if mode == CONSTANT_FRICTION else 0.0
    mu_b = mu if mode == CONSTANT_FRICTION else ALCIATORE_A + ALCIATORE_B
    mu_s = draw(st.floats(0.0, min(2.0, 1.0 / max(mu_b, 1e-9))))  # Table's mu_s mu_b <= 1
    steps = draw(st.one_of(st.integers(1, 12), st.integers(1, 1000), st.just(1000)))
    e = draw(st.one_of(st.just(1.0), st.just(0.0), st.floats(0.0, 1.0)))
    m2 = draw(st.sampled_from([M, M * 0.7, M * 1.4]))
    return v1, w1, v2, w2, n, e, mode, mu, mu_s, steps, m2


@given(impacts())
def test_no_energy_is_gained_at_any_step_count(impact):
    """Kinetic energy, translation and spin, never rises; e = 1 and no friction keep it.

    Steps 1-1000, restitution in [0, 1] (1 included), every friction mode, cloth friction up
    to ``Table``'s bound ``mu_s mu_b <= 1``. The balls leave the impact separating, and
    without cloth friction the momentum is kept.
    """
    v1, w1, v2, w2, n, e, mode, mu, mu_s, steps, m2 = impact
    a1, b1, a2, b2 = mathavan(v1, w1, v2, w2, n, e=e, mode=mode, mu=mu, mu_s=mu_s, steps=steps,
                              m2=m2)  # fmt: skip
    before = energy(M, v1, w1) + energy(m2, v2, w2)
    after = energy(M, a1, b1) + energy(m2, a2, b2)
    assert after <= before * (1.0 + 1e-13)
    assert float((a2 - a1) @ n) >= -1e-12 * float(np.abs((v1 - v2) @ n))  # they part
    if mu_s == 0.0 or mode == FRICTIONLESS:
        np.testing.assert_allclose(M * a1 + m2 * a2, M * v1 + m2 * v2, rtol=0, atol=1e-12)
    if mode == FRICTIONLESS and e == 1.0:
        assert after == pytest.approx(before, rel=1e-13)


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


def test_a_table_whose_cloth_friction_could_stall_the_impact_is_refused():
    """``mu_slide`` times the largest ball-ball friction above 1: refused, named."""
    Table(model="spin", ball_model="mathavan", ball_friction=0.5, mu_slide=2.0)  # the edge
    with pytest.raises(ValueError, match=r"mu_slide \* ball_friction <= 1.*mu_slide=2.5"):
        Table(model="spin", ball_model="mathavan", ball_friction=0.5, mu_slide=2.5)
    with pytest.raises(ValueError, match="ball_friction='alciatore'"):
        Table(model="spin", ball_model="mathavan", mu_slide=9.0)
    Table(model="spin", ball_model="frictional", mu_slide=9.0)  # the other model: no bound
