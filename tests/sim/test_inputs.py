"""One argument check for every simulator entry point, and the numeric limits (issue 11).

Item 7: ``simulate``, ``shoot`` and ``simulate_batch`` reject the same bad arguments with
the same ``ValueError``. Item 6: values beyond float64's comfortable range are rejected
naming the limit, and extreme but valid scales stay exact. Item 8: every array layout
runs the one compiled version of the kernels.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.batch import simulate_batch, simulate_batch_threads
from pool_env.sim.inputs import max_speed, reachable_speed
from pool_env.sim.kernels import limits, validation
from pool_env.sim.kernels.roll import level as roll_level
from pool_env.testing.invariants import check_shot

POS = [[1.0, 0.6], [1.5, 0.6]]
VEL = [[1.0, 0.0], [0.0, 0.0]]


def _message(call) -> str:
    with pytest.raises(ValueError, match=r".") as info:
        call()
    return str(info.value)


@pytest.mark.parametrize("cap", [-5, 2.5, "7", 2**63, True, None, np.float64(3.0)])
def test_every_entry_point_rejects_a_bad_event_cap_alike(table: Table, cap) -> None:
    single = _message(lambda: simulate(table, POS, VEL, max_events=cap))
    assert "max_events" in single
    assert _message(lambda: simulate(table, POS, VEL, max_events=cap, record=False)) == single
    assert _message(lambda: shoot(table, POS, 0.0, 1.0, max_events=cap)) == single
    batch = np.array([POS, POS])
    vel = np.array([VEL, VEL])
    assert _message(lambda: simulate_batch(table, batch, vel, max_events=cap)) == single
    on = np.ones((2, 2), bool)
    assert _message(lambda: simulate_batch_threads(table, batch, vel, on, 2, cap)) == single


def test_the_largest_event_cap_is_accepted(table: Table) -> None:
    cap = np.int64(2**63 - 1)
    n_events = simulate(table, POS, VEL).n_events
    assert simulate(table, POS, VEL, max_events=cap).n_events == n_events
    batch = simulate_batch(table, np.array([POS]), np.array([VEL]), max_events=cap)
    assert batch.n_events[0] == n_events


@pytest.mark.parametrize("bad", ["table", None, {"length": 2.0}, Table])
def test_a_bad_table_is_a_value_error_everywhere(bad) -> None:
    single = _message(lambda: simulate(bad, POS, VEL))
    assert "table must be a pool_env.Table" in single
    assert _message(lambda: shoot(bad, POS, 0.0, 1.0)) == single
    assert _message(lambda: simulate_batch(bad, np.array([POS]), np.array([VEL]))) == single
    on = np.ones((1, 2), bool)
    assert _message(lambda: simulate_batch_threads(bad, [POS], [VEL], on, 2)) == single


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"speed": 1 + 2j}, "speed"),
        ({"speed": "3"}, "speed"),
        ({"speed": True}, "speed"),
        ({"angle": 1j}, "angle"),
        ({"angle": "0"}, "angle"),
        ({"cue": 0.0}, "cue"),
        ({"cue": True}, "cue"),
    ],
)
def test_shot_arguments_of_the_wrong_kind(table: Table, kwargs, message) -> None:
    args = {"angle": 0.0, "speed": 1.0, "cue": 0} | kwargs
    assert message in _message(lambda: shoot(table, POS, **args))


@pytest.mark.parametrize(
    "velocities",
    [np.array(VEL) * (1 + 1j), [["1", "0"], ["0", "0"]], np.array(VEL, dtype=bool)],
)
def test_arrays_must_hold_real_numbers(table: Table, velocities) -> None:
    """Complex velocities used to lose their imaginary part silently."""
    single = _message(lambda: simulate(table, POS, velocities))
    assert "velocities must be" in single
    batch = _message(lambda: simulate_batch(table, np.array([POS]), np.array([velocities])))
    assert "velocities must be" in batch


@pytest.mark.parametrize(
    ("kwargs", "limit"),
    [
        ({"ball_radius": 1e-9}, "ball_radius must lie in [0.0001, 10000] m"),
        ({"length": 1e5}, "length must lie in [0.0001, 10000] m"),
        ({"width": 2e4}, "width must lie in"),
        ({"ball_mass": 1e308}, "ball_mass must lie in [1e-12, 1e+12] kg"),
        ({"mu_roll": 1e-200}, "mu_roll * g must lie in [1e-06, 1e+06] m/s^2"),
        ({"mu_roll": 1e200, "g": 1e200}, "mu_roll * g must be finite"),
        ({"length": 1j}, "length must be a real number"),
        ({"e_ball": "1"}, "e_ball must be a real number"),
        ({"pockets": [(1.0, 0.0, 1e300)]}, "within 10000 m"),
    ],
)
def test_tables_beyond_the_numeric_limits(kwargs, limit: str) -> None:
    assert limit in _message(lambda: Table(**kwargs))


def test_speeds_beyond_the_limits(table: Table) -> None:
    """A speed above ~1.34e154 m/s used to give a no-op shot; every such speed is refused."""
    for speed in (1.35e154, 1e200, 1.1 * limits.MAX_SPEED):
        message = _message(lambda s=speed: shoot(table, POS, 0.0, s))
        assert "the simulator's numeric limits" in message
        assert message == _message(lambda s=speed: shoot(table, POS, 0.0, s, record=False))
    # On this table the rolling distance binds first: v^2 / (2 mu g) <= MAX_ROLL.
    fastest = math.sqrt(2.0 * table.deceleration * limits.MAX_ROLL)
    assert max_speed(table) == pytest.approx(fastest, rel=1e-15)
    shoot(table, POS, 0.0, 0.999 * fastest, record=False)
    with pytest.raises(ValueError, match="free rolling distance"):
        shoot(table, POS, 0.0, 1.001 * fastest)
    vel = np.array([[[1.001 * fastest, 0.0], [0.0, 0.0]]])
    with pytest.raises(ValueError, match=r"table 0: ball 0 has speed .* free rolling distance"):
        simulate_batch(table, np.array([POS]), vel)


def test_energy_that_could_drive_a_light_ball_past_the_limits_is_refused(table: Table) -> None:
    """Issue 20 item 9: a light ball sped to 14 km/s by impacts ended 1.2e-9 m past a rail.

    Kinetic energy never grows, so the lightest ball can never move faster than
    sqrt(sum m v^2 / m_min); a scene where that passes the speed limits is refused (the
    limits then bound every speed of the shot, not only the initial ones). One ball moving,
    or equal masses: the bound is the initial speed, as before.
    """
    fastest = max_speed(table)
    pos = [[1.0, 0.6], [1.5, 0.6], [2.0, 0.6]]
    masses = [1.0, 1e-6, 1.0]
    ok = [[0.999 * fastest / 1e3, 0.0], [0.0, 0.0], [0.0, 0.0]]  # sqrt(1 / 1e-6) = 1e3
    assert reachable_speed(ok, masses) == pytest.approx(0.999 * fastest, rel=1e-15)
    simulate(table, pos, ok, masses, record=False)
    fast = [[1.001 * fastest / 1e3, 0.0], [0.0, 0.0], [0.0, 0.0]]
    message = _message(lambda: simulate(table, pos, fast, masses))
    assert message.startswith("the scene's kinetic energy could speed ball 1 (the lightest)")
    assert "the simulator's numeric limits" in message
    assert message == _message(lambda: simulate(table, pos, fast, masses, record=False))
    assert message == _message(lambda: shoot(table, pos, 0.0, fast[0][0], masses=masses))
    batch = _message(lambda: simulate_batch(table, np.array([pos]), np.array([fast]), masses))
    assert batch == f"table 0: {message}"
    # equal masses: the root of the sum of squared speeds, each ball within the limit alone
    both = [[0.8 * fastest, 0.0], [0.0, 0.0], [0.0, -0.8 * fastest]]
    assert reachable_speed(both) == pytest.approx(math.sqrt(1.28) * fastest, rel=1e-15)
    assert "kinetic energy could speed ball 0" in _message(lambda: simulate(table, pos, both))
    # one ball moving: exactly its speed, whatever the masses (a shot is judged as before)
    assert reachable_speed(ok, [1e-6, 1.0, 1.0]) == 0.999 * fastest / 1e3


def test_the_energy_limit_is_named_alike_on_the_spin_level() -> None:
    """A spin table's energy refusal says energy, never spin.

    Each validation code means one thing on both levels: the codes once overlapped, and a
    roll batch then failed reading a spin array it never had.
    """
    table = Table(model="spin", pockets="none")
    fastest = max_speed(table)
    pos = [[1.0, 0.6], [1.5, 0.6], [2.0, 0.6]]
    masses = [1.0, 1e-6, 1.0]
    fast = [[1.001 * fastest / 1e3, 0.0], [0.0, 0.0], [0.0, 0.0]]
    message = _message(lambda: simulate(table, pos, fast, masses))
    assert message.startswith("the scene's kinetic energy could speed ball 1 (the lightest)")
    batch = _message(lambda: simulate_batch(table, np.array([pos]), np.array([fast]), masses))
    assert batch == f"table 0: {message}"
    assert len({validation.TOO_ENERGETIC, validation.BAD_SPIN, validation.SPIN_TOO_FAST}) == 3


def test_no_ball_ever_passes_the_energy_bound() -> None:
    """A light ball rattles between a heavy one and a rail: faster than any initial speed.

    Never faster than the energy bound sqrt(sum m v^2 / m_min).
    """
    table = Table(pockets="none", e_ball=1.0, e_cushion=1.0, mu_roll=1e-3)
    r = table.ball_radius
    pos = [[0.6, 0.6], [r + 0.05, 0.6]]
    vel = np.array([[-2.0, 0.0], [0.0, 0.0]])
    masses = [1.0, 1e-2]  # the bound: 20 m/s
    result = simulate(table, pos, vel, masses)
    bound = reachable_speed(vel, masses)
    state = result.segments[2]  # every anchor's (x, y, vx, vy): the speeds after each event
    fastest = float(np.hypot(state[:, 2], state[:, 3]).max())
    assert 2.0 * 2.0 < fastest <= bound * (1 + 1e-12)


@pytest.mark.parametrize("mass", [1e308, 1e-300, 2e12, 0.0, float("nan")])
def test_masses_beyond_the_limits(table: Table, mass: float) -> None:
    """Equal masses of 1e308 used to overflow and stop both balls."""
    message = _message(lambda: simulate(table, POS, VEL, masses=[mass, mass]))
    assert "ball 0 has mass" in message and "[1e-12, 1e+12] kg" in message
    batch = _message(lambda: simulate_batch(table, np.array([POS]), np.array([VEL]), [mass] * 2))
    assert batch == f"table 0: {message}"


@pytest.mark.parametrize("distance", [3e3, limits.MAX_LENGTH - 1.0])
@pytest.mark.parametrize("both_moving", [False, True])
def test_a_long_approach_stays_exact(distance: float, both_moving: bool) -> None:
    """G: a ball travelling kilometres before a grazing impact does not overlap its target.

    The ray-circle discriminant used to cancel the rounding of |d|^2 against itself:
    1e-8 m of overlap after 3 km, 3e-8 m after 10 km (and 2e-6 m after 90 km, which the
    limit on the table length now excludes). Now it is ~2e-16 of the distance.
    """
    table = Table(length=distance + 1.0, mu_roll=1e-4, pockets="none")
    r = table.ball_radius
    speed = 1.5 * math.sqrt(2.0 * table.deceleration * distance)
    rng = np.random.default_rng(int(distance))
    worst = math.inf
    for offset in rng.uniform(-1.99, 1.99, 20) * r:
        velocities = [[speed, 0.0], [-0.3 if both_moving else 0.0, 0.0]]
        result = simulate(table, [[r + 0.01, 0.6], [distance, 0.6 + offset]], velocities)
        impact = next(ev for ev in result.events if ev.kind == "ball")
        p = result.positions_at(impact.time)
        worst = min(worst, float(np.hypot(*(p[1] - p[0]))) - 2.0 * r)
    assert worst > -1e-10


@pytest.mark.parametrize(
    ("table_kwargs", "masses", "speed"),
    [
        ({"ball_radius": limits.MIN_LENGTH, "length": 0.01, "width": 0.005}, None, 0.05),
        ({"length": limits.MAX_LENGTH, "width": 5e3, "ball_radius": 10.0}, None, 20.0),
        # the cue ball the lightest: a heavy cue ball's energy could drive the lightest ball
        # past the speed limits (test_energy_that_could_drive_a_light_ball_past_the_limits)
        ({}, [limits.MIN_MASS, limits.MAX_MASS, 1.0], 5.0),
        ({}, [limits.MAX_MASS, limits.MAX_MASS, limits.MAX_MASS / 4], 5.0),
        ({"mu_roll": 1e5}, None, limits.MAX_SPEED),
    ],
)
def test_extreme_but_valid_scales(table_kwargs, masses, speed: float) -> None:
    """G, P, E, T at the edges of the documented limits: a shot into two resting balls."""
    table = Table(pockets="none", **table_kwargs)
    r = table.ball_radius
    speed = min(speed, 0.999 * max_speed(table))
    gap = min(0.3 * table.stop_distance(speed), 0.3 * table.length)
    y = table.width / 2
    x1 = 5 * r + gap
    positions = [[3 * r, y], [x1, y + 0.5 * r], [x1 + 2 * r + 0.5 * gap, y - 0.3 * r]]
    result = shoot(table, positions, 0.0, speed, masses=masses)
    assert result.first_contact == (0, 1)
    assert check_shot(table, result, masses) == []


def test_one_compiled_version_for_every_array_layout(table: Table) -> None:
    """Read-only, big-endian, float32 or strided inputs used to compile a second version."""
    pos = np.array(POS)
    shoot(table, pos, 0.0, 1.0)
    shoot(table, pos, 0.0, 1.0, masses=[0.17, 0.2])
    shoot(table, pos, 0.0, 1.0, record=False)
    simulate(table, pos, np.array(VEL))
    simulate_batch(table, np.array([POS]), np.array([VEL]))
    entry = roll_level.ENTRIES  # the roll table's compiled entry points
    kernels = (entry.packed_shot, entry.packed_strike, validation.validate, entry.run_batch)
    counts = [len(k.signatures) for k in kernels]
    frozen = pos.copy()
    frozen.setflags(write=False)
    variants = [frozen, pos.astype(">f8"), pos.astype(np.float32), np.asfortranarray(pos)]
    variants.append(np.repeat(pos, 2, axis=0)[::2])
    for p in variants:
        r = simulate(table, p, frozen, masses=np.array([0.17, 0.2]).astype(">f8"))
        plain = simulate(table, np.array(p, np.float64), pos.copy(), masses=[0.17, 0.2])
        np.testing.assert_array_equal(r.positions, plain.positions)
        simulate(table, p, frozen, record=False)
        shoot(table, p, 0.0, 1.0, record=False)
        batch = np.broadcast_to(p, (3, 2, 2))  # read-only view
        simulate_batch(table, batch, batch * 0.0, active=np.ones((3, 2), bool))
    assert [len(k.signatures) for k in kernels] == counts
