"""Hard cases on the snooker table's big round jaws (4 in corner, 2.5 in centre), both levels.

A jaw is a curved cushion segment found like every other event: grazing it by a hair
either side, a ball rolling along the rail into it, a ball at rest against it, and fast
rattles between the two jaws of a pocket, which must end. Every shot passes every
invariant (``pool_env.testing.invariants.check_shot``).
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.testing.invariants import check_shot

LEVELS = ("roll", "spin")


def _table(level: str, **values: float) -> Table:
    return Table.preset("snooker", model=level, **values)


def _run(table: Table, pos, vel):
    pos, vel = np.asarray(pos, dtype=float), np.asarray(vel, dtype=float)
    result = simulate(table, pos, vel)
    assert check_shot(table, result, samples=200) == []
    assert not result.hit_event_cap
    return result


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize(("hair", "touches"), [(-1e-9, True), (1e-9, False)])
def test_grazing_a_round_jaw(level: str, hair: float, touches: bool) -> None:
    """A ball passing the centre pocket's left jaw at its contact distance, plus or minus.

    The path is tangent to the jaw's contact circle (radius ``r + R``) at 45 degrees up
    its arc, inside the pocket's opening, moved ``hair`` off it.
    """
    table = _table(level)
    jaw = table.jaws[1]  # bottom centre
    centre, rho = jaw.tip_centres[0], jaw.tip_radius + table.ball_radius
    n = np.array([1.0, 1.0]) / np.sqrt(2.0)  # the contact point's outward normal
    t = np.array([n[1], -n[0]])  # the path's direction: into the pocket
    touch = centre + rho * n
    start = touch - 0.3 * t + hair * n
    result = _run(table, [start], [list(0.8 * t)])
    points = [e for e in result.events if e.kind == "point" and e.j == 2]
    assert bool(points) == touches


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("corner", [0, 2])
def test_rolling_along_the_rail_into_the_round_jaw_drops(level: str, corner: int) -> None:
    """Along the bottom rail (centre at ``R``) into a corner: past the round jaw, potted."""
    table = _table(level)
    r = table.ball_radius
    x, v = (0.6, -1.0) if corner == 0 else (table.length - 0.6, 1.0)
    result = _run(table, [[x, r]], [[v, 0.0]])
    assert result.pocketed[0] == corner


@pytest.mark.parametrize("level", LEVELS)
def test_a_ball_at_rest_against_a_jaw_stays_and_is_hit_cleanly(level: str) -> None:
    """At rest touching the corner jaw: no event of its own; struck, the jaw holds it.

    The ball sits in the corner's opening against the round jaw (110 degrees up its
    contact circle), then a second ball drives it into the jaw.
    """
    table = _table(level)
    jaw = table.jaws[0]
    rho = jaw.tip_radius + table.ball_radius
    out = np.array([np.cos(np.radians(110.0)), np.sin(np.radians(110.0))])
    resting = jaw.tip_centres[0] + rho * out
    still = _run(table, [resting], [[0.0, 0.0]])
    assert still.n_events == 0
    np.testing.assert_array_equal(still.positions[0], resting)
    hitter = np.array([0.6, 0.35])
    aim = (resting - hitter) / np.hypot(*(resting - hitter))
    result = _run(table, [resting, hitter], [[0.0, 0.0], list(2.0 * aim)])
    impacts = [(e.kind, e.i) for e in result.events if e.kind in ("ball", "cushion", "point")]
    assert impacts[0][0] == "ball"
    # Driven into the jaw, the resting ball meets it at once (it was touching).
    assert impacts[1] == ("point", 0)


@pytest.mark.parametrize("level", LEVELS)
@pytest.mark.parametrize("pocket", [0, 1])
@pytest.mark.parametrize("angle", [20.0, 40.0, 60.0])
def test_rattles_between_the_jaws_end(level: str, pocket: int, angle: float) -> None:
    """Fast balls at steep angles into lively jaws (e_jaw 0.99): the event loop ends."""
    table = _table(level, e_jaw=0.99, e_cushion=0.99 if level == "roll" else 0.9)
    jaw = table.jaws[pocket]
    middle, axis = jaw.points.mean(axis=0), -jaw.fall_normal
    theta = np.radians(angle)
    u = np.array(
        [axis[0] * np.cos(theta) - axis[1] * np.sin(theta),
         axis[0] * np.sin(theta) + axis[1] * np.cos(theta)]
    )  # fmt: skip
    for offset in np.linspace(-0.04, 0.04, 9):
        start = middle + offset * np.array([-u[1], u[0]]) - 0.35 * u
        r = table.ball_radius
        start = np.clip(start, r + 1e-3, [table.length - r - 1e-3, table.width - r - 1e-3])
        result = _run(table, [start], [list(6.0 * u)])
        assert result.n_events < 2000
