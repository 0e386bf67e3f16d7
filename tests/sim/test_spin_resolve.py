"""The ball-ball impact kernel with spin against closed forms and laws: throw, 30/90 rules.

Each closed form is derived in ``spin_collide``'s module docstring; here they are written out
again independently, in the frame of the impact. The cushion: ``test_spin_cushion.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from pool_env.sim.kernels.spin.collide import ball_ball_spin
from pool_env.sim.kernels.spin.params import (
    ALCIATORE_FRICTION,
    CONSTANT_FRICTION,
    FRICTIONLESS,
    POOLTOOL_FRICTION,
)

R = 0.028575
M = 0.170097


def collide(v1, w1, v2, w2, n, m1=M, m2=M, e=0.95, mode=ALCIATORE_FRICTION, mu=0.0):
    """The kernel's result as (v1', w1', v2', w2') numpy vectors (v 2D, w 3D)."""
    out = np.full(10, np.nan)
    ball_ball_spin(*v1, *w1, *v2, *w2, *n, m1, m2, R, e, mode, mu, out)
    return out[0:2], out[2:5], out[5:7], out[7:10]


def unit(angle):
    return np.array([math.cos(angle), math.sin(angle)])


def alciatore(slip):
    return 9.951e-3 + 0.108 * math.exp(-1.088 * slip)


def energy(m, v, w):
    return 0.5 * m * float(v @ v) + 0.5 * 0.4 * m * R * R * float(w @ w)


def stun_throw(speed, cut, e):
    """The object ball's throw (deg) off the line of centres for a stun cue ball (closed form).

    Ball 2 leaves with ``(1 + e) v cos(cut) / 2`` along ``n`` and, along the tangent,
    ``min(mu (1 + e) v cos / 2, v sin / 7)``; mu from the slip speed ``v sin(cut)``.
    """
    mu = alciatore(speed * math.sin(cut))
    return math.degrees(math.atan(min(mu, 2.0 * math.tan(cut) / (7.0 * (1.0 + e)))))


def object_ball_throw(speed, cut, e=0.95):
    """The kernel's throw (deg) of ball 2 for a stun cue ball along +x and cut ``cut``."""
    _, _, v2, _ = collide((speed, 0.0), (0, 0, 0), (0, 0), (0, 0, 0), unit(cut), e=e)
    return cut - math.atan2(v2[1], v2[0])


# --- ball-ball ---------------------------------------------------------------------------


def test_frictionless_is_the_textbook_exchange_and_keeps_spins():
    """Mode 0: normal components exchanged with restitution, tangents and spins untouched."""
    n = unit(0.7)
    v1, v2 = np.array([1.3, -0.4]), np.array([-0.2, 0.5])
    w1, w2 = np.array([3.0, -7.0, 11.0]), np.array([-5.0, 2.0, -13.0])
    m1, m2, e = 0.17, 0.23, 0.8
    a, b, c, d = collide(v1, w1, v2, w2, n, m1, m2, e, FRICTIONLESS, 0.5)
    u1, u2 = v1 @ n, v2 @ n
    u1_new = (m1 * u1 + m2 * u2 + m2 * e * (u2 - u1)) / (m1 + m2)
    u2_new = (m1 * u1 + m2 * u2 + m1 * e * (u1 - u2)) / (m1 + m2)
    np.testing.assert_allclose(a, v1 + (u1_new - u1) * n, rtol=0, atol=1e-15)
    np.testing.assert_allclose(c, v2 + (u2_new - u2) * n, rtol=0, atol=1e-15)
    assert (b == w1).all() and (d == w2).all()


def test_equal_masses_elastic_frictionless_swap_normal_components():
    _, _, v2, _ = collide((2.0, 0.0), (0, 0, 0), (0, 0), (0, 0, 0), (1.0, 0.0), e=1.0, mode=0)
    v1, _, _, _ = collide((2.0, 0.0), (0, 0, 0), (0, 0), (0, 0, 0), (1.0, 0.0), e=1.0, mode=0)
    assert v1.tolist() == [0.0, 0.0] and v2.tolist() == [2.0, 0.0]


