"""Racks as the WPA rules rack them, drawn by each reset (issue 35), or in the fixed order.

``rack_order="random"`` (the default): 9-ball the 1 on the apex and the 9 in the centre;
10-ball the 1 on the apex and the 10 in the middle of the third row; 8-ball the 8 in the
centre of the third row and a solid and a stripe in the back corners; every other ball on
the other spots in a random order, drawn from the table's generator. ``"fixed"``: the racks
of ``pool_env.sim.layouts`` every episode.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

from pool_env import PoolEnv, PoolVectorEnv, Table
from pool_env.sim.layouts import (
    RACK_ROWS,
    foot_spot,
    rack_eight_ball,
    rack_nine_ball,
    rack_spots,
    rack_ten_ball,
    shuffled_spots,
)

TABLE = Table()
SCENES = {"nine": "nine_ball", "ten": "ten_ball", "eight": "eight_ball"}
FIXED = {"nine": rack_nine_ball, "ten": rack_ten_ball, "eight": rack_eight_ball}
IDS = {
    "nine": "pool_env/NineBallGame-v2",
    "ten": "pool_env/TenBallGame-v1",
    "eight": "pool_env/EightBallGame-v1",
}

#: Racks drawn for the statistics (one reset of that many tables).
N_RACKS = 2000

#: Standard normal quantile of the chi-square bounds (p ~ 3e-7 per one-sided check).
Z = 5.0


def spots_of(rack: str, positions: np.ndarray, table: Table = TABLE) -> np.ndarray:
    """``(B, n)`` the spot (index into ``rack_spots``) of each object ball, checked exact."""
    spots = rack_spots(table, rack)
    balls = positions[:, 1:, None, :]  # (B, n, 1, 2) against (n, 2) spots
    d = np.abs(balls - spots[None, None]).sum(axis=-1)
    index = d.argmin(axis=-1)
    assert (d.min(axis=-1) == 0.0).all(), "a ball off the rack's spots"
    return index


def rows_of(rack: str) -> list[list[int]]:
    """The spots of each row, apex first."""
    out, start = [], 0
    for size in RACK_ROWS[rack]:
        out.append(list(range(start, start + size)))
        start += size
    return out


def chi2_upper(df: int, z: float = Z) -> float:
    """The chi-square quantile at the normal's ``z`` (Wilson-Hilferty)."""
    c = 2.0 / (9.0 * df)
    return df * (1.0 - c + z * math.sqrt(c)) ** 3


def many_racks(rack: str, n: int = N_RACKS, seed: int = 35_000) -> np.ndarray:
    """``(n, balls)`` spots of ``n`` racks, one per table of a vector env of the game id."""
    env = gym.make_vec(IDS[rack], num_envs=n)
    env.reset(seed=seed)
    out = spots_of(rack, env.unwrapped.positions)
    env.close()
    return out


@pytest.mark.parametrize("rack", ["nine", "ten", "eight"])
def test_the_rules_balls_are_where_the_rules_put_them(rack: str) -> None:
    spots = many_racks(rack, 500)
    rows = rows_of(rack)
    centre = rows[2][1]  # the third row's middle: 9-ball's centre of the diamond
    assert (np.sort(spots, axis=1) == np.arange(spots.shape[1])).all()  # a permutation
    if rack == "nine":
        assert (spots[:, 0] == 0).all() and (spots[:, 8] == centre).all()
    elif rack == "ten":
        assert (spots[:, 0] == 0).all() and (spots[:, 9] == centre).all()
    else:
        assert (spots[:, 7] == centre).all()
        corners = [rows[-1][0], rows[-1][-1]]
        for ball_at in (spots == corners[0], spots == corners[1]):
            assert (ball_at.sum(axis=1) == 1).all()
        at_corner = np.argwhere(np.isin(spots, corners))[:, 1] + 1  # ball numbers, rack by rack
        pairs = np.sort(at_corner.reshape(-1, 2), axis=1)
        assert (pairs[:, 0] <= 7).all() and (pairs[:, 1] >= 9).all()  # a solid and a stripe
        solid_first = spots[np.arange(len(spots)), pairs[:, 0] - 1] == corners[0]
        assert 0 < solid_first.sum() < len(spots)  # which corner the solid takes: drawn too


