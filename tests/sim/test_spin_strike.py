"""The cue strike kernel and the pooltool cue mapping against closed forms (TP A-30, A-31)."""

from __future__ import annotations

import doctest
import math
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from pool_env.sim import cue
from pool_env.sim.cue import POOLTOOL_CUE_MASS, from_pooltool
from pool_env.sim.kernels.spin.strike import cue_strike

R = 0.028575
M = 0.170097
TIP = 0.0106045
END = M / 30.0
WIDEN = 1.0 + TIP / R  # axis offset over contact offset
POOLTOOL = SimpleNamespace(ball_radius=R, ball_mass=M, cue_tip_radius=TIP)


def strike(speed, angle, a, b, elevation=0.0, m_end=END, r_tip=TIP):
    out = np.full(5, np.nan)
    cue_strike(speed, angle, a, b, elevation, R, M, m_end, r_tip, out)
    return out[0:2], out[2:5]


def slip(v, w):
    """The cloth contact's slip u = (vx - R wy, vy + R wx)."""
    return np.array([v[0] - R * w[1], v[1] + R * w[0]])


def squirt_deg(a_contact):
    rest = 1.0 - a_contact * a_contact
    return math.degrees(math.atan(2.5 * a_contact * math.sqrt(rest) / (1 + 30 + 2.5 * rest)))


def test_centre_hit_slides_without_spin():
    v, w = strike(2.0, 0.3, 0.0, 0.0)
    np.testing.assert_allclose(v, [2.0 * math.cos(0.3), 2.0 * math.sin(0.3)], rtol=1e-15)
    assert (w == 0.0).all()


@pytest.mark.parametrize("angle", [0.0, 1.0, -2.5])
def test_contact_at_two_fifths_radius_rolls_at_once(angle):
    """Contact b' = 0.4 (axis offset 0.4 (1 + r_tip / R)): w R = v, no slip at the cloth."""
    v, w = strike(1.7, angle, 0.0, 0.4 * WIDEN)
    assert np.abs(slip(v, w)).max() < 1e-15
    v, w = strike(1.7, angle, 0.0, 0.3 * WIDEN)  # lower: still sliding forward (stun-ish)
    forward = np.array([math.cos(angle), math.sin(angle)])
    assert slip(v, w) @ forward == pytest.approx(1.7 * (1 - 2.5 * 0.3), rel=1e-13)


def test_draw_spins_backwards_follow_forwards():
    for b, sign in ((-0.5, -1.0), (0.5, 1.0)):
        v, w = strike(1.0, 0.0, 0.0, b)
        assert v.tolist() == [1.0, 0.0]
        assert w[1] == pytest.approx(sign * 2.5 * 0.5 / WIDEN / R, rel=1e-14)


@pytest.mark.parametrize(("a_contact", "degrees"), [(0.3, 1.2), (0.5, 1.9), (0.7, 2.2)])
def test_squirt_figures(a_contact, degrees):
    """TP A-31 with m_end = m / 30; right english squirts the ball left (counter-clockwise)."""
    v, _ = strike(1.0, 0.0, a_contact * WIDEN, 0.0)
    alpha = math.degrees(math.atan2(v[1], v[0]))
    assert alpha == pytest.approx(squirt_deg(a_contact), abs=1e-12)
    assert round(alpha, 1) == degrees
    v, _ = strike(1.0, 0.0, -a_contact * WIDEN, 0.0)  # left english: to the right
    assert math.degrees(math.atan2(v[1], v[0])) == pytest.approx(-squirt_deg(a_contact), abs=1e-12)
    assert np.hypot(*v) == pytest.approx(1.0, rel=1e-15)


def cue_frame(angle, elevation):
    """Aim f, cue direction d, the cue's right s and up u as 3-vectors."""
    f = np.array([math.cos(angle), math.sin(angle), 0.0])
    z = np.array([0.0, 0.0, 1.0])
    d = math.cos(elevation) * f - math.sin(elevation) * z
    return f, d, np.cross(f, z), math.sin(elevation) * f + math.cos(elevation) * z


