"""One precedence rule on every front: the caller's keywords over its config over the id's.

``pool_env.game.sections.resolve``: an explicit ``config=`` is played as it is (the id's
registered defaults apply only without one), and a keyword the caller passes beside it
overrides it. Checked on random configs through every front: ``gym.make`` on the ids,
``gym.make_vec`` (the native vector env), ``PoolEnv``, ``PoolVectorEnv``, and the
two-player fronts (``PoolDuelEnv``, the PettingZoo AEC env, and ``VersusPolicyEnv``).
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from pool_env import PoolConfig, PoolEnv, PoolVectorEnv, Table, default_config
from pool_env.envs.registration import ENV_IDS, GAME_IDS
from tests.profiles import examples

RACKS = {"nine": "nine_ball", "ten": "ten_ball", "eight": "eight_ball"}
OBJECT_BALLS = {"nine": 9, "ten": 10, "eight": 15}
#: Action columns before a spin table's two tip columns.
WIDTHS = {"solitaire": 2, "nine": 6, "ten": 7, "eight": 5}
SETTINGS = settings(
    max_examples=examples(20), deadline=None, suppress_health_check=[HealthCheck.too_slow]
)  # fmt: skip


@st.composite
def configs(draw: st.DrawFn, games: tuple[str, ...] = ("solitaire", *RACKS)) -> PoolConfig:
    """A random config: game, model, scene, ranges, noise and the game's own options."""
    game = draw(st.sampled_from(games))
    model = draw(st.sampled_from(["roll", "spin"]))
    low = draw(st.sampled_from([0.3, 0.45, 1.0]))
    keys: dict[str, Any] = {
        "game": game,
        "model": model,
        "aim": draw(st.sampled_from(["cut", "relative", "absolute"])),
        "speed_range": (low, low + draw(st.sampled_from([1.0, 4.0]))),
        "noise": draw(st.sampled_from([None, (0.01, 0.1), "fastfiz", ("fastfiz", 2.0)])),
        "max_shots": draw(st.sampled_from([None, 7, 30])),
        "reward_pot": draw(st.sampled_from([1.0, 2.5])),
    }
    if game == "solitaire":
        keys["scene"] = draw(st.sampled_from(["one_ball", "random", "nine_ball"]))
        keys["end_on_miss"] = draw(st.booleans())
    else:
        keys["scene"] = RACKS[game]
        keys["break_speed_range"] = draw(st.sampled_from([(8.0, 12.0), (5.0, 9.0)]))
    return default_config(**keys)


def _played(config: PoolConfig, source: PoolConfig) -> None:
    """The env plays ``source``: its config's sections, and what they decide."""
    assert config.source == source
    assert config.game == source.rules.game
    assert config.table.model == source.table.model
    assert config.end_on_miss == source.task.end_on_miss
    assert config.speed_range == source.task.speed_range
    assert config.max_shots == source.task.max_shots
    assert config.task.scene.spec == source.task.scene
    assert config.rewards["pot"] == source.rewards.scales["pot"]
    spin = 2 if source.table.model == "spin" else 0
    assert config.action_size == WIDTHS[source.rules.game] + spin


@SETTINGS
@given(config=configs(), env_id=st.sampled_from(sorted(ENV_IDS)))
def test_gym_make_plays_the_config_given_whatever_the_id(config: PoolConfig, env_id: str) -> None:
    env = gym.make(env_id, config=config)
    _played(env.unwrapped.config, config)
    assert env.action_space.shape == (env.unwrapped.config.action_size,)
    assert env.spec.max_episode_steps == ENV_IDS[env_id][1]  # the id keeps its TimeLimit


@SETTINGS
@given(config=configs(), env_id=st.sampled_from(sorted(ENV_IDS)))
def test_gym_make_vec_plays_the_config_given_whatever_the_id(
    config: PoolConfig, env_id: str
) -> None:
    envs = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point", config=config)
    _played(envs.unwrapped.config, config)
    assert envs.single_action_space.shape == (envs.unwrapped.config.action_size,)


@SETTINGS
@given(config=configs())
def test_the_classes_play_the_config_given(config: PoolConfig) -> None:
    _played(PoolEnv(config=config).config, config)
    _played(PoolVectorEnv(2, config=config).config, config)


@SETTINGS
@given(config=configs(games=tuple(RACKS)), end_on_foul=st.booleans())
def test_the_two_player_fronts_play_the_config_given(config: PoolConfig, end_on_foul: bool) -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv, VersusPolicyEnv

    config = config.override(end_on_foul=end_on_foul)
    if end_on_foul:  # one agent's run-out mode: refused with two players, on both fronts
        for front in (PoolDuelEnv, VersusPolicyEnv):
            with pytest.raises(ValueError, match="end_on_foul=True is the one-agent run-out"):
                front(config=config)
        return
    for duel in (PoolDuelEnv(config=config), VersusPolicyEnv(config=config).duel):
        _played(duel.config, config)
        assert duel.config.players == 2


