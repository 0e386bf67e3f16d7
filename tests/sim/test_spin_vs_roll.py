"""A rolling ball on the spin level follows the roll level's path until its first impact.

Rolling is the one state the two levels share (deceleration ``mu_roll g`` along the
velocity), so up to the first event a spin shot started rolling must meet the same rail,
jaw facing, jaw point, pocket or ball as the roll level's shot, at the same time and place
(to rounding): a cross-check of every event predictor of the spin level on straight paths.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.testing.scenes_random import random_layout


@pytest.mark.parametrize("pockets", ["jaws", "circles", "none"])
def test_first_event_matches_the_roll_level(pockets: str) -> None:
    roll = Table(pockets=pockets)
    spin = Table(pockets=pockets, model="spin")
    r = roll.ball_radius
    rng = np.random.default_rng(11)
    kinds = set()
    for _ in range(150):
        pos = random_layout(roll, int(rng.integers(1, 5)), rng, min_gap=0.01)
        angle = rng.uniform(-math.pi, math.pi)
        if pockets != "none" and rng.random() < 0.5:  # at a pocket, to reach the jaws
            aim = roll.pockets[int(rng.integers(6)), :2] - pos[0] + rng.normal(0, 0.02, 2)
            angle = math.atan2(aim[1], aim[0])
        speed = rng.uniform(0.3, 6.0)
        vel = np.zeros_like(pos)
        vel[0] = speed * np.array([math.cos(angle), math.sin(angle)])
        ang = np.zeros((len(pos), 3))
        ang[0, :2] = [-vel[0, 1] / r, vel[0, 0] / r]  # rolling
        a = simulate(roll, pos, vel)
        b = simulate(spin, pos, vel, angular_velocities=ang)
        ea, eb = a.events[0], b.events[0]
        assert (ea.kind, ea.i, ea.j) == (eb.kind, eb.i, eb.j)
        assert eb.time == pytest.approx(ea.time, rel=1e-9, abs=1e-12)
        np.testing.assert_allclose(
            b.positions_at(eb.time), a.positions_at(ea.time), rtol=0, atol=1e-9
        )
        kinds.add(ea.kind)
    expected = {"none": {"cushion", "ball", "stop"}, "circles": {"cushion", "ball", "pocket"}}
    assert kinds >= expected.get(pockets, {"jaw", "point", "pocket", "cushion", "ball"})
