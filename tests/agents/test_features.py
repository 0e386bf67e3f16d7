"""The ghost-ball features: the shots of the baselines' geometry exactly, in every form seen.

The batched computation (:func:`agents.learned.features.ghost_feature_batch`) is checked against the
per-shot reference built from :func:`agents.baselines.geometry.ghost_shots`, :func:`cue_speed` and
:func:`shot_to_action` on random layouts of both pocket models and every aim mode; the
ghost-ball agent's own action must be one of the feature rows; and the native vector env's
wrapper must give the training envs what the evaluation wrapper gives.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from agents.baselines.aiming import shot_to_action
from agents.baselines.base import env_spec
from agents.baselines.geometry import cue_speed, ghost_shots
from agents.baselines.ghost_ball import ARRIVAL_SPEED, GhostBallAgent
from agents.learned.features import GhostBallFeatures, GhostShotFeatures
from agents.training.run_config import TrainConfig
from agents.training.train_lib import make_vec
from pool_env import encode_observations, nearest_object_ball
from pool_env.sim.table import standard_pockets

ONE = "pool_env/OneBallRoll-v1"
PER = GhostShotFeatures.PER_SHOT


def _reference(features: GhostShotFeatures, pos: np.ndarray, on: np.ndarray) -> np.ndarray:
    """The features written out shot by shot from the geometry module (the slow, plain way)."""
    table, spec = features.spec.table, features.spec
    diagonal = math.hypot(table.length, table.width)
    out = np.zeros((features.mouths.n, PER))
    j = nearest_object_ball(pos, on, 0)[0]
    if j < 0:
        return out.ravel().astype(np.float32)
    row = 0
    for shot in sorted(
        ghost_shots(table, features.mouths, pos, on, [j]), key=lambda s: -s.tolerance
    ):
        action = shot_to_action(shot.angle, cue_speed(table, shot, ARRIVAL_SPEED), pos, on, spec)
        if action is None:
            continue
        out[row] = (
            1.0,
            float(shot.clear),
            float(action[0]),
            math.cos(shot.cut),
            shot.cue_distance / diagonal,
            (shot.ball_distance + 2.0 * table.ball_radius) / diagonal,
            shot.approach_cos,
            float(action[1]),
        )
        row += 1
    return np.clip(out, -1.0, 1.0).ravel().astype(np.float32)


def _scatter(rng: np.random.Generator, table: pool_env.Table, n: int) -> tuple:
    r = table.ball_radius
    pos = np.stack([rng.uniform(r, table.length - r, n), rng.uniform(r, table.width - r, n)], 1)
    on = rng.random(n) < 0.7
    on[0] = True
    return pos, on


@pytest.mark.parametrize("aim", ["cut", "relative", "absolute"])
@pytest.mark.parametrize("pockets", ["jaws", "circles"])
def test_batched_features_equal_the_geometry_shot_by_shot(aim: str, pockets: str) -> None:
    kwargs: dict = {"aim": aim}
    if pockets == "circles":
        kwargs["table"] = pool_env.Table(pockets=standard_pockets(2.54, 1.27, 0.028575))
    env = gym.make("pool_env/PoolRoll-v1", n_balls=6, **kwargs)
    features = GhostShotFeatures(env_spec(env))
    rng = np.random.default_rng(7)
    layouts = [_scatter(rng, features.spec.table, 7) for _ in range(60)]
    batch = np.stack([features(pos, on) for pos, on in layouts])
    reference = np.stack([_reference(features, pos, on) for pos, on in layouts])
    rows = reference.reshape(len(layouts), -1, PER)
    # The layouts exercise what the features distinguish: blocked and open paths, no shot.
    assert 0.0 < rows[..., 1][rows[..., 0] > 0].mean() < 1.0
    assert (rows[..., 0].sum(axis=1) < features.mouths.n).any()
    np.testing.assert_allclose(batch, reference, rtol=0, atol=2e-6)
    table = features.spec.table
    pos = np.stack([p for p, _ in layouts])
    on = np.stack([o for _, o in layouts])
    together = features.of_observations(encode_observations(pos, on, table.length, table.width))
    np.testing.assert_allclose(together, reference, rtol=0, atol=2e-4)  # float32 layouts


def test_ghost_ball_agent_plays_a_feature_row() -> None:
    """In the default cut aim, the agent's action is (aim, speed) of one of the rows."""
    env = GhostBallFeatures(gym.make(ONE))
    agent = GhostBallAgent(env)
    raw = env.env.observation_space.shape[0]
    played = 0
    for seed in range(100):
        obs, _ = env.reset(seed=seed)
        action = agent.act(obs[None, :raw])[0]
        if agent.last_plan["kind"] != "ghost":
            continue
        rows = obs[raw:].reshape(-1, PER)
        rows = rows[rows[:, 0] > 0.5]
        gap = np.abs(rows[:, [2, 7]] - action).max(axis=1).min()
        assert gap < 1e-5, (seed, rows, action)
        played += 1
    assert played >= 90


def test_native_vector_wrapper_gives_the_evaluation_features() -> None:
    config = TrainConfig(n_envs=4, vec="native", wrapper="ghost_features", seed=3)
    venv = make_vec(config)
    env = GhostBallFeatures(gym.make(ONE))
    try:
        obs = venv.reset()
        assert venv.observation_space.shape == env.observation_space.shape == obs.shape[1:]
        for i in range(4):
            expected, _ = env.reset(seed=3 + i)
            np.testing.assert_array_equal(obs[i], expected)
        _, _, dones, infos = venv.step(np.zeros((4, 2), np.float32))
        assert dones.all()  # one shot per episode: each terminal observation has features too
        env.reset(seed=3)
        after, *_ = env.step(np.zeros(2, np.float32))
        np.testing.assert_array_equal(infos[0]["terminal_observation"], after)
    finally:
        venv.close()
        env.close()


def test_native_vec_refuses_a_wrapper_it_cannot_apply() -> None:
    with pytest.raises(ValueError, match="pocket_features"):
        make_vec(TrainConfig(n_envs=2, vec="native", wrapper="pocket_features"))
