"""Defaults in one place: every front plays by the game ids' defaults unless told otherwise.

The ids' defaults are their registered arguments (``pool_env.registration.ENV_IDS``) over
:func:`pool_env.game.config.make_config`'s. ``PoolVectorEnv`` passes its arguments through
to ``make_config``; ``PoolEnv`` spells them out in its signature, which must agree; the
two-player fronts of :mod:`pool_env.multiagent` take the game id's (issue 21 item 6: they
had drifted to absolute aim and 0.5-10 m/s where every id uses cut aim and 0.45-4.5 m/s).
"""

from __future__ import annotations

import inspect
from dataclasses import fields, is_dataclass
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from pool_env import PoolEnv
from pool_env.game.config import DEFAULT_SPEED_RANGE, GameConfig, make_config
from pool_env.game.kernels import params as kp
from pool_env.registration import ENV_IDS, GAME_IDS


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


def test_poolenv_signature_defaults_are_make_configs() -> None:
    env = inspect.signature(PoolEnv).parameters
    config = inspect.signature(make_config).parameters
    shared = set(env) & set(config)
    assert len(shared) >= 15  # every decision-process argument
    for name in shared:
        assert env[name].default == config[name].default, name


@pytest.mark.parametrize("env_id", GAME_IDS)
def test_the_two_player_fronts_default_to_the_game_ids(env_id: str) -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.multiagent import PoolDuelEnv, VersusPolicyEnv

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
        assert config.max_shots == config.shot_limit == duel.max_shots == steps
        for f in fields(GameConfig):
            if f.name not in ("players", "max_shots", "shot_limit", "params"):
                assert _same(getattr(config, f.name), getattr(single, f.name)), f.name
        differ = set(np.flatnonzero(config.params != single.params).tolist())
        assert differ == {kp.PLAYERS, kp.SHOT_LIMIT}


def test_an_argument_still_overrides_the_default() -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.multiagent import PoolDuelEnv

    duel = PoolDuelEnv("eight", aim="absolute", speed_range=(0.5, 10.0), max_shots=7)
    assert duel.config.aim == "absolute" and duel.speed_range == (0.5, 10.0)
    assert duel.config.aim_range == (-np.pi, np.pi) and duel.max_shots == 7
    with pytest.raises(ValueError, match="game must be"):
        PoolDuelEnv("snooker")
