"""Defaults in one place: every front plays by the game ids' defaults unless told otherwise.

The ids' defaults are their registered arguments (``pool_env.envs.registration.ENV_IDS``) over
:func:`pool_env.default_config`'s. Every front takes one sectioned config and keyword
overrides (issue 31): no front spells the keys out in its signature, and none copies a
config field onto itself; the
two-player fronts of :mod:`pool_env.envs.multiagent` take the game id's (issue 21 item 6: they
had drifted to absolute aim and 0.5-10 m/s where every id uses cut aim and 0.45-4.5 m/s).
"""

from __future__ import annotations

import inspect
from dataclasses import fields, is_dataclass
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import pool_env.game.config as config_module
from pool_env import PoolEnv, PoolVectorEnv, Table, default_config
from pool_env.envs.registration import (
    CURRENT_IDS,
    ENV_IDS,
    GAME_IDS,
    SPIN_ONLY,
    TASKS,
    roll_id,
    spin_id,
)
from pool_env.game.config import DEFAULT_SPEED_RANGE, GameConfig, TaskConfig, make_config
from pool_env.game.kernels import params as kp
from pool_env.game.sections import DEFAULT_MODEL, KEYS
from pool_env.sim.table import SPIN_ONLY as SPIN_PARAMS


def _same(a: Any, b: Any) -> bool:
    """Equal values, arrays and (field by field) dataclasses such as Table and ScenePlan."""
    if is_dataclass(a) and not isinstance(a, type):
        return type(a) is type(b) and all(
            _same(getattr(a, f.name), getattr(b, f.name)) for f in fields(a)
        )
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b)
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b, strict=True))
    return bool(a == b)


FRONTS = {"PoolEnv": PoolEnv, "PoolVectorEnv": PoolVectorEnv, "make_config": make_config}


@pytest.mark.parametrize("front", sorted(FRONTS))
def test_one_signature_source(front: str) -> None:
    """Every front takes the sectioned config and overrides: no key is spelled out twice."""
    params = inspect.signature(FRONTS[front]).parameters
    assert params["config"].default is None
    assert params["overrides"].kind is inspect.Parameter.VAR_KEYWORD
    assert not set(params) & set(KEYS), "a config key in a front's signature"


def test_every_key_is_documented_where_help_and_the_site_show_it() -> None:
    spec = (Path(__file__).parents[2] / "docs/environments/specification.md").read_text()
    doc = PoolEnv.__doc__ or ""
    for key in KEYS:
        assert f"``{key}``" in doc, f"PoolEnv's docstring does not name {key}"
        assert f"`{key}`" in spec, f"the specification page does not name {key}"


def test_no_config_field_is_copied_onto_a_front() -> None:
    env = PoolEnv()
    config_fields = {f.name for f in fields(GameConfig)}
    assert not config_fields & set(vars(env)), "a config field copied onto PoolEnv"
    vector = PoolVectorEnv(2)
    assert not config_fields & set(vars(vector)), "a config field copied onto PoolVectorEnv"


def test_overrides_reach_their_sections_and_bad_keys_are_refused() -> None:
    config = default_config(scene="one_ball", noise=(0.01, 0.1), game="nine", end_on_foul=True)
    assert config.task.scene == "one_ball" and config.noise.sigmas == (0.01, 0.1)
    assert config.rules.game == "nine" and config.rules.end_on_foul
    assert default_config(task={"aim": "absolute"}).task.aim == "absolute"
    assert make_config(config, scene="nine_ball").source.rules == config.rules  # kept
    with pytest.raises(ValueError, match="unknown config key 'scenery'"):
        PoolEnv(scenery="one_ball")
    with pytest.raises(ValueError, match="end_on_foul is a rule of game 'nine' or 'eight'"):
        PoolEnv(end_on_foul=True)
    with pytest.raises(ValueError, match="unknown task keys"):
        default_config(task={"game": "nine"})
    with pytest.raises(ValueError, match=r"config must be a pool_env\.PoolConfig"):
        PoolEnv(config={"scene": "one_ball"})


@pytest.mark.parametrize(
    "env_id",
    # a one-visit id (end_on_foul: SnookerBreak) is one player's; the duel plays the frame's
    [i for i in GAME_IDS if i in CURRENT_IDS and not ENV_IDS[i][0].get("end_on_foul")],
)
def test_the_two_player_fronts_default_to_the_game_ids(env_id: str) -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

    kwargs, steps = ENV_IDS[env_id]
    single = gym.make(env_id).unwrapped.config
    assert single.aim == "cut" and single.speed_range == DEFAULT_SPEED_RANGE
    spin = {"model": kwargs["model"]} if "model" in kwargs else {}  # a v1 id: model="spin"
    fronts = (PoolDuelEnv(kwargs["game"], **spin), VersusPolicyEnv(game=kwargs["game"], **spin))
    for duel in (fronts[0], fronts[1].duel):
        config = duel.config
        # What a second player changes: the players, and the rack's limit, which counts both
        # players' shots (the id truncates through its TimeLimit of the same number).
        assert config.players == 2
        assert config.max_shots == config.shot_limit == duel.config.max_shots == steps
        for f in fields(GameConfig):
            if f.name not in ("players", "shot_limit", "params", "source", "task"):
                assert _same(getattr(config, f.name), getattr(single, f.name)), f.name
        for f in fields(TaskConfig):
            if f.name != "max_shots":
                assert _same(getattr(config.task, f.name), getattr(single.task, f.name)), f.name
        differ = set(np.flatnonzero(config.params != single.params).tolist())
        assert differ == {kp.PLAYERS, kp.SHOT_LIMIT}


