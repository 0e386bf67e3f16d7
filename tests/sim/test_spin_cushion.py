"""The Han 2005 cushion kernel against its closed forms and laws (``spin_cushion``).

The rail-frame closed forms derived in the kernel's module docstring are written out again
here (:func:`han_rail_frame`) and checked at any orientation of the cushion.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from pool_env.sim.kernels.spin.cushion import cushion_han
from tests.sim.test_spin_resolve import R, energy, finite, spins, unit

H = 1.27 * R  # the WPA nose height, 63.5 % of the ball's diameter


def bounce(v, w, n=(-1.0, 0.0), h=H, e=0.85, f=0.2):
    """The kernel's result as (v', w'); the default cushion is a rail at +x (normal -x)."""
    out = np.full(5, np.nan)
    cushion_han(*v, *w, *n, R, h, e, f, out)
    return out[0:2], out[2:5]


def han_rail_frame(vx, vy, wx, wy, wz, h, e, f):
    """Han's eqs. 24 and 25 in the rail frame (x into the cushion), written out."""
    st_, ct = h / R - 1.0, math.sqrt(1.0 - (h / R - 1.0) ** 2)
    s_y = vy + R * (wz * ct - wx * st_)
    s_t = -(vx * st_ + R * wy)
    slip = math.hypot(s_y, s_t)
    if 2.0 / 7.0 * slip <= f * (1 + e) * vx * ct:  # sticking
        vx_new = vx * (1 - (1 + e) * ct * ct - 2 / 7 * st_ * st_) - 2 / 7 * R * wy * st_
        vy_new = 5 / 7 * vy - 2 / 7 * R * (wz * ct - wx * st_)
    else:
        k = f * (1 + e) * vx * ct / slip
        vx_new = vx * (1 - (1 + e) * ct * ct) - k * st_ * (vx * st_ + R * wy)
        vy_new = vy - k * s_y
    return vx_new, vy_new


def test_head_on_stun_ball_rebounds_with_the_closed_form():
    """Sticks (tan theta <= 3.5 f (1 + e)); speed [(1+e) cos^2 + (2/7) sin^2 - 1] v, topspin."""
    sin_t = H / R - 1.0
    cos2 = 1.0 - sin_t * sin_t
    v, w = bounce((2.0, 0.0), (0, 0, 0))
    factor = 1.85 * cos2 + 2.0 / 7.0 * sin_t * sin_t - 1.0
    assert factor == pytest.approx(0.735964, abs=1e-6)
    np.testing.assert_allclose(v, [-2.0 * factor, 0.0], rtol=1e-15, atol=1e-16)
    # topspin for the way back (-x): w = (v / R) z x f has wy < 0
    np.testing.assert_allclose(w, [0.0, -5.0 / 7.0 * 2.0 / R * sin_t, 0.0], rtol=1e-14, atol=1e-13)


def test_equator_contact_without_friction_is_the_textbook_reflection():
    """Contact at the equator, f_c = 0: v_n -> -e v_n, tangent and spin kept; e = 1 keeps angles."""
    v, w = bounce((1.2, 0.7), (3.0, -4.0, 5.0), h=R, e=1.0, f=0.0)
    np.testing.assert_allclose(v, [-1.2, 0.7], rtol=1e-15)
    np.testing.assert_allclose(w, [3.0, -4.0, 5.0], rtol=0)
    v, _ = bounce((1.2, 0.7), (0, 0, 0), h=R, e=0.6, f=0.0)
    np.testing.assert_allclose(v, [-0.72, 0.7], rtol=1e-15)


def test_a_ball_han_leaves_moving_into_the_cushion_slides_along_it():
    """e_c = 0 at h = 1.27 R: Han leaves vx sin^2(theta) into the cushion; it becomes 0."""
    v, w = bounce((1.0, 0.5), (0, 0, 0), e=0.0, f=0.0)
    assert v.tolist() == [0.0, 0.5] and (w == 0).all()
    v, _ = bounce((1.0, 0.5), (0, 0, 0), e=0.1, f=0.0)  # (1 + e) cos^2 > 1: Han's own rebound
    sin_t = H / R - 1.0
    assert v[0] == pytest.approx(1.0 - 1.1 * (1 - sin_t * sin_t), rel=1e-14) and v[0] < 0.0


def rebound_angle(wz):
    """Rebound angle (deg) off the normal of a 45-degree shot at the rail, spin wz."""
    v, _ = bounce((1.0, 1.0), (0.0, 0.0, wz))
    return math.degrees(math.atan2(v[1], -v[0]))


def test_running_english_widens_the_rebound_and_reverse_narrows_it():
    """Moving +x +y into the +x rail, running english is wz < 0 here (its contact slips less)."""
    plain = rebound_angle(0.0)
    assert rebound_angle(-30.0) > plain > rebound_angle(30.0)
    # natural (rolling-matched) running english: no slip along the rail, vy kept
    sin_t = H / R - 1.0
    matched = -1.0 / (R * math.sqrt(1 - sin_t * sin_t))
    v, _ = bounce((1.0, 1.0), (0.0, 0.0, matched))
    assert v[1] == pytest.approx(1.0, rel=1e-12)


