"""A lump of balls pressed into a rail meets it as one body (issue 11, item 2).

A heavy ball driving a light one into a rail used to re-collide at one instant until the
event cap stopped every ball on the table. The lump rule (``resolve.lump_off_rail``)
reverses the lump's normal velocity with the rail's restitution as a whole; these tests
check the reproducers, the rule's closed form, and what it conserves and loses.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.sim.kernels.contact import V_ZENO, lump_off_rail, lump_off_rails
from pool_env.testing.invariants import check_shot
from pool_env.testing.scenes_random import within_limits
from tests.helpers_sim import normal_velocities, speed_after, unfold

M_LIGHT = 0.17


def _driven_into_rail(table: Table, ratio: float):
    """The issue's scene, heavy ball ``ratio`` times the others.

    The heavy ball at 1 m/s drives a light one resting on the right rail; ball 2 rolls on
    its own far away. At a million to one the heavy ball's energy could drive a light ball
    past the speed limits (``sim.inputs.reachable_speed``): every speed is then scaled down
    by one factor (the heavy ball at ~0.44 m/s, started 0.5 m from the lump so that it
    still reaches it).
    """
    length, r = table.length, table.ball_radius
    positions = [[1.0, 0.6], [length - r, 0.6], [0.3, 0.2]]
    masses = [M_LIGHT * ratio, M_LIGHT, M_LIGHT]
    given = np.array([[1.0, 0.0], [0.0, 0.0], [0.0, 2.0]])
    velocities = within_limits(table, given, masses)
    if velocities is not given:
        positions[0][0] = length - 3 * r - 0.5
    return positions, velocities, masses


def _free_rest_point_y(table: Table, y0: float, speed: float) -> float:
    """Where a ball rolling along y from ``y0`` rests, the rails unfolded."""
    r = table.ball_radius
    y = y0 + speed * speed / (2.0 * table.deceleration)
    if table.e_cushion == 1.0:
        return unfold(y, r, table.width - r)
    raise NotImplementedError


@pytest.mark.parametrize(
    ("e", "ratio"),
    [(1.0, 1e3), (1.0, 1e4), (1.0, 1e6), (0.0, 100.0), (0.0, 1e6), (None, 1e3), (None, 1e6)],
)
def test_heavy_ball_drives_light_ball_into_rail(e: float | None, ratio: float) -> None:
    """T, G, P, E: a handful of events, no cap, and ball 2 is never stopped."""
    kw = {} if e is None else {"e_ball": e, "e_cushion": e}
    table = Table(pockets="none", **kw)
    positions, velocities, masses = _driven_into_rail(table, ratio)
    result = simulate(table, positions, velocities, masses=masses)
    assert not result.hit_event_cap
    assert result.n_events <= 64  # was the 10,000-event cap
    assert check_shot(table, result, masses) == []
    # Ball 2 keeps rolling until it stops by itself or meets the lump: never frozen at the
    # instant of the wedge.
    wedge_time = next(ev.time for ev in result.events if ev.kind == "ball")
    ball_2_events = [ev for ev in result.events if 2 in (ev.i, ev.j) and ev.time <= wedge_time]
    assert all(ev.kind == "cushion" for ev in ball_2_events)
    assert not any(ev.kind == "stop" and ev.i == 2 for ev in result.events if ev.time <= wedge_time)


def test_issue_reproducer_leaves_ball_2_alone() -> None:
    """C: in the issue's elastic scene ball 2 rests where a free ball would."""
    table = Table(pockets="none", e_ball=1, e_cushion=1)
    positions, velocities, masses = _driven_into_rail(table, 1000.0)
    result = simulate(table, positions, velocities, masses=masses)
    assert result.n_events <= 64
    assert not any(2 in (ev.i, ev.j) for ev in result.events if ev.kind == "ball")
    np.testing.assert_allclose(
        result.positions[2], [0.3, _free_rest_point_y(table, 0.2, 2.0)], atol=1e-9
    )


