"""Jaw geometry pinned by the WPA numbers, and jaw contacts pinned by closed forms.

Every expected number here comes from the regulation spec (written out below as literals,
never imported from :mod:`pool_env.sim.pockets`) or from plane geometry applied to it; the
table's documented geometry (``Table.jaws``) and the simulator must agree with it.

WPA equipment specifications: corner mouth 4.5 - 4.625 in, side mouth 5 - 5.125 in (between
the points; the model takes the narrow end), facings cut at 142 degrees to the rail at the
corners (the 45-degree corner cut plus 7) and 104 at the sides (90 plus 14), shelf (mouth
to the edge of the hole, where the model puts the fall line) 1 5/8 - 1 7/8 in at corners
and 0 - 3/8 in at sides (the model takes the middle of each range).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.table import JawSpec
from pool_env.testing.invariants import check_shot
from pool_env.testing.reference import reference_simulate
from tests.helpers_sim import normal_velocities

INCH = 0.0254  # m, exactly
CORNER_MOUTH_SPEC = 4.5 * INCH
SIDE_MOUTH_SPEC = 5.0 * INCH
CORNER_CUT_SPEC = 142.0  # degrees, facing to rail
SIDE_CUT_SPEC = 104.0
CORNER_SHELF_SPEC = 0.5 * (1.625 + 1.875) * INCH
SIDE_SHELF_SPEC = 0.5 * (0.0 + 0.375) * INCH
L, W, R = 2.54, 1.27, 0.028575  # the 9-ft table (docs/physics.md defaults)
SIDES = (1, 4)

TABLE = Table()
A = TABLE.deceleration


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=np.float64)
    return v / np.hypot(*v)


def _arc_time(speed: float, s: float) -> float:
    return 2 * s / (speed + math.sqrt(speed * speed - 2 * A * s))


# The points of each pocket, from the mouths and the table's size alone: a corner's points
# are mouth / sqrt(2) from the corner along each rail (the mouth is cut at 45 degrees), a
# side's are half the mouth either side of the middle of the long rail.
_C = CORNER_MOUTH_SPEC / math.sqrt(2.0)
_S = SIDE_MOUTH_SPEC / 2.0
SPEC_POINTS = [
    [(_C, 0.0), (0.0, _C)],
    [(L / 2 - _S, 0.0), (L / 2 + _S, 0.0)],
    [(L - _C, 0.0), (L, _C)],
    [(_C, W), (0.0, W - _C)],
    [(L / 2 - _S, W), (L / 2 + _S, W)],
    [(L - _C, W), (L, W - _C)],
]


def test_the_table_is_the_specified_one() -> None:
    assert (TABLE.length, TABLE.width, TABLE.ball_radius) == (L, W, R)
    assert TABLE.pocket_model == "jaws" and len(TABLE.jaws) == 6


@pytest.mark.parametrize("k", range(6))
def test_points_where_the_spec_puts_them(k: int) -> None:
    np.testing.assert_allclose(TABLE.jaws[k].points, SPEC_POINTS[k], rtol=0, atol=1e-15)


@pytest.mark.parametrize("k", range(6))
def test_facings_cut_at_the_spec_angle(k: int) -> None:
    """The angle at each point between its rail (away from the pocket) and its facing."""
    jaw = TABLE.jaws[k]
    cut = SIDE_CUT_SPEC if k in SIDES else CORNER_CUT_SPEC
    for side in range(2):
        point = jaw.points[side]
        other = jaw.points[1 - side]
        # The rail runs from the point away from the pocket: along its nose line, away
        # from the other point's side (for a corner, the rail the point lies on).
        on_x_rail = point[1] in (0.0, W)
        rail = np.array([1.0, 0.0]) if on_x_rail else np.array([0.0, 1.0])
        if rail @ (other - point) > 0:
            rail = -rail
        facing = _unit(jaw.facings[side][1] - jaw.facings[side][0])
        angle = math.degrees(math.acos(float(rail @ facing)))
        assert angle == pytest.approx(cut, abs=1e-10)
        # The facing runs into the cushion, away from the table (beyond the nose line).
        inward = np.array([0.0, 1.0 if point[1] == 0.0 else -1.0])
        if not on_x_rail:
            inward = np.array([1.0 if point[0] == 0.0 else -1.0, 0.0])
        assert facing @ inward < 0


@pytest.mark.parametrize("k", range(6))
def test_fall_line_at_the_shelf_depth_and_the_throat_width_there(k: int) -> None:
    """The fall line is the mouth moved in by the shelf, narrowed by the cut.

    The facings lean into the throat by ``cut - 135`` degrees (corner: the mouth is at 45
    degrees to the rails) or ``cut - 90`` (side) from the mouth's normal, so ``h`` behind
    the mouth the throat is ``mouth - 2 h tan(lean)`` wide.
    """
    jaw = TABLE.jaws[k]
    side = k in SIDES
    mouth = SIDE_MOUTH_SPEC if side else CORNER_MOUTH_SPEC
    shelf = SIDE_SHELF_SPEC if side else CORNER_SHELF_SPEC
    lean = math.radians(SIDE_CUT_SPEC - 90.0 if side else CORNER_CUT_SPEC - 135.0)
    points = np.array(SPEC_POINTS[k])
    middle = points.mean(axis=0)
    to_table = _unit([L / 2, W / 2] - middle)
    normal = np.asarray(jaw.fall_normal)
    # The fall line is parallel to the mouth, its normal pointing back to the table.
    assert float(normal @ (points[1] - points[0])) == pytest.approx(0.0, abs=1e-15)
    assert normal @ to_table > 0
    for end in jaw.fall_line:
        assert float((middle - end) @ normal) == pytest.approx(shelf, abs=1e-15)
    width = float(np.hypot(*(jaw.fall_line[1] - jaw.fall_line[0])))
    assert width == pytest.approx(mouth - 2.0 * shelf * math.tan(lean), abs=1e-15)


def _tip_centre(point, rail_away, into_table, cut_deg: float, radius: float) -> np.ndarray:
    """The centre of the circle of ``radius`` tangent to a rail nose and to its facing.

    Solved from the two tangency conditions (a point ``radius`` inside the cushion from
    each line), independently of the construction along the bisector.
    """
    cut = math.radians(cut_deg)
    facing = math.cos(cut) * rail_away - math.sin(cut) * into_table
    # Normals of the two lines towards the cushion side of each: -into_table for the nose;
    # for the facing, the one on the rail's side (the table's is across the throat).
    n_face = np.array([-facing[1], facing[0]])
    if n_face @ rail_away < 0:
        n_face = -n_face
    matrix = np.array([-into_table, n_face])
    rhs = np.array([radius, radius]) + matrix @ point
    return np.linalg.solve(matrix, rhs)


@pytest.mark.parametrize(("corner_r", "side_r"), [(0.004, 0.0015), (0.0015, 0.006)])
def test_round_tips_tangent_to_nose_and_facing(corner_r: float, side_r: float) -> None:
    """Each pocket's tips have its own kind's radius and touch both the nose and the facing."""
    table = Table(pockets=JawSpec(corner_tip_radius=corner_r, side_tip_radius=side_r))
    for k, jaw in enumerate(table.jaws):
        radius = side_r if k in SIDES else corner_r
        assert jaw.tip_radius == radius
        for side in range(2):
            point = np.array(SPEC_POINTS[k][side])
            other = np.array(SPEC_POINTS[k][1 - side])
            on_x_rail = point[1] in (0.0, W)
            rail = np.array([1.0, 0.0]) if on_x_rail else np.array([0.0, 1.0])
            if rail @ (other - point) > 0:
                rail = -rail
            if on_x_rail:
                inward = np.array([0.0, 1.0 if point[1] == 0.0 else -1.0])
            else:
                inward = np.array([1.0 if point[0] == 0.0 else -1.0, 0.0])
            cut = SIDE_CUT_SPEC if k in SIDES else CORNER_CUT_SPEC
            centre = _tip_centre(point, rail, inward, cut, radius)
            np.testing.assert_allclose(jaw.tip_centres[side], centre, rtol=0, atol=1e-15)
            # The rail ends where the tip touches the nose: r / tan(cut / 2) from the point.
            back = radius / math.tan(math.radians(cut) / 2)
            np.testing.assert_allclose(jaw.rail_ends[side], point + back * rail, atol=1e-15)


@pytest.mark.parametrize("corner_r", [0.004, 0.0015])
@pytest.mark.parametrize("offset", [-1e-9, 1e-9])
def test_grazing_a_corner_point_of_the_corner_radius(corner_r: float, offset: float) -> None:
    """A path passing a corner tip's centre at ``tip + R -/+ 1e-9``: hits the point or not."""
    table = Table(pockets=JawSpec(corner_tip_radius=corner_r, side_tip_radius=0.001))
    point, rail, inward = np.array(SPEC_POINTS[0][0]), np.array([1.0, 0.0]), np.array([0, 1.0])
    centre = _tip_centre(point, rail, inward, CORNER_CUT_SPEC, corner_r)
    # Closest approach in the direction 100 degrees from the centre (above the tip, towards
    # the throat), travelling down-left past it into the pocket.
    g = np.array([math.cos(math.radians(100.0)), math.sin(math.radians(100.0))])
    u = np.array([-g[1], g[0]])
    closest = centre + (corner_r + R + offset) * g
    start = closest - 0.2 * u
    result = shoot(table, [start], math.atan2(u[1], u[0]), 1.0)
    first = result.events[0]
    if offset < 0:
        assert (first.kind, first.j) == ("point", 0)
        # Entry into the contact circle rho = tip + R, a chord's half before the closest.
        rho, miss = corner_r + R, corner_r + R + offset
        s = float((closest - start) @ u) - math.sqrt((rho - miss) * (rho + miss))
        assert first.time == pytest.approx(_arc_time(1.0, s), rel=1e-9)
    else:
        assert (first.kind, first.j) != ("point", 0)
    assert check_shot(table, result) == []


