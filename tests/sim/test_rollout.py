"""The batched rollout (``pool_env.sim.rollout``): each row is one ``shoot()``, bit for bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot
from pool_env.sim import rollout
from pool_env.sim.layouts import break_scene

LEVELS = ("roll", "spin")


def _shots(model: str, n: int, seed: int, speeds: tuple[float, float]) -> np.ndarray:
    """``n`` random shot rows; tips and elevations on the spin level only."""
    rng = np.random.default_rng(seed)
    rows = np.zeros((n, 5))
    rows[:, 0] = rng.uniform(-math.pi, math.pi, n)
    rows[:, 1] = rng.uniform(*speeds, n)
    if model == "spin":
        rows[:, 2:4] = rng.uniform(-0.6, 0.6, (n, 2))
        rows[:, 4] = rng.uniform(0.0, 0.4, n)
    return rows


def _assert_rows_are_shots(table, layout, rows, out, cue=0, masses=None, active=None):
    """Every row of ``out`` equals the ``shoot()`` of that row, bit for bit."""
    on = np.ones(layout.shape[0], bool) if active is None else np.asarray(active)
    balls = np.flatnonzero(on)
    for s, (angle, speed, a, b, elevation) in enumerate(rows):
        shot = shoot(
            table, layout[balls], angle, speed, int(np.searchsorted(balls, cue)),
            None if masses is None else masses[balls], tip=(a, b), elevation=elevation,
            record=False,
        )  # fmt: skip
        assert np.array_equal(out.positions[s, balls], shot.positions), s
        assert np.array_equal(out.positions[s, ~on], layout[~on]), s
        assert np.array_equal(out.pocketed[s, balls], shot.pocketed), s
        assert np.all(out.pocketed[s, ~on] == -1), s
        assert np.array_equal(out.pocket_order[s, balls], shot.pocket_order), s
        assert np.array_equal(out.cushions_after_contact[s, balls], shot.cushions_after_contact)
        assert out.n_events[s] == shot.n_events, s
        assert out.hit_event_cap[s] == shot.hit_event_cap, s
        hit = shot.first_hit
        assert np.array_equal(out.first_hit[s, balls], np.where(hit >= 0, balls[hit], -1)), s
        second = shot.second_hit
        want = np.where(second >= 0, balls[second], -1)
        assert np.array_equal(out.second_hit[s, balls], want), s
        assert np.array_equal(out.cushions_at_second[s, balls], shot.cushions_at_second), s
        contact = shot.first_contact
        want = [-1, -1] if contact is None else [balls[contact[0]], balls[contact[1]]]
        assert out.first_contact[s].tolist() == list(want), s


@pytest.mark.parametrize("model", LEVELS)
def test_two_ball_rows_equal_shoot(model: str) -> None:
    """Two balls on a table with pockets, shots of 0.3-4 m/s: pots, rails, misses."""
    table = Table(model=model)
    layout = np.array([[0.6, 0.5], [1.9, 0.8]])
    rows = _shots(model, 300, 1, (0.3, 4.0))
    out = rollout(table, layout, rows)
    assert np.any(out.pocketed >= 0) and np.any(out.first_contact[:, 0] == 0)
    _assert_rows_are_shots(table, layout, rows, out)


@pytest.mark.parametrize("model", LEVELS)
def test_breaks_equal_shoot_with_masses_and_inactive_balls(model: str) -> None:
    """9-ball breaks, one rack ball off the table, unequal masses, the cue ball not row 0."""
    table = Table(model=model)
    layout = break_scene(table, "nine")[::-1].copy()  # the cue ball is the last row
    cue = layout.shape[0] - 1
    active = np.ones(layout.shape[0], bool)
    active[3] = False
    masses = np.linspace(0.15, 0.18, layout.shape[0])
    rows = _shots(model, 40, 2, (5.0, 9.0))
    rows[:, 0] = np.random.default_rng(3).normal(0.0, 0.01, 40)  # at the rack
    out = rollout(table, layout, rows, cue=cue, masses=masses, active=active)
    assert np.all(np.any(out.first_contact == cue, axis=1))
    _assert_rows_are_shots(table, layout, rows, out, cue, masses, active)


@pytest.mark.parametrize("model", LEVELS)
def test_threads_do_not_change_results(model: str) -> None:
    table = Table(model=model)
    layout = np.array([[0.6, 0.5], [1.9, 0.8], [1.2, 0.3]])
    rows = _shots(model, 400, 4, (0.5, 3.0))
    one, two = rollout(table, layout, rows, threads=1), rollout(table, layout, rows, threads=3)
    for name in one.__slots__:
        assert np.array_equal(getattr(one, name), getattr(two, name)), name


def test_two_columns_are_centre_hits_and_results_are_fresh() -> None:
    table = Table(model="spin")
    layout = np.array([[0.6, 0.5], [1.9, 0.8]])
    rows = _shots("roll", 10, 5, (0.5, 2.0))
    out = rollout(table, layout, rows[:, :2])
    assert np.array_equal(out.positions, rollout(table, layout, rows).positions)
    out.positions[...] = 0.0
    assert layout[0, 0] == 0.6 and rollout(table, layout, rows).positions[0, 1, 0] != 0.0


def test_refused_shot_is_named() -> None:
    """A speed beyond the limits: the first such row is named, nothing returned."""
    table = Table()
    rows = np.array([[0.0, 1.0], [0.0, 1e6], [0.0, 2e6]])
    with pytest.raises(ValueError, match=r"^shot 1: ball 0 has speed"):
        rollout(table, [[0.6, 0.5], [1.9, 0.8]], rows)
    with pytest.raises(ValueError, match=r"^shot 0: balls 0 and 1 overlap"):
        rollout(table, [[0.6, 0.5], [0.61, 0.5]], rows[:1])


@pytest.mark.parametrize(
    ("model", "rows", "message"),
    [
        ("roll", [[0.0, 1.0, 0.1, 0.0, 0.0]], "shot 0 puts spin"),
        ("spin", [[0.0, 1.0], [np.nan, 1.0]], "shot 1 has a non-finite angle"),
        ("spin", [[0.0, -1.0]], "shot 0 needs a non-negative"),
        ("spin", [[0.0, 1.0, 1.5, 0.0, 0.0]], "shot 0 has tip offsets"),
        ("spin", [[0.0, 1.0, 0.0, 0.0, 2.0]], "shot 0 has elevation"),
        ("spin", [[0.0, 1.0, 0.0]], "shots must have shape"),
    ],
)
def test_bad_shots(model: str, rows: list, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        rollout(Table(model=model), [[0.6, 0.5], [1.9, 0.8]], rows)


def test_bad_arguments() -> None:
    layout = [[0.6, 0.5], [1.9, 0.8]]
    with pytest.raises(ValueError, match="cue ball 0 is not active"):
        rollout(Table(), layout, [[0.0, 1.0]], active=[False, True])
    with pytest.raises(ValueError, match="active must be 2 booleans"):
        rollout(Table(), layout, [[0.0, 1.0]], active=[True])
    with pytest.raises(ValueError, match="threads"):
        rollout(Table(), layout, [[0.0, 1.0]], threads=0)
    with pytest.raises(ValueError, match="cue"):
        rollout(Table(), layout, [[0.0, 1.0]], cue=2)
