"""The spin level against the closed forms of its equations of motion, to 1e-9 m.

Sliding friction ``mu_s``, rolling resistance ``mu_r``, spin deceleration ``sd``, ``g``:
a stun ball (no spin) slides ``12 v0^2 / (49 mu_s g)`` in ``2 v0 / (7 mu_s g)`` and then
rolls at ``5 v0 / 7``; a ball with ``w R = v`` rolls at once; a spinning ball stops in place
after ``|wz| / sd``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, simulate

TOL = 1e-9
BIG = Table(length=600.0, width=600.0, model="spin", pockets="none")


def _kinds(result) -> list[str]:
    return [e.kind for e in result.events]


@pytest.mark.parametrize("v0", [0.05, 0.7, 2.0, 5.4])
@pytest.mark.parametrize("angle", [0.0, 0.9, 2.5, -2.0, math.pi / 2])
def test_stun_slide_then_roll(v0: float, angle: float) -> None:
    t = BIG
    mu_s, mu_r, g = t.mu_slide, t.mu_roll, t.g
    u = np.array([math.cos(angle), math.sin(angle)])
    p0 = np.array([300.0, 300.0])
    r = simulate(t, [p0], [v0 * u])
    assert _kinds(r) == ["slide_roll", "stop"]
    t_slide = 2.0 * v0 / (7.0 * mu_s * g)
    assert r.events[0].time == pytest.approx(t_slide, rel=1e-14)
    slide = 12.0 * v0 * v0 / (49.0 * mu_s * g)
    np.testing.assert_allclose(r.positions_at(t_slide), [p0 + slide * u], rtol=0, atol=TOL)
    # Rolling at 5/7 of the speed: the segment written by the transition.
    _, _, state, _ = r.segments
    np.testing.assert_allclose(state[1, 2:4], 5.0 / 7.0 * v0 * u, rtol=0, atol=1e-12)
    np.testing.assert_allclose(
        state[1, 4:6],
        5.0 / 7.0 * v0 / t.ball_radius * np.array([-u[1], u[0]]),
        rtol=1e-12,
        atol=1e-12,
    )
    v1 = 5.0 / 7.0 * v0
    rest = p0 + (slide + v1 * v1 / (2.0 * mu_r * g)) * u
    np.testing.assert_allclose(r.positions, [rest], rtol=0, atol=TOL)
    assert r.duration == pytest.approx(t_slide + v1 / (mu_r * g), rel=1e-13)
    # Between the events the path follows the closed forms.
    for tau in (0.3 * t_slide, 0.9 * t_slide):
        s = v0 * tau - 0.5 * mu_s * g * tau * tau
        np.testing.assert_allclose(r.positions_at(tau), [p0 + s * u], rtol=0, atol=TOL)


@pytest.mark.parametrize("v0", [0.3, 2.0, 7.0])
def test_natural_roll_rolls_at_once(v0: float) -> None:
    """Contact at ``b = 0.4 R`` above centre gives ``w R = (5/2) b v / R = v``: rolling."""
    t = BIG
    r_ball = t.ball_radius
    b = 0.4 * r_ball
    w = 2.5 * v0 * b / (r_ball * r_ball)  # (5/2) v b / R^2
    res = simulate(t, [[300.0, 300.0]], [[0.0, v0]], angular_velocities=[[-w, 0.0, 0.0]])
    assert _kinds(res) == ["stop"]
    d = v0 * v0 / (2.0 * t.mu_roll * t.g)
    np.testing.assert_allclose(res.positions, [[300.0, 300.0 + d]], rtol=0, atol=TOL)


@pytest.mark.parametrize("wz", [-30.0, 0.5, 12.0])
def test_spinning_ball_stops_in_place(wz: float) -> None:
    t = BIG
    res = simulate(t, [[3.0, 4.0]], [[0.0, 0.0]], angular_velocities=[[0.0, 0.0, wz]])
    assert _kinds(res) == ["spin_stop"]
    assert res.events[0].time == pytest.approx(abs(wz) / t.spin_decel, rel=1e-15)
    assert res.positions.tolist() == [[3.0, 4.0]]
    assert res.motion_states.tolist() == [0]


def test_rolling_ball_rests_spinning_then_stops() -> None:
    """A rolling ball with side spin left over at its stop spins on in place."""
    t = BIG
    v0, wz = 0.2, 30.0
    res = simulate(t, [[3.0, 4.0]], [[v0, 0.0]], angular_velocities=[[0.0, v0 / t.ball_radius, wz]])
    assert _kinds(res) == ["roll_spin", "spin_stop"]
    t_roll = v0 / (t.mu_roll * t.g)
    assert res.events[0].time == pytest.approx(t_roll, rel=1e-14)
    assert res.events[1].time == pytest.approx(wz / t.spin_decel, rel=1e-14)
    np.testing.assert_allclose(
        res.positions, [[3.0 + v0 * v0 / (2 * t.mu_roll * t.g), 4.0]], rtol=0, atol=TOL
    )


@pytest.mark.parametrize("v0", [0.5, 2.0])
@pytest.mark.parametrize("spin", [-1.0, 2.5])
def test_slide_with_back_and_top_spin(v0: float, spin: float) -> None:
    """Any spin along the path: slip ``u0 = v0 - R wy``, slide ``2 |u0| / (7 mu g)``.

    With ``w0 = k v0 / R`` the slip is ``(1 - k) v0``; the speed after the slide is
    ``(5 + 2 k) v0 / 7`` (angular momentum about the contact point is conserved).
    """
    t = BIG
    mu_s, g, r_ball = t.mu_slide, t.g, t.ball_radius
    res = simulate(
        t, [[10.0, 20.0]], [[v0, 0.0]], angular_velocities=[[0.0, spin * v0 / r_ball, 0.0]]
    )
    slip = (1.0 - spin) * v0
    t_slide = 2.0 * abs(slip) / (7.0 * mu_s * g)
    assert res.events[0].kind == "slide_roll"
    assert res.events[0].time == pytest.approx(t_slide, rel=1e-14)
    v1 = (5.0 + 2.0 * spin) * v0 / 7.0
    x_slide = v0 * t_slide - 0.5 * mu_s * g * math.copysign(1.0, slip) * t_slide**2
    _, _, state, _ = res.segments
    assert state[1, 2] == pytest.approx(v1, abs=1e-12)
    np.testing.assert_allclose(
        res.positions_at(t_slide), [[10.0 + x_slide, 20.0]], atol=TOL, rtol=0
    )
