"""Candidate-shot actions: a feature row picked by score, refined by a small residual.

The decoding must play exactly the chosen row's env action (the ghost-ball shot the
features computed from the env's own aim mode and ranges), never an invalid row, and
shift it by the stated residual scales; the ``gym.Env`` wrapper, the native vector env's
wrapper and a loaded model must decode the same way.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401  (registers the ids)
from agents.learned.candidates import (
    AIM_RESIDUAL,
    SPEED_RESIDUAL,
    FirstRowAgent,
    GhostCandidates,
    decode_candidates,
)
from agents.learned.features import GhostBallFeatures, GhostShotFeatures
from agents.training.runs import process_seconds

ONE = "pool_env/OneBallRoll-v1"
PER = GhostShotFeatures.PER_SHOT


def _rows(valid: list[bool], aims: list[float], speeds: list[float]) -> np.ndarray:
    """One observation: 6 raw numbers, then feature rows with the given columns."""
    rows = np.zeros((len(valid), PER), np.float32)
    rows[:, 0] = valid
    rows[:, 2] = aims
    rows[:, 7] = speeds
    return np.concatenate([np.full(6, 0.5, np.float32), rows.ravel()])[None]


def test_the_highest_scoring_valid_row_is_played_with_its_residual() -> None:
    obs = _rows([True, True, False], [0.2, -0.4, 0.9], [-0.5, 0.1, 0.3])
    # Row 2 scores highest but is invalid: row 1 (the best valid) is played.
    act = np.array([[0.1, 0.5, 0.9, 0.0, 0.0]])
    np.testing.assert_allclose(decode_candidates(obs, act, 3), [[-0.4, 0.1]], atol=1e-7)
    act = np.array([[0.6, 0.5, 0.9, 1.0, -0.5]])
    expected = [[0.2 + AIM_RESIDUAL, -0.5 - 0.5 * SPEED_RESIDUAL]]
    np.testing.assert_allclose(decode_candidates(obs, act, 3), expected, atol=1e-6)
    # Out-of-range actions are clipped first (as SB3 clips), results to the action box.
    act = np.array([[5.0, 0.0, 0.0, 7.0, 0.0]])
    np.testing.assert_allclose(decode_candidates(obs, act, 3), [[0.2 + AIM_RESIDUAL, -0.5]])
    edge = _rows([True], [0.99], [1.0])
    np.testing.assert_allclose(decode_candidates(edge, np.ones((1, 3)), 1), [[1.0, 1.0]])


def test_no_valid_row_refines_a_full_hit_at_the_middle_speed() -> None:
    obs = _rows([False, False], [0.7, 0.7], [0.7, 0.7])
    act = np.array([[1.0, -1.0, -1.0, 1.0]])
    expected = [[-AIM_RESIDUAL, SPEED_RESIDUAL]]
    np.testing.assert_allclose(decode_candidates(obs, act, 2), expected, atol=1e-7)


def test_bad_shapes_are_refused() -> None:
    obs = _rows([True, True], [0.0, 0.0], [0.0, 0.0])
    with pytest.raises(ValueError, match="actions"):
        decode_candidates(obs, np.zeros((1, 3)), 2)
    with pytest.raises(ValueError, match="feature rows"):
        decode_candidates(obs[:, :10], np.zeros((1, 4)), 2)


def test_first_row_plays_the_ghost_ball_shot_of_row_zero_on_the_simulator() -> None:
    """Same layouts, same outcomes: the wrapper's row 0 is the features' row-0 action."""
    cand = GhostCandidates(gym.make(ONE))
    feats = GhostBallFeatures(gym.make(ONE))
    agent = FirstRowAgent(cand.n_rows)
    raw = cand.unwrapped.observation_space.shape[0]
    assert cand.n_rows == 6 and cand.action_space.shape == (8,)
    pots = 0
    for seed in range(40):
        obs, _ = cand.reset(seed=seed)
        ref_obs, _ = feats.reset(seed=seed)
        np.testing.assert_array_equal(obs, ref_obs)
        action, _ = agent.predict(obs)
        obs[:] = 0.0  # the caller's array: the wrapper decodes on its own copy
        row0 = ref_obs[raw : raw + PER]
        _, r, _, _, info = cand.step(action)
        _, r_ref, _, _, info_ref = feats.step(row0[[2, 7]] if row0[0] else np.zeros(2, np.float32))
        assert (r, info["potted"], info["scratch"]) == (r_ref, info_ref["potted"],
                                                         info_ref["scratch"])  # fmt: skip
        pots += bool(info["potted"])
    assert pots >= 34  # row 0 pots ~93% (results/agents.md); 34/40 is its 1% quantile
    cand.close()
    feats.close()


def test_step_before_reset_is_an_error() -> None:
    env = GhostCandidates(gym.make(ONE))
    with pytest.raises(RuntimeError, match="reset"):
        env.step(np.zeros(8, np.float32))


def test_the_vector_wrapper_decodes_as_the_gym_wrapper() -> None:
    pytest.importorskip("stable_baselines3")
    from stable_baselines3.common.env_util import make_vec_env

    from agents.training.vec_features import GhostCandidatesVecEnv

    n = 3
    vec = GhostCandidatesVecEnv(make_vec_env(ONE, n_envs=n, seed=7))
    ref = make_vec_env(lambda: GhostCandidates(gym.make(ONE)), n_envs=n, seed=7)
    rng = np.random.default_rng(0)
    try:
        first = vec.reset()
        np.testing.assert_array_equal(first, ref.reset())
        first[:] = 0.0  # the caller scribbles on its array: the decoding must not see it
        assert vec.action_space == ref.action_space
        for _ in range(3):
            actions = rng.uniform(-1, 1, (n, 8)).astype(np.float32)
            obs, rewards, dones, infos = vec.step(actions)
            ref_obs, ref_rewards, ref_dones, ref_infos = ref.step(actions)
            np.testing.assert_array_equal(dones, ref_dones)
            np.testing.assert_array_equal(obs, ref_obs)
            obs[:] = 0.0
            np.testing.assert_array_equal(rewards, ref_rewards)
            for a, b in zip(infos, ref_infos, strict=True):
                np.testing.assert_array_equal(a["terminal_observation"], b["terminal_observation"])
    finally:
        vec.close()
        ref.close()


def test_process_seconds_counts_from_the_process_start() -> None:
    first = process_seconds()
    assert 0.0 < first < 3600.0  # this test process started under an hour ago
    assert process_seconds() >= first
