"""Scene layouts: legal, reproducible, the right balls in the right places; re-spotting."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import PoolEnv, Table, check_layout, free_spot
from pool_env.envs.seeding import seed_table
from pool_env.game import step as game
from pool_env.game.config import make_config
from pool_env.game.kernels.layout import sample_layouts
from pool_env.game.kernels.params import RESTARTS, TRIES
from pool_env.game.scenes import MAX_TRIES, n_object_balls, placement, plan_scene
from pool_env.game.scenes import RESTARTS as RESTARTS_DEFAULT
from pool_env.game.state import new_state
from pool_env.sim.layouts import foot_spot, head_spot, rack_eight_ball, rack_nine_ball

TABLE = Table()
R = TABLE.ball_radius


def _layouts(
    scene: object,
    n: int | None,
    rng: np.random.Generator,
    count: int,
    table: Table = TABLE,
    rack_order: str = "random",
) -> np.ndarray:
    """``count`` layouts of a scene drawn one after another from ``rng`` (as resets do)."""
    config = make_config(table=table, scene=scene, n_balls=n, rack_order=rack_order)
    state = new_state(count, config.n_balls)
    for i in range(count):
        state.use_generator(i, rng)
    game.reset(config, state, np.arange(count))
    return state.positions


def sample_scene(
    scene: str, table: Table, n: int, rng: np.random.Generator, rack_order: str = "random"
) -> np.ndarray:
    """One layout of a named scene."""
    return _layouts(scene, n, rng, 1, table, rack_order)[0]


def _crowd(rng: np.random.Generator, n: int, box: tuple[float, float, float, float]) -> np.ndarray:
    """``n`` balls drawn uniformly in ``box`` by the scenes' own sampler."""
    params = placement(TABLE)
    out = np.zeros((1, n, 2))
    state = new_state(1, 1)
    state.use_generator(0, rng)
    fell_back = sample_layouts(
        params, TABLE.pockets, np.zeros(1, np.intp), out, state.ptrs, np.zeros((0, 2)),
        np.array(box), np.zeros((n, 2)),
    )  # fmt: skip
    assert not fell_back[0]
    return out[0]


def _legal(table: Table, layout: np.ndarray) -> None:
    check_layout(table, layout)  # the simulator's own checks: inside, apart, out of pockets
    d = layout[:, None, :] - layout[None, :, :]
    dist = np.hypot(d[..., 0], d[..., 1]) + np.eye(len(layout)) * 1.0
    assert dist.min() >= 2 * R - 1e-9


@pytest.mark.parametrize(("scene", "n"), [("one_ball", 1), ("random", 3), ("random", 15)])
def test_random_scenes_are_legal_and_cover_the_table(scene: str, n: int) -> None:
    rng = np.random.default_rng(1)
    layouts = _layouts(scene, n, rng, 300)
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
    for _ in range(50):  # the fixed order: tests/game/test_rack_order.py has the drawn one
        layout = sample_scene(scene, TABLE, n_object_balls(scene, None), rng, "fixed")
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
    with pytest.raises(
        ValueError, match=r"scene='random', n_balls=15: cannot lay out.*fewer balls"
    ):
        plan_scene("random", tiny, 15)
    with pytest.raises(ValueError, match="rack does not fit"):
        plan_scene("nine_ball", Table(length=0.5, width=0.5), None)


def test_a_crowded_scene_is_decided_at_construction_and_every_reset_succeeds() -> None:
    # Issue 11 (5): 11 balls on a 0.4 x 0.2 m table used to fail on 120 of 200 resets.
    small = {"length": 0.4, "width": 0.2}
    env = PoolEnv(table=small, n_balls=11)
    for seed in range(200):
        env.reset(seed=seed)
        check_layout(env.config.table, env.positions)
    with pytest.raises(ValueError, match=r"n_balls=13: cannot lay out the scene.*fewer balls"):
        PoolEnv(table=small, n_balls=13)  # 14 balls do not fit: refused before any reset


def test_when_random_placement_keeps_failing_the_plans_grid_layout_is_used() -> None:
    config = make_config(table={"length": 0.4, "width": 0.2}, n_balls=11)
    plan = config.scene
    check_layout(config.table, plan.fallback)  # the grid is legal
    params = config.params.copy()
    params[TRIES] = params[RESTARTS] = 1  # one try, one attempt: 12 balls cannot succeed
    state = new_state(3, 12)
    for i in range(3):
        seed_table(state, i, i)
    fell_back = sample_layouts(
        params, config.table.pockets, np.arange(3), state.positions, state.ptrs, plan.placed,
        plan.box, plan.fallback,
    )  # fmt: skip
    assert fell_back.all()
    np.testing.assert_array_equal(state.positions, np.repeat(plan.fallback[None], 3, axis=0))
    assert params[TRIES] < MAX_TRIES and config.params[RESTARTS] == RESTARTS_DEFAULT


def test_fixed_and_callable_scenes() -> None:
    fixed = np.array([[0.5, 0.5], [1.0, 0.5]])
    assert plan_scene(fixed, TABLE, None).n_objects == 1
    config = make_config(scene=fixed)
    state = new_state(2, 2)
    game.reset(config, state, np.arange(2))
    np.testing.assert_array_equal(state.positions, [fixed, fixed])
    fixed[0] = 0.0  # the scene was copied: changing the caller's array changes nothing
    assert not config.scene.fixed.flags.writeable
    game.reset(config, state, np.arange(2))
    np.testing.assert_array_equal(state.positions, [[[0.5, 0.5], [1.0, 0.5]]] * 2)

    def two_random(table: Table, rng: np.random.Generator) -> np.ndarray:
        return np.array([[0.5, 0.5], [1.0, 0.5], rng.uniform([1.5, 0.3], [2.0, 0.9])])

    assert plan_scene(two_random, TABLE, 2).n_objects == 2
    a, b = _layouts(two_random, 2, np.random.default_rng(3), 2)
    assert a.shape == (3, 2) and not np.array_equal(a, b)  # a draw per table
    with pytest.raises(ValueError, match="n_balls=4 does not match"):
        plan_scene(two_random, TABLE, 4)


@pytest.mark.parametrize(
    ("layout", "message"),
    [
        ([[0.5, 0.5], [0.51, 0.5]], "overlap"),
        ([[0.5, 0.5], [3.0, 0.5]], "off the table"),
        ([[0.5, 0.5], [0.0, 0.0]], "pocket"),
        ([[0.5, 0.5]], "at least one object ball"),
    ],
)
def test_invalid_fixed_layouts_are_rejected(layout: list, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        plan_scene(np.array(layout), TABLE, None)


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
    crowd = _crowd(rng, 15, (0.4, 0.9, 0.4, 0.85))
    pos = np.vstack([[0.1, 0.1], crowd])
    occupied = np.ones(16, bool)
    occupied[0] = False
    spot = free_spot(TABLE, pos, occupied)
    _legal(TABLE, np.vstack([spot, crowd]))
