"""The closed-form cue ball of the spin-aware baselines against the spin simulator.

:mod:`agents.baselines.cue_path` never runs the event loop; here every prediction is checked
against :func:`pool_env.shoot` on ``Table(model="spin")``: the 30-degree rule's deflection
(TP B-13's closed form), draw coming back on a full hit, the stun ball's stop distance,
resting points after cushions, the throw- and squirt-corrected contact potting in the
named pocket, and the inverse speed model.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from agents.baselines.cue_path import (
    Motion,
    after_contact,
    along,
    collide,
    launch_speed,
    strike,
)
from agents.baselines.geometry import ghost_shots, pocket_mouths
from agents.baselines.spin_play import plan_contact, traced_pots
from pool_env import Table, shoot

R = 0.028575
SPIN = Table(model="spin")
OPEN = Table(model="spin", pockets="none")
LIMIT = 0.5 * (1.0 + SPIN.cue_tip_radius / R)  # the spin env's default tip limit


def _cut_shot(table: Table, cut_deg: float, tip_b: float, speed: float = 2.0):
    """A cue ball 0.6 m from the ghost point of a ``cut_deg`` cut, struck at ``tip_b``."""
    cue, ball = np.array([0.7, 0.635]), np.array([1.3, 0.70])
    u = np.array([math.cos(math.radians(cut_deg)), math.sin(math.radians(cut_deg))])
    ghost = ball - 2 * R * u
    heading = (ghost - cue) / np.hypot(*(ghost - cue))
    angle = math.atan2(heading[1], heading[0])
    result = shoot(table, [cue, ball], angle, speed, tip=(0.0, tip_b))
    arriving = along(table, strike(table, angle, speed, (0.0, tip_b)), np.hypot(*(ghost - cue)))
    assert arriving is not None
    normal = (ball - ghost) / (2 * R)
    return result, ghost, normal, arriving


@pytest.mark.parametrize("cut_deg", [10.0, 28.0, 45.0, 60.0])
def test_thirty_degree_rule_of_a_rolling_cue_ball(cut_deg: float) -> None:
    """Frictionless elastic balls: a rolling cue ball leaves at TP B-13's angle from its line.

    The model's deflection equals the closed form, and so does the simulator's cue ball
    (struck at ``b' = 2/5``, so that it rolls from the start) once it rolls again.
    """
    table = Table(model="spin", pockets="none", ball_friction=0.0, e_ball=1.0)
    phi = math.radians(cut_deg)
    expected = math.atan(math.sin(phi) * math.cos(phi) / (math.sin(phi) ** 2 + 0.4))
    rolling = Motion(np.array([0.5, 0.0]), np.array([0.0, 0.5 / R, 0.0]))
    normal = np.array([math.cos(phi), -math.sin(phi)])  # the object ball leaves clockwise
    cue_after, _ = collide(table, rolling, normal)
    trace = after_contact(table, pocket_mouths(table), np.array([1.0, 0.635]), cue_after)
    last = trace.rest - trace.legs[-1][0]
    assert math.atan2(last[1], last[0]) == pytest.approx(expected, abs=1e-12)
    cue = np.array([0.8, 0.635])
    ball = np.array([1.0, 0.635]) + 2 * R * normal
    result = shoot(table, [cue, ball], 0.0, 0.5, tip=(0.0, 0.4 * (1 + table.cue_tip_radius / R)))
    contact = next(e.time for e in result.events if e.kind == "ball")
    rolls = [e.time for e in result.events if e.kind == "slide_roll" and e.time > contact]
    moved = result.positions[0] - result.positions_at(rolls[0])[0]
    assert math.atan2(moved[1], moved[0]) == pytest.approx(expected, abs=1e-9)


def test_draw_comes_back_on_a_full_hit_as_the_simulator_says() -> None:
    cue, ball = np.array([0.9, 0.635]), np.array([1.2, 0.635])
    tip = (0.0, -0.6)
    result = shoot(OPEN, [cue, ball], 0.0, 2.0, tip=tip)
    arriving = along(OPEN, strike(OPEN, 0.0, 2.0, tip), 0.3 - 2 * R)
    assert arriving is not None
    cue_after, _ = collide(OPEN, arriving, np.array([1.0, 0.0]))
    trace = after_contact(OPEN, pocket_mouths(OPEN), ball - [2 * R, 0.0], cue_after)
    assert trace.rest[0] < 1.2 - 2 * R - 0.1  # it came back more than 10 cm
    np.testing.assert_allclose(trace.rest, result.positions[0], atol=1e-9)


@pytest.mark.parametrize("speed", [0.2, 0.4, 0.6, 0.8])
def test_stun_ball_stops_at_the_closed_form_distance(speed: float) -> None:
    """A centre hit slides ``12 v^2 / (49 mu_s g)`` then rolls ``(5 v / 7)^2 / (2 mu_r g)``."""
    mu_s_g, mu_r_g = OPEN.mu_slide * OPEN.g, OPEN.deceleration
    expected = 12 * speed**2 / (49 * mu_s_g) + (5 * speed / 7) ** 2 / (2 * mu_r_g)
    start = np.array([0.1, 0.635])
    trace = after_contact(OPEN, pocket_mouths(OPEN), start, strike(OPEN, 0.0, speed, (0, 0)))
    assert trace.rest[0] - start[0] == pytest.approx(expected, rel=1e-12)
    assert shoot(OPEN, [start], 0.0, speed).positions[0, 0] == pytest.approx(
        trace.rest[0], abs=1e-9
    )


@pytest.mark.parametrize("tip_b", [-0.6, -0.3, 0.0, 0.3, 0.6])
@pytest.mark.parametrize("cut_deg", [0.0, 30.0, 50.0])
def test_resting_point_after_contact_and_cushions_matches_the_simulator(
    tip_b: float, cut_deg: float
) -> None:
    """Throw, the curved slide, Han cushions: the predicted rest within 1 mm of the simulator's."""
    result, ghost, normal, arriving = _cut_shot(OPEN, cut_deg, tip_b)
    cue_after, _ = collide(OPEN, arriving, normal)
    trace = after_contact(OPEN, pocket_mouths(OPEN), ghost, cue_after)
    assert np.hypot(*(trace.rest - result.positions[0])) < 1e-3


@pytest.mark.parametrize("slip_ratio", [1.0, 1.0 - 2.5 * 0.4, -0.5, 2.0])
@pytest.mark.parametrize("dist", [0.05, 0.3, 1.5])
def test_launch_speed_inverts_the_straight_slide_and_roll(slip_ratio: float, dist: float) -> None:
    there = 0.8
    speed = launch_speed(OPEN, slip_ratio, dist, there)
    spin_v = (1.0 - slip_ratio) * speed  # s = (1 - slip ratio) v along the path
    motion = Motion(np.array([speed, 0.0]), np.array([0.0, spin_v / R, 0.0]))
    arrived = along(OPEN, motion, dist)
    assert arrived is not None
    assert arrived.vel[0] == pytest.approx(there, rel=1e-9)


@pytest.mark.parametrize("tip", [(0.0, 0.0), (0.0, LIMIT), (0.0, -LIMIT), (0.4, 0.0), (-0.3, 0.3)])
@pytest.mark.parametrize("cut_deg", [0.0, 25.0, 45.0])
def test_planned_contact_pots_the_named_ball_in_the_named_pocket(
    tip: tuple[float, float], cut_deg: float
) -> None:
    """Throw and squirt allowed for: the object ball drops where the plan sends it.

    The predicted cue-ball rest is the simulator's within 5 mm on the cue's vertical line;
    with side spin within 5 cm (the squirt turns the velocity off the slip, so the real
    approach bends a little, which :func:`~agents.baselines.cue_path.along` leaves out).
    """
    mouths = pocket_mouths(SPIN)
    ball = np.array([1.9, 0.9])
    corner = mouths.targets[5]  # top right corner
    u = (corner - ball) / np.hypot(*(corner - ball))
    c, s = math.cos(math.radians(-cut_deg)), math.sin(math.radians(-cut_deg))
    d = np.array([c * u[0] - s * u[1], s * u[0] + c * u[1]])
    positions = np.array([ball - 2 * R * u - 0.7 * d, ball])
    shot = next(
        x for x in ghost_shots(SPIN, mouths, positions, np.ones(2, bool), [1]) if x.pocket == 5
    )
    contact = plan_contact(SPIN, mouths, shot, positions, tip, 0.6)
    assert contact is not None
    result = shoot(SPIN, positions, contact.aim, contact.speed, tip=tip)
    assert result.pocketed[1] == 5
    if result.pocketed[0] < 0 and contact.path.pocket < 0:
        bound = 5e-3 if tip[0] == 0.0 else 5e-2
        assert np.hypot(*(contact.path.rest - result.positions[0])) < bound


def test_without_the_throw_correction_thin_cuts_miss() -> None:
    """The throw is real: aiming at the plain ghost point misses a long 45-degree cut."""
    mouths = pocket_mouths(SPIN)
    ball = np.array([1.2, 0.4])
    corner = mouths.targets[5]
    u = (corner - ball) / np.hypot(*(corner - ball))
    c, s = math.cos(math.radians(-45.0)), math.sin(math.radians(-45.0))
    d = np.array([c * u[0] - s * u[1], s * u[0] + c * u[1]])
    positions = np.array([ball - 2 * R * u - 0.5 * d, ball])
    shot = next(
        x for x in ghost_shots(SPIN, mouths, positions, np.ones(2, bool), [1]) if x.pocket == 5
    )
    contact = plan_contact(SPIN, mouths, shot, positions, (0.0, 0.0), 0.6)
    assert contact is not None
    plain = shoot(SPIN, positions, shot.angle, contact.speed)
    corrected = shoot(SPIN, positions, contact.aim, contact.speed)
    assert corrected.pocketed[1] == 5
    assert plain.pocketed[1] != 5


def test_traced_pots_find_the_rail_shot_of_a_ball_frozen_to_a_rail() -> None:
    """No direct pot is playable (a ball on the right rail), but the traced fan finds one.

    Its strikes' object balls drop; the simulator agrees for most, the best included.
    """
    positions = np.array([[1.7371776881, 0.9238090263], [2.5066147565, 0.3269272575]])
    pots = traced_pots(SPIN, pocket_mouths(SPIN), positions, np.ones(2, bool), [1], 4.5)
    assert len(pots) >= 10
    agree = 0
    for pot in pots:
        result = shoot(SPIN, positions, pot.aim, pot.speed)
        agree += result.pocketed[1] == pot.pocket and result.pocketed[0] < 0
    assert agree >= len(pots) // 2
    best = shoot(SPIN, positions, pots[0].aim, pots[0].speed)
    assert best.pocketed[1] == pots[0].pocket and best.pocketed[0] < 0
