"""The spin level's Zeno rules against closed forms: a stuck lump, the pressed cushion.

These pin :mod:`pool_env.sim.kernels.spin.zeno` for the mutation catalogue
(``tools/mutant_catalogue/spin.py``): each rule's outcome is a closed form.
"""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import Table, simulate

R = 0.028575


def _dead_rail_table(e_ball: float) -> Table:
    # Frictionless impacts and an equator-high rail: every impulse is along x, so the spins
    # and the y velocities pass the one-instant sequence untouched.
    return Table(
        model="spin", pockets="none", e_ball=e_ball, e_cushion=0.0, ball_friction=0.0,
        cushion_friction=0.0, cushion_height=R,
    )  # fmt: skip


@pytest.mark.parametrize("e_ball", [0.95, 0.5, 0.0])
def test_a_sliding_ball_wedging_another_into_a_dead_rail_sticks_and_rolls_with_it(
    e_ball: float,
) -> None:
    """The stuck-lump rule (``spin_zeno.stick``) in closed form.

    Ball 0 rests against the rail ``x = R``; ball 1 touches it and slides in at
    ``(-0.8, 0.05)`` m/s without spin. The impacts repeat at one instant and the pair
    sticks: each ball takes its slide's end, the natural-roll velocity ``v - (2/7) u``
    (``u = v`` without spin: ``(5/7) v``; ball 0's is 0), the lump their mean, and the dead
    rail takes the part into it. So both roll up the rail at ``(5/7) 0.05 / 2`` m/s, side
    by side, and stop ``v^2 / 2a`` further up.
    """
    table = _dead_rail_table(e_ball)
    pos = np.array([[R, 0.6], [3 * R, 0.6]])
    result = simulate(table, pos, [[0.0, 0.0], [-0.8, 0.05]])
    assert not result.hit_event_cap
    v = 5.0 / 7.0 * 0.05 / 2.0
    travel = v * v / (2.0 * table.deceleration)
    np.testing.assert_allclose(result.positions, pos + [0.0, travel], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(result.angular_velocities[:, :2], 0.0)


@pytest.mark.parametrize("wy", [-40.0, -80.0])
def test_backspin_pressing_a_ball_into_a_rail_rolls_it_off_at_once(wy: float) -> None:
    """The pressed-cushion rule (``spin_zeno.pressed_roll``) in closed form.

    A still ball touching the rail ``x = R`` with spin ``wy < 0`` slips at
    ``u = (-R wy, 0)``, ``u_x > 0``: the cloth's friction, along ``-u``, drives it into the
    rail. At the rail the rule ends the slide at once: the rolling velocity
    ``v - (2/7) u = ((2/7) R wy, 0)`` points into the rail, which takes it; the ball is left
    at rest against the rail, neither through it nor re-hitting it without end.
    """
    table = _dead_rail_table(0.9)
    result = simulate(table, [[R, 0.6]], [[0.0, 0.0]], angular_velocities=[[0.0, wy, 0.0]])
    assert not result.hit_event_cap and result.n_events < 10
    np.testing.assert_allclose(result.positions, [[R, 0.6]], rtol=0, atol=1e-12)
