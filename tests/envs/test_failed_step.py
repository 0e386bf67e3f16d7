"""A step that fails changes nothing: the single env and every table of the vector env.

A step places the cue ball in hand and draws the execution noise before the simulator runs,
and the simulator may refuse the shot (a ``ValueError``). The specification says a refused
step changes nothing; these tests make the simulator refuse (its entry points in
:mod:`pool_env.game.step` patched to raise), then check the whole state (positions, balls
on, rack, shot counts, each generator's state, the observation) is as before, and that the
next step plays exactly as the same step on a fresh env seeded alike.
"""

from __future__ import annotations

from typing import Any

import gymnasium as gym
import numpy as np
import pytest

from pool_env.game import step as game_step
from pool_env.game.codec import encode_placement

NOISE = (0.003, 0.05)  # the noise is drawn before the simulator runs

#: Rules ids (a break with the cue ball in hand behind the head string, then ball in hand
#: after fouls) and solitaire (no ball in hand: the noise only).
IDS = [
    "pool_env/NineBallGame-v2",
    "pool_env/EightBallGameRoll-v1",
    "pool_env/TenBallGame-v1",
    "pool_env/OneBall-v1",
]

#: Bit generators besides Gymnasium's PCG64: the other kind of the same family (saved as
#: words too), and one saved through its state dict.
BIT_GENERATORS = [None, np.random.PCG64DXSM, np.random.MT19937]


def _refuse(*args: Any, **kwargs: Any) -> None:
    raise ValueError("the simulator refuses this shot")


def _plain(value: Any) -> Any:
    """A generator's state dict with its arrays as lists (MT19937 keeps an array)."""
    if isinstance(value, dict):
        return {key: _plain(v) for key, v in value.items()}
    return value.tolist() if isinstance(value, np.ndarray) else value


def _everything(env: Any) -> dict[str, Any]:
    """The whole changing state of a (vector) env, as plain values."""
    raw = env.unwrapped
    state = raw._state
    generators = raw.np_random if isinstance(raw.np_random, tuple) else (raw.np_random,)
    return {
        "positions": state.positions.tolist(),
        "on_table": state.on_table.tolist(),
        "shots": state.shots.tolist(),
        "rack": state.rack.tolist(),
        "rng": [_plain(g.bit_generator.state) for g in generators],
        "observation": raw._observation().tolist()
        if hasattr(raw, "_observation")
        else raw._observations().tolist(),
        "done": getattr(raw, "_done", np.zeros(0)).tolist(),
    }


def _make(env_id: str, bit_generator: Any, seed: int) -> Any:
    env = gym.make(env_id, noise=NOISE)
    env.reset(seed=seed)
    if bit_generator is not None:  # a user's generator of another kind
        env.unwrapped.np_random = np.random.Generator(bit_generator(seed))
    return env


def _refused_step_changes_nothing(
    env: Any, action: np.ndarray, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Step ``env`` with the simulator refusing the shot: it raises, and nothing changed."""
    before = _everything(env)
    with monkeypatch.context() as patch:
        patch.setattr(game_step, "simulate_checked_arrays", _refuse)
        with pytest.raises(ValueError, match="refuses this shot"):
            env.step(action)
    assert _everything(env) == before


@pytest.mark.parametrize("bit_generator", BIT_GENERATORS, ids=["pcg64", "dxsm", "mt19937"])
@pytest.mark.parametrize("env_id", IDS)
def test_a_refused_step_changes_nothing_and_the_next_plays_as_on_a_fresh_env(
    env_id: str, bit_generator: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    env, fresh = _make(env_id, bit_generator, 3), _make(env_id, bit_generator, 3)
    rng = np.random.default_rng(0)
    for _ in range(4):  # a break, then shots with (or without) ball in hand
        action = rng.uniform(-1.0, 1.0, env.action_space.shape).astype(np.float32)
        _refused_step_changes_nothing(env, action, monkeypatch)
        got, want = env.step(action), fresh.step(action)
        assert np.array_equal(got[0], want[0]) and got[1:4] == want[1:4]
        assert got[4] == want[4]
        assert _everything(env) == _everything(fresh)
        if got[2] or got[3]:
            env.reset()
            fresh.reset()


def test_a_refused_placement_on_a_covered_point_is_undone(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Ball in hand asked onto the 1 (covered): the step moves the cue ball to the nearest
    # free point in Python, after the compiled placement; both are undone.
    env = gym.make("pool_env/NineBallGameRoll-v2", noise=NOISE)
    env.reset(seed=0, options={"rules": {"ball_in_hand": True}})
    raw = env.unwrapped
    action = np.zeros(env.action_space.shape)
    action[2:4] = encode_placement(raw.config, raw.positions[1])
    before = _everything(env)
    _refused_step_changes_nothing(env, action, monkeypatch)
    env.step(action)  # played now: the cue ball was placed next to the 1
    assert not np.array_equal(raw.positions[0], np.array(before["positions"][0][0]))


@pytest.mark.parametrize(
    ("env_id", "kwargs"),
    [("pool_env/NineBallGame-v2", {}), ("pool_env/PoolRoll-v1", {"end_on_miss": True})],
)
def test_a_batch_with_a_refused_table_leaves_every_table_unchanged(
    env_id: str, kwargs: dict[str, Any], monkeypatch: pytest.MonkeyPatch
) -> None:
    def make() -> Any:
        envs = gym.make_vec(env_id, num_envs=4, vectorization_mode="vector_entry_point",
                            noise=NOISE, **kwargs)  # fmt: skip
        envs.reset(seed=5)
        return envs

    envs, fresh = make(), make()
    rng = np.random.default_rng(1)
    refused = 0
    for _ in range(6):  # autoresets pending included (end_on_miss ends episodes often)
        actions = rng.uniform(-1.0, 1.0, envs.action_space.shape).astype(np.float32)
        before = _everything(envs)
        if np.all(before["done"]):  # every table resets: nothing shoots, nothing refused
            envs.step(actions), fresh.step(actions)
            continue
        with monkeypatch.context() as patch:
            patch.setattr(game_step, "run_batch_arrays", _refuse)
            patch.setattr(game_step, "simulate_checked_arrays", _refuse)
            with pytest.raises(ValueError, match="refuses this shot"):
                envs.step(actions)
        refused += 1
        assert _everything(envs) == before
        got, want = envs.step(actions), fresh.step(actions)
        for a, b in zip(got[:4], want[:4], strict=True):
            np.testing.assert_array_equal(a, b)
        assert got[4].keys() == want[4].keys()
        for key in got[4]:
            np.testing.assert_array_equal(got[4][key], want[4][key])
        assert _everything(envs) == _everything(fresh)
    assert refused >= 4