@pytest.mark.parametrize("e_cushion", [1.0, 0.85, 0.3, 0.0])
@pytest.mark.parametrize("ratio", [1.0, 100.0, 1e6])
def test_inelastic_lump_off_rail_closed_form(e_cushion: float, ratio: float) -> None:
    """C, P, E: an inelastic impact at a rail leaves one lump, which rebounds as a whole.

    The pusher (mass ``M``) reaches the resting ball (``m``, touching the right rail) at
    speed ``v``. The pair sticks at ``M v / (M + m)`` (momentum conserved) and meets the
    rail as one body: both leave at ``-e_cushion M v / (M + m)``. The rail's impulse is
    ``-(1 + e_cushion) M v`` and the energy lost is exactly
    ``M v^2 / 2 - (M + m) (e_cushion M v / (M + m))^2 / 2``.
    """
    table = Table(pockets="none", e_ball=0.0, e_cushion=e_cushion)
    length, r = table.length, table.ball_radius
    gap = 0.3
    positions = [[length - 3 * r - gap, 0.6], [length - r, 0.6]]
    masses = [M_LIGHT * ratio, M_LIGHT]
    # 1.2 m/s, or slower where the pusher's energy could drive the light ball past the
    # speed limits (a million to one: ~0.44 m/s); the closed form holds at any speed.
    v0 = float(within_limits(table, np.array([[1.2, 0.0], [0.0, 0.0]]), masses)[0, 0])
    result = simulate(table, positions, [[v0, 0.0], [0.0, 0.0]], masses=masses)
    assert check_shot(table, result, masses) == []
    big, small = masses
    v = speed_after(table, v0, gap)
    common = big * v / (big + small)
    expected = -e_cushion * common
    first = result.events[0]
    assert (first.kind, first.i, first.j) == ("ball", 0, 1)
    _, _, state, _ = result.segments
    rows = state[result.event_first_segment[0] : result.event_first_segment[0] + 2]
    np.testing.assert_allclose(rows[:, 2], [expected, expected], rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(rows[:, 3], [0.0, 0.0])
    # Momentum changes only by the rail's impulse, -(1 + e) M v along its normal.
    impulse = (big + small) * expected - big * v
    assert impulse == pytest.approx(-(1.0 + e_cushion) * big * v, rel=1e-12)
    # Energy: exactly the inelastic pair loss plus (1 - e^2) of the lump's normal energy.
    lost = 0.5 * big * v * v - 0.5 * (big + small) * expected * expected
    pair_loss = 0.5 * big * v * v - 0.5 * (big + small) * common * common
    lump_loss = 0.5 * (1.0 - e_cushion**2) * (big + small) * common * common
    assert lost == pytest.approx(pair_loss + lump_loss, rel=1e-12)
    # The lump leaves together: nothing else happens at that instant.
    assert all(ev.time > first.time for ev in result.events[1:])


def test_equal_masses_frozen_on_rail_unchanged() -> None:
    """C: a shot at a ball frozen on the rail still follows the sequential rule.

    The lump rule only ends cascades that stick; an ordinary impact is exact.
    """
    table = Table(pockets="none")
    length, r = table.length, table.ball_radius
    result = simulate(table, [[1.5, 0.6], [length - r, 0.6]], [[1.0, 0.0], [0.0, 0.0]])
    kinds = [ev.kind for ev in result.events]
    assert kinds[:2] == ["ball", "cushion"]
    v = speed_after(table, 1.0, length - 3 * r - 1.5)
    u0, u1 = normal_velocities(M_LIGHT, M_LIGHT, v, 0.0, table.e_ball)
    _, _, state, _ = result.segments
    rows = state[result.event_first_segment[0] : result.event_first_segment[0] + 2]
    np.testing.assert_allclose(rows[:, 2], [u0, u1], rtol=1e-12)
    assert check_shot(table, result) == []


@pytest.mark.parametrize("angle", [0.0, 0.3, 1.0, 2.5, -2.0, math.pi / 4])
@pytest.mark.parametrize("e", [1.0, 0.85, 0.0])
def test_lump_off_rail_any_normal(angle: float, e: float) -> None:
    """C: for a unit normal at any angle, ``v_n -> -e v_n`` and the tangent is kept."""
    nx, ny = math.cos(angle), math.sin(angle)
    tx, ty = -ny, nx
    vn, vt = -0.7, 0.4  # into the rail
    vx, vy = vn * nx + vt * tx, vn * ny + vt * ty
    ox, oy, hit = lump_off_rail(vx, vy, nx, ny, e)
    assert hit
    assert ox * nx + oy * ny == pytest.approx(-e * vn, abs=1e-15)
    assert ox * tx + oy * ty == pytest.approx(vt, abs=1e-15)
    # Energy per unit mass drops by exactly (1 - e^2) vn^2 / 2.
    drop = 0.5 * (vx * vx + vy * vy) - 0.5 * (ox * ox + oy * oy)
    assert drop == pytest.approx(0.5 * (1 - e * e) * vn * vn, abs=1e-15)
    # Leaving or sliding along the rail: untouched.
    assert lump_off_rail(-vx, -vy, nx, ny, e) == (-vx, -vy, False)
    assert lump_off_rail(tx, ty, nx, ny, e)[2] is False
    # Slower than V_ZENO into the rail: the normal component stops.
    sx, sy, _ = lump_off_rail(-0.5 * V_ZENO * nx + vt * tx, -0.5 * V_ZENO * ny + vt * ty, nx, ny, e)
    assert sx * nx + sy * ny == pytest.approx(0.0, abs=1e-21)


def test_lump_off_rails_corner_and_jam() -> None:
    """C: a corner (orthogonal rails) is order-free; a V releases; opposite rails jam."""
    corner = np.array([[1.0, 0.0], [0.0, 1.0]])
    a = lump_off_rails(-0.5, -0.25, corner, 2, 0.5)
    b = lump_off_rails(-0.5, -0.25, corner[::-1].copy(), 2, 0.5)
    assert a == b == (0.25, 0.125)
    # Two facings of a V opening upwards, 0.8 rad apart: an elastic lump falling into it
    # leaves after a few reflections, with its speed and out of both facings.
    facings = np.array([[math.cos(0.4), math.sin(0.4)], [-math.cos(0.4), math.sin(0.4)]])
    vx, vy = lump_off_rails(0.0, -1.0, facings, 2, 1.0)
    assert math.hypot(vx, vy) == pytest.approx(1.0, rel=1e-14)
    assert all(vx * nx + vy * ny >= 0.0 for nx, ny in facings)
    # Opposite rails turn an elastic lump into each other forever: it jams, at rest.
    opposite = np.array([[1.0, 0.0], [-1.0, 0.0]])
    assert lump_off_rails(-1.0, 0.3, opposite, 2, 1.0) == (0.0, 0.0)
    # Touching a rail it leaves: unchanged.
    assert lump_off_rails(0.3, 0.2, corner, 2, 0.5) == (0.3, 0.2)


@pytest.mark.parametrize("cap", [1, 3, 20])
def test_the_cap_says_which_balls_it_stopped(cap: int) -> None:
    """The cap never freezes a ball silently.

    ``stopped_by_cap`` names every ball still moving at that instant (ball 2, rolling on
    its own, included), with and without recording and in a batch.
    """
    table = Table(pockets="none", e_ball=1, e_cushion=1)
    positions, velocities, masses = _driven_into_rail(table, 1000.0)
    result = simulate(table, positions, velocities, masses=masses, max_events=cap)
    assert result.hit_event_cap
    # Independently, from the uncapped shot: the balls moving after its first `cap` events.
    full = simulate(table, positions, velocities, masses=masses)
    ball, seg_t, state, _ = full.segments
    t_cap = full.event_times[cap - 1]
    assert t_cap == result.duration
    moving = np.zeros(3, bool)
    for b in range(3):
        last = np.flatnonzero(ball[: full.event_first_segment[cap]] == b)[-1]
        speed = math.hypot(*state[last, 2:4])
        moving[b] = speed - table.deceleration * (t_cap - seg_t[last]) > 0.0
    assert moving[2]  # the unrelated ball was rolling when the cap stopped the table
    np.testing.assert_array_equal(result.stopped_by_cap, moving)
    quiet = simulate(table, positions, velocities, masses=masses, max_events=cap, record=False)
    np.testing.assert_array_equal(quiet.stopped_by_cap, moving)
    from pool_env.sim.batch import simulate_batch

    batch = simulate_batch(
        table, np.array([positions]), np.array([velocities]), masses, max_events=cap
    )
    np.testing.assert_array_equal(batch.stopped_by_cap[0], moving)
    under = simulate(table, positions, velocities, masses=masses)
    assert not under.stopped_by_cap.any()
