"""The spin level's API: Table fields and their checks, shoot/simulate arguments, refusals.

The roll level must stay as it was: its defaults, its parameter array and its refusal of
anything that needs spin.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim import (
    STATE_NAMES,
    SpinShotResult,
    rollout,
    simulate_batch,
    simulate_batch_threads,
)
from pool_env.sim.kernels.params import N_PARAMS
from pool_env.sim.kernels.spin.params import (
    ALCIATORE_FRICTION,
    CONSTANT_FRICTION,
    FRICTIONLESS,
    POOLTOOL_FRICTION,
    S_CUSHION_HEIGHT,
    S_FRICTION_MODE,
    S_MU_BALL,
    S_SLIDE_DECEL,
    S_SPIN_DECEL,
)


def test_defaults_and_sources() -> None:
    t = Table(model="spin", pockets="none")
    r = t.ball_radius
    assert Table().model == "roll"
    assert t.mu_slide == 0.2
    assert t.spin_decel == pytest.approx(2.5 * 0.444 * 9.81, rel=1e-15)
    assert t.ball_friction == "alciatore"
    assert t.cushion_friction == 0.2
    assert t.cushion_height == pytest.approx(1.27 * r, rel=1e-15)
    assert t.cue_tip_radius == 0.0106
    assert t.cue_end_mass == pytest.approx(t.ball_mass / 30.0, rel=1e-15)
    p = t.spin_params
    np.testing.assert_array_equal(p[:N_PARAMS], t.params)
    assert p[S_SLIDE_DECEL] == 0.2 * 9.81
    assert p[S_SPIN_DECEL] == t.spin_decel
    assert p[S_FRICTION_MODE] == ALCIATORE_FRICTION
    assert p[S_CUSHION_HEIGHT] == t.cushion_height
    assert not p.flags.writeable


@pytest.mark.parametrize(
    ("friction", "mode", "mu"),
    [
        (0.0, FRICTIONLESS, 0.0),
        (0.06, CONSTANT_FRICTION, 0.06),
        ("alciatore", ALCIATORE_FRICTION, 0),
        ("pooltool", POOLTOOL_FRICTION, 0),
    ],
)
def test_ball_friction_modes(friction, mode, mu) -> None:
    t = Table(model="spin", pockets="none", ball_friction=friction)
    assert t.spin_params[S_FRICTION_MODE] == mode
    assert t.spin_params[S_MU_BALL] == mu


def test_roll_params_unchanged() -> None:
    """The roll level's parameter array is the one it always was (same length, values)."""
    t = Table()
    assert t.params.shape == (N_PARAMS,)
    assert t.params.tolist() == [2.54, 1.27, 0.028575, 0.01 * 9.81, 0.95, 0.65, 0.17, 0.65]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"model": "slide"}, "model must be"),
        ({"model": 3}, "model must be"),
        ({"mu_slide": 0.0}, "mu_slide"),
        ({"mu_slide": math.nan}, "mu_slide"),
        ({"spin_decel": -1.0}, "spin_decel"),
        ({"spin_decel": math.inf}, "spin_decel"),
        ({"ball_friction": "marlow"}, "ball_friction"),
        ({"ball_friction": -0.01}, "ball_friction"),
        ({"ball_friction": True}, "ball_friction"),
        ({"cushion_friction": -0.2}, "cushion_friction"),
        ({"cushion_height": 0.02}, "cushion_height"),
        ({"cushion_height": 2 * 0.028575}, "cushion_height"),
        ({"cue_tip_radius": 0.0}, "cue_tip_radius"),
        ({"cue_end_mass": 0.0}, "cue_end_mass"),
    ],
)
def test_bad_spin_parameters(kwargs, match) -> None:
    with pytest.raises(ValueError, match=match):
        Table(**{"pockets": "none", **kwargs} if "model" not in kwargs else kwargs)


