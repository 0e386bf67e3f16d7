"""Pocket jaws: the regulation geometry, closed forms and the hard cases of docs/physics.md.

Expected values are derived here from the table's documented geometry (``Table.jaws``:
points, rail ends, tip centres, facings, fall lines), offset by ``R`` in this file, never
from the kernels' own rows. Scenes with several impacts are also compared with the
independent 50-digit reference (``pool_env/testing/reference/``).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.pockets import CORNER_CUT_DEG, CORNER_MOUTH, SIDE_CUT_DEG, SIDE_MOUTH
from pool_env.testing.invariants import check_shot
from pool_env.testing.reference import reference_simulate

TABLE = Table()
R = TABLE.ball_radius
A = TABLE.deceleration


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=np.float64)
    return v / np.hypot(*v)


def _offset_facing(table: Table, k: int, side: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Start, inward direction and free-side normal of a facing, offset by ``R``.

    That is the line a ball centre touches (facing ``side`` of pocket ``k``).
    """
    jaw = table.jaws[k]
    start, end = jaw.facings[side]
    d = _unit(end - start)
    n = np.array([-d[1], d[0]])
    if n @ (jaw.points[1 - side] - jaw.points[side]) < 0:
        n = -n
    return start + table.ball_radius * n, d, n


def _fall_delta(table: Table, k: int, p) -> float:
    jaw = table.jaws[k]
    return float((np.asarray(p) - jaw.fall_line[0]) @ jaw.fall_normal)


def _arc_time(speed: float, s: float) -> float:
    return 2 * s / (speed + math.sqrt(speed * speed - 2 * A * s))


def _max_error(ours, ref) -> float:
    with mp.workdps(50):
        return max(
            float(mp.sqrt((mp.mpf(float(x)) - rx) ** 2 + (mp.mpf(float(y)) - ry) ** 2))
            for (x, y), (rx, ry) in zip(ours.positions, ref.positions, strict=True)
        )


def _matches_reference(table: Table, pos, vel) -> None:
    ours = simulate(table, pos, vel)
    ref = reference_simulate(table, pos, vel, max_events=400)
    assert [(k, i, j) for _, k, i, j in ref.events] == [(e.kind, e.i, e.j) for e in ours.events]
    assert ours.pocketed.tolist() == ref.pocketed
    assert _max_error(ours, ref) < 1e-9


# -- geometry ----------------------------------------------------------------------------


@pytest.mark.parametrize("k", range(6))
def test_regulation_geometry(k: int) -> None:
    jaw = TABLE.jaws[k]
    corner = k not in (1, 4)
    mouth = CORNER_MOUTH if corner else SIDE_MOUTH
    assert np.hypot(*(jaw.points[1] - jaw.points[0])) == pytest.approx(mouth, abs=1e-15)
    cut = math.radians(CORNER_CUT_DEG if corner else SIDE_CUT_DEG)
    for side in range(2):
        rail_dir = _unit(jaw.rail_ends[side] - jaw.points[side])
        facing_dir = _unit(jaw.facings[side][1] - jaw.facings[side][0])
        assert math.acos(float(rail_dir @ facing_dir)) == pytest.approx(cut, abs=1e-12)
        # The tip touches the nose at the rail's end and the facing at its start.
        c = jaw.tip_centres[side]
        assert np.hypot(*(c - jaw.rail_ends[side])) == pytest.approx(jaw.tip_radius, abs=1e-15)
        assert np.hypot(*(c - jaw.facings[side][0])) == pytest.approx(jaw.tip_radius, abs=1e-15)
        assert float((jaw.rail_ends[side] - c) @ rail_dir) == pytest.approx(0.0, abs=1e-15)
    # The throat narrows inwards, and the fall line lies behind the mouth by the shelf.
    inner = np.hypot(*(jaw.facings[0][1] - jaw.facings[1][1]))
    assert inner < mouth
    middle = jaw.points.mean(axis=0)
    shelf = float((middle - jaw.fall_line[0]) @ jaw.fall_normal)
    assert shelf == pytest.approx(0.04445 if corner else 0.0047625, abs=1e-15)


