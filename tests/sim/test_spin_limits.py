"""The energy limit on the spin level counts the spin (issue 19, what remained: item 2).

Kinetic energy, translation and spin, never grows on the spin level, and spin turns into
speed (cloth friction, throw, cushion friction), so the bound on every translational speed
of a shot is ``sqrt(sum_k m_k (v_k^2 + (2/5) R^2 |w_k|^2) / min m)``
(:mod:`pool_env.sim.kernels.limits`). A scene whose energy could drive a ball past the
speed limits is refused, and a scene a hair under the bound runs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.sim.batch import simulate_batch
from pool_env.sim.inputs import max_speed
from pool_env.sim.spin_inputs import reachable_spin_speed


def _message(call) -> str:
    with pytest.raises(ValueError, match=r".") as info:
        call()
    return str(info.value)


@pytest.fixture(scope="module")
def spin_table() -> Table:
    return Table(model="spin", pockets="none")


@pytest.mark.parametrize("axis", [0, 1, 2])
def test_spin_energy_at_the_edge_of_the_limit(spin_table: Table, axis: int) -> None:
    """A still ball's spin alone, a hair under and over the bound (any axis).

    Translation alone counted 0 here, and the scene over the edge ran: a still ball with
    backspin of surface speed ``s`` rolls off at ``(2/7) s``.
    """
    table = spin_table
    fastest = max_speed(table)
    edge = fastest / (math.sqrt(0.4) * table.ball_radius)  # rad/s where the bound meets it
    assert edge * table.ball_radius < 1e3  # the surface-speed limit is not what refuses
    pos = [[1.0, 0.6]]
    still = [[0.0, 0.0]]
    under = np.zeros((1, 3))
    under[0, axis] = 0.999 * edge
    assert reachable_spin_speed(table, still, under) == pytest.approx(0.999 * fastest, rel=1e-14)
    if axis == 2:  # spinning in place: cheap to simulate to rest
        result = simulate(table, pos, still, angular_velocities=under, record=False)
        assert result.positions.tolist() == pos
    over = under * (1.001 / 0.999)
    message = _message(lambda: simulate(table, pos, still, angular_velocities=over))
    assert message.startswith("the scene's kinetic energy could speed ball 0 (the lightest)")
    assert "spin counts" in message and f"{1.001 * fastest:.6g}"[:5] in message
    batch = _message(
        lambda: simulate_batch(
            table, np.array([pos]), np.zeros((1, 1, 2)), angular_velocities=[over]
        )
    )
    assert batch == f"table 0: {message}"


def test_a_heavy_balls_spin_counts_over_the_lightest_mass(spin_table: Table) -> None:
    """The spin's energy is weighed like the translation's: ``m_k / m_min``."""
    table = spin_table
    fastest = max_speed(table)
    r = table.ball_radius
    pos = [[1.0, 0.6], [1.5, 0.6]]
    still = [[0.0, 0.0], [0.0, 0.0]]
    masses = [1.0, 1e-4]  # ball 0's energy over ball 1's mass: x 1e4, speeds x 100
    ang = np.zeros((2, 3))
    ang[0, 2] = 1.001 * fastest / (100.0 * math.sqrt(0.4) * r)
    assert reachable_spin_speed(table, still, ang, masses) == pytest.approx(1.001 * fastest)
    message = _message(lambda: simulate(table, pos, still, masses, angular_velocities=ang))
    assert message.startswith("the scene's kinetic energy could speed ball 1 (the lightest)")
    ang[0, 2] *= 0.999 / 1.001
    simulate(table, pos, still, masses, angular_velocities=ang, record=False)


@pytest.mark.parametrize(("b", "side"), [(-0.6, 0.0), (0.0, 0.8), (-0.5, 0.5)])
def test_spin_turned_into_speed_stays_under_the_bound(spin_table: Table, b, side) -> None:
    """A still ball with backspin (and side) rolls off faster than any initial speed (0).

    Its rolling speed is the closed form ``(2/7) R |w_xy|`` (angular momentum about the
    cloth contact), under the energy bound ``sqrt(2/5) R |w|``.
    """
    table = spin_table
    r = table.ball_radius
    w = np.array([[side * 40.0, b * 40.0, 3.0]])  # rad/s
    result = simulate(table, [[1.2, 0.6]], [[0.0, 0.0]], angular_velocities=w)
    state = result.segments[2]  # every anchor's (x, y, vx, vy, ...) after each event
    fastest = float(np.hypot(state[:, 2], state[:, 3]).max())
    assert fastest == pytest.approx(2.0 / 7.0 * r * math.hypot(w[0, 0], w[0, 1]), rel=1e-12)
    assert 0.0 < fastest <= reachable_spin_speed(table, [[0.0, 0.0]], w)
