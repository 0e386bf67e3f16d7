"""Hard cases of the spin level on curved paths (the roll level's, redone), and rails.

Invariants: G (no overlap beyond 1e-9 m, nothing outside the playing region), C (closed
forms to 1e-9 m), D (bit-identical reruns), T (no event cap).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.kernels.spin.cushion import cushion_han
from pool_env.testing.invariants import check_geometry, check_termination

TOL = 1e-9
R = 0.028575


def _big(**kw) -> Table:
    return Table(length=20.0, width=20.0, model="spin", pockets="none", **kw)


def _state(t: Table, p0, v0, w0, tau: float):
    """Position and velocity of a sliding ball (closed form) after ``tau`` in its slide."""
    r = t.ball_radius
    u = np.array([v0[0] - r * w0[1], v0[1] + r * w0[0]])
    a = -t.mu_slide * t.g * u / np.hypot(*u)
    return np.asarray(p0) + np.asarray(v0) * tau + 0.5 * a * tau * tau, np.asarray(v0) + a * tau, a


@pytest.mark.parametrize("offset", [-1e-9, 1e-9])
@pytest.mark.parametrize("side_spin", [-60.0, 40.0])
def test_graze_a_hair_inside_and_outside_on_a_curve(offset: float, side_spin: float) -> None:
    """A ball on a parabola passes a resting ball at 2R + offset on its convex side.

    On the convex side the closest approach of the curve to a point on its normal at
    ``p(t*)`` is exactly that normal distance: a hit iff ``offset < 0``.
    """
    t = _big(ball_friction=0.0)
    p0, v0 = np.array([5.0, 10.0]), np.array([1.5, 0.0])
    w0 = (side_spin, 0.0, 0.0)  # spin about x: the slip is sideways, the path curves
    tau = 0.04
    p, v, a = _state(t, p0, v0, w0, tau)
    normal = np.array([-v[1], v[0]]) / np.hypot(*v)
    if normal @ a > 0:
        normal = -normal  # the convex side: away from the curvature
    obj = p + (2 * R + offset) * normal
    res = simulate(t, [p0, obj], [v0, [0, 0]], angular_velocities=[w0, [0, 0, 0]])
    hits = [e for e in res.events if e.kind == "ball"]
    if offset < 0:
        assert hits and hits[0].time == pytest.approx(tau, abs=1e-4)
    else:
        assert not hits
        assert res.positions[1].tolist() == obj.tolist()
    assert check_geometry(t, res, samples=500) == []


def test_touching_starts() -> None:
    """Touching balls: approaching collides at once, separating or still is no event."""
    t = _big()
    a, b = [5.0, 5.0], [5.0 + 2 * R, 5.0]
    res = simulate(t, [a, b], [[0.5, 0.0], [0.0, 0.0]])  # closing: impact now
    assert res.events[0].kind == "ball" and res.events[0].time <= 1e-15  # 2R to rounding
    res = simulate(t, [a, b], [[-0.5, 0.0], [0.0, 0.0]])  # opening
    assert all(e.kind != "ball" for e in res.events)
    res = simulate(t, [a, b], [[0.0, 0.0], [0.0, 0.0]], angular_velocities=[[0, 0, 9], [0, 0, -9]])
    assert [e.kind for e in res.events] == ["spin_stop", "spin_stop"]
    # Sliding away with draw: the curve brings it back, into an impact (never through).
    res = simulate(t, [a, b], [[-0.3, 0.0], [0.0, 0.0]], angular_velocities=[[0, 60.0, 0], [0] * 3])
    kinds = [e.kind for e in res.events]
    assert kinds[0] == "slide_roll" and "ball" in kinds
    assert res.events[0].time > 0.0
    assert check_geometry(t, res, samples=2000) == []


def test_sliding_ball_reaches_its_transition_at_impact() -> None:
    """The object ball sits exactly where the stun cue ball starts to roll (C, G).

    Head-on, frictionless, elastic: the rolling cue ball stops and follows with ``2/7`` of
    its speed ``v1 = 5 v0 / 7`` after a slide of ``2 v1^2 / (49 mu g)``; the object ball
    slides off at ``v1`` without spin.
    """
    t = _big(ball_friction=0.0, e_ball=1.0)
    v0, mu, g = 2.0, t.mu_slide, t.g
    slide = 12 * v0 * v0 / (49 * mu * g)
    p0 = np.array([2.0, 10.0])
    obj = p0 + [slide + 2 * R, 0.0]
    res = simulate(t, [p0, obj], [[v0, 0.0], [0.0, 0.0]])
    kinds = [(e.kind, e.i) for e in res.events]
    assert ("ball", 0) in kinds
    v1 = 5.0 / 7.0 * v0
    follow = 2 * v1 * v1 / (49 * mu * g) + (2 / 7 * v1) ** 2 / (2 * t.mu_roll * g)
    np.testing.assert_allclose(res.positions[0], p0 + [slide + follow, 0], rtol=0, atol=TOL)
    obj_travel = 12 * v1 * v1 / (49 * mu * g) + (5 / 7 * v1) ** 2 / (2 * t.mu_roll * g)
    np.testing.assert_allclose(res.positions[1], obj + [obj_travel, 0], rtol=0, atol=TOL)
    assert check_geometry(t, res, samples=500) == []


@pytest.mark.parametrize("behind", [0.0, 0.3])
def test_same_line_same_way_no_phantom_hit(behind: float) -> None:
    """Two rolling balls on one line (equal accelerations: the degree drop)."""
    t = _big()
    p = [[2.0, 10.0], [2.2, 10.0]]
    v = [[1.0 + behind, 0.0], [1.0, 0.0]]
    w = [[0, (1.0 + behind) / R, 0], [0, 1.0 / R, 0]]
    res = simulate(t, p, v, angular_velocities=w)
    hits = [e for e in res.events if e.kind == "ball"]
    if behind == 0.0:
        assert not hits
        np.testing.assert_allclose(np.diff(res.positions[:, 0]), [0.2], rtol=0, atol=1e-12)
    else:
        assert hits
    assert check_geometry(t, res, samples=500) == []


def test_rail_rebound_head_on() -> None:
    """A rolling ball into a rail: Han 2005 at the contact, then the closed-form slide (C)."""
    t = Table(model="spin", pockets="none")
    v0, d = 1.5, 0.8
    y0 = t.width / 2
    x0 = t.length - R - d
    res = simulate(t, [[x0, y0]], [[v0, 0.0]], angular_velocities=[[0, v0 / R, 0]])
    assert res.events[0].kind == "cushion" and res.events[0].j == 1
    a = t.mu_roll * t.g
    v1 = math.sqrt(v0 * v0 - 2 * a * d)
    assert res.events[0].time == pytest.approx((v0 - v1) / a, rel=1e-13)
    out = np.empty(5)
    cushion_han(v1, 0.0, 0.0, v1 / R, 0.0, -1.0, 0.0, R, t.cushion_height, t.e_cushion,
                t.cushion_friction, out)  # fmt: skip
    _, _, state, _ = res.segments
    np.testing.assert_allclose(state[1, 2:7], out, rtol=1e-13, atol=1e-13)
    assert out[0] < 0.0  # it comes back
    # After the rebound: slide, then roll, straight back along y = y0 (no side spin).
    u = out[0] - R * out[3]
    mu = t.mu_slide * t.g
    t_s = 2 * abs(u) / (7 * mu)
    x_s = out[0] * t_s - 0.5 * mu * math.copysign(1, u) * t_s * t_s
    v_roll = out[0] - math.copysign(1, u) * mu * t_s
    x_end = t.length - R + x_s - v_roll * v_roll / (2 * a)
    np.testing.assert_allclose(res.positions, [[x_end, y0]], rtol=0, atol=TOL)


def test_side_spin_turns_the_rebound() -> None:
    """Side spin ``wz`` turns the rebound from the top rail (nose contact above centre).

    The contact point's slip along the rail gains ``-wz R cos(theta)``: friction against it
    speeds ``vx`` up for ``wz > 0`` and slows it for ``wz < 0`` (G, T, and the order).
    """
    t = Table(model="spin", pockets="none")
    v = 1.0 / math.sqrt(2.0)
    after = []
    for wz in (-20.0, 0.0, 20.0):
        res = simulate(t, [[1.0, 0.9]], [[v, v]], angular_velocities=[[-v / R, v / R, wz]])
        k = next(k for k, e in enumerate(res.events) if e.kind == "cushion")
        assert res.events[k].j == 3
        _, _, state, _ = res.segments
        after.append(state[res.event_first_segment[k], 2])
        assert check_geometry(t, res, samples=300) == [] and check_termination(res) == []
    assert after[0] < after[1] < after[2]


def test_shoot_natural_roll_tip() -> None:
    """A centre-line hit at contact height 2/5 R rolls at once (the tip-contact scaling)."""
    t = Table(length=40.0, width=40.0, model="spin", pockets="none")
    b = 0.4 * (1 + t.cue_tip_radius / t.ball_radius)
    res = shoot(t, [[1.0, 20.0]], 0.0, 2.0, tip=(0.0, b))
    assert [e.kind for e in res.events] == ["stop"]
    np.testing.assert_allclose(
        res.positions, [[1.0 + 4.0 / (2 * t.mu_roll * t.g), 20.0]], rtol=0, atol=TOL
    )


def test_rerun_is_bit_identical() -> None:
    t = Table(model="spin", pockets="jaws")
    pos = [[0.7, 0.6], [1.9, 0.64], [1.96, 0.6], [1.96, 0.66], [2.2, 1.0]]
    a = shoot(t, pos, 0.02, 6.0, tip=(0.3, -0.4), elevation=0.1)
    b = shoot(t, pos, 0.02, 6.0, tip=(0.3, -0.4), elevation=0.1)
    fields = ("positions", "event_times", "event_kinds", "angular_velocities")
    for name in fields:
        assert np.array_equal(getattr(a, name), getattr(b, name))
    assert check_geometry(t, a, samples=500) == [] and check_termination(a) == []


@pytest.mark.parametrize("tilt", [0.0, 1e-12, -1e-12, 1e-7])
def test_along_a_rail_a_hair_off_parallel(tilt: float) -> None:
    """A rolling ball along the bottom rail line, a hair off parallel (G, T)."""
    t = Table(model="spin", pockets="none")
    v = 1.2
    vel = [[v * math.cos(tilt), -v * math.sin(tilt)]]
    res = simulate(t, [[0.3, R]], vel, angular_velocities=[[-vel[0][1] / R, vel[0][0] / R, 0.0]])
    assert check_geometry(t, res, samples=2000) == [] and check_termination(res) == []


@pytest.mark.parametrize("wx", [-40.0, 40.0])
def test_slip_presses_a_ball_into_the_rail(wx: float) -> None:
    """A ball on the bottom rail line sliding along it, its slip turning it in or away.

    Slip ``u_y = R wx``: the cloth's friction ``-mu g u / |u|`` turns the ball into the
    rail for ``wx > 0``, away for ``wx < 0``. Held at the rail by the pressed-cushion rule,
    never through it (G, T, E).
    """
    from pool_env.testing.invariants import check_spin_energy

    t = Table(model="spin", pockets="none")
    res = simulate(t, [[0.5, R]], [[1.0, 0.0]], angular_velocities=[[wx, 1.0 / R, 0.0]])
    assert check_geometry(t, res, samples=2000) == [] and check_termination(res) == []
    assert check_spin_energy(t, res) == []
    if wx > 0:  # pressed in from the start: an impact now, then it rolls along the rail
        assert res.events[0].kind == "cushion" and res.events[0].time == 0.0
        assert not any(e.kind == "cushion" and e.j == 2 for e in res.events[1:])
    else:
        assert res.events[0].kind == "slide_roll"


def test_long_roll_a_hair_into_a_rail_on_a_big_table() -> None:
    """Fuzz shot 9007: a long rolling piece, a normal speed of 7e-9 m/s into the rail.

    The approach tolerance must scale with the piece's own speeds (here ~25 m/s), not with
    the sliding deceleration over the piece's 9600 s: the ball hits the rail (G).
    """
    t = Table(length=5332.0, width=2666.0, ball_radius=60.0, mu_roll=2.6e-4, model="spin",
              pockets="none")  # fmt: skip
    y = t.width - t.ball_radius
    vel = np.array([[-25.0, 7.4e-9]])
    ang = np.array([[-vel[0, 1] / 60.0, vel[0, 0] / 60.0, 0.0]])
    res = simulate(t, [[3000.0, y]], vel, angular_velocities=ang)
    assert any(e.kind == "cushion" and e.j == 3 for e in res.events)
    assert check_geometry(t, res, samples=2000) == [] and check_termination(res) == []