@pytest.mark.parametrize("rack", ["nine", "ten", "eight"])
def test_every_free_ball_reaches_every_free_spot_uniformly(rack: str) -> None:
    """Counts of ball-on-spot over 2000 racks: every cell reached, each ball uniform (chi^2).

    In 8-ball every ball but the 8 is uniform over the 14 other spots: a ball is in a given
    corner with probability (1/7)(1/2) = 1/14, and in each of the 12 others with
    (1 - 2/14) / 12 = 1/14.
    """
    spots = many_racks(rack)
    n_balls = spots.shape[1]
    pinned = {"nine": {1, 9}, "ten": {1, 10}, "eight": {8}}[rack]
    free = [b for b in range(1, n_balls + 1) if b not in pinned]
    free_spots = sorted(set(range(n_balls)) - {int(spots[0, b - 1]) for b in pinned})
    counts = np.zeros((len(free), len(free_spots)), dtype=np.int64)
    for i, ball in enumerate(free):
        counts[i] = [(spots[:, ball - 1] == s).sum() for s in free_spots]
    assert counts.sum(axis=1).tolist() == [N_RACKS] * len(free)  # never on a pinned spot
    assert (counts > 0).all()  # every position reached
    expected = N_RACKS / len(free_spots)
    statistic = ((counts - expected) ** 2 / expected).sum(axis=1)
    assert statistic.max() < chi2_upper(len(free_spots) - 1), statistic


@pytest.mark.parametrize("rack", ["nine", "ten", "eight"])
def test_a_seed_gives_its_rack_and_other_seeds_others(rack: str) -> None:
    env = gym.make(IDS[rack])
    seen = []
    for seed in range(20):
        env.reset(seed=seed)
        first = env.unwrapped.positions
        env.reset(seed=seed)
        np.testing.assert_array_equal(env.unwrapped.positions, first)  # reproducible
        seen.append(tuple(spots_of(rack, first[None])[0]))
    assert len(set(seen)) == 20  # 7! or more orders: twenty seeds, twenty racks
    vector = PoolVectorEnv(4, **gym.spec(IDS[rack]).kwargs)
    vector.reset(seed=5)
    tables = [tuple(row) for row in spots_of(rack, vector.positions)]
    assert len(set(tables)) == 4  # a rack per table
    assert tables[2] == seen[7]  # table i of reset(seed=s) is the env seeded s + i
    vector.close()


@pytest.mark.parametrize("rack", ["nine", "ten", "eight"])
def test_fixed_order_is_the_fixed_rack_and_the_cue_ball_unchanged(rack: str) -> None:
    fixed = gym.make(IDS[rack], rack_order="fixed")
    drawn = gym.make(IDS[rack])
    for seed in range(10):
        fixed.reset(seed=seed)
        drawn.reset(seed=seed)
        layout = fixed.unwrapped.positions
        np.testing.assert_array_equal(layout[1:], FIXED[rack](TABLE))
        np.testing.assert_array_equal(layout[0], drawn.unwrapped.positions[0])  # drawn first
    assert fixed.unwrapped.config.scene.rack is None
    assert drawn.unwrapped.config.scene.rack == rack


def test_solitaire_rack_scenes_draw_the_order_too() -> None:
    env = PoolEnv(scene="nine_ball")
    orders = set()
    for seed in range(5):
        env.reset(seed=seed)
        spots = spots_of("nine", env.positions[None])[0]
        assert spots[0] == 0 and spots[8] == 4
        np.testing.assert_array_equal(env.positions[1], foot_spot(TABLE))  # the 1 on the spot
        orders.add(tuple(spots))
    assert len(orders) == 5
    random_scene = PoolEnv(scene="random", rack_order="fixed")  # no rack: nothing to order
    assert random_scene.config.scene.rack is None


@pytest.mark.parametrize("bad", ["shuffled", "Random", None, 1])
def test_a_bad_rack_order_names_the_key(bad: object) -> None:
    with pytest.raises(ValueError, match="rack_order must be one of"):
        PoolEnv(scene="nine_ball", rack_order=bad)
    with pytest.raises(ValueError, match="rack_order must be one of"):
        gym.make("pool_env/EightBallGame-v1", rack_order=bad)


def test_shuffled_spots_draws_from_the_generator_alone() -> None:
    """The same generator state gives the same rack; every rack is a permutation."""
    for rack in RACK_ROWS:
        a = shuffled_spots(rack, np.random.default_rng(3))
        b = shuffled_spots(rack, np.random.default_rng(3))
        np.testing.assert_array_equal(a, b)
        assert sorted(a.tolist()) == list(range(sum(RACK_ROWS[rack])))