def test_an_argument_still_overrides_the_default() -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv

    duel = PoolDuelEnv("eight", aim="absolute", speed_range=(0.5, 10.0), max_shots=7)
    assert duel.config.aim == "absolute" and duel.config.speed_range == (0.5, 10.0)
    assert duel.config.aim_range == (-np.pi, np.pi) and duel.config.max_shots == 7
    with pytest.raises(ValueError, match="game must be"):
        PoolDuelEnv("bagatelle")


# -- one default table (issue 48) -------------------------------------------------------------

#: The configurable id: what ``gym.make("pool_env/Pool-v1")`` plays is the default table.
DEFAULT_ID = spin_id("Pool")


def _duel(**kwargs: Any) -> GameConfig:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv

    return PoolDuelEnv(**kwargs).config


def _versus(**kwargs: Any) -> GameConfig:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import VersusPolicyEnv

    return VersusPolicyEnv(**kwargs).config


#: Every front, built with no table and no model: its parsed config.
NO_TABLE_FRONTS = {
    "PoolEnv()": lambda: PoolEnv().config,
    "PoolEnv(config=default_config())": lambda: PoolEnv(config=default_config()).config,
    "PoolVectorEnv(2)": lambda: PoolVectorEnv(2).config,
    "make_config()": lambda: make_config(),
    "make_config(default_config())": lambda: make_config(default_config()),
    "PoolDuelEnv()": lambda: _duel(),
    "PoolDuelEnv('ten')": lambda: _duel(game="ten"),
    "VersusPolicyEnv()": lambda: _versus(),
    "VersusPolicyEnv(game='eight')": lambda: _versus(game="eight"),
}


def _default_table() -> Table:
    return gym.make(DEFAULT_ID).unwrapped.config.table


@pytest.mark.parametrize("front", list(NO_TABLE_FRONTS))
def test_every_front_plays_the_table_of_the_v1_ids(front: str) -> None:
    """``PoolEnv()`` is ``pool_env/Pool-v1``'s table: the spin table, as every front's."""
    table = NO_TABLE_FRONTS[front]().table
    assert table.model == "spin" and table.has_spin
    assert _same(table, _default_table())


def test_every_v1_id_plays_the_default_table_and_every_roll_id_the_roll_table() -> None:
    default = _default_table()
    assert default.model == DEFAULT_MODEL == "spin"
    for task, (kwargs, _) in TASKS.items():
        # A task on a table of its own (snooker's, three-cushion's carom) plays it.
        own = kwargs.get("table")
        table = default if own is None else Table(**own, model=DEFAULT_MODEL)
        assert _same(gym.make(spin_id(task)).unwrapped.config.table, table), task
        if task in SPIN_ONLY:
            assert roll_id(task) not in gym.registry, task
            continue
        roll = gym.make(roll_id(task)).unwrapped.config.table
        # A game's own table on the roll level keeps what that level reads.
        shared = None if own is None else {k: v for k, v in own.items() if k not in SPIN_PARAMS}
        expected = Table(model="roll") if shared is None else Table(**shared, model="roll")
        assert roll.model == "roll" and _same(roll, expected), task


@pytest.mark.parametrize("front", list(NO_TABLE_FRONTS))
def test_every_front_reads_the_one_default(front: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """One constant, read by make_config: a front that copied the default would not follow.

    The ids register their model, so they keep their tables whatever the default is.
    """
    monkeypatch.setattr(config_module, "DEFAULT_MODEL", "roll")
    assert NO_TABLE_FRONTS[front]().table.model == "roll"
    assert _default_table().model == "spin"
    assert gym.make(roll_id("Pool")).unwrapped.config.table.model == "roll"


def test_a_table_given_keeps_its_model_and_a_dict_without_one_gets_the_default() -> None:
    assert PoolEnv(model="roll").config.table.model == "roll"
    assert PoolEnv(table=Table(model="roll")).config.table.model == "roll"  # the table's own
    circles = PoolEnv(table={"pockets": "circles"}).config.table  # no model named: the default
    assert circles.model == DEFAULT_MODEL and circles.pocket_model == "circles"
    assert PoolEnv(table={"pockets": "circles", "model": "roll"}).config.table.model == "roll"
    duel = _duel(model="roll")
    assert duel.table.model == "roll" and duel.action_size == 6  # 9-ball's, no tip columns
    with pytest.raises(
        ValueError, match=r"model='spin' but the table given is Table\(model='roll'\)"
    ):
        gym.make(DEFAULT_ID, table=Table(model="roll"))
