"""Reset's inputs at the edges (issue 20 items 6 and 7).

Racks that could never end, NaN rows of balls off the table, options that are not a dict,
numpy integers as seeds and fouls.

Every refusal is a ``ValueError`` at reset, and the environment's state is then what it was.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.envs.multiagent import PoolDuelEnv
from tests.game.test_games import IDS, KWARGS, NINE_MISS, ON_EIGHT, layout, parked


def _snapshot(env: Any) -> tuple:
    raw = env.unwrapped
    state = raw._state
    return (state.positions.tobytes(), state.on_table.tobytes(), state.shots.tobytes(),
            state.rack.tobytes())  # fmt: skip


def _env(game: str) -> gym.Env:
    env = gym.make(IDS[game], **KWARGS)
    env.reset(seed=0)
    return env


def _without(balls: dict, ball: int) -> dict:
    return {b: p for b, p in balls.items() if b != ball}


EIGHT_ONLY = {0: (0.3, 0.3), 8: parked(0)}
SOLIDS_CLEARED_NO_EIGHT = {0: (0.3, 0.3), 11: parked(0), 12: parked(1)}


@pytest.mark.parametrize(
    ("game", "balls", "rules", "match"),
    [
        ("nine", _without(NINE_MISS, 9), {}, "the 9 must be on the table"),
        ("eight", _without(ON_EIGHT, 8), {"groups": ("solids", "stripes")},
         "the 8 must be on the table"),
        ("eight", SOLIDS_CLEARED_NO_EIGHT, {"groups": ("solids", "stripes")},
         "the 8 must be on the table"),
        ("eight", EIGHT_ONLY, {}, "open 8-ball table needs an object ball other than the 8"),
        ("eight", EIGHT_ONLY, {"break": True}, "open 8-ball table needs"),
        ("eight", ON_EIGHT, {"break": True, "groups": ("solids", "stripes")},
         "assigned after the break"),
        ("nine", NINE_MISS, {"fouls": (3, 0)}, "fouls"),
        ("nine", NINE_MISS, {"fouls": (0, -1)}, "fouls"),
        ("nine", NINE_MISS, {"fouls": (True, True)}, "fouls"),
        ("nine", NINE_MISS, {"fouls": (1.0, 0)}, "fouls"),
        ("nine", NINE_MISS, {"shooter": 2}, "shooter"),
        ("nine", NINE_MISS, {"shooter": True}, "shooter"),
    ],
)  # fmt: skip
def test_a_rack_the_rules_could_never_finish_is_refused(game, balls, rules, match) -> None:
    env = _env(game)
    before = _snapshot(env)
    with pytest.raises(ValueError, match=match):
        env.reset(options={**layout(game, balls), "rules": rules})
    assert _snapshot(env) == before


def test_the_refused_racks_are_refused_by_every_front() -> None:
    options = {**layout("eight", _without(ON_EIGHT, 8)), "rules": {}}
    vec = gym.make_vec(IDS["eight"], 2, vectorization_mode="vector_entry_point", **KWARGS)
    vec.reset(seed=0)
    before = _snapshot(vec)
    with pytest.raises(ValueError, match="the 8 must be on the table"):
        vec.reset(options=options)
    assert _snapshot(vec) == before
    duel = PoolDuelEnv("eight")
    with pytest.raises(ValueError, match="the 8 must be on the table"):
        duel.reset(options=options)
    # the shooter of a two-player rack: 0 or 1, as an int
    for shooter in (1, np.int64(1)):
        duel.reset(options={**layout("eight", ON_EIGHT), "rules": {"shooter": shooter}})
        assert duel.agent_selection == "player_1"


def test_numpy_integer_fouls_are_taken_like_python_ints() -> None:
    env = _env("nine")
    env.reset(options={**layout("nine", NINE_MISS), "rules": {"fouls": [np.int64(1), 0]}})
    assert env.unwrapped.rack["fouls"] == (1, 0)
    assert type(env.unwrapped.rack["fouls"][0]) is int


def test_nan_rows_of_balls_off_the_table_are_refused() -> None:
    env = _env("nine")
    before = _snapshot(env)
    options = layout("nine", NINE_MISS)
    options["positions"][5] = np.nan  # ball 5 is off the table
    assert not options["on_table"][5]
    with pytest.raises(ValueError, match=r"row 5 is not finite"):
        env.reset(options=options)
    assert _snapshot(env) == before
    options["positions"][5] = (0.0, 0.0)  # any finite point will do
    env.reset(options=options)
    assert np.isfinite(env.unwrapped.positions).all()
    vec = gym.make_vec(IDS["nine"], 2, vectorization_mode="vector_entry_point", **KWARGS)
    batch = np.stack([options["positions"]] * 2)
    batch[1, 7] = np.inf
    with pytest.raises(ValueError, match=r"table 1: options\['positions'\] row 7"):
        vec.reset(options={"positions": batch, "on_table": options["on_table"]})
    solitaire = gym.make("pool_env/PoolRoll-v1", n_balls=2)
    with pytest.raises(ValueError, match="row 2 is not finite"):
        solitaire.reset(options={"positions": [[0.3, 0.3], [1, 0.6], [np.nan, 0.0]],
                                 "on_table": [True, True, False]})  # fmt: skip


@pytest.mark.parametrize("options", [[1], "positions", 3, (("rules", {}),)])
def test_options_that_are_not_a_dict_raise_value_error(options) -> None:
    for env in (_env("nine"), gym.make("pool_env/OneBallRoll-v1"),
                gym.make_vec("pool_env/OneBallRoll-v1", 2, vectorization_mode="vector_entry_point"),
                PoolDuelEnv("nine")):  # fmt: skip
        with pytest.raises(ValueError, match="options must be a dict or None"):
            env.reset(options=options)


@pytest.mark.parametrize("seed", [np.int64(5), np.uint32(5), np.int8(5)])
def test_numpy_integer_seeds_are_accepted_like_python_ints(seed) -> None:
    a, b = gym.make("pool_env/OneBallRoll-v1"), gym.make("pool_env/OneBallRoll-v1")
    obs_a, _ = a.reset(seed=seed)
    obs_b, _ = b.reset(seed=5)
    assert np.array_equal(obs_a, obs_b)
    assert a.unwrapped.np_random_seed == 5 and type(a.unwrapped.np_random_seed) is int
    vec = gym.make_vec("pool_env/OneBallRoll-v1", 2, vectorization_mode="vector_entry_point")
    obs_v, _ = vec.reset(seed=seed)
    assert np.array_equal(obs_v[0], obs_a)


def test_a_seed_beyond_64_bits_plays_alike_in_the_single_and_the_vector_env() -> None:
    seed = 2**70
    single = gym.make(IDS["nine"], noise=(0.01, 0.05))
    vec = gym.make_vec(IDS["nine"], 2, vectorization_mode="vector_entry_point",
                       noise=(0.01, 0.05))  # fmt: skip
    obs_s, _ = single.reset(seed=seed)
    obs_v, _ = vec.reset(seed=seed)
    assert np.array_equal(obs_s, obs_v[0])
    assert vec.unwrapped.np_random_seed == (seed, seed + 1)
    action = np.array([0.1, 0.3, 0.0, 0.0, 0.0, 0.0], np.float32)
    out_s = single.step(action)
    out_v = vec.step(np.stack([action, action]))
    assert np.array_equal(out_s[0], out_v[0][0]) and out_s[1] == out_v[1][0]
    with pytest.raises(ValueError, match="non-negative integer"):
        single.reset(seed=-(2**70))
    with pytest.raises(ValueError, match="non-negative integer"):
        vec.reset(seed=-(2**70))
