"""The API contract of simulate/shoot/Table/ShotResult, and clear errors for bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.layouts import break_scene, foot_spot, head_spot, rack_eight_ball, rack_nine_ball
from pool_env.sim.table import CORNER_MOUTH, SIDE_MOUTH

R = Table().ball_radius


def test_standard_pockets_match_the_mouths(table: Table) -> None:
    """A ball rolling along a rail is captured exactly inside the mouth."""
    assert table.pockets.shape == (6, 3)
    corner = table.pockets[0]
    # On the rail line y = R, the corner circle ends CORNER_MOUTH / sqrt(2) from the corner.
    reach = math.sqrt(corner[2] ** 2 - R**2)
    assert reach == pytest.approx(CORNER_MOUTH / math.sqrt(2))
    side = table.pockets[1]
    half = math.sqrt(side[2] ** 2 - (R - side[1]) ** 2)
    assert half == pytest.approx(SIDE_MOUTH / 2)
    assert Table(pockets="none").pockets.shape == (0, 3)
    custom = Table(pockets=[(1.0, 0.0, 0.1)])
    np.testing.assert_array_equal(custom.pockets, [[1.0, 0.0, 0.1]])


def test_table_is_frozen(table: Table) -> None:
    with pytest.raises(AttributeError):
        table.length = 3.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        table.pockets[0, 0] = 1.0


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"length": 0.0}, "length"),
        ({"width": -1.0}, "width"),
        ({"ball_radius": float("nan")}, "ball_radius"),
        ({"ball_mass": 0.0}, "ball_mass"),
        ({"mu_roll": -0.1}, "mu_roll"),
        ({"g": float("inf")}, "g"),
        ({"e_ball": 1.5}, "e_ball"),
        ({"e_cushion": -0.1}, "e_cushion"),
        ({"e_ball": float("nan")}, "e_ball"),
        ({"pockets": "six"}, "unknown pocket"),
        ({"pockets": [(1.0, 2.0)]}, "shape"),
        ({"pockets": [(1.0, 2.0, -0.1)]}, "radius"),
        ({"pockets": [(1.0, float("nan"), 0.1)]}, "finite"),
        ({"length": 0.05}, "cannot hold"),
    ],
)
def test_bad_table_parameters(kwargs, message) -> None:
    with pytest.raises(ValueError, match=message):
        Table(**kwargs)


@pytest.mark.parametrize(
    ("positions", "velocities", "message"),
    [
        ([[1.0, 0.6], [1.0 + 2 * R - 1e-6, 0.6]], None, "overlap"),
        ([[0.01, 0.6]], None, "off the table"),
        ([[1.0, 2.0]], None, "off the table"),
        ([[float("nan"), 0.6]], None, "non-finite position"),
        ([[1.0, 0.6]], [[float("inf"), 0.0]], "non-finite velocity"),
        ([[0.0, 0.0]], None, "behind pocket 0's fall line"),
        ([[0.03, -0.012]], None, "inside a jaw .* of pocket 0"),
        ([[1.27, -0.01]], None, "behind pocket 1's fall line"),
        ([[1.22, -0.004]], None, "inside a jaw .* of pocket 1"),
        ([[1.0, 0.02]], None, "off the table"),
        ([1.0, 0.6], None, "shape"),
        ([[1.0, 0.6, 0.0]], None, "shape"),
        ([["a", 0.6]], None, "numbers"),
        ([[1.0, 0.6]], [[0.0, 0.0], [0.0, 0.0]], "rows"),
    ],
)
def test_bad_scenes(table: Table, positions, velocities, message) -> None:
    velocities = np.zeros((len(positions), 2)) if velocities is None else velocities
    with pytest.raises(ValueError, match=message):
        simulate(table, positions, velocities)


def test_inside_a_capture_circle_is_rejected() -> None:
    with pytest.raises(ValueError, match="inside pocket 0"):
        simulate(Table(pockets="circles"), [[0.05, 0.05]], [[0.0, 0.0]])


def test_bad_masses_and_caps(table: Table) -> None:
    pos = [[1.0, 0.6]]
    with pytest.raises(ValueError, match="mass"):
        simulate(table, pos, [[0.0, 0.0]], masses=[0.0])
    with pytest.raises(ValueError, match="masses"):
        simulate(table, pos, [[0.0, 0.0]], masses=[0.1, 0.2])
    with pytest.raises(ValueError, match="max_events"):
        simulate(table, pos, [[0.0, 0.0]], max_events=-1)
    with pytest.raises(ValueError, match="Table"):
        simulate("table", pos, [[0.0, 0.0]])  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"angle": float("nan")}, "angle"),
        ({"speed": -1.0}, "speed"),
        ({"speed": float("inf")}, "speed"),
        ({"cue": 3}, "cue"),
        ({"cue": -1}, "cue"),
    ],
)
def test_bad_shots(table: Table, kwargs, message) -> None:
    args = {"angle": 0.0, "speed": 1.0, "cue": 0} | kwargs
    with pytest.raises(ValueError, match=message):
        shoot(table, [[1.0, 0.6], [1.5, 0.6]], **args)


def test_inputs_are_never_modified(table: Table) -> None:
    pos = break_scene(table, "nine")
    before = pos.copy()
    shoot(table, pos, 0.0, 8.0)
    np.testing.assert_array_equal(pos, before)


def test_result_contract(table: Table) -> None:
    positions = break_scene(table, "nine")
    result = shoot(table, positions, 0.01, 8.0)
    assert result.positions.shape == (10, 2)
    assert result.pocketed.shape == (10,)
    times = [e.time for e in result.events]
    assert times == sorted(times)
    assert {e.kind for e in result.events} <= {"ball", "cushion", "pocket", "stop", "jaw", "point"}
    assert result.duration == times[-1]
    np.testing.assert_array_equal(result.positions_at(0.0), positions)
    # positions_at(duration) is the final state, bit for bit.
    np.testing.assert_array_equal(result.positions_at(result.duration), result.positions)
    for event in result.events:
        if event.kind == "pocket":
            assert result.pocketed[event.i] == event.j
            assert result.pocketed_at(event.time)[event.i]
    with pytest.raises(ValueError, match="duration"):
        result.positions_at(result.duration + 1.0)
    with pytest.raises(ValueError, match="duration"):
        result.positions_at(-1e-9)
    quiet = shoot(table, positions, 0.01, 8.0, record=False)
    np.testing.assert_array_equal(quiet.positions, result.positions)
    assert quiet.n_events == result.n_events and quiet.events == []
    with pytest.raises(ValueError, match="record=False"):
        quiet.positions_at(0.0)


def test_event_cap_reports_instead_of_hanging(table: Table) -> None:
    positions = break_scene(table, "eight")
    result = shoot(table, positions, 0.0, 8.0, max_events=20)
    assert result.hit_event_cap and result.n_events == 20
    # Every ball was stopped where it was; nothing overlaps.
    d = np.hypot(*(result.positions[:, None] - result.positions[None]).transpose(2, 0, 1))
    assert d[np.triu_indices(16, 1)].min() > 2 * R - 1e-9


def test_nothing_moves(table: Table) -> None:
    result = shoot(table, [[1.0, 0.6]], 0.0, 0.0)
    assert result.n_events == 0 and result.duration == 0.0
    np.testing.assert_array_equal(result.positions, [[1.0, 0.6]])


def test_layouts(table: Table) -> None:
    nine = rack_nine_ball(table)
    eight = rack_eight_ball(table)
    np.testing.assert_allclose(nine[0], foot_spot(table))
    np.testing.assert_allclose(eight[0], foot_spot(table))
    np.testing.assert_allclose(nine[8], foot_spot(table) + [2 * R * math.sqrt(3), 0])  # the 9
    np.testing.assert_allclose(eight[7], foot_spot(table) + [2 * R * math.sqrt(3), 0])  # the 8
    for rack in (nine, eight):
        d = np.hypot(*(rack[:, None] - rack[None]).transpose(2, 0, 1))
        off = d[np.triu_indices(len(rack), 1)]
        assert off.min() == pytest.approx(2 * R, abs=1e-12)  # touching, not overlapping
    spaced = rack_nine_ball(table, gap=1e-3)
    d = np.hypot(*(spaced[:, None] - spaced[None]).transpose(2, 0, 1))
    assert d[np.triu_indices(9, 1)].min() == pytest.approx(2 * R + 1e-3)
    np.testing.assert_allclose(break_scene(table, "eight")[0], head_spot(table))
    ten = break_scene(table, "ten")  # the 1 on the foot spot, the 10 in the third row's middle
    np.testing.assert_allclose(ten[1], foot_spot(table))
    assert ten[10, 1] == pytest.approx(table.width / 2) and ten[10, 0] == pytest.approx(ten[4, 0])
    with pytest.raises(ValueError, match="rack"):
        break_scene(table, "twelve")
    with pytest.raises(ValueError, match="gap"):
        rack_nine_ball(table, gap=-1.0)
    with pytest.raises(ValueError, match="fit"):
        rack_eight_ball(Table(length=0.9, width=0.3), gap=0.0)
