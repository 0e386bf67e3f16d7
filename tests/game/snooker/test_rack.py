"""Snooker's frame state given at reset (``options["rules"]``): bad values refused by name."""

from __future__ import annotations

import numpy as np
import pytest

from pool_env import PoolEnv
from pool_env.game.games.snooker import rack_state as sk

GOOD = [0, 0, 0, sk.RED_ON, 0, 0, 0, 0, -1]  # player 0 on a red, no score, no winner


@pytest.fixture(scope="module")
def env() -> PoolEnv:
    return PoolEnv(game="snooker", scene="snooker")


# the column, its key (as the message names it), a bad value, the valid range's words
BAD = [
    (sk.SHOOTER, "shooter", 5, "in 0..1"), (sk.SHOOTER, "shooter", -1, "in 0..1"),
    (sk.SCORE_0, "score_0", -1, ">= 0"), (sk.SCORE_1, "score_1", -3, ">= 0"),
    (sk.IN_HAND, "ball_in_hand", 2, "in 0..1"), (sk.FREE_BALL, "free_ball", -1, "in 0..1"),
    (sk.BREAK, "break", -1, ">= 0"), (sk.RESPOTTED, "respotted_black", 2, "in 0..1"),
    (sk.WINNER, "winner", 2, "in -1..1"), (sk.WINNER, "winner", -2, "in -1..1"),
]  # fmt: skip


@pytest.mark.parametrize(("column", "key", "value", "valid"), BAD)
def test_a_raw_row_value_out_of_range_is_refused_and_changes_nothing(
    env: PoolEnv, column: int, key: str, value: int, valid: str
) -> None:
    env.reset(seed=0, options={"rules": {"score_0": 5, "break": 3}})
    rack, positions, on = env.rack, env.positions.copy(), env.on_table.copy()
    row = list(GOOD)
    row[column] = value
    with pytest.raises(ValueError, match=rf"'{key}'\) must be {valid}, got {value}"):
        env.reset(seed=1, options={"rules": row})
    assert env.rack == rack
    np.testing.assert_array_equal(env.positions, positions)
    np.testing.assert_array_equal(env.on_table, on)


def test_a_good_raw_row_is_taken() -> None:
    env = PoolEnv(game="snooker", scene="snooker")
    row = list(GOOD)
    row[sk.SHOOTER], row[sk.SCORE_1], row[sk.WINNER] = 1, 12, -1
    env.reset(seed=0, options={"rules": row})
    assert (env.rack["shooter"], env.rack["score_1"], env.rack["winner"]) == (1, 12, None)


def test_a_negative_score_in_a_dict_says_the_valid_range(env: PoolEnv) -> None:
    with pytest.raises(ValueError, match=r"\['score_0'\] must be an integer >= 0, got -1"):
        env.reset(seed=0, options={"rules": {"score_0": -1}})
    with pytest.raises(ValueError, match=r"\['shooter'\] must be an integer in 0..1, got 5"):
        env.reset(seed=0, options={"rules": {"shooter": 5}})
