"""pool_env's spin level against the independent 50-digit spin reference.

Random scenes on a pocketless spin table: 2-4 balls, the cue ball sent at an object ball
with a random spin (side, top/draw, sliding), sometimes a second ball spinning in place,
random restitutions, ball-ball friction (Alciatore's fit, a constant, or none), cushion
friction and sometimes unequal masses; kept when pool_env counts 1-3 impacts (ball-ball plus
cushion: a selection rule only). The event sequences (kind and balls) must be equal and
every final position within 1e-9 m of the reference's. A fixed set of scenes that covers
every event kind runs by default; ``-m slow`` runs 100 more.
"""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest
from mpmath import mp, mpf

from pool_env import Table, simulate
from pool_env.testing.scenes_random import random_layout
from pool_env.testing.spin_reference import spin_reference_simulate

TOLERANCE = 1e-9  # m
KINDS = {"ball", "cushion", "slide_roll", "roll_spin", "stop", "spin_stop"}


def _scene(seed: int, preset: str | None = None) -> tuple | None:
    """A random spin scene with 1-3 impacts, or None if this seed gives another count.

    ``preset``: on that (pocketless) preset's table, else a pocketless default-sized one.
    """
    rng = np.random.default_rng(seed)
    friction = str(rng.choice(["alciatore", "alciatore", "none", "const"]))
    make = (
        partial(Table, model="spin", pockets="none")
        if preset is None
        else partial(Table.preset, preset)
    )
    table = make(
        e_ball=float(rng.choice([0.95, 1.0, rng.uniform(0.5, 1.0)])),
        e_cushion=float(rng.choice([0.65, rng.uniform(0.3, 1.0)])),
        ball_friction=(
            "alciatore" if friction == "alciatore" else
            0.0 if friction == "none" else float(rng.uniform(0.01, 0.2))
        ),
        cushion_friction=float(rng.choice([0.2, rng.uniform(0.0, 0.4)])),
    )  # fmt: skip
    n = int(rng.integers(2, 5))
    pos = random_layout(table, n, rng, min_gap=1e-3)
    target = pos[int(rng.integers(1, n))]
    aim = np.arctan2(*(target - pos[0])[::-1]) + rng.normal(0.0, 0.15)
    speed = rng.uniform(0.3, 3.0)
    vel, ang = np.zeros((n, 2)), np.zeros((n, 3))
    vel[0] = speed * np.array([np.cos(aim), np.sin(aim)])
    r = table.ball_radius
    ang[0] = rng.normal(0.0, 1.0, 3) * [speed / r, speed / r, 60.0]
    if rng.random() < 0.3:
        ang[int(rng.integers(1, n)), 2] = rng.uniform(-40.0, 40.0)  # spinning in place
    masses = rng.uniform(0.12, 0.25, n) if rng.random() < 0.2 else None
    res = simulate(table, pos, vel, masses, angular_velocities=ang)
    impacts = sum(e.kind in ("ball", "cushion") for e in res.events)
    if not 1 <= impacts <= 3:
        return None
    return table, pos, vel, ang, masses


def _scenes(seeds: range, count: int, preset: str | None = None) -> list[tuple]:
    return [s for s in (_scene(seed, preset) for seed in seeds) if s is not None][:count]


FAST = _scenes(range(0, 40), 14)
SLOW = _scenes(range(1000, 1300), 100)
#: The carom table (``Table.preset("carom")``): UMB size, 61.5 mm balls, 37 mm nose.
CAROM = _scenes(range(2000, 2100), 12, "carom")


def _tie_groups(times: list) -> list[slice]:
    """Runs of reference events at one instant (50-digit times within 1e-30 s)."""
    groups, start = [], 0
    for k in range(1, len(times) + 1):
        if k == len(times) or times[k] - times[k - 1] > mpf("1e-30"):
            groups.append(slice(start, k))
            start = k
    return groups


def _compare(scene: tuple) -> float:
    table, pos, vel, ang, masses = scene
    ours = simulate(table, pos, vel, masses, angular_velocities=ang)
    ref = spin_reference_simulate(table, pos, vel, ang, masses, max_events=400)
    mine = [(e.kind, e.i, e.j) for e in ours.events]
    theirs = [(k, i, j) for _, k, i, j in ref.events]
    assert len(mine) == len(theirs), (mine, theirs)
    # Events at one instant of the model (two balls that start sliding together at an impact
    # and roll at the same time) come in rounding order in float64: compare them as sets.
    for g in _tie_groups([t for t, _, _, _ in ref.events]):
        assert sorted(mine[g]) == sorted(theirs[g]), (mine, theirs)
    assert ours.motion_states.tolist() == ref.states
    with mp.workdps(50):
        return max(
            float(mp.sqrt((mpf(float(x)) - rx) ** 2 + (mpf(float(y)) - ry) ** 2))
            for (x, y), (rx, ry) in zip(ours.positions, ref.positions, strict=True)
        )


def test_fast_scenes_cover_every_event_kind() -> None:
    assert len(FAST) == 14
    kinds = {
        e.kind
        for table, pos, vel, ang, masses in FAST
        for e in simulate(table, pos, vel, masses, angular_velocities=ang).events
    }
    assert kinds >= KINDS


@pytest.mark.parametrize("scene", FAST, ids=lambda s: f"{len(s[1])}balls")
def test_matches_reference(scene: tuple) -> None:
    assert _compare(scene) < TOLERANCE


def test_carom_scenes_are_on_the_carom_table() -> None:
    assert len(CAROM) == 12
    assert {(t.length, t.ball_radius, t.cushion_height) for t, *_ in CAROM} == {
        (2.84, 0.03075, 0.037)
    }
    kinds = {
        e.kind
        for table, pos, vel, ang, masses in CAROM
        for e in simulate(table, pos, vel, masses, angular_velocities=ang).events
    }
    assert {"ball", "cushion"} <= kinds


@pytest.mark.parametrize("scene", CAROM, ids=lambda s: f"{len(s[1])}balls")
def test_carom_matches_reference(scene: tuple) -> None:
    assert _compare(scene) < TOLERANCE


@pytest.mark.slow
@pytest.mark.parametrize("scene", SLOW, ids=lambda s: f"{len(s[1])}balls")
def test_matches_reference_more_scenes(scene: tuple) -> None:
    assert _compare(scene) < TOLERANCE
