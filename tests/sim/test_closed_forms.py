"""The simulator against closed forms: rolling, impacts, cushions, corners, pockets."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from tests.helpers_sim import normal_velocities, speed_after, stop_point, time_to, unfold

ANGLES = [k * math.pi / 4 for k in range(8)] + [0.3, 2.0, -2.5, 4.0]


@pytest.mark.parametrize("angle", ANGLES)
@pytest.mark.parametrize("speed", [1e-6, 1e-3, 0.1, 0.3])
def test_free_ball_stops_at_closed_form(carom: Table, angle: float, speed: float) -> None:
    centre = np.array([carom.length / 2, carom.width / 2])
    result = shoot(carom, [centre], angle, speed)
    np.testing.assert_allclose(
        result.positions[0], stop_point(carom, centre, speed, angle), rtol=0, atol=1e-14
    )
    assert result.duration == pytest.approx(speed / carom.deceleration, rel=1e-14)
    assert [e.kind for e in result.events] == ["stop"]
    # The path is a straight segment at every instant, travelled at s = v t - a t^2 / 2.
    t = result.duration / 3
    s = speed * t - 0.5 * carom.deceleration * t * t
    expected = centre + s * np.array([math.cos(angle), math.sin(angle)])
    np.testing.assert_allclose(result.positions_at(t)[0], expected, rtol=0, atol=1e-14)


@pytest.mark.parametrize("angle", [0.0, math.pi / 2, math.pi, -math.pi / 2])
@pytest.mark.parametrize(("e", "mass_b"), [(1.0, 0.17), (0.95, 0.17), (0.5, 0.25), (0.0, 0.1)])
def test_head_on_impact_every_direction(carom: Table, angle, e, mass_b) -> None:
    table = Table(e_ball=e, pockets="none")
    u = np.array([math.cos(angle), math.sin(angle)])
    centre = np.array([table.length / 2, table.width / 2])
    a_pos = centre - 0.25 * u
    b_pos = centre + 0.05 * u
    speed = 0.25  # slow enough that neither ball reaches a rail
    masses = [0.17, mass_b]
    result = shoot(table, [a_pos, b_pos], angle, speed, masses=masses)
    gap = 0.30 - 2 * table.ball_radius
    v_hit = speed_after(table, speed, gap)
    ua, ub = normal_velocities(0.17, mass_b, v_hit, 0.0, e)
    impact = result.events[0]
    assert impact.kind == "ball"
    assert impact.time == pytest.approx(time_to(table, speed, gap), rel=1e-13)
    contact = a_pos + gap * u
    # Each ball rolls on from the contact point along the line of centres.
    expect_a = contact + math.copysign(ua * ua / (2 * table.deceleration), ua) * u
    expect_b = contact + 2 * table.ball_radius * u + ub * ub / (2 * table.deceleration) * u
    np.testing.assert_allclose(result.positions[0], expect_a, atol=1e-12)
    np.testing.assert_allclose(result.positions[1], expect_b, atol=1e-12)


@pytest.mark.parametrize("offset_fraction", [0.0, 0.25, 0.5, -0.7, 0.95])
@pytest.mark.parametrize("e", [1.0, 0.8])
def test_oblique_impact_matches_line_of_centres(offset_fraction: float, e: float) -> None:
    table = Table(e_ball=e, pockets="none")
    r = table.ball_radius
    b_pos = np.array([1.4, 0.635])
    b = offset_fraction * 2 * r  # impact parameter
    a_pos = np.array([1.0, 0.635 - b])
    speed = 0.4  # slow enough that neither ball reaches a rail
    result = shoot(table, [a_pos, b_pos], 0.0, speed)
    # Contact: cue centre at x_c on y = 0.635 - b, with |pb - pc| = 2R.
    x_c = b_pos[0] - math.sqrt(4 * r * r - b * b)
    travel = x_c - a_pos[0]
    v = speed_after(table, speed, travel)
    n = (b_pos - np.array([x_c, a_pos[1]])) / (2 * r)
    va = np.array([v, 0.0])
    ua, ub = normal_velocities(0.17, 0.17, va @ n, 0.0, e)
    va_after = va + (ua - va @ n) * n
    vb_after = ub * n

    def rest(p, vel):
        s = float(np.hypot(*vel))
        return p if s == 0 else p + vel / s * s * s / (2 * table.deceleration)

    np.testing.assert_allclose(
        result.positions[0], rest(np.array([x_c, a_pos[1]]), va_after), atol=1e-12
    )
    np.testing.assert_allclose(result.positions[1], rest(b_pos, vb_after), atol=1e-12)


def test_seed_misprint_would_pass_through() -> None:
    """E = 1, equal masses, head-on: the corrected formula exchanges velocities.

    The seed's printed sign would leave the striker's velocity unchanged (pass-through).
    """
    table = Table(e_ball=1.0, pockets="none")
    result = shoot(table, [[1.0, 0.6], [1.2, 0.6]], 0.0, 0.5)
    assert result.positions[0][0] == pytest.approx(1.2 - 2 * table.ball_radius, abs=1e-12)


@pytest.mark.parametrize("e_cushion", [1.0, 0.85, 0.3])
@pytest.mark.parametrize("angle", [0.4, 2.5, -0.9, -2.2])
def test_single_cushion_rebound(e_cushion: float, angle: float) -> None:
    table = Table(e_cushion=e_cushion, pockets="none")
    p0 = np.array([table.length / 2, table.width / 2])
    u = np.array([math.cos(angle), math.sin(angle)])
    r = table.ball_radius
    # Arc length to each rail line the ball heads for; the nearer one is hit.
    lines = [table.length - r if u[0] > 0 else r, table.width - r if u[1] > 0 else r]
    reach = [(lines[k] - p0[k]) / u[k] for k in range(2)]
    axis = int(np.argmin(reach))
    s1 = reach[axis]
    speed = math.sqrt(2 * table.deceleration * (s1 + 0.2))  # 0.2 m to spare after the rail
    result = shoot(table, [p0], angle, speed)
    rail = 2 * axis + (1 if u[axis] > 0 else 0)
    assert [(e.kind, e.j) for e in result.events] == [("cushion", rail), ("stop", -1)]
    assert result.events[0].time == pytest.approx(time_to(table, speed, s1), rel=1e-13)
    v1 = speed_after(table, speed, s1) * u
    v1[axis] *= -e_cushion
    hit = p0 + s1 * u
    s_after = float(np.hypot(*v1))
    expected = hit + v1 / s_after * s_after**2 / (2 * table.deceleration)
    np.testing.assert_allclose(result.positions[0], expected, atol=1e-12)


@pytest.mark.parametrize("speed", [0.5, 3.0, 15.0])
@pytest.mark.parametrize("angle", [0.3, 1.2, 2.8, -1.9])
def test_elastic_rails_are_mirrors(speed: float, angle: float) -> None:
    """With e_cushion = 1 the path unfolds into a straight line through mirrored tables."""
    table = Table(e_cushion=1.0, pockets="none")
    r = table.ball_radius
    p0 = np.array([0.7, 0.4])
    straight = stop_point(table, p0, speed, angle)
    expected = [unfold(straight[0], r, table.length - r), unfold(straight[1], r, table.width - r)]
    result = shoot(table, [p0], angle, speed)
    np.testing.assert_allclose(result.positions[0], expected, atol=1e-9)
    assert not result.hit_event_cap


@pytest.mark.parametrize("corner", [(0, 0), (1, 0), (0, 1), (1, 1)])
def test_45_degrees_into_a_square_corner(corner) -> None:
    """Both rails are hit; the ball comes straight back, whatever the order of the two hits."""
    table = Table(e_cushion=1.0, pockets="none")
    r = table.ball_radius
    target = np.array([table.length - r if corner[0] else r, table.width - r if corner[1] else r])
    start = target + np.array([-0.3 if corner[0] else 0.3, -0.3 if corner[1] else 0.3])
    direction = target - start
    angle = math.atan2(direction[1], direction[0])
    speed = math.sqrt(2 * table.deceleration * (0.3 * math.sqrt(2) + 0.2))
    result = shoot(table, [start], angle, speed)
    assert sorted(e.kind for e in result.events) == ["cushion", "cushion", "stop"]
    # Back along the incoming line, 0.2 m from the corner.
    back = target - direction / np.hypot(*direction) * 0.2
    np.testing.assert_allclose(result.positions[0], back, atol=1e-9)


@pytest.mark.parametrize("k", range(6))
def test_straight_pot_into_every_pocket(k: int) -> None:
    table = Table(pockets="circles")
    px, py, radius = table.pockets[k]
    centre = np.array([table.length / 2, table.width / 2 + 0.1])
    direction = np.array([px, py]) - centre
    result = shoot(table, [centre], math.atan2(direction[1], direction[0]), 4.0)
    assert result.pocketed.tolist() == [k]
    assert result.events[-1].kind == "pocket" and result.events[-1].j == k
    # Captured where the centre entered the capture circle.
    assert np.hypot(*(result.positions[0] - [px, py])) == pytest.approx(radius, abs=1e-12)


@pytest.mark.parametrize("side", [-1.0, 1.0])
def test_just_missing_a_side_pocket(side: float) -> None:
    """Rolling parallel to the rail past the side pocket: captured iff within its circle."""
    table = Table(pockets="circles")
    _, py, radius = table.pockets[1]
    lane = py + radius + side * 1e-9  # centre line 1 nm outside (+) or inside (-) the circle
    result = shoot(table, [[0.6, lane]], 0.0, 3.0)
    assert (result.pocketed[0] == 1) == (side < 0)


def test_simulate_moves_several_balls_and_keeps_inputs(carom: Table) -> None:
    pos = np.array([[0.5, 0.3], [2.0, 1.0]])
    vel = np.array([[0.1, 0.0], [0.0, -0.2]])
    pos0, vel0 = pos.copy(), vel.copy()
    result = simulate(carom, pos, vel)
    np.testing.assert_array_equal(pos, pos0)
    np.testing.assert_array_equal(vel, vel0)
    np.testing.assert_allclose(result.positions[0], stop_point(carom, pos[0], 0.1, 0.0), atol=1e-14)
    np.testing.assert_allclose(
        result.positions[1], stop_point(carom, pos[1], 0.2, -math.pi / 2), atol=1e-14
    )