@SETTINGS
@given(
    config=configs(games=("solitaire",)),
    env_id=st.sampled_from([i for i in ENV_IDS if i not in GAME_IDS]),
    key=st.sampled_from(["end_on_miss", "aim", "noise", "model"]),
)
def test_a_keyword_beside_a_config_overrides_it_on_every_front(
    config: PoolConfig, env_id: str, key: str
) -> None:
    """The caller's keyword wins over the caller's config, the rest of the config stays."""
    value = {
        "end_on_miss": not config.task.end_on_miss,
        "aim": "absolute" if config.task.aim != "absolute" else "cut",
        "noise": (0.02, 0.2),
        "model": "spin" if config.table.model != "spin" else "roll",
    }[key]
    expected = config.override(**{key: value})
    _played(gym.make(env_id, config=config, **{key: value}).unwrapped.config, expected)
    vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point",
                       config=config, **{key: value})  # fmt: skip
    _played(vec.unwrapped.config, expected)
    _played(PoolEnv(config=config, **{key: value}).config, expected)


@pytest.mark.parametrize("env_id", sorted(ENV_IDS))
def test_without_a_config_the_id_defaults_apply_under_the_callers_keywords(env_id: str) -> None:
    registered, _ = ENV_IDS[env_id]
    assert gym.make(env_id).unwrapped.config.source == default_config(**registered)
    played = gym.make(env_id, aim="absolute").unwrapped.config.source
    assert played == default_config(**registered).override(aim="absolute")
    vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point")
    assert vec.unwrapped.config.source == default_config(**registered)


# -- behaviour: what the findings saw played ---------------------------------------------

#: A slow full hit that pots nothing: the object ball stops ~1 m on, far from any pocket.
_NO_POT = np.array([[0.5, 0.635], [0.8, 0.635]])


def _misses_end_the_episode(env: Any, vector: bool) -> bool:
    options = {"positions": _NO_POT}
    env.reset(seed=0, options=options)
    width = (env.single_action_space if vector else env.action_space).shape[0]
    action = np.zeros(width, dtype=np.float32)
    action[1] = -1.0  # the slowest speed of the range
    if vector:
        _, _, terminated, _, info = env.step(action[None])
        assert tuple(info["potted"][0]) == ()
        return bool(terminated[0])
    _, _, terminated, _, info = env.step(action)
    assert info["potted"] == ()
    return bool(terminated)


@pytest.mark.parametrize("end_on_miss", [False, True])
def test_the_one_ball_id_plays_the_configs_end_on_miss_and_model(end_on_miss: bool) -> None:
    """The finding: end_on_miss=False, model="roll" in a config played as the id's True, spin."""
    config = default_config(scene="one_ball", end_on_miss=end_on_miss, model="roll")
    env = gym.make("pool_env/OneBall-v1", config=config)
    assert env.action_space.shape == (2,)  # the roll table: no tip columns
    assert _misses_end_the_episode(env, vector=False) is end_on_miss
    vec = gym.make_vec("pool_env/OneBall-v1", num_envs=1, config=config)
    assert vec.single_action_space.shape == (2,)
    assert _misses_end_the_episode(vec, vector=True) is end_on_miss


def test_an_eight_ball_config_plays_eight_ball_under_a_nine_ball_id() -> None:
    config = default_config(scene="eight_ball", game="eight", model="roll")
    for env in (
        gym.make("pool_env/NineBallGameRoll-v1", config=config).unwrapped,
        gym.make_vec("pool_env/NineBallGameRoll-v1", num_envs=2, config=config).unwrapped,
    ):
        env.reset(seed=3)
        assert env.positions.shape[-2] == 1 + OBJECT_BALLS["eight"]  # 15 balls racked
        assert env.config.action_size == WIDTHS["eight"]


def test_a_ten_ball_config_plays_ten_ball_in_a_duel() -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    from pool_env.envs.multiagent import PoolDuelEnv

    duel = PoolDuelEnv(config=default_config(scene="ten_ball", game="ten", model="roll"))
    duel.reset(seed=1)
    assert duel.positions.shape == (1 + OBJECT_BALLS["ten"], 2)
    assert duel.action_space("player_0").shape == (WIDTHS["ten"],)


def test_a_roll_table_in_a_config_plays_under_a_spin_id() -> None:
    """The finding: refused with a message about model='spin', which the caller never wrote."""
    config = default_config(scene="one_ball", table=Table(model="roll"))
    env = gym.make("pool_env/OneBall-v1", config=config)
    assert env.unwrapped.config.table.model == "roll" and env.action_space.shape == (2,)