@pytest.mark.parametrize("speed", [0.2, 0.5, 1.0, 2.0, 4.0])
@pytest.mark.parametrize("cut_deg", [1.0, 10.0, 20.0, 30.0, 45.0, 60.0, 80.0])
def test_stun_throw_matches_the_closed_form(speed, cut_deg):
    cut = math.radians(cut_deg)
    expected = stun_throw(speed, cut, 0.95)
    assert math.degrees(object_ball_throw(speed, cut)) == pytest.approx(expected, abs=1e-10)


@pytest.mark.parametrize(
    ("speed", "spin_md", "cut_deg"),
    [(0.2, 6.0, 35.7), (0.5, 5.2, 31.8), (1.0, 4.3, 27.3), (2.0, 3.3, 21.7), (4.0, 2.4, 16.1)],
)
def test_maximum_throw_against_speed_is_spin_md_curve(speed, spin_md, cut_deg):
    """The derived curve of docs/sources.md (max throw over the cut), to 0.1 degree, and its peak.

    The peak is where friction stops sticking, ``mu(v sin) = 2 tan / (7 (1 + e))``.
    """
    cuts = np.radians(np.linspace(0.5, 89.5, 17801))
    throws = [math.degrees(object_ball_throw(speed, c)) for c in cuts]
    best = int(np.argmax(throws))
    assert round(throws[best], 1) == spin_md
    assert math.degrees(cuts[best]) == pytest.approx(cut_deg, abs=0.1)


@pytest.mark.parametrize(
    ("speed", "maximum"), [(0.2, 5.857), (0.5, 5.088), (1.0, 4.238), (2.0, 3.281), (4.0, 2.387)]
)
def test_pooltool_mode_gives_pooltool_throw(speed, maximum):
    """Mode 3: pooltool's impulse mu e c, so its maximum throw is below the Coulomb curve's.

    Closed form ``atan(min(mu e v cos, v sin / 7) / ((1 + e) v cos / 2))``; the maxima are
    the figures pooltool 0.6.0's FrictionalInelastic gives (derived from its formulas).
    """
    e = 0.95
    best = 0.0
    for cut in np.radians(np.linspace(0.5, 89.5, 17801)):
        _, _, v2, _ = collide(
            (speed, 0.0), (0, 0, 0), (0, 0), (0, 0, 0), unit(cut), mode=POOLTOOL_FRICTION
        )
        throw = math.degrees(cut - math.atan2(v2[1], v2[0]))
        mu = alciatore(speed * math.sin(cut))
        tangent = min(mu * e * math.cos(cut), math.sin(cut) / 7)
        assert throw == pytest.approx(
            math.degrees(math.atan(tangent / ((1 + e) / 2 * math.cos(cut)))), abs=1e-10
        )
        best = max(best, throw)
    assert best == pytest.approx(maximum, abs=1e-3)
    _, _, same, _ = collide(
        (speed, 0.0), (0, 0, 30.0), (0, 0), (0, 0, 0), unit(0.3), e=1.0, mode=POOLTOOL_FRICTION
    )
    _, _, ref, _ = collide((speed, 0.0), (0, 0, 30.0), (0, 0), (0, 0, 0), unit(0.3), e=1.0)
    assert (same == ref).all()  # the two agree at e = 1


@pytest.mark.parametrize(("m1", "m2"), [(M, M), (0.1, 0.4), (0.5, 0.05)])
def test_throw_is_capped_at_the_no_slip_result(m1, m2):
    """A huge mu gives the sticking result: ball 2's contact point moves with ball 1's."""
    v1, w1, v2, w2 = np.array([1.5, 0.2]), np.zeros(3), np.zeros(2), np.zeros(3)
    n = unit(0.5)
    a, b, c, d = collide(v1, w1, v2, w2, n, m1, m2, mode=CONSTANT_FRICTION, mu=1e3)
    n3 = np.array([*n, 0.0])
    slip = (np.array([*a, 0.0]) + np.cross(b, R * n3)) - (np.array([*c, 0.0]) - np.cross(d, R * n3))
    slip -= (slip @ n3) * n3
    assert np.abs(slip).max() < 1e-14
    # and the sticking impulse is (2/7) mu_r |s| (|s| m / 7 for equal masses)
    tangent = np.array([-n[1], n[0]])
    reduced = m1 * m2 / (m1 + m2)
    assert (c @ tangent) * m2 == pytest.approx((v1 @ tangent) * 2 / 7 * reduced, rel=1e-13)


