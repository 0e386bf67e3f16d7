"""Scene layouts: legal, reproducible, the right balls in the right places; re-spotting."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table
from pool_env.scenes import (
    check_layout,
    free_spot,
    make_sampler,
    n_object_balls,
    sample_scene,
    sample_uniform,
)
from pool_env.sim.layouts import foot_spot, head_spot, rack_eight_ball, rack_nine_ball

TABLE = Table()
R = TABLE.ball_radius


def _legal(table: Table, layout: np.ndarray) -> None:
    check_layout(table, layout)  # the simulator's own checks: inside, apart, out of pockets
    d = layout[:, None, :] - layout[None, :, :]
    dist = np.hypot(d[..., 0], d[..., 1]) + np.eye(len(layout)) * 1.0
    assert dist.min() >= 2 * R - 1e-9


@pytest.mark.parametrize(("scene", "n"), [("one_ball", 1), ("random", 3), ("random", 15)])
def test_random_scenes_are_legal_and_cover_the_table(scene: str, n: int) -> None:
    rng = np.random.default_rng(1)
    layouts = np.stack([sample_scene(scene, TABLE, n, rng) for _ in range(300)])
    assert layouts.shape == (300, n + 1, 2)
    for layout in layouts:
        _legal(TABLE, layout)
    xs, ys = layouts[..., 0].ravel(), layouts[..., 1].ravel()
    assert xs.min() < 0.3  # uniform over the whole table
    assert xs.max() > TABLE.length - 0.3
    assert ys.min() < 0.2
    assert ys.max() > TABLE.width - 0.2


@pytest.mark.parametrize(
    ("scene", "rack"), [("nine_ball", rack_nine_ball), ("eight_ball", rack_eight_ball)]
)
def test_break_scenes_rack_on_the_foot_spot_and_cue_in_the_kitchen(
    scene: str, rack: object
) -> None:
    rng = np.random.default_rng(2)
    for _ in range(50):
        layout = sample_scene(scene, TABLE, n_object_balls(scene, None), rng)
        np.testing.assert_array_equal(layout[1:], rack(TABLE))  # type: ignore[operator]
        np.testing.assert_array_equal(layout[1], foot_spot(TABLE))  # the 1 at the apex
        assert R <= layout[0, 0] <= TABLE.length / 4
        _legal(TABLE, layout)


def test_same_seed_same_layout_and_different_seeds_differ() -> None:
    a = sample_scene("random", TABLE, 5, np.random.default_rng(7))
    b = sample_scene("random", TABLE, 5, np.random.default_rng(7))
    c = sample_scene("random", TABLE, 5, np.random.default_rng(8))
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, c)


def test_n_object_balls() -> None:
    assert n_object_balls("one_ball", None) == 1
    assert n_object_balls("nine_ball", 9) == 9
    assert n_object_balls("random", None) == 3
    assert n_object_balls("random", 15) == 15
    for scene, n in [("nine_ball", 3), ("random", 0), ("random", 16), ("one_ball", 2)]:
        with pytest.raises(ValueError, match="n_balls"):
            n_object_balls(scene, n)
    with pytest.raises(ValueError, match="scene must be one of"):
        n_object_balls("snooker", None)


def test_a_scene_that_cannot_fit_says_so() -> None:
    tiny = Table(length=0.2, width=0.2, pockets="none")  # 15 balls would cover 96%
    with pytest.raises(ValueError, match=r"cannot lay out the scene.*fewer balls"):
        sample_uniform(tiny, 15, np.random.default_rng(0))
    with pytest.raises(ValueError, match=r"scene='random', n_balls=15: cannot lay out"):
        make_sampler("random", tiny, 15)
    with pytest.raises(ValueError, match="rack does not fit"):
        make_sampler("nine_ball", Table(length=0.5, width=0.5), None)


def test_fixed_and_callable_scenes() -> None:
    fixed = np.array([[0.5, 0.5], [1.0, 0.5]])
    sample, n = make_sampler(fixed, TABLE, None)
    assert n == 1
    out = sample(np.random.default_rng(0))
    np.testing.assert_array_equal(out, fixed)
    out[0] = 0.0  # a copy each time: the scene itself cannot be changed through it
    np.testing.assert_array_equal(sample(np.random.default_rng(0)), fixed)

    def two_random(table: Table, rng: np.random.Generator) -> np.ndarray:
        return sample_uniform(table, 3, rng)

    sample, n = make_sampler(two_random, TABLE, 2)
    assert n == 2
    assert sample(np.random.default_rng(3)).shape == (3, 2)
    with pytest.raises(ValueError, match="n_balls=4 does not match"):
        make_sampler(two_random, TABLE, 4)


@pytest.mark.parametrize(
    ("layout", "message"),
    [
        ([[0.5, 0.5], [0.51, 0.5]], "overlap"),
        ([[0.5, 0.5], [3.0, 0.5]], "off the table"),
        ([[0.5, 0.5], [0.0, 0.0]], "pocket"),
        ([[0.5, 0.5]], "N >= 2"),
    ],
)
def test_invalid_fixed_layouts_are_rejected(layout: list, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        make_sampler(np.array(layout), TABLE, None)


def test_free_spot_is_the_head_spot_when_free() -> None:
    pos = np.array([[0.1, 0.1], [2.0, 0.6]])
    spot = free_spot(TABLE, pos, np.array([False, True]))
    np.testing.assert_array_equal(spot, head_spot(TABLE))


def test_free_spot_next_to_a_ball_on_the_head_spot_is_2r_away_on_its_far_side() -> None:
    hs = head_spot(TABLE)
    blocker = hs + np.array([0.01, 0.0])  # a ball 1 cm past the head spot along +x
    spot = free_spot(TABLE, np.stack([hs, blocker]), np.array([False, True]))
    np.testing.assert_allclose(spot, blocker - [2 * R, 0.0], atol=1e-6)
    assert np.hypot(*(spot - blocker)) >= 2 * R


def test_free_spot_between_two_blocking_balls_is_where_their_circles_meet() -> None:
    hs = head_spot(TABLE)
    a, b = hs - np.array([1.5 * R, 0.0]), hs + np.array([1.5 * R, 0.0])
    spot = free_spot(TABLE, np.stack([hs, a, b]), np.array([False, True, True]))
    assert abs(spot[0] - hs[0]) < 1e-6
    assert abs(abs(spot[1] - hs[1]) - math.sqrt((2 * R) ** 2 - (1.5 * R) ** 2)) < 1e-5
    for ball in (a, b):
        assert np.hypot(*(spot - ball)) >= 2 * R
    # Exactly the nearest point: nothing free closer to the head spot (dense check).
    rng = np.random.default_rng(0)
    pts = hs + rng.uniform(-3 * R, 3 * R, (20000, 2))
    free = (np.hypot(*(pts - a).T) >= 2 * R) & (np.hypot(*(pts - b).T) >= 2 * R)
    assert np.hypot(*(pts[free] - hs).T).min() >= np.hypot(*(spot - hs)) - 1e-9


def test_free_spot_in_a_crowd_is_legal() -> None:
    rng = np.random.default_rng(5)
    crowd = sample_uniform(TABLE, 15, rng, box=(0.4, 0.9, 0.4, 0.85))
    pos = np.vstack([[0.1, 0.1], crowd])
    occupied = np.ones(16, bool)
    occupied[0] = False
    spot = free_spot(TABLE, pos, occupied)
    _legal(TABLE, np.vstack([spot, crowd]))
