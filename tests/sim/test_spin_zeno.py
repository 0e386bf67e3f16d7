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


@pytest.mark.parametrize("e_ball", [1.0, 0.9999])
@pytest.mark.parametrize("gap", [1e-11, 1e-10])
def test_two_balls_their_spins_press_together_stay_together_whatever_e(
    e_ball: float, gap: float
) -> None:
    """The pressed-pair rule (``spin_zeno.pressed_pair``) in closed form, for any ``e``.

    Balls 0 and 1 lie ``gap`` apart on a line along x, still, with opposite topspins
    ``wy = +-40`` rad/s: each slips at ``u_x = -+R wy``, so the cloth's friction
    (``mu_s g`` against the slip) drives them into each other with equal and opposite
    forces. They meet midway and stay there: the contact holds them together against the
    frictions, which cancel, until their spins are spent; they end at rest, the gap closed
    from both sides. With ``e = 1`` (or 0.9999) the model's bounces under that load part
    them by ``s^2 / (2 a)``, about 1e-11 m here, and come back microseconds later at the
    same speed: without the rule, the shot ran into the event cap, which also froze ball 2,
    rolling elsewhere on the table. Ball 2 rolls from the start and stops after
    ``v^2 / (2 a_roll)`` along its velocity, exactly.
    """
    table = Table(model="spin", pockets="none", e_ball=e_ball)
    pos = np.array([[1.0, 0.4], [1.0 + 2 * R + gap, 0.4], [0.5, 0.9]])
    v = np.array([0.25, 0.1])
    vel = np.array([[0.0, 0.0], [0.0, 0.0], v])
    ang = np.array([[0.0, 40.0, 0.0], [0.0, -40.0, 0.0], [-v[1] / R, v[0] / R, 0.0]])
    result = simulate(table, pos, vel, angular_velocities=ang)
    assert not result.hit_event_cap and result.n_events < 20
    speed = np.hypot(*v)
    stop = pos[2] + v / speed * speed**2 / (2.0 * table.deceleration)
    np.testing.assert_allclose(result.positions[2], stop, rtol=0, atol=1e-12)
    met = pos[:2] + [[gap / 2, 0.0], [-gap / 2, 0.0]]
    np.testing.assert_allclose(result.positions[:2], met, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(result.angular_velocities, 0.0)


@pytest.mark.parametrize("gap", [1e-11, 1e-10])
def test_a_ball_its_spin_presses_into_an_elastic_rail_stays_there(gap: float) -> None:
    """The pressed-cushion rule (``spin_zeno.pressed_roll``) at ``e_cushion = 1``.

    A still ball ``gap`` from the rail ``x = R``, with backspin ``wy = -40`` rad/s: its slip
    ``u = (-R wy, 0)`` points away from the rail, so the cloth's friction drives it in. At
    an equator-high, frictionless, elastic rail each impact returns its normal speed
    whole, and friction brings it back a few microseconds later at that speed, for as long
    as the slip lasts: without the rule the shot ran into the event cap, freezing ball 1,
    rolling elsewhere. Parting by less than the contact tolerance, the ball is held at the
    rail: the rule ends its slide there, at rest against the rail (its rolling velocity
    ``(2/7) R wy`` points into it), and ball 1 stops where its roll ends, exactly.
    """
    table = Table(
        model="spin", pockets="none", e_cushion=1.0, cushion_friction=0.0, cushion_height=R
    )
    pos = np.array([[R + gap, 0.6], [1.5, 0.3]])
    v = np.array([0.25, 0.1])
    vel = np.array([[0.0, 0.0], v])
    ang = np.array([[0.0, -40.0, 0.0], [-v[1] / R, v[0] / R, 0.0]])
    result = simulate(table, pos, vel, angular_velocities=ang)
    assert not result.hit_event_cap and result.n_events < 20
    speed = np.hypot(*v)
    stop = pos[1] + v / speed * speed**2 / (2.0 * table.deceleration)
    np.testing.assert_allclose(result.positions[1], stop, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.positions[0], [R, 0.6], rtol=0, atol=1e-12)
    np.testing.assert_array_equal(result.angular_velocities, 0.0)