def test_jaw_geometry_is_read_only() -> None:
    with pytest.raises(ValueError, match="read-only"):
        TABLE.jaws[0].points[0, 0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        TABLE.rails[0, 0, 0] = 1.0
    with pytest.raises((AttributeError, TypeError)):
        TABLE.jaws[0].tip_radius = 0.0  # type: ignore[misc]
    assert Table(pockets="none").jaws == () and Table(pockets="circles").jaws == ()
    assert TABLE.rails.shape == (6, 2, 2) and Table(pockets="none").rails.shape == (4, 2, 2)


# -- closed forms ------------------------------------------------------------------------


@pytest.mark.parametrize("speed", [0.5, 1.0, 4.0])
def test_straight_into_the_side_pocket(speed: float) -> None:
    """Down the side pocket's axis: potted where the centre reaches the fall line."""
    start = np.array([TABLE.length / 2, 0.5])
    result = shoot(TABLE, [start], -math.pi / 2, speed)
    depth = _fall_delta(TABLE, 1, start)
    assert [(e.kind, e.j) for e in result.events] == [("pocket", 1)]
    assert result.events[0].time == pytest.approx(_arc_time(speed, depth), rel=1e-13)
    np.testing.assert_allclose(result.positions[0], start - [0.0, depth], atol=1e-14)


def test_along_the_rail_into_the_corner() -> None:
    """Along the bottom rail into the corner: off the far facing and down the fall line."""
    table = Table(e_jaw=0.6)
    x0, speed = 1.0, 1.2
    a_point, d, n = _offset_facing(table, 0, 1)  # the left rail's facing
    # Where the centre line y = R meets the offset facing (inside the facing, above the
    # fall line: the conditions for this path).
    lam = (R - a_point[1]) / d[1]
    hit = a_point + lam * d
    assert 0 < lam < np.hypot(*np.subtract(*table.jaws[0].facings[1][::-1]))
    assert _fall_delta(table, 0, hit) > 0
    u = np.array([-1.0, 0.0])
    v_hit = math.sqrt(speed**2 - 2 * A * (x0 - hit[0]))
    out = v_hit * (u - (1 + 0.6) * (u @ n) * n)
    # Then straight to the fall line.
    fall_n = table.jaws[0].fall_normal
    s_fall = _fall_delta(table, 0, hit) / -(_unit(out) @ fall_n)
    expected = hit + s_fall * _unit(out)
    result = shoot(table, [[x0, R]], math.pi, speed)
    kinds = [(e.kind, e.j) for e in result.events if e.kind != "point"]  # a tangential touch
    assert kinds == [("jaw", 1), ("pocket", 0)]
    np.testing.assert_allclose(result.positions[0], expected, atol=1e-12)
    t_fall = _arc_time(speed, x0 - hit[0]) + _arc_time(float(np.hypot(*out)), s_fall)
    assert result.events[-1].time == pytest.approx(t_fall, rel=1e-12)


@pytest.mark.parametrize("incidence_deg", [0.0, 20.0, 50.0])
@pytest.mark.parametrize("e_jaw", [1.0, 0.5])
def test_off_a_facing_at_a_known_angle(incidence_deg: float, e_jaw: float) -> None:
    """A ball in the corner's throat meets a facing: the normal component reflects with e."""
    table = Table(e_jaw=e_jaw)
    a_point, d, n = _offset_facing(table, 0, 0)
    contact = a_point + 0.01 * d  # 1 cm into the facing, in front of the fall line
    assert _fall_delta(table, 0, contact) > R
    phi = math.radians(incidence_deg)
    u = -math.cos(phi) * n - math.sin(phi) * d  # towards the facing, and outwards along it
    start = contact - 0.005 * u
    speed = 0.8
    result = shoot(table, [start], math.atan2(u[1], u[0]), speed)
    first = result.events[0]
    assert (first.kind, first.j) == ("jaw", 0)
    assert first.time == pytest.approx(_arc_time(speed, 0.005), rel=1e-12)
    _, _, state, _ = result.segments
    v_after = state[1, 2:]
    v_hit = speed - A * first.time
    expected = v_hit * (u - (1 + e_jaw) * (u @ n) * n)
    np.testing.assert_allclose(v_after, expected, atol=1e-13)
    # The angle of reflection: tan(out) = tan(in) / e from the facing's normal.
    if e_jaw == 1.0:
        out = math.atan2(abs(float(v_after @ d)), float(v_after @ n))
        assert out == pytest.approx(phi, abs=1e-12)


# -- hard cases (docs/physics.md, with jaws) -----------------------------------------------


def _graze_start(table: Table, k: int, side: int, normal_deg: float, offset: float):
    """A path past a point, ``rho + offset`` from its centre at the closest.

    The point is tip ``side`` of pocket ``k``; the closest approach is in direction
    ``normal_deg`` from the tip centre.
    """
    jaw = table.jaws[k]
    c = jaw.tip_centres[side]
    rho = jaw.tip_radius + table.ball_radius
    g = np.array([math.cos(math.radians(normal_deg)), math.sin(math.radians(normal_deg))])
    u = np.array([g[1], -g[0]])  # perpendicular, travelling down-right past the tip
    closest = c + (rho + offset) * g
    return closest - 0.3 * u, u


@pytest.mark.parametrize("offset", [-1e-9, 1e-9])
def test_grazing_a_point(offset: float) -> None:
    """A hair inside the point's reach hits it; a hair outside passes (G, C)."""
    start, u = _graze_start(TABLE, 1, 0, 50.0, offset)
    result = shoot(TABLE, [start], math.atan2(u[1], u[0]), 1.0)
    touched = [(e.kind, e.j) for e in result.events if e.kind in ("point", "jaw", "cushion")]
    if offset < 0:
        assert touched[0] == ("point", 2)
    else:
        assert ("point", 2) not in touched
    assert check_shot(TABLE, result) == []
    _matches_reference(TABLE, [start], [1.0 * u])


def test_rattling_between_the_facings_of_a_corner() -> None:
    """In off one facing, across to the other and back, and out again (G, T, C)."""
    table = Table(e_jaw=1.0)
    angle, b = 3.741553916216298, 0.058889366188946635
    u = np.array([math.cos(angle), math.sin(angle)])
    start = np.array([0.4, 0.4]) + b * np.array([-u[1], u[0]])
    result = shoot(table, [start], angle, 1.5)
    jaws = [e.j for e in result.events if e.kind == "jaw"]
    assert jaws == [0, 1, 0]
    assert result.pocketed[0] == -1  # it rattles and stays out
    assert check_shot(table, result) == []
    _matches_reference(table, [start], [1.5 * u])


@pytest.mark.parametrize("e_ball", [0.0, 0.5, 1.0])
def test_wedged_between_a_facing_and_a_ball(e_ball: float) -> None:
    """A ball at rest touching a facing, driven into it by another (T, G, E)."""
    table = Table(e_ball=e_ball, e_jaw=0.0)
    a_point, d, n = _offset_facing(table, 1, 0)  # the side pocket's left facing
    wedged = a_point + 0.002 * d  # touching the facing, in front of the fall line
    assert _fall_delta(table, 1, wedged) > 0
    w = _unit([1.0, 1.0])  # the pusher comes down from the table, pressing into the facing
    assert w @ n > 0.5
    pusher = wedged + (2 * R + 0.05) * w
    pos = np.array([wedged, pusher])
    vel = np.array([[0.0, 0.0], -0.5 * w])
    result = simulate(table, pos, vel)
    assert not result.hit_event_cap and result.n_events < 200
    assert check_shot(table, result) == []


def _driven_into_a_point(e_ball: float, e_jaw: float):
    """A light ball touching point 2 (side pocket 1, tip 0), a heavy one driving it in.

    The heavy ball starts 5 cm away along the point's normal ``g`` at 0.5 m/s straight at
    it (masses 1e-3 and 1 kg): the scenes of the 100k fuzz that reached the event cap.
    """
    table = Table(e_ball=e_ball, e_jaw=e_jaw)
    jaw = table.jaws[1]
    g = _unit([1.0, 1.0])
    light = jaw.tip_centres[0] + (jaw.tip_radius + R) * g
    pos = np.array([light, light + (2 * R + 0.05) * g])
    masses = np.array([1e-3, 1.0])
    return table, pos, np.array([[0.0, 0.0], -0.5 * g]), masses, g


@pytest.mark.parametrize("e_jaw", [0.0, 0.65])
def test_a_heavy_ball_drives_a_light_one_into_a_point_closed_form(e_jaw: float) -> None:
    """With ``e_ball = 0`` the lump meets the point as one body (T, P, E, closed form).

    The heavy ball arrives at ``v1 = sqrt(v^2 - 2 a d)``; the inelastic impact gives both
    ``V1 = M v1 / (M + m)``; the light ball leaves the point at ``e_jaw V1``, the pair
    meets again inelastically at ``V2 = (M V1 - m e_jaw V1) / (M + m)``, sticks, and the
    lump leaves the point at ``e_jaw V2``: both roll ``(e_jaw V2)^2 / (2 a)`` out along the
    normal, touching. Reflecting only the light ball at the point (the lump pressing on
    into it) ran into the event cap at one instant.
    """
    table, pos, vel, masses, g = _driven_into_a_point(0.0, e_jaw)
    result = simulate(table, pos, vel, masses)
    assert not result.hit_event_cap and result.n_events <= 5
    assert check_shot(table, result, masses) == []
    m, big = masses
    v1 = math.sqrt(0.5**2 - 2 * A * 0.05)
    v_lump = e_jaw * (big * v1 - m * e_jaw * v1) / (big + m) * big / (big + m)
    moved = (result.positions - pos) @ g
    assert moved[0] == pytest.approx(v_lump**2 / (2 * A), rel=1e-12, abs=1e-12)
    assert moved[1] == pytest.approx(moved[0] - 0.05, rel=1e-12, abs=1e-12)
    gap = float(np.hypot(*(result.positions[1] - result.positions[0])))
    assert gap == pytest.approx(2 * R, abs=1e-9)


@pytest.mark.parametrize("e_jaw", [0.0, 0.65])
def test_a_heavy_ball_drives_a_light_one_into_a_point_elastic_balls(e_jaw: float) -> None:
    """With ``e_ball = 0.95`` the pair rattles, sticks by the Zeno rule, and leaves (T, G)."""
    table, pos, vel, masses, g = _driven_into_a_point(0.95, e_jaw)
    result = simulate(table, pos, vel, masses)
    assert not result.hit_event_cap and result.n_events < 100
    assert check_shot(table, result, masses) == []
    moved = (result.positions - pos) @ g
    assert moved[0] >= -1e-12 and moved[1] == pytest.approx(moved[0] - 0.05, abs=1e-9)
    assert (moved[0] > 0.01) == (e_jaw > 0)  # out of the point only if it rebounds


def test_at_rest_touching_a_point() -> None:
    """Resting against a point: no event; moving into it collides now, away from it none."""
    jaw = TABLE.jaws[1]
    c = jaw.tip_centres[0]
    g = _unit([1.0, 1.0])
    p = c + (jaw.tip_radius + R) * g
    assert simulate(TABLE, [p], [[0.0, 0.0]]).n_events == 0
    into = shoot(TABLE, [p], math.atan2(-g[1], -g[0]) + 0.3, 0.5)
    assert (into.events[0].kind, into.events[0].j) == ("point", 2)
    assert into.events[0].time < 1e-15  # now, up to the rounding of p
    away = shoot(TABLE, [p], math.atan2(g[1], g[0]), 0.5)
    assert all(e.kind != "point" for e in away.events)
    assert check_shot(TABLE, into) == [] and check_shot(TABLE, away) == []


@pytest.mark.parametrize("extra", [-1e-9, 1e-9])
def test_a_slow_ball_just_reaching_the_fall_line(extra: float) -> None:
    """Straight into the side pocket, stopping a hair short of the fall line or past (C, G)."""
    start = np.array([TABLE.length / 2, 0.3])
    depth = _fall_delta(TABLE, 1, start)
    speed = math.sqrt(2 * A * (depth + extra))
    result = shoot(TABLE, [start], -math.pi / 2, speed)
    assert (result.pocketed[0] == 1) == (extra > 0)
    if extra < 0:
        np.testing.assert_allclose(result.positions[0], start - [0, depth + extra], atol=1e-12)
        assert 0 < _fall_delta(TABLE, 1, result.positions[0]) < 2e-9
    assert check_shot(TABLE, result) == []


def test_two_balls_entering_one_pocket_at_once() -> None:
    """Side by side, touching, straight into the side pocket: both drop at one instant."""
    x = TABLE.length / 2
    pos = np.array([[x - R, 0.4], [x + R, 0.4]])
    vel = np.array([[0.0, -1.0], [0.0, -1.0]])
    result = simulate(TABLE, pos, vel)
    assert result.pocketed.tolist() == [1, 1]
    pots = [e for e in result.events if e.kind == "pocket"]
    assert [e.i for e in pots] == [0, 1] and pots[0].time == pots[1].time
    assert check_shot(TABLE, result) == []
    again = simulate(TABLE, pos, vel)
    np.testing.assert_array_equal(again.positions, result.positions)


@pytest.mark.parametrize("tilt", [0.0, 1e-10, -1e-10, 1e-7])
def test_along_the_rail_a_hair_off_parallel_into_the_jaw(tilt: float) -> None:
    """Along the bottom rail into the corner, exactly or a hair off parallel (G, T)."""
    y0 = R + (1e-9 if tilt > 0 else 0.0)
    result = shoot(TABLE, [[1.0, y0]], math.pi + tilt, 1.5)
    assert result.pocketed[0] == 0
    assert not result.hit_event_cap and result.n_events < 10
    assert check_shot(TABLE, result) == []


def test_a_jaw_table_without_pockets_pays_nothing_for_jaws() -> None:
    """The same shot off the rails on a carom table and a jaw table away from the pockets."""
    pos = [[1.0, 0.6]]
    carom = shoot(Table(pockets="none"), pos, 0.3, 2.0)
    jaws = shoot(TABLE, pos, 0.3, 2.0)
    assert [(e.kind, e.j) for e in carom.events][:2] == [(e.kind, e.j) for e in jaws.events][:2]