def test_sliding_friction_is_coulomb_with_the_normal_impulse():
    """Friction mu |J_n| (not pooltool's mu e_b c): ball 2 takes mu (1 + e) c / 2 sideways."""
    n = unit(1.2)  # a thin cut: sliding throughout
    v1 = np.array([1.0, 0.0])
    mu, e = 0.06, 0.5
    _, _, c, _ = collide(
        v1, np.zeros(3), np.zeros(2), np.zeros(3), n, e=e, mode=CONSTANT_FRICTION, mu=mu
    )
    tangent = np.array([n[1], -n[0]])  # the direction of ball 1's tangential motion
    assert c @ tangent == pytest.approx(mu * (1 + e) * (v1 @ n) / 2, rel=1e-13)


def test_side_english_throws_the_object_ball_the_other_way():
    """A full hit with right english (wz > 0) throws ball 2 left, the spin goes with it.

    Ball 1's front spins at ``R wz`` to the left (+y); ball 2 takes
    ``min(mu (1 + e) v / 2, R wz / 7)`` of it and the same ``wz`` change as ball 1.
    """
    speed, wz, e = 1.0, 40.0, 0.95
    _, w1, v2, w2 = collide((speed, 0.0), (0, 0, wz), (0, 0), (0, 0, 0), (1.0, 0.0), e=e)
    kick = min(alciatore(R * wz) * (1 + e) * speed / 2, R * wz / 7)
    assert v2[1] == pytest.approx(kick, rel=1e-13) and v2[1] > 0.0
    assert w2[2] == pytest.approx(-2.5 * kick / R, rel=1e-13)
    assert w1[2] - wz == pytest.approx(w2[2], rel=1e-13)


def test_full_hit_with_follow_rubs_the_vertical_slip():
    """A rolling cue ball's front turns downwards at ``v``: friction ``min(mu J_n, m v / 7)``.

    It acts upwards on ball 1 (the vertical velocities are dropped) and takes
    ``(5 / (2 m R)) T_z`` of topspin from both balls about ``y``; ``wz`` and the in-plane
    tangent stay zero.
    """
    speed, e = 1.5, 0.95
    f = np.array([1.0, 0.0])
    v1, w1, v2, w2 = collide(speed * f, rolling(speed, f), (0, 0), (0, 0, 0), f, e=e)
    lift = min(alciatore(speed) * (1 + e) * speed / 2, speed / 7)  # T_z / m
    assert w1[1] == pytest.approx(speed / R - 2.5 * lift / R, rel=1e-13)
    assert w2[1] == pytest.approx(-2.5 * lift / R, rel=1e-13)
    assert v1[1] == v2[1] == 0.0 and w1[2] == w2[2] == 0.0
    assert v2[0] == pytest.approx((1 + e) * speed / 2, rel=1e-15)


def rolling(speed, direction):
    """Spin of a ball rolling at ``speed`` along ``direction``: w = (v / R) z x f."""
    return np.array([-direction[1], direction[0], 0.0]) * speed / R


def roll_velocity(v, w):
    """The velocity a sliding ball rolls at once its slide ends: v - (2/7) u (closed form)."""
    u = np.array([v[0] - R * w[1], v[1] + R * w[0]])
    return v - (2.0 / 7.0) * u


@pytest.mark.parametrize("cut_deg", [5.0, 14.5, 28.0, 30.0, 48.6, 60.0, 85.0])
@pytest.mark.parametrize("speed", [0.3, 2.0])
def test_thirty_degree_rule(cut_deg, speed):
    """A rolling cue ball, frictionless elastic equal balls: deflection atan[sc / (s^2 + 2/5)]."""
    cut = math.radians(cut_deg)
    f = np.array([1.0, 0.0])
    v1, w1, _, _ = collide(
        speed * f, rolling(speed, f), (0, 0), (0, 0, 0), unit(cut), e=1.0, mode=0
    )
    final = roll_velocity(v1, w1)
    deflection = math.atan2(-final[1], final[0])
    s, c = math.sin(cut), math.cos(cut)
    assert deflection == pytest.approx(math.atan(s * c / (s * s + 0.4)), abs=1e-12)