def _offset_facing(k: int, side: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A point, the inward direction and the throat-side normal of a facing offset by ``R``.

    From the spec: the facing leaves the point at the cut angle to the rail.
    """
    point = np.array(SPEC_POINTS[k][side])
    other = np.array(SPEC_POINTS[k][1 - side])
    jaw = TABLE.jaws[k]
    d = _unit(jaw.facings[side][1] - jaw.facings[side][0])
    n = np.array([-d[1], d[0]])
    if n @ (other - point) < 0:
        n = -n
    return point + R * n, d, n


@pytest.mark.parametrize("k", [0, 1])
@pytest.mark.parametrize("depth", [0.3, 0.7])
def test_a_facing_runs_on_past_the_fall_line(k: int, depth: float) -> None:
    """Just in front of the fall line, straight at a facing: it bounces off the facing.

    The cushion's facing goes on into the hole; only the centre reaching the fall line
    drops the ball. A centre ``depth`` of the way from the fall line towards the point at
    which the offset facing crosses it, 5 mm from the facing, rolls at it along its normal:
    it touches the facing before the fall line (whose distance shrinks only by
    ``n . fall_normal`` per metre), and the normal speed reflects with ``e_jaw``.
    """
    table = Table(e_jaw=0.5)
    jaw = table.jaws[k]
    a_point, d, n = _offset_facing(k, 0)
    normal = np.asarray(jaw.fall_normal)
    fall_point = jaw.fall_line[0]
    # Where the offset facing crosses the fall line, and how far in front of it the contact
    # lies: the contact is on the offset facing, `lead` back from that crossing.
    lam_fall = float((fall_point - a_point) @ normal) / float(d @ normal)
    lean = float(n @ normal)  # fall-line distance lost per metre along -n
    assert lean > 0
    gap = 0.005
    lead = depth * gap * lean / -float(d @ normal)  # contact ahead of the crossing
    contact = a_point + (lam_fall - lead) * d
    start = contact + gap * n
    ahead = float((contact - fall_point) @ normal)
    assert ahead > 0  # the contact is in front of the fall line ...
    assert ahead < gap * lean  # ... by less than the whole run would lose
    speed = 0.6
    result = shoot(table, [start], math.atan2(-n[1], -n[0]), speed)
    first = result.events[0]
    assert (first.kind, first.j) == ("jaw", 2 * k)
    assert first.time == pytest.approx(_arc_time(speed, gap), rel=1e-12)
    _, _, state, _ = result.segments
    v_hit = speed - A * first.time
    np.testing.assert_allclose(state[1, 2:], 0.5 * v_hit * n, atol=1e-13)


@pytest.mark.parametrize(("k", "side"), [(1, 0), (1, 1), (0, 0), (2, 0)])
@pytest.mark.parametrize("delta", [0.2e-3, 1e-3])
def test_a_ball_crossing_the_rail_line_beside_a_round_tip_meets_the_tip(
    k: int, side: int, delta: float
) -> None:
    """Straight down onto the bottom rail line, ``delta`` past the rail's end towards the point.

    The straight nose stops where the tip touches it, ``r / tan(cut / 2)`` before the point;
    from there to the point the cushion is the tip's arc, which the ball (moving along
    ``-y``, ``delta`` from the tip centre's line) meets ``sqrt(rho^2 - delta^2) - r`` above
    the nose, below the rail line ``y = R``: a point contact, not a rail one.
    """
    jaw = TABLE.jaws[k]
    radius = jaw.tip_radius
    point = np.array(SPEC_POINTS[k][side])
    other = np.array(SPEC_POINTS[k][1 - side])
    rail = np.array([1.0, 0.0]) if (other - point)[0] < 0 else np.array([-1.0, 0.0])
    cut = SIDE_CUT_SPEC if k in SIDES else CORNER_CUT_SPEC
    centre = _tip_centre(point, rail, np.array([0.0, 1.0]), cut, radius)
    rho = radius + R
    x = centre[0] - delta * rail[0]  # towards the point from the tangent line x = centre
    y0 = 0.2
    hit_y = centre[1] + math.sqrt(rho * rho - delta * delta)
    assert hit_y < R  # beyond the rail line: the straight rail is not there
    speed = 1.0
    result = shoot(TABLE, [[x, y0]], -math.pi / 2, speed)
    first = result.events[0]
    assert (first.kind, first.j) == ("point", 2 * k + side)
    assert first.time == pytest.approx(_arc_time(speed, y0 - hit_y), rel=1e-12)
    # Reflected off the line from the tip's centre (restitution e_jaw = e_cushion here).
    n = _unit([x, hit_y] - centre)
    v_hit = speed - A * first.time
    u = np.array([0.0, -1.0])
    expected = v_hit * (u - (1 + TABLE.e_jaw) * (u @ n) * n)
    _, _, state, _ = result.segments
    np.testing.assert_allclose(state[1, 2:], expected, atol=1e-12)


def _rail_frame(k: int, side: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A point from the spec, its rail's direction away from the pocket, and into the table."""
    point = np.array(SPEC_POINTS[k][side])
    other = np.array(SPEC_POINTS[k][1 - side])
    if point[1] in (0.0, W):
        rail = np.array([1.0, 0.0])
        inward = np.array([0.0, 1.0 if point[1] == 0.0 else -1.0])
    else:
        rail = np.array([0.0, 1.0])
        inward = np.array([1.0 if point[0] == 0.0 else -1.0, 0.0])
    if rail @ (other - point) > 0:
        rail = -rail
    return point, rail, inward


def _placed(table: Table, p) -> str:
    """``"free"`` if a ball at rest may stand at ``p``, else the refusal's message."""
    try:
        result = shoot(table, [p], 0.0, 0.0)
    except ValueError as exc:
        return str(exc)
    assert result.n_events == 0
    return "free"


@pytest.mark.parametrize("k", range(6))
@pytest.mark.parametrize("side", [0, 1])
def test_the_playing_region_ends_at_the_offset_facings_and_points(k: int, side: int) -> None:
    """A centre a micrometre inside an offset facing or point is refused, outside it stands.

    The facing line and the tip circle come from the spec (point, cut angle, tip tangent to
    nose and facing), offset by ``R``; the fall line from the shelf. This pins where the
    simulator draws its region (which the invariant G of ``pool_env.testing`` also reads).
    """
    jaw = TABLE.jaws[k]
    cut = SIDE_CUT_SPEC if k in SIDES else CORNER_CUT_SPEC
    point, rail, inward = _rail_frame(k, side)
    c = math.radians(cut)
    d = math.cos(c) * rail - math.sin(c) * inward  # the facing, into the pocket
    n = np.array([-d[1], d[0]])
    if n @ rail > 0:  # the throat's side, away from the rail's cushion
        n = -n
    normal = np.asarray(jaw.fall_normal)
    fall_point = np.array(SPEC_POINTS[k]).mean(axis=0) - normal * (
        SIDE_SHELF_SPEC if k in SIDES else CORNER_SHELF_SPEC
    )
    # Halfway from the point to where the offset facing meets the fall line.
    a_point = point + R * n
    lam_fall = float((fall_point - a_point) @ normal) / float(d @ normal)
    on_facing = a_point + 0.5 * lam_fall * d
    hair = 1e-6
    assert f"inside a jaw (facing or point) of pocket {k}" in _placed(TABLE, on_facing - hair * n)
    assert _placed(TABLE, on_facing + hair * n) == "free"
    # The tip: its contact circle, in the middle of its normal cone (between the nose's
    # normal and the facing's).
    centre = _tip_centre(point, rail, inward, cut, jaw.tip_radius)
    g = _unit(inward + n)
    rho = jaw.tip_radius + R
    assert f"of pocket {k}" in _placed(TABLE, centre + (rho - hair) * g)
    assert _placed(TABLE, centre + (rho + hair) * g) == "free"
    # The fall line, in the middle of the throat.
    assert f"behind pocket {k}'s fall line" in _placed(TABLE, fall_point - hair * normal)
    assert _placed(TABLE, fall_point + hair * normal) == "free"


# --- a tie between a ball impact and a facing contact ---------------------------------------


def _tie_scene(theta_deg: float, v_dir: tuple[float, float], speed: float):
    """Ball 0 touching a corner facing and ball 1 at once, moving into both.

    In the frame of facing 0 of pocket 0 (``d`` along it, ``n`` across the throat): ball 0
    sits a femtometre into the offset facing (within the input tolerance, so contact is
    certain and the tie exact in float64), 2 cm along it; ball 1 touches ball 0 along the
    line of centres at ``theta_deg`` from ``n`` (non-orthogonal to the facing's normal).
    Returns ``(positions, velocities, d, n, c)``.
    """
    a_point, d, n = _offset_facing(0, 0)
    p0 = a_point + 0.02 * d - 1e-15 * n
    th = math.radians(theta_deg)
    c = math.cos(th) * n - math.sin(th) * d  # ball 1 across the throat, towards the table
    p1 = p0 + (2 * R - 1e-16) * c
    v = speed * _unit(v_dir[0] * n + v_dir[1] * c)
    return np.array([p0, p1]), np.array([v, [0.0, 0.0]]), d, n, c


@pytest.mark.parametrize(("theta_deg", "v_dir"), [(60.0, (-0.8, 1.0)), (75.0, (-1.0, 1.0))])
def test_ball_impact_then_facing_at_the_same_instant(theta_deg: float, v_dir) -> None:
    """The documented tie order (ball before cushion, jaw and point) on a facing.

    By hand: the impact along the line of centres (``e_ball``), then the facing reflects
    what is left of ball 0's normal speed into it (``e_jaw``); both at t = 0. The reverse
    order (facing first) sends ball 1 off at another speed: the sequence and the speeds
    after the instant pin it.
    """
    table = Table(e_jaw=0.7, e_ball=0.9)
    pos, vel, _, n, c = _tie_scene(theta_deg, v_dir, 0.6)
    assert _placed(table, pos[0]) == "free" and _placed(table, pos[1]) == "free"
    v0 = vel[0]
    assert v0 @ n < 0 and v0 @ c > 0  # into the facing and into ball 1
    un = float(v0 @ c)
    u0, u1 = normal_velocities(table.ball_mass, table.ball_mass, un, 0.0, table.e_ball)
    after0 = v0 + (u0 - un) * c
    after1 = u1 * c
    assert after0 @ n < 0  # still into the facing after the impact: it bounces at once
    after0 = after0 - (1 + table.e_jaw) * float(after0 @ n) * n
    assert (after1 - after0) @ c > 0  # separating: no third event at t = 0
    result = simulate(table, pos, vel)
    head = [(e.kind, e.i, e.j, e.time) for e in result.events[:2]]
    assert head == [("ball", 0, 1, 0.0), ("jaw", 0, 0, 0.0)]
    assert result.events[2].time > 0.0
    ball, t, state, _ = result.segments
    for k, expected in ((0, after0), (1, after1)):
        last = np.flatnonzero((ball == k) & (t == 0.0))[-1]
        np.testing.assert_allclose(state[last, 2:], expected, rtol=0, atol=1e-14)
    # The whole shot (what the balls do after the instant) against the 50-digit reference.
    ref = reference_simulate(table, pos, vel, max_events=400)
    assert [(e.kind, e.i, e.j) for e in result.events] == [(k, i, j) for _, k, i, j in ref.events]
    for (x, y), (rx, ry) in zip(result.positions, ref.positions, strict=True):
        assert math.hypot(x - float(rx), y - float(ry)) < 1e-9
    # The reverse order would give ball 1 a visibly different speed.
    reflected = v0 - (1 + table.e_jaw) * float(v0 @ n) * n
    _, wrong1 = normal_velocities(
        table.ball_mass, table.ball_mass, float(reflected @ c), 0.0, table.e_ball
    )
    assert abs(wrong1 - u1) > 0.05


# --- a lump against a dead facing -----------------------------------------------------------


@pytest.mark.parametrize("e_ball", [0.95, 0.5, 0.0])
def test_a_ball_wedged_against_a_dead_facing_leaves_as_a_lump_along_it(e_ball: float) -> None:
    """``e_jaw = 0``: the facing takes every impulse along its normal, the balls share the rest.

    Ball 0 rests on the side pocket's left facing, 4 mm in from its start; ball 1 touches it
    along the facing's normal and drives it in at 0.8 m/s while moving 0.05 m/s outwards
    along the facing. Every impulse (ball on ball, facing on ball) is along that normal, so
    the pair's momentum along the facing, ``m * 0.05``, is conserved; the Zeno rule ends the
    cascade with the pair stuck against the facing, each ball rolling along it at
    0.025 m/s: ``0.025^2 / 2a`` further out (the analogue, on a facing, of the dead-rail case
    of ``tests/sim/test_pinned_hard_cases.py``).
    """
    table = Table(e_ball=e_ball, e_jaw=0.0)
    a_point, d, n = _offset_facing(1, 0)
    p0 = a_point + 0.004 * d
    pos = np.array([p0, p0 + 2 * R * n])
    vel = np.array([[0.0, 0.0], -0.8 * n - 0.05 * d])
    assert _placed(table, pos[0]) == "free" and _placed(table, pos[1]) == "free"
    result = simulate(table, pos, vel)
    assert not result.hit_event_cap and result.pocketed.tolist() == [-1, -1]
    travel = 0.025**2 / (2 * table.deceleration)
    np.testing.assert_allclose(result.positions, pos - travel * d, rtol=0, atol=1e-12)
