"""The CI sample of the spin fuzz (``python -m tools.fuzz --model spin``).

The fuzz's own scenes and checks on the spin level: spin tables with random parameters,
every scene kind of the roll fuzz (touching layouts, breaks, lumps driven into rails, masses
spread over a million to one, jaw, circle and pocketless tables, scaled tables), cue strikes
with random tips and elevations and random initial spins; every invariant (G, P, E, T, O
and M) on each shot, and the rerun is bit-identical. Every draw is a real shot: the fuzz
scales a draw past the limits down to them (``tools.fuzz_spin.admitted``), so nothing is
refused.
"""

from __future__ import annotations

from itertools import islice

import numpy as np
import pytest

from pool_env import Table
from pool_env.sim.inputs import max_speed
from pool_env.sim.kernels.limits import MAX_SPEED
from pool_env.sim.spin_inputs import reachable_spin_speed
from pool_env.sim.spin_models import BALL_MODELS, CUSHION_MODELS
from tests.profiles import examples
from tools.fuzz import cases, shot_problems
from tools.fuzz_spin import admitted

SHOTS = examples(60)


@pytest.mark.parametrize("seed", [7, 2042])
def test_spin_fuzz_sample(seed: int) -> None:
    for shot, (table, _pos, _vel, masses, run) in enumerate(islice(cases(seed, "spin"), SHOTS)):
        result = run()  # every draw is within the limits: a ValueError fails the test
        assert shot_problems(table, result, masses, samples=200) == [], f"shot {shot}"
        again = run()
        np.testing.assert_array_equal(again.positions, result.positions)
        np.testing.assert_array_equal(again.event_times, result.event_times)


def test_admitted_scales_a_draw_to_the_bound() -> None:
    """A draw past the energy bound or the surface-speed limit is scaled to 0.999 of it."""
    table = Table(model="spin")
    vel = np.array([[2.0, 0.0], [0.0, 0.0]])
    ang = np.zeros((2, 3))
    masses = np.array([table.ball_mass, table.ball_mass])
    assert admitted(table, vel, ang, masses) == 1.0  # within: unchanged
    # Ball 1 spins at 2 MAX_SPEED of surface speed: both bounds are passed.
    ang[1, 2] = 2.0 * MAX_SPEED / table.ball_radius
    factor = admitted(table, vel, ang, masses)
    reach = reachable_spin_speed(table, vel * factor, ang * factor, masses)
    surface = table.ball_radius * abs(ang[1, 2]) * factor
    assert max(reach / max_speed(table), surface / MAX_SPEED) == pytest.approx(0.999, rel=1e-12)
    # A heavy ball's energy driving a light one (mass ratio 1e6) past the speed limit.
    masses = np.array([1e6 * table.ball_mass, table.ball_mass])
    vel[0, 0], ang[1, 2] = 10.0, 0.0
    factor = admitted(table, vel, ang, masses)
    assert factor * 10.0 * 1e3 == pytest.approx(0.999 * max_speed(table), rel=1e-12)


def test_the_spin_fuzz_draws_every_model_elastic_tables_included() -> None:
    """Every accepted cushion and ball model is drawn, on elastic tables too (issue 49).

    Mathavan's at several step counts; elastic: ``e_ball = 1`` and ``e_cushion = 1``.
    """
    tables = [case[0] for case in islice(cases(11, "spin"), 300)]
    assert {t.cushion_model for t in tables} == set(CUSHION_MODELS)
    assert {t.ball_model for t in tables} == set(BALL_MODELS)
    steps = {t.mathavan_steps for t in tables if t.ball_model == "mathavan"}
    assert 1000 in steps and len(steps) > 20 and min(steps) < 100
    for name, models in (("cushion_model", CUSHION_MODELS), ("ball_model", BALL_MODELS)):
        for model in models:
            assert any(
                getattr(t, name) == model and t.e_ball == 1.0 and t.e_cushion == 1.0 for t in tables
            ), (name, model)