def test_thirty_degree_rule_maximum_is_33_7_at_28_deg():
    cut = math.atan(math.sqrt(2.0 / 7.0))  # the maximum of atan[sc / (s^2 + 2/5)]
    f = np.array([1.0, 0.0])
    v1, w1, _, _ = collide(f, rolling(1.0, f), (0, 0), (0, 0, 0), unit(cut), e=1.0, mode=0)
    final = roll_velocity(v1, w1)
    assert math.degrees(cut) == pytest.approx(28.13, abs=0.01)
    assert math.degrees(math.atan2(-final[1], final[0])) == pytest.approx(33.75, abs=0.01)


@pytest.mark.parametrize("cut_deg", [10.0, 45.0, 70.0])
def test_ninety_degree_rule_for_a_stun_ball(cut_deg):
    """A stun cue ball leaves along the tangent line and keeps it when it starts rolling."""
    n = unit(math.radians(cut_deg))
    v1, w1, v2, _ = collide((1.0, 0.0), (0, 0, 0), (0, 0), (0, 0, 0), n, e=1.0, mode=0)
    assert abs(v1 @ v2) < 1e-16 and (w1 == 0).all()
    final = roll_velocity(v1, w1)
    assert abs(final @ v2) < 1e-16
    np.testing.assert_allclose(final, (5.0 / 7.0) * v1, rtol=1e-15)


finite = st.floats(-8.0, 8.0, allow_nan=False)
spins = st.floats(-300.0, 300.0, allow_nan=False)


@given(
    v=st.tuples(finite, finite, finite, finite),
    w=st.tuples(spins, spins, spins, spins, spins, spins),
    angle=st.floats(-math.pi, math.pi),
    m1=st.floats(0.01, 1.0),
    m2=st.floats(0.01, 1.0),
    e=st.floats(0.0, 1.0),
    mode=st.sampled_from([FRICTIONLESS, CONSTANT_FRICTION, ALCIATORE_FRICTION]),
    mu=st.floats(0.0, 2.0),
)
def test_ball_ball_laws(v, w, angle, m1, m2, e, mode, mu):
    """Momentum conserved, energy never gained, friction bounded by mu J_n and by sticking."""
    n = unit(angle)
    v1, v2 = np.array(v[:2]), np.array(v[2:])
    w1, w2 = np.array(w[:3]), np.array(w[3:])
    a, b, c, d = collide(v1, w1, v2, w2, n, m1, m2, e, mode, mu)
    scale = m1 * np.abs(v1).max() + m2 * np.abs(v2).max() + 1e-300
    np.testing.assert_allclose(m1 * a + m2 * c, m1 * v1 + m2 * v2, rtol=0, atol=4e-16 * scale)
    before = energy(m1, v1, w1) + energy(m2, v2, w2)
    assert energy(m1, a, b) + energy(m2, c, d) <= before * (1 + 1e-13) + 1e-300
    approach = (v1 - v2) @ n
    if approach <= 0.0:
        assert (a == v1).all() and (c == v2).all() and (b == w1).all() and (d == w2).all()
        return
    # the spins change by R n x T / I_k: the same torque on both, none about n
    torque1, torque2 = (b - w1) * m1, (d - w2) * m2
    np.testing.assert_allclose(torque1, torque2, atol=1e-12 * (np.abs(torque1).max() + 1))
    assert abs(torque1[:2] @ n) <= 1e-12 * (np.abs(torque1).max() + 1)
    # normal exchange with restitution
    assert (c - a) @ n == pytest.approx(e * approach, rel=1e-9, abs=1e-12)


def test_frame_rotation_rotates_the_result():
    v1, w1 = np.array([1.1, 0.3]), np.array([5.0, -20.0, 30.0])
    n = unit(0.4)
    base = collide(v1, w1, (0, 0), (0, 0, 0), n)
    turn = 1.1
    rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
    rot3 = np.eye(3)
    rot3[:2, :2] = rot
    turned = collide(rot @ v1, rot3 @ w1, (0, 0), (0, 0, 0), rot @ n)
    for got, ref in zip(turned, base, strict=True):
        expected = (rot if got.size == 2 else rot3) @ ref
        np.testing.assert_allclose(got, expected, atol=1e-13)