def test_roll_table_refuses_spin() -> None:
    t = Table()
    pos = [[1.0, 0.6]]
    with pytest.raises(ValueError, match="model='spin'"):
        shoot(t, pos, 0.0, 1.0, tip=(0.0, 0.3))
    with pytest.raises(ValueError, match="model='spin'"):
        shoot(t, pos, 0.0, 1.0, elevation=0.1)
    with pytest.raises(ValueError, match="model='spin'"):
        simulate(t, pos, [[1.0, 0.0]], angular_velocities=[[0.0, 0.0, 0.0]])
    # An explicit zero tip is no spin and is accepted.
    assert shoot(t, pos, 0.0, 1.0, tip=(0.0, 0.0)).positions.tolist() == (
        shoot(t, pos, 0.0, 1.0).positions.tolist()
    )


@pytest.mark.parametrize(
    "kwargs",
    [
        {"cushion_model": "stronge", "ball_model": "mathavan"},
        {"mu_slide": 0.3},
        {"spin_decel": 5.0},
        {"ball_friction": 0.05},
        {"cushion_friction": 0.0},
        {"cushion_height": 0.03},
        {"cue_tip_radius": 0.011},
        {"cue_end_mass": 0.01},
        {"cushion_omega_ratio": 1.5},
        {"mathavan_steps": 10},
    ],
)
def test_the_roll_table_refuses_spin_only_parameters(kwargs) -> None:
    """A spin-only value away from its default means nothing on the roll table: refused.

    The message names each parameter as given and the model it applies to.
    """
    for table_kwargs in (kwargs, {"model": "roll", **kwargs}):
        with pytest.raises(ValueError, match="apply to model='spin' only") as info:
            Table(**table_kwargs)
        for name, value in kwargs.items():
            assert f"{name}={value!r}" in str(info.value)
    Table(model="spin", **kwargs)  # the spin table reads them


def test_the_roll_table_takes_spin_only_defaults_and_round_trips() -> None:
    """Each default, given explicitly, is accepted; ``replace`` of a roll table works."""
    table = Table(mu_slide=0.2, spin_decel=None, ball_friction="alciatore", mathavan_steps=1000,
                  cushion_model="han", ball_model="frictional")  # fmt: skip
    assert dataclasses.replace(table, length=2.0).length == 2.0
    scaled = Table(ball_radius=0.03, ball_mass=0.2, g=9.7)  # defaults that follow R, m, g
    assert dataclasses.replace(scaled, e_ball=0.9).e_ball == 0.9
    assert repr(table) == repr(Table())


@pytest.mark.parametrize(
    ("tip", "elevation", "match"),
    [((1.5, 0.0), 0.0, "tip"), ((0.0, -1.01), 0.0, "tip"), ((0.1,), 0.0, "tip"),
     ((0.0, math.nan), 0.0, "tip"), ((0.0, 0.0), -0.1, "elevation"),
     ((0.0, 0.0), math.pi / 2, "elevation")],
)  # fmt: skip
def test_bad_tip(tip, elevation, match) -> None:
    t = Table(model="spin", pockets="none")
    with pytest.raises(ValueError, match=match):
        shoot(t, [[1.0, 0.6]], 0.0, 1.0, tip=tip, elevation=elevation)


@pytest.mark.parametrize(
    ("tip", "tip_radius", "plays"),
    [
        ((1.0, 1.0), None, False),  # the default 10.6 mm tip: a' = b' = 0.73, off the ball
        ((0.9, 0.9), 1e-4, False),  # a 0.1 mm tip: the contact is the axis point, off
        ((0.7, 0.7), None, True),  # a'^2 + b'^2 = 0.52
        ((0.7, 0.7), 1e-4, True),
        ((1.0, 0.0), 1e-4, True),  # a grazing hit on the outline
    ],
)
def test_a_tip_must_meet_the_ball_on_its_surface(tip, tip_radius, plays) -> None:
    """The contact offset (a, b) / (1 + r_tip / R) lies within the ball's outline, or raise."""
    kwargs = {} if tip_radius is None else {"cue_tip_radius": tip_radius}
    t = Table(model="spin", pockets="none", **kwargs)
    reach = 1.0 + t.cue_tip_radius / t.ball_radius
    assert (tip[0] ** 2 + tip[1] ** 2 <= reach**2) is plays  # the case is what it says
    layout = [[1.0, 0.6], [2.0, 0.9]]
    if plays:
        shoot(t, layout, 0.0, 1.0, tip=tip)
        rollout(t, layout, [[0.0, 1.0, *tip, 0.0]])
    else:
        with pytest.raises(ValueError, match="off its surface"):
            shoot(t, layout, 0.0, 1.0, tip=tip)
        with pytest.raises(ValueError, match="off its surface"):
            rollout(t, layout, [[0.0, 1.0, *tip, 0.0]])


