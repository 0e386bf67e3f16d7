"""The nearest free point (issue 20 item 1): exact next to every edge of the allowed region.

:func:`pool_env.free_spot` places a ball in hand on a covered point, a scratched cue ball and
a re-spotted ball. The allowed region is a box (the rails' lines; the head string behind it)
minus discs (other balls, capture circles). Its nearest point used to be searched among the
target, the balls' and pockets' circles only, so a target covered next to a rail or the head
string went to a pocket's edge ~1 m away. Here: the closed form at a rail and at the head
string, the same reached from a normal step, and a property test against a brute-force grid
on random layouts that touch every kind of edge.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import pool_env  # noqa: F401  (registers the ids)
from pool_env import free_spot
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.layout import free_points
from pool_env.game.scenes import CLEARANCE, placement
from tests.game.test_games import KWARGS, action, fit, layout, parked
from tests.game.test_wpa import TABLE, R
from tests.profiles import examples

W, L = TABLE.width, TABLE.length
REACH = 2 * R + CLEARANCE
HEAD = L / 4


@pytest.mark.parametrize("behind", [False, True])
def test_the_nearest_free_point_next_to_an_edge_of_the_allowed_box(behind: bool) -> None:
    # A ball just inside an edge of the allowed centres (the bottom rail's y = R, or the
    # head string's x = L / 4) covers the target on that edge: the nearest free point is
    # where the ball's placement circle (2R + clearance) meets the edge, at
    # sqrt(reach^2 - gap^2) from the target.
    gap = 0.01
    if behind:
        target, ball = (HEAD, W / 2), (HEAD - gap, W / 2)
    else:
        target, ball = (1.0, R), (1.0, R + gap)
    positions = np.array([(0.0, 0.0), ball])
    got = free_spot(TABLE, positions, np.array([False, True]), np.array(target),
                    behind_head_string=behind)  # fmt: skip
    assert math.dist(got, target) == pytest.approx(math.sqrt(REACH**2 - gap**2), abs=1e-12)
    assert (got[1] == R) if not behind else (got[0] == HEAD)
    assert math.dist(got, ball) >= 2 * R


def test_ball_in_hand_next_to_a_ball_on_the_rail_stays_by_it_from_a_normal_step() -> None:
    # The reproduction: the 1 lies 1 cm off the bottom rail line at x = 1.0, the
    # cue ball in hand is placed on (1.0, R). It used to land near (1.74, 0.82) and hit the
    # 9 first: a foul the agent did not play. Now it goes where the 1's circle meets the
    # rail line, and a shot straight along +x misses the 1 (no contact, nothing else near).
    env = gym.make("pool_env/NineBallGameRoll-v2", **KWARGS)
    balls = {0: (0.3, 0.3), 1: (1.0, R + 0.01), 9: parked(1)}
    env.reset(seed=0, options={**layout("nine", balls), "rules": {"ball_in_hand": True}})
    u = (1.0 - R) / (L - 2 * R) * 2 - 1
    env.step(fit(env, action(0.0, 0.0, (u, -1.0))))  # placement (1.0, R); speed 0: it stays there
    got = env.unwrapped.positions[0]
    want_x = 1.0 - math.sqrt(REACH**2 - 0.01**2)  # the nearer of the two crossings
    np.testing.assert_allclose(got, [want_x, R], rtol=0, atol=1e-12)


def _nearest_on_a_grid(target: np.ndarray, balls: np.ndarray, behind: bool) -> float:
    """The distance from ``target`` to the nearest free point of a dense grid."""
    params = placement(TABLE)
    if behind:
        params[kp.X_HIGH] = HEAD
    lo = params[[kp.X_LOW, kp.Y_LOW]]
    hi = params[[kp.X_HIGH, kp.Y_HIGH]]
    best = math.inf
    # Fine near the target (0.5 mm), coarse over the whole table: the answer is within
    # a few reaches of the target whenever a nearby point is free.
    for half, step in ((3 * REACH, 5e-4), (None, 1e-2)):
        if half is None:
            x0, y0, x1, y1 = *lo, *hi
        else:
            x0, y0 = np.maximum(lo, target - half)
            x1, y1 = np.minimum(hi, target + half)
        xs = np.append(np.arange(x0, x1, step), x1)
        ys = np.append(np.arange(y0, y1, step), y1)
        grid = np.ascontiguousarray(np.stack(np.meshgrid(xs, ys), -1).reshape(-1, 2))
        ok = free_points(params, TABLE.pockets, grid, balls, REACH * REACH)
        if ok.any():
            best = min(best, float(np.hypot(*(grid[ok] - target).T).min()))
    return best


EDGES = ("rail", "head_string", "pocket", "balls")


@st.composite
def covered_targets(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, bool]:
    """A target next to one kind of edge, covered by balls around it."""
    edge = draw(st.sampled_from(EDGES))
    behind = edge == "head_string" or draw(st.booleans())
    x_high = HEAD if behind else L - R
    u = draw(st.floats(0.0, 1.0))
    if edge == "rail":
        side = draw(st.integers(0, 3))
        along = [R + u * (x_high - R), R + u * (W - 2 * R)]
        target = [(along[0], R), (along[0], W - R), (R, along[1]), (x_high, along[1])][side]
    elif edge == "head_string":
        target = (HEAD + draw(st.floats(-REACH, REACH)), R + u * (W - 2 * R))
    elif edge == "pocket":
        p = TABLE.pockets[draw(st.integers(0, TABLE.n_pockets - 1))]
        phi = draw(st.floats(0.0, 2 * math.pi))
        rho = p[2] * draw(st.floats(0.0, 1.5))
        target = (p[0] + rho * math.cos(phi), p[1] + rho * math.sin(phi))
    else:
        target = (R + u * (x_high - R), R + draw(st.floats(0.0, 1.0)) * (W - 2 * R))
    target = np.array(target, dtype=np.float64)
    balls: list[np.ndarray] = []
    for _ in range(draw(st.integers(1, 5))):  # around the target, covering it
        off = np.array([draw(st.floats(-1.5, 1.5)), draw(st.floats(-1.5, 1.5))]) * REACH
        c = np.clip(target + off, [R, R], [L - R, W - R])
        if all(math.dist(c, b) >= 2 * R for b in balls):
            balls.append(c)
    return target, np.array(balls).reshape(-1, 2), behind


@settings(max_examples=examples(100), deadline=None)
@given(covered_targets())
def test_the_placed_point_is_the_nearest_free_point_on_a_grid(case) -> None:
    target, balls, behind = case
    positions = np.vstack([[0.0, 0.0], balls])
    occupied = np.arange(len(positions)) > 0
    got = free_spot(TABLE, positions, occupied, target, behind_head_string=behind)
    params = placement(TABLE)
    if behind:
        params[kp.X_HIGH] = HEAD
    slack = (REACH - CLEARANCE / 2) ** 2  # free_spot's own rounding allowance
    assert free_points(params, TABLE.pockets, got[None].copy(), balls, slack)[0]
    best = _nearest_on_a_grid(target, np.ascontiguousarray(balls), behind)
    # No free grid point is nearer (the crossings are lifted 1e-6 relative, ~6e-8 m).
    assert math.dist(got, target) <= best + 1e-7
