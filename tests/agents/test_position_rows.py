"""Position rows: the spin ghost-ball agent's strikes as rows, and a preference that picks one.

The decoding must play exactly the chosen row's env action, the row with the largest
``score + PICK_SCALE * (w . f)`` among the valid ones and never an invalid one; a zero
preference must play the ghost agent's own strike; each row's action must be the one the
ghost agent computes for that ball, pocket, tip and speed; the observation must lie in
its space; the vector wrapper must see and play what the gym wrapper does.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from agents.baselines.base import decode_observation
from agents.baselines.ghost_ball import PositionOption, best_option
from agents.learned.position_rows import (
    ACTION,
    PER_ROW,
    PICK_SCALE,
    PREFERENCE_COLUMNS,
    SCORE,
    VALID,
    PositionCandidates,
    decode_position,
)

POOL = "pool_env/Pool-v1"
KWARGS = {"n_balls": 3, "end_on_miss": True, "noise": [0.003, 0.05, 0.05]}
W = len(PREFERENCE_COLUMNS)


def _obs(valid: list[bool], scores: list[float], features: np.ndarray) -> np.ndarray:
    """One observation of rows only: valid flags, scores, features, actions ``k / 10``."""
    n = len(valid)
    rows = np.zeros((n, PER_ROW))
    rows[:, VALID] = valid
    rows[:, SCORE] = scores
    rows[:, list(PREFERENCE_COLUMNS)] = features
    rows[:, ACTION : ACTION + 4] = (np.arange(n) / 10.0)[:, None]
    return np.concatenate([np.full(5, 0.3), rows.ravel()])[None]


def test_a_zero_preference_plays_the_best_score_and_the_first_of_a_tie() -> None:
    feats = np.zeros((4, W))
    obs = _obs([True, True, True, False], [0.5, 0.5, 0.2, 0.9], feats)
    actions, pick = decode_position(obs, np.zeros((1, W)), 4)
    assert pick[0] == 0  # row 3 scores more but is invalid; rows 0 and 1 tie
    np.testing.assert_array_equal(actions[0], np.zeros(4, np.float32))


def test_the_row_played_is_the_argmax_of_score_plus_the_scaled_preference() -> None:
    rng = np.random.default_rng(3)
    for _ in range(200):
        valid = list(rng.random(6) < 0.6)
        valid[int(rng.integers(6))] = True
        scores = rng.random(6)
        feats = rng.uniform(-1, 1, (6, W))
        w = rng.uniform(-1.5, 1.5, (1, W))  # beyond the box: decoding clips it
        obs = _obs(valid, list(scores), feats)
        actions, pick = decode_position(obs, w, 6)
        utility = scores + PICK_SCALE * feats @ np.clip(w[0], -1, 1)
        expected = int(np.argmax(np.where(valid, utility, -np.inf)))
        assert pick[0] == expected and valid[pick[0]]
        np.testing.assert_allclose(actions[0], np.full(4, expected / 10.0), rtol=1e-6)


def test_the_preference_overrides_a_score_gap_it_outweighs() -> None:
    feats = np.zeros((2, W))
    feats[1, 0] = 1.0  # row 1 is better on the first preference column
    obs = _obs([True, True], [0.52, 0.50], feats)
    w = np.zeros((1, W))
    assert decode_position(obs, w, 2)[1][0] == 0
    w[0, 0] = 0.3  # 0.1 x 0.3 = 0.03 > the 0.02 gap
    assert decode_position(obs, w, 2)[1][0] == 1


def test_bad_shapes_and_rowless_observations_are_refused() -> None:
    obs = _obs([True], [0.5], np.zeros((1, W)))
    with pytest.raises(ValueError, match=rf"\(B, {W}\) actions"):
        decode_position(obs, np.zeros((1, W + 1)), 1)
    with pytest.raises(ValueError, match="hold no 40 position rows"):
        decode_position(obs, np.zeros((1, W)), 40)
    with pytest.raises(ValueError, match="without a valid position row"):
        decode_position(_obs([False], [0.5], np.zeros((1, W))), np.zeros((1, W)), 1)


def test_a_roll_env_is_refused() -> None:
    with pytest.raises(ValueError, match="spin env"):
        PositionCandidates(gym.make("pool_env/OneBallRoll-v1"))


def test_rows_are_the_ghost_agents_strikes_and_a_zero_preference_plays_its_choice() -> None:
    env = PositionCandidates(gym.make(POOL, **KWARGS))
    features = env.position_rows
    ghost = features.ghost
    n_raw = env.unwrapped.observation_space.shape[0]
    seen_rows = 0
    for seed in range(10000, 10006):
        obs, _ = env.reset(seed=seed)
        assert env.observation_space.contains(obs)
        positions, on_table = decode_observation(obs[:n_raw], ghost.spec.table)
        rows = obs[n_raw:].reshape(features.n_rows, PER_ROW)
        options, _, _ = ghost.position_options(positions, on_table)
        for row in rows[rows[:, VALID] > 0.5]:
            if row[1] < 0:  # the ghost agent's own play when it has no option
                continue
            # the row's action is one of the ghost agent's strikes, with its score
            hits = [
                o
                for o in options
                if np.array_equal(o.action, row[ACTION : ACTION + 4].astype(np.float32))
            ]
            assert hits and np.isclose(hits[0].score, row[SCORE], atol=1e-6)
            seen_rows += 1
        played, pick = decode_position(obs[None], np.zeros((1, W)), features.n_rows)
        np.testing.assert_array_equal(played[0], ghost.plan(positions, on_table))
        assert pick[0] == 0
        scores = rows[rows[:, VALID] > 0.5, SCORE]
        assert np.all(np.diff(scores) <= 0.0)  # best ghost score first
    assert seen_rows > 20


def test_random_preferences_play_valid_rows_and_the_observations_stay_in_the_space() -> None:
    env = PositionCandidates(gym.make(POOL, n_balls=5, end_on_miss=True, noise=KWARGS["noise"]))
    rng = np.random.default_rng(1)
    obs, _ = env.reset(seed=123)
    rows_seen = set()
    for _ in range(12):
        rows = obs[-env.n_rows * PER_ROW :].reshape(env.n_rows, PER_ROW)
        action = rng.uniform(-1, 1, W).astype(np.float32)
        obs, _, terminated, truncated, info = env.step(action)
        assert rows[info["position_row"], VALID] > 0.5
        np.testing.assert_array_equal(
            info["env_action"], rows[info["position_row"], ACTION : ACTION + 4]
        )
        rows_seen.add(info["position_row"])
        assert env.observation_space.contains(obs)
        if terminated or truncated:
            obs, _ = env.reset(seed=int(rng.integers(1 << 30)))
    assert len(rows_seen) > 1  # the preference does move the choice


def test_best_option_takes_the_first_best_score_else_the_most_forgiving_scratch() -> None:
    def option(score: float | None, tolerance: float) -> PositionOption:
        shot = type("Shot", (), {"tolerance": tolerance})()
        return PositionOption(shot, None, 0.3, np.zeros(4, np.float32), score)  # type: ignore[arg-type]

    a, b, c = option(0.4, 0.01), option(0.4, 0.02), option(None, 0.05)
    assert best_option([c, a, b]) is a
    d, e = option(None, 0.01), option(None, 0.03)
    assert best_option([d, e, option(None, 0.03)]) is e
    assert best_option([]) is None


def test_step_before_reset_is_an_error() -> None:
    env = PositionCandidates(gym.make(POOL, **KWARGS))
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(W, np.float32))


def test_the_vector_wrapper_sees_and_plays_as_the_gym_wrapper() -> None:
    pytest.importorskip("stable_baselines3")
    from stable_baselines3.common.env_util import make_vec_env

    from agents.training.vec_features import PositionCandidatesVecEnv
    from agents.vec.native_vec import make_native_vec_env

    n = 2
    vec = PositionCandidatesVecEnv(make_native_vec_env(POOL, n, 7, KWARGS))
    ref = make_vec_env(lambda: PositionCandidates(gym.make(POOL, **KWARGS)), n_envs=n, seed=7)
    rng = np.random.default_rng(0)
    try:
        first = vec.reset()
        np.testing.assert_array_equal(first, ref.reset())
        first[:] = 0.0  # the caller scribbles on its array: the decoding must not see it
        assert vec.action_space == ref.action_space
        assert vec.observation_space == ref.observation_space
        ended = 0
        for _ in range(4):
            actions = rng.uniform(-1, 1, (n, W)).astype(np.float32)
            obs, rewards, dones, infos = vec.step(actions)
            ref_obs, ref_rewards, ref_dones, ref_infos = ref.step(actions)
            np.testing.assert_array_equal(dones, ref_dones)
            np.testing.assert_array_equal(obs, ref_obs)
            np.testing.assert_array_equal(rewards, ref_rewards)
            for a, b in zip(infos, ref_infos, strict=True):
                if "terminal_observation" in b:
                    ended += 1
                    np.testing.assert_array_equal(
                        a["terminal_observation"], b["terminal_observation"]
                    )
        assert ended > 0
    finally:
        vec.close()
        ref.close()


def test_a_loaded_model_decodes_raw_observations_as_the_wrapper(tmp_path) -> None:
    pytest.importorskip("stable_baselines3")
    import torch
    import yaml
    from stable_baselines3 import PPO

    import agents

    wrapped = PositionCandidates(gym.make(POOL, **KWARGS))
    model = PPO("MlpPolicy", wrapped, n_steps=8, batch_size=8, seed=0, device="cpu")
    with torch.no_grad():  # a policy whose mean is not zero: not the ghost agent's choice
        model.policy.action_net.bias.fill_(0.7)
    model.save(tmp_path / "ppo_position.zip")
    config = {"env_id": POOL, "env_kwargs": KWARGS, "wrapper": "position_candidates"}
    (tmp_path / "ppo_position_config.yaml").write_text(yaml.safe_dump({**config, "algo": "ppo"}))
    policy = agents.load(tmp_path / "ppo_position.zip")
    env = policy.make_env()
    raw = np.stack([env.reset(seed=s)[0] for s in range(3)])
    obs = np.stack([wrapped.reset(seed=s)[0] for s in range(3)])
    preference, _ = model.predict(obs, deterministic=True)
    expected, _ = decode_position(obs, preference, wrapped.n_rows)
    got, _ = policy.predict(raw)
    np.testing.assert_array_equal(got, expected)
    assert got.shape == (3, 4)
    wrapped.reset(seed=2)
    np.testing.assert_array_equal(wrapped.step(preference[2])[4]["env_action"], expected[2])


def test_without_noise_the_replays_say_what_the_env_does_with_the_row() -> None:
    """Noiseless replays all agree: a row pots (SIM_POT +1) exactly when the env pots it."""
    from agents.learned.position_rows import SIM_NEXT, SIM_POT, SIM_SCRATCH

    env = PositionCandidates(gym.make(POOL, n_balls=3, end_on_miss=True))
    checked = 0
    for seed in range(20000, 20004):
        obs, _ = env.reset(seed=seed)
        rows = obs[-env.n_rows * PER_ROW :].reshape(env.n_rows, PER_ROW)
        for k in np.flatnonzero(rows[:, VALID] > 0.5):
            if rows[k, 1] < 0:
                continue
            assert rows[k, SIM_POT] in (-1.0, 1.0) and rows[k, SIM_SCRATCH] in (-1.0, 1.0)
            assert (rows[k, SIM_NEXT] > -1.0) <= (rows[k, SIM_POT] == 1.0)
            env.reset(seed=seed)
            played = env.env.step(rows[k, ACTION : ACTION + 4])[4]
            target_potted = len(played["potted"]) > 0 and not played["scratch"]
            assert target_potted == (rows[k, SIM_POT] == 1.0), (seed, k)
            checked += 1
    assert checked > 5


def test_the_committed_model_loads_behind_its_wrapper() -> None:
    """models/ppo_position.zip: its config applies the wrapper; raw observations decode."""
    pytest.importorskip("stable_baselines3")
    from pathlib import Path

    import agents
    from agents.evaluation.evaluate import load_model

    path = Path(__file__).resolve().parents[2] / "models" / "ppo_position.zip"
    policy = agents.load(path)
    assert (policy.env_id, policy.wrapper) == (POOL, "position_candidates")
    assert policy.env_kwargs == KWARGS
    env, wrapped = policy.make_env(), PositionCandidates(policy.make_env())
    raw = np.stack([env.reset(seed=s)[0] for s in range(60000, 60003)])
    obs = np.stack([wrapped.reset(seed=s)[0] for s in range(60000, 60003)])
    preference, _ = load_model(path).predict(obs, deterministic=True)
    expected, _ = decode_position(obs, preference, wrapped.n_rows)
    got, _ = policy.predict(raw)
    np.testing.assert_array_equal(got, expected)