def test_bad_angular_velocities() -> None:
    t = Table(model="spin", pockets="none")
    pos, vel = [[1.0, 0.6]], [[1.0, 0.0]]
    for bad, match in (([[0.0, 0.0]], "shape"), ([[0.0, math.inf, 0.0]], "finite"),
                       ([[0.0, 0.0, 1e6]], "surface speed")):  # fmt: skip
        with pytest.raises(ValueError, match=match):
            simulate(t, pos, vel, angular_velocities=bad)


def test_spin_input_not_modified_and_results_do_not_alias() -> None:
    t = Table(model="spin", pockets="none")
    pos = np.array([[1.0, 0.6], [1.5, 0.62]])
    vel = np.array([[1.0, 0.0], [0.0, 0.0]])
    ang = np.array([[0.0, -20.0, 5.0], [0.0, 0.0, 0.0]])
    copies = pos.copy(), vel.copy(), ang.copy()
    r = simulate(t, pos, vel, angular_velocities=ang)
    for a, b in zip((pos, vel, ang), copies, strict=True):
        np.testing.assert_array_equal(a, b)
    assert isinstance(r, SpinShotResult)
    assert not np.shares_memory(r.positions, pos)
    assert r.angular_velocities.shape == (2, 3)
    assert [STATE_NAMES[s] for s in r.motion_states] == ["stationary", "stationary"]


def test_roll_result_has_no_spin() -> None:
    r = shoot(Table(pockets="none"), [[1.0, 0.6]], 0.0, 1.0)
    np.testing.assert_array_equal(r.angular_velocities, np.zeros((1, 3)))
    assert r.motion_states.tolist() == [0]


def test_spin_batches_equal_single_shots() -> None:
    """A spin batch (serial, parallel, threads) equals one simulate() per table, bit for bit."""
    t = Table(model="spin", pockets="circles")
    rng = np.random.default_rng(3)
    pos = np.array([[[0.5, 0.6], [1.5, 0.62], [2.0, 0.3]], [[0.7, 0.2], [0.7, 0.9], [2.2, 1.0]]])
    vel = np.zeros_like(pos)
    vel[:, 0] = rng.normal(0, 2.0, (2, 2))
    ang = rng.normal(0, 30.0, (2, 3, 3))
    active = np.array([[True, True, True], [True, False, True]])
    single = []
    for b in range(2):
        on = active[b]
        r = simulate(t, pos[b][on], vel[b][on], angular_velocities=ang[b][on], record=False)
        single.append((r.positions, r.pocketed, r.n_events))
    for run in (
        lambda: simulate_batch(t, pos, vel, active=active, angular_velocities=ang),
        lambda: simulate_batch(t, pos, vel, active=active, angular_velocities=ang, parallel=True),
        lambda: simulate_batch_threads(t, pos, vel, active, threads=2, angular_velocities=ang),
    ):
        out = run()
        for b in range(2):
            np.testing.assert_array_equal(out.positions[b][active[b]], single[b][0])
            np.testing.assert_array_equal(out.pocketed[b][active[b]], single[b][1])
            assert out.n_events[b] == single[b][2]
        np.testing.assert_array_equal(out.positions[1, 1], pos[1, 1])  # inactive: unchanged


def test_batch_spin_arguments() -> None:
    pos = np.array([[[1.0, 0.6]]])
    with pytest.raises(ValueError, match="model='spin'"):
        simulate_batch(Table(), pos, np.zeros_like(pos), angular_velocities=np.zeros((1, 1, 3)))
    t = Table(model="spin", pockets="none")
    with pytest.raises(ValueError, match="shape"):
        simulate_batch(t, pos, np.zeros_like(pos), angular_velocities=np.zeros((1, 3)))
    with pytest.raises(ValueError, match="table 0: angular_velocities must be finite"):
        simulate_batch(t, pos, np.zeros_like(pos), angular_velocities=np.full((1, 1, 3), np.nan))
