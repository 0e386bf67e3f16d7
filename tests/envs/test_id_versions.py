"""Ids tell the truth: an id whose spaces change takes a new version, an old one plays as before.

``data/id_spaces.json`` is the record of every registered id's action and observation spaces
and time limit. A change of any of them under the same id fails here: register the changed
task under its next version (``pool_env.envs.registration.VERSIONS``), keep the old version
playing as it did (``EARLIER_VERSIONS``) and add the new id to the record
(``python -m tests.envs.test_id_versions --add``, which never rewrites a recorded id).
The two-player duel is recorded under its PettingZoo name, whose suffix is its version
(``pool_duel_v1``: with the push-out; ``pool_duel_v2``: on the spin table by default, whose
``model="roll"`` plays v1's spaces).

``data/nine_v1_trace.npz`` is 9-ball as ``pool_env/NineBallGame-v1`` and its roll twin played
before the push-out (commit ``097e0ad``; ``data/nine_v1_trace.py`` says how it was made):
the ``-v1`` ids still play it, bit for bit.
"""

from __future__ import annotations

import importlib.util
import json
import sys
import warnings
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from pool_env.envs.registration import CURRENT_IDS, EARLIER_VERSIONS, ENV_IDS, LEGACY_IDS, spin_id

DATA = Path(__file__).parent / "data"
RECORD = DATA / "id_spaces.json"
EVERY_ID = [*ENV_IDS, *LEGACY_IDS]
#: The duel's games: its PettingZoo name (``metadata["name"]``, which carries the version)
#: with each game is recorded too.
DUEL_GAMES = ("nine", "ten", "eight", "snooker")
#: The duel's games of its v1 (the roll table, before the spin table came).
V1_DUEL_GAMES = ("nine", "ten", "eight")


def _box(space: gym.spaces.Box) -> dict[str, Any]:
    """A Box as data: shape, dtype and its bounds (one value where every entry shares it)."""

    def bound(values: np.ndarray) -> Any:
        flat = values.ravel().tolist()
        return flat[0] if len(set(flat)) == 1 else flat

    return {
        "shape": list(space.shape),
        "dtype": str(space.dtype),
        "low": bound(space.low),
        "high": bound(space.high),
    }


def spaces_of(env_id: str) -> dict[str, Any]:
    """What the record keeps of ``env_id``: its spaces and its time limit."""
    with warnings.catch_warnings():  # an earlier version is out of date: checked below
        warnings.simplefilter("ignore", DeprecationWarning)
        env = gym.make(env_id)
    try:
        return {
            "action": _box(env.action_space),
            "observation": _box(env.observation_space),
            "max_episode_steps": env.spec.max_episode_steps,
        }
    finally:
        env.close()


def duel_spaces_of(game: str, **kwargs: Any) -> tuple[str, dict[str, Any]]:
    """The duel's record key (its versioned name and the game) and its spaces."""
    from pool_env.envs.multiagent import PoolDuelEnv

    duel = PoolDuelEnv(game, **kwargs)
    agent = duel.possible_agents[0]
    key = f"{duel.metadata['name']}/{game}"
    return key, {
        "action": _box(duel.action_space(agent)),
        "observation": _box(duel.observation_space(agent)),
    }


def _record() -> dict[str, Any]:
    return json.loads(RECORD.read_text())


@pytest.mark.parametrize("env_id", EVERY_ID)
def test_an_ids_spaces_are_the_recorded_ones(env_id: str) -> None:
    record = _record()
    assert env_id in record, (
        f"{env_id} is not in {RECORD.name}: add it (python -m tests.envs.test_id_versions --add)"
    )
    assert spaces_of(env_id) == record[env_id], (
        f"the spaces of {env_id} changed: register the task under its next version "
        "(pool_env.envs.registration.VERSIONS) and keep this one as it was"
    )


@pytest.mark.parametrize("game", DUEL_GAMES)
def test_the_duels_spaces_are_the_recorded_ones_under_its_name(game: str) -> None:
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    key, spaces = duel_spaces_of(game)
    assert key in _record(), f"{key} is not recorded: a new name (version) of the duel?"
    assert spaces == _record()[key], (
        f"the duel's spaces changed under {key}: bump the version in its metadata name"
    )


@pytest.mark.parametrize("game", V1_DUEL_GAMES)
def test_the_duels_earlier_version_is_its_roll_table(game: str) -> None:
    """v2 made the spin table the default: v1's spaces are the roll table's, still played."""
    pytest.importorskip("pettingzoo", reason="needs the multiagent extra")
    key, spaces = duel_spaces_of(game, model="roll")
    assert key == f"pool_duel_v2/{game}" and spaces == _record()[f"pool_duel_v1/{game}"]
    assert spaces["action"]["shape"][0] + 2 == _record()[key]["action"]["shape"][0]  # the tip


def test_the_record_holds_no_id_that_is_gone() -> None:
    duels = {k for k in _record() if k.startswith("pool_duel_")}
    assert set(_record()) - duels == set(EVERY_ID)


@pytest.mark.parametrize(("task", "version"), list(EARLIER_VERSIONS))
def test_an_earlier_version_is_reported_out_of_date(task: str, version: int) -> None:
    with pytest.warns(DeprecationWarning, match="out of date"):
        gym.make(spin_id(task, version)).close()
    assert spin_id(task) in CURRENT_IDS and spin_id(task) != spin_id(task, version)


def test_nine_ball_v2_has_the_push_out_and_v1_has_not() -> None:
    v1, v2 = _record()["pool_env/NineBallGame-v1"], _record()["pool_env/NineBallGame-v2"]
    assert v2["action"]["shape"][0] == v1["action"]["shape"][0] + 1  # the option column
    assert v2["observation"]["shape"][0] == v1["observation"]["shape"][0] + 2  # its features
    env = gym.make("pool_env/NineBallGame-v2").unwrapped
    assert env.config.rules.push_out is True
    env.reset(seed=0)
    assert "push_out" in env.config.ruleset.info_keys


def _trace_module() -> Any:
    spec = importlib.util.spec_from_file_location("nine_v1_trace", DATA / "nine_v1_trace.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_nine_ball_v1_plays_as_before_the_push_out_bit_for_bit() -> None:
    recorded = np.load(DATA / "nine_v1_trace.npz")
    played = _trace_module().trace()
    assert set(played) == set(recorded.files)
    for key in recorded.files:
        np.testing.assert_array_equal(played[key], recorded[key], err_msg=key)
    # The trace can tell: it has pots, endings, and rewards of each sign.
    rewards = np.concatenate([recorded[k] for k in recorded.files if k.endswith("rewards")])
    assert (rewards > 0).any() and (rewards < 0).any()
    assert np.concatenate([recorded[k] for k in recorded.files if k.endswith("endings")]).any()


def _add_new_ids() -> list[str]:
    """Record the spaces of every id not recorded yet (a recorded one is never rewritten)."""
    record = _record() if RECORD.exists() else {}
    added = [env_id for env_id in EVERY_ID if env_id not in record]
    for env_id in added:
        record[env_id] = spaces_of(env_id)
    for game in DUEL_GAMES:
        key, spaces = duel_spaces_of(game)
        if key not in record:
            record[key] = spaces
            added.append(key)
    RECORD.write_text(json.dumps(record, indent=1, sort_keys=True) + "\n")
    return added


if __name__ == "__main__":
    if sys.argv[1:] != ["--add"]:
        raise SystemExit("usage: python -m tests.envs.test_id_versions --add")
    print("added:", ", ".join(_add_new_ids()) or "none")