@pytest.mark.parametrize("f", [0.0, 0.05, 0.2, 1.0])
@pytest.mark.parametrize(
    "state",
    [(1.0, 0.0, 0, 0, 0), (1.0, 1.0, 0, 0, 0), (2.0, -0.5, 10, 40, -60), (0.3, 2.0, 0, -20, 90)],
)
def test_han_matches_its_rail_frame_closed_forms(f, state):
    for h in (R, H, 1.4 * R):
        v, _ = bounce(state[:2], state[2:], h=h, f=f)
        np.testing.assert_allclose(v, han_rail_frame(*state, h, 0.85, f), rtol=1e-12, atol=1e-14)


def test_slip_stick_boundary_carries_mu():
    """Just past (2/7)|s| = f (1 + e) c the contact slides; the boundary without f would not."""
    sin_t = H / R - 1.0
    cos_t = math.sqrt(1 - sin_t * sin_t)
    vx, vy, e = 1.0, 1.0, 0.85
    wy = -vx * sin_t / R  # removes the vertical slip, so |s| = |vy|
    f = 0.99 * (2.0 / 7.0) * vy / ((1 + e) * vx * cos_t)  # sliding, barely
    v, _ = bounce((vx, vy), (0.0, wy, 0.0), f=f, e=e)
    # sliding: vy' = vy - f (1 + e) c, not the sticking (5/7) vy
    assert v[1] == pytest.approx(vy - f * (1 + e) * vx * cos_t, rel=1e-13)
    assert v[1] - 5.0 / 7.0 * vy == pytest.approx(0.01 * 2.0 / 7.0 * vy, rel=1e-9)
    np.testing.assert_allclose(v, han_rail_frame(vx, vy, 0.0, wy, 0.0, H, e, f), rtol=1e-13)


@given(
    v=st.tuples(finite, finite),
    w=st.tuples(spins, spins, spins),
    angle=st.floats(-math.pi, math.pi),
    h=st.floats(0.5 * R, 1.8 * R),
    e=st.floats(0.0, 1.0),
    f=st.floats(0.0, 2.0),
)
def test_han_laws(v, w, angle, h, e, f):
    """Energy never gained, it leaves the cushion, mirror symmetry, no change unless moving in."""
    n = unit(angle)
    vel, spin = np.array(v), np.array(w)
    a, b = bounce(vel, spin, n, h, e, f)
    if not vel @ n < 0.0:
        assert (a == vel).all() and (b == spin).all()
        return
    assert energy(1.0, a, b) <= energy(1.0, vel, spin) * (1 + 1e-13)
    assert a @ n >= -1e-15 * np.abs(vel).max()  # it leaves the cushion, or slides along it
    # the rail-frame closed forms (x = -n into the cushion, y = z x x), any orientation
    x, y = -n, np.array([n[1], -n[0]])
    vx_ref, vy_ref = han_rail_frame(vel @ x, vel @ y, spin[:2] @ x, spin[:2] @ y, spin[2], h, e, f)
    tol = 1e-12 * (np.abs(vel).max() + R * np.abs(spin).max())
    np.testing.assert_allclose([a @ x, a @ y], [min(vx_ref, 0.0), vy_ref], atol=tol)
    # mirror in the normal's line: the tangent flips; w is a pseudo-vector
    t = np.array([-n[1], n[0]])
    mirror = np.eye(2) - 2.0 * np.outer(t, t)
    spin_m = np.array([*(-(mirror @ spin[:2])), -spin[2]])
    a_m, b_m = bounce(mirror @ vel, spin_m, n, h, e, f)
    np.testing.assert_allclose(a_m, mirror @ a, atol=tol)
    np.testing.assert_allclose(b_m, [*(-(mirror @ b[:2])), -b[2]], atol=tol / R)


def test_the_docstring_quotes_the_tables_defaults() -> None:
    """The module's worked figures use Table's cushion defaults, and the closed form gives them."""
    import re

    from pool_env import Table
    from pool_env.sim.kernels.spin import cushion

    doc = " ".join(cushion.__doc__.split())
    quoted = re.search(
        r"``Table``'s defaults \(``e_c = ([\d.]+)``, ``f_c = ([\d.]+)``, ``h = ([\d.]+) R``\)"
        r" it is ``([\d.]+) vx``",
        doc,
    )
    assert quoted is not None
    e_c, f_c, h, factor = (float(g) for g in quoted.groups())
    table = Table(model="spin")
    assert (e_c, f_c) == (table.e_cushion, table.cushion_friction)
    assert h == pytest.approx(table.cushion_height / table.ball_radius)
    sin2 = (h - 1.0) ** 2  # sin(theta) = (h - R) / R
    rebound = (1 + e_c) * (1 - sin2) + (2 / 7) * sin2 - 1  # a head-on stun ball, in vx
    assert factor == pytest.approx(rebound, abs=5e-4)