@given(
    speed=st.floats(0.01, 10.0),
    angle=st.floats(-math.pi, math.pi),
    a=st.floats(-1.0, 1.0),
    b=st.floats(-1.0, 1.0),
    elevation=st.floats(0.0, 1.4),
)
def test_spin_is_contact_cross_impulse_over_inertia(speed, angle, a, b, elevation):
    assume(a * a + b * b <= 1.0)  # API range (the contact point then lies on the ball)
    """Spin w = Q x J / I with Q on the ball's surface and J along the cue; in-plane speed kept."""
    v, w = strike(speed, angle, a, b, elevation)
    f, d, s, u = cue_frame(angle, elevation)
    ac, bc = a / WIDEN, b / WIDEN
    q = R * (ac * s + bc * u - math.sqrt(1.0 - ac * ac - bc * bc) * d)
    assert np.linalg.norm(q) == pytest.approx(R, rel=1e-12)
    impulse = M * (speed / math.cos(elevation)) * d  # V along the cue, V cos(e) = speed
    expected = np.cross(q, impulse) / (0.4 * M * R * R)
    scale = speed / math.cos(elevation) / R  # the spin's natural size
    np.testing.assert_allclose(w, expected, rtol=1e-11, atol=1e-13 * scale)
    assert np.hypot(*v) == pytest.approx(speed, rel=1e-14)
    # the velocity turns from the aim by the squirt only, towards the side away from english
    turn = math.atan2(f[0] * v[1] - f[1] * v[0], f[:2] @ v)
    assert turn == pytest.approx(math.radians(squirt_deg(ac)), abs=1e-12)


def test_elevated_side_english_spins_about_the_aim_line():
    """Masse: with elevation, side english gives w . f = (5 V / 2 R) a' sin(e)."""
    elevation = math.radians(60.0)
    _, w = strike(1.0, 0.0, 0.5, 0.0, elevation)
    assert w[0] == pytest.approx(
        2.5 * (1.0 / math.cos(elevation)) / R * 0.5 / WIDEN * math.sin(elevation)
    )
    assert w[2] == pytest.approx(2.5 / R * 0.5 / WIDEN, rel=1e-14)  # V cos(e) = speed


# --- from_pooltool ---------------------------------------------------------------------------


def pooltool_strike(V0, phi, theta, a, b):
    """The 2D InstantaneousPoint of pooltool 0.6.0 for its parameters, written out in its frame.

    Ball frame: x to the ball's left, y backwards along the cue, z up; ``v = 2 V0 / (1 + m/M +
    (5/2)(a^2 + b^2))``, ``w = (v / (2/5 R)) (b, a sin, -a cos)``, then a turn by
    ``phi + 90 deg``; squirt ``-atan(...)`` turns the velocity only.
    """
    t, p = math.radians(theta), math.radians(phi)
    v = 2 * V0 / (1 + M / POOLTOOL_CUE_MASS + 2.5 * (a * a + b * b))
    vb = np.array([0.0, -v * math.cos(t)])
    wb = v / (0.4 * R) * np.array([b, a * math.sin(t), -a * math.cos(t)])
    turn = p + math.pi / 2
    rot = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
    alpha = -math.radians(squirt_deg(a))
    rot_squirt = np.array([[math.cos(alpha), -math.sin(alpha)], [math.sin(alpha), math.cos(alpha)]])
    return rot_squirt @ rot @ vb, np.array([*(rot @ wb[:2]), wb[2]])


