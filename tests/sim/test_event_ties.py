"""Ties between event kinds: a ball touching a rail and another ball at the same instant.

The event order is (time, kind, ids) with pocket < ball < cushion < stop (docs/physics.md,
"Determinism").
When a ball touches a rail and a ball at once, moving into both, with non-orthogonal
normals, the order changes the outcome: the ball impact first, then the rail, is the
documented rule. The scenes start at that instant (t = 0, positions exact), so the tie is
exact in float64 too. Expected values are derived here by hand from the impact and
cushion laws (tests/helpers_sim.py), and checked against the 50-digit reference.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.testing.reference import reference_simulate
from tests.helpers_sim import normal_velocities

TABLE = Table(pockets="none")
R = TABLE.ball_radius
THETA = math.radians(30.0)  # line of centres at 30 degrees to the rail: not orthogonal


def _to_rail(rail: int, x: float, y: float) -> tuple[float, float]:
    """Map a point of the bottom-rail frame (rail 2, y = R) to the frame of ``rail``."""
    length, width = TABLE.length, TABLE.width
    return {2: (x, y), 3: (x, width - y), 0: (y, x), 1: (length - y, x)}[rail]


def _vector_to_rail(rail: int, vx: float, vy: float) -> tuple[float, float]:
    return {2: (vx, vy), 3: (vx, -vy), 0: (vy, vx), 1: (-vy, vx)}[rail]


def _scene(rail: int, v: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """Ball 0 on the rail line moving into it and into ball 1, which rests touching it."""
    p0 = np.array(_to_rail(rail, 0.6, R))
    # Ball 1 a hair (1e-16 m) into ball 0: whatever the rounding of the frame change, the
    # pair is in contact at t = 0, so the tie is exact (the contact rule: approaching
    # means collide now).
    offset = np.array(_vector_to_rail(rail, math.cos(THETA), math.sin(THETA)))
    positions = np.array([p0, p0 + (2 * R - 1e-16) * offset])
    velocities = np.array([_vector_to_rail(rail, *v), (0.0, 0.0)])
    return positions, velocities


def _by_hand(v: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """Velocities after the tie in the bottom-rail frame: ball impact, then the rail."""
    n = np.array([math.cos(THETA), math.sin(THETA)])
    v0 = np.array(v)
    un = float(v0 @ n)
    assert un > 0.0  # approaching ball 1
    u0, u1 = normal_velocities(TABLE.ball_mass, TABLE.ball_mass, un, 0.0, TABLE.e_ball)
    v0 = v0 + (u0 - un) * n
    v1 = u1 * n
    assert v0[1] < 0.0  # still into the rail: it bounces at the same instant
    v0[1] = -TABLE.e_cushion * v0[1]
    assert float((v1 - v0) @ n) > 0.0  # separating from ball 1: no third event at t = 0
    return v0, v1


def _rest(p: np.ndarray, v: np.ndarray) -> np.ndarray:
    speed = float(np.hypot(*v))
    return p + v / speed * speed * speed / (2 * TABLE.deceleration)


@pytest.mark.parametrize("rail", [0, 1, 2, 3])
@pytest.mark.parametrize("v", [(0.42, -0.14), (0.3, -0.08)])
def test_ball_impact_then_rail_at_the_same_instant(rail: int, v: tuple[float, float]) -> None:
    positions, velocities = _scene(rail, v)
    result = simulate(TABLE, positions, velocities)
    v0, v1 = _by_hand(v)
    stops = sorted(
        (float(np.hypot(*v_k)) / TABLE.deceleration, k) for k, v_k in enumerate((v0, v1))
    )
    assert [(e.kind, e.i, e.j) for e in result.events] == [
        ("ball", 0, 1),
        ("cushion", 0, rail),
        ("stop", stops[0][1], -1),
        ("stop", stops[1][1], -1),
    ]
    assert result.events[0].time == 0.0 and result.events[1].time == 0.0
    rest0 = _to_rail(rail, *_rest(np.array([0.6, R]), v0))
    rest1 = _to_rail(rail, *_rest(positions_base_1(), v1))
    np.testing.assert_allclose(result.positions[0], rest0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.positions[1], rest1, rtol=0, atol=1e-12)
    for (t, k), event in zip(stops, result.events[2:], strict=True):
        assert event.i == k
        assert event.time == pytest.approx(t, rel=1e-12)


def positions_base_1() -> np.ndarray:
    """Ball 1's centre in the bottom-rail frame."""
    return np.array([0.6 + 2 * R * math.cos(THETA), R + 2 * R * math.sin(THETA)])


@pytest.mark.parametrize("rail", [2, 1])
@pytest.mark.parametrize("v", [(0.42, -0.14), (0.8, -0.3), (0.5, -0.6)])
def test_tie_sequences_match_the_reference(rail: int, v: tuple[float, float]) -> None:
    """The exact event sequence and final state of the 50-digit reference, re-collisions too.

    With (0.8, -0.3) and (0.5, -0.6) the rail sends ball 0 back into ball 1 at the same
    instant: ball, cushion, ball, all at t = 0.
    """
    positions, velocities = _scene(rail, v)
    ours = simulate(TABLE, positions, velocities)
    ref = reference_simulate(TABLE, positions, velocities)
    assert [(e.kind, e.i, e.j) for e in ours.events] == [(k, i, j) for _, k, i, j in ref.events]
    with mp.workdps(50):
        for (x, y), (rx, ry) in zip(ours.positions, ref.positions, strict=True):
            assert abs(mp.mpf(float(x)) - rx) < 1e-12
            assert abs(mp.mpf(float(y)) - ry) < 1e-12
        for event, (t, _, _, _) in zip(ours.events, ref.events, strict=True):
            assert abs(mp.mpf(event.time) - t) <= 1e-12 * max(1, abs(t))
    if rail == 2:  # y = R is exact at 50 digits too (x = L - R is rounded in float64)
        assert ref.near_ties  # so the reference takes the tie order as well


def test_reversing_the_tie_order_would_move_the_balls() -> None:
    """The scenes are sensitive: rail first, then ball, ends a quarter metre elsewhere."""
    v = np.array([0.42, -0.14])
    n = np.array([math.cos(THETA), math.sin(THETA)])
    v_rail = v * [1.0, -TABLE.e_cushion]
    un = float(v_rail @ n)
    _, u1 = normal_velocities(TABLE.ball_mass, TABLE.ball_mass, un, 0.0, TABLE.e_ball)
    wrong1 = _rest(positions_base_1(), u1 * n)
    _, right1 = _by_hand(tuple(v))
    assert np.hypot(*(wrong1 - _rest(positions_base_1(), right1))) > 0.05