@pytest.mark.parametrize(
    "shot",
    [(2.0, 90.0, 0.0, 0.0, 0.25), (3.5, 17.0, 0.0, 0.3, -0.4), (1.0, 200.0, 35.0, -0.5, 0.1)],
)
def test_from_pooltool_ports_a_shot_exactly(shot):
    angle, speed, tip, elevation = from_pooltool(*shot, table=POOLTOOL)
    v, w = strike(speed, angle, tip[0], tip[1], elevation)
    v_pt, w_pt = pooltool_strike(*shot)
    np.testing.assert_allclose(v, v_pt, rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(w, w_pt, rtol=1e-12, atol=1e-12)


@given(
    v0=st.floats(0.05, 10.0),
    phi=st.floats(-720.0, 720.0),
    theta=st.floats(0.0, 85.0),
    radius=st.floats(0.0, 0.72),
    turn=st.floats(0.0, 2 * math.pi),
)
def test_from_pooltool_ports_random_shots(v0, phi, theta, radius, turn):
    shot = (v0, phi, theta, radius * math.cos(turn), radius * math.sin(turn))
    angle, speed, tip, elevation = from_pooltool(*shot, table=POOLTOOL)
    v, w = strike(speed, angle, tip[0], tip[1], elevation)
    v_pt, w_pt = pooltool_strike(*shot)
    np.testing.assert_allclose(v, v_pt, rtol=1e-12, atol=1e-13 * v0)
    np.testing.assert_allclose(w, w_pt, rtol=1e-11, atol=1e-11 * v0 / R / math.cos(elevation))


def test_from_pooltool_centre_hit_is_1_54_times_the_stick_speed():
    _, speed, tip, elevation = from_pooltool(1.0, 0.0, 0.0, 0.0, 0.0, table=POOLTOOL)
    assert speed == pytest.approx(2.0 / (1.0 + M / 0.567), rel=1e-15)
    assert round(speed, 2) == 1.54 and tip == (0.0, 0.0) and elevation == 0.0


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ((0.0, 0, 0, 0, 0), "V0"),
        ((-1.0, 0, 0, 0, 0), "V0"),
        ((math.nan, 0, 0, 0, 0), "V0"),
        ((1.0, math.inf, 0, 0, 0), "phi"),
        ((1.0, 0, 90.0, 0, 0), "theta"),
        ((1.0, 0, -1.0, 0, 0), "theta"),
        ((1.0, 0, 0, "0.1", 0), "a"),
        ((1.0, 0, 0, 0, True), "b"),
        ((1.0, 0, 0, 0.8, 0.7), "on the ball"),
        ((1.0, 0, 0, 0.0, 0.75), "outside"),
    ],
)
def test_from_pooltool_rejects_bad_input(args, message):
    with pytest.raises(ValueError, match=message):
        from_pooltool(*args, table=POOLTOOL)


def test_from_pooltool_rejects_a_bad_cue_mass():
    with pytest.raises(ValueError, match="cue_mass"):
        from_pooltool(1.0, 0.0, 0.0, 0.0, 0.0, table=POOLTOOL, cue_mass=0.0)


def test_from_pooltool_reads_a_spin_table():
    """The default table and a given one: their ball mass, radius and tip radius are used."""
    from pool_env import Table

    if "cue_tip_radius" not in Table.__dataclass_fields__:
        pytest.skip("Table(model='spin') comes with the spin loop (branch spin)")
    table = Table(model="spin", ball_mass=M, ball_radius=R, cue_tip_radius=TIP)
    assert from_pooltool(2.0, 30.0, 10.0, 0.2, -0.3, table) == from_pooltool(
        2.0, 30.0, 10.0, 0.2, -0.3, table=POOLTOOL
    )
    default = Table(model="spin")
    _, speed, tip, _ = from_pooltool(1.0, 0.0, 0.0, 0.0, 0.3)
    assert tip[1] == pytest.approx(0.3 * (1 + default.cue_tip_radius / default.ball_radius))
    assert speed == pytest.approx(2.0 / (1 + default.ball_mass / 0.567 + 2.5 * 0.09))


def test_from_pooltool_docstring_example_holds():
    assert doctest.testmod(cue, raise_on_error=True).attempted >= 1
