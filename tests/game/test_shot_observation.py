"""The ``"shots"`` observation: ghost-ball geometry in the action's units, on every front.

Closed forms (a straight-in shot, the cut's sine and cosine), the physics (the aim and speed
a row offers pot its ball on the roll table), the rules (the reference ball is the ball on,
not the nearest ball), and the fronts (single env, native vector env, the two-player env)
giving the same numbers. The batched computation itself is checked against the geometry
shot by shot in ``tests/agents/test_features.py``, through the agents' wrapper that calls it.
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import pool_env  # noqa: F401  (registers the ids)
from agents.baselines.geometry import ghost_shots
from pool_env import obs_layout
from pool_env.envs.multiagent import PoolDuelEnv
from pool_env.game.shot_features import SHOT_FEATURES, table_mouths

PER = len(SHOT_FEATURES)
COLUMN = {name: k for k, name in enumerate(SHOT_FEATURES)}


def rows(env: gym.Env, obs: np.ndarray) -> np.ndarray:
    """The observation's shot rows, ``(pockets, len(SHOT_FEATURES))``."""
    return obs[obs_layout(env.unwrapped.config)["shots"]].reshape(-1, PER)


def test_the_option_appends_a_row_per_pocket_and_keeps_the_balls() -> None:
    plain = gym.make("pool_env/OneBall-v1")
    shots = gym.make("pool_env/OneBall-v1", observation="shots")
    n_pockets = table_mouths(shots.unwrapped.config.table).n
    assert shots.observation_space.shape == (plain.observation_space.shape[0] + PER * n_pockets,)
    a, _ = plain.reset(seed=4)
    b, _ = shots.reset(seed=4)
    np.testing.assert_array_equal(b[: a.shape[0]], a)
    assert obs_layout(shots.unwrapped.config)["shots"] == slice(a.shape[0], b.shape[0])
    assert "shots" not in obs_layout(plain.unwrapped.config)


def test_a_straight_in_shot_reads_a_full_hit() -> None:
    """Cue, ball and the pocket's target on one line: cut 0, aim action 0, cos 1."""
    env = gym.make("pool_env/OneBallRoll-v1", observation="shots")
    table = env.unwrapped.config.table
    target = table_mouths(table).targets[0]
    centre = np.array([table.length / 2, table.width / 2])
    u = (target - centre) / np.linalg.norm(target - centre)
    ball = centre + 0.3 * u
    cue = centre - 0.3 * u
    obs, _ = env.reset(seed=0, options={"positions": np.stack([cue, ball])})
    straight = [
        r for r in rows(env, obs) if r[COLUMN["valid"]] > 0 and r[COLUMN["cos_cut"]] > 0.9999
    ]
    assert len(straight) == 1
    row = straight[0]
    assert row[COLUMN["aim"]] == pytest.approx(0.0, abs=1e-6)
    assert row[COLUMN["clear"]] == 1.0
    diagonal = math.hypot(table.length, table.width)
    assert row[COLUMN["cue_distance"]] == pytest.approx((0.6 - 2 * table.ball_radius) / diagonal)


@pytest.mark.parametrize("env_id", ["pool_env/OneBall-v1", "pool_env/Pool-v1"])
def test_each_rows_aim_is_the_sine_of_its_cut(env_id: str) -> None:
    """Cut aim: the cue ball's path passes ``sin(cut)`` diameters from the ball's centre."""
    env = gym.make(env_id, observation="shots")
    seen = 0
    for seed in range(40):
        obs, _ = env.reset(seed=seed)
        for row in rows(env, obs):
            if row[COLUMN["valid"]] == 0:
                assert not row.any()  # invalid rows are zeros, and come last
                continue
            seen += 1
            aim, cos_cut = row[COLUMN["aim"]], row[COLUMN["cos_cut"]]
            assert aim**2 + cos_cut**2 == pytest.approx(1.0, abs=1e-5)
            assert cos_cut >= math.cos(math.radians(85.0)) - 1e-6
    assert seen > 50


def test_rows_come_easiest_first_and_invalid_last() -> None:
    env = gym.make("pool_env/OneBallRoll-v1", observation="shots")
    for seed in range(30):
        obs, _ = env.reset(seed=seed)
        valid = rows(env, obs)[:, COLUMN["valid"]]
        assert np.all(np.diff(valid) <= 0)  # 1s then 0s


def test_the_first_rows_shot_pots_its_ball_on_the_roll_table() -> None:
    """The physics behind the numbers: row 0's aim and speed, played, pot the ball."""
    env = gym.make("pool_env/OneBallRoll-v1", observation="shots")
    played = potted = 0
    for seed in range(150):
        obs, _ = env.reset(seed=seed)
        row = rows(env, obs)[0]
        if row[COLUMN["valid"]] == 0 or row[COLUMN["clear"]] == 0:
            continue
        *_, info = env.step(np.array([row[COLUMN["aim"]], row[COLUMN["speed"]]]))
        played += 1
        potted += info["potted"] == (1,)
    assert played > 100
    assert potted / played > 0.9


def test_under_the_rules_the_rows_aim_at_the_ball_on() -> None:
    """9-ball: the reference is the lowest ball, though another ball is nearer the cue."""
    env = gym.make("pool_env/NineBallGameRoll-v2", observation="shots")
    table = env.unwrapped.config.table
    pos = np.zeros((10, 2))
    on = np.zeros(10, dtype=bool)
    pos[0], pos[1], pos[5], pos[9] = (0.9, 0.6), (1.8, 0.4), (1.1, 0.7), (2.2, 1.0)
    on[[0, 1, 5, 9]] = True
    obs, _ = env.reset(seed=0, options={"positions": pos, "on_table": on, "rules": {}})
    expected = ghost_shots(table, table_mouths(table), pos, on, [1])
    got = rows(env, obs)
    cuts = sorted(round(math.cos(s.cut), 5) for s in expected)
    assert sorted(round(float(c), 5) for c in got[got[:, 0] > 0, COLUMN["cos_cut"]]) == cuts


def test_every_front_gives_the_same_features() -> None:
    single = gym.make("pool_env/OneBall-v1", observation="shots")
    vector = gym.make_vec("pool_env/OneBall-v1", num_envs=3, observation="shots")
    many, _ = vector.reset(seed=11)
    for k in range(3):
        one, _ = single.reset(seed=11 + k)
        np.testing.assert_array_equal(many[k], one)
    actions = np.zeros((3, 4), dtype=np.float32)
    many, *_ = vector.step(actions)
    vector.close()

    pos = np.zeros((10, 2))
    on = np.zeros(10, dtype=bool)
    pos[[0, 1, 4, 9]] = (0.7, 0.5), (1.9, 0.9), (1.2, 0.3), (2.1, 0.2)
    on[[0, 1, 4, 9]] = True
    duel = PoolDuelEnv("nine", observation="shots", model="roll")
    duel.reset(seed=3, options={"positions": pos, "on_table": on})
    game = gym.make("pool_env/NineBallGameRoll-v2", observation="shots")
    obs, _ = game.reset(seed=3, options={"positions": pos, "on_table": on})
    assert rows(game, obs)[0, COLUMN["valid"]] == 1.0
    np.testing.assert_array_equal(duel.observe(duel.agent_selection), obs)


@pytest.mark.parametrize(
    "env_id", ["pool_env/OneBall-v1", "pool_env/NineBallGame-v2", "pool_env/EightBallGameRoll-v1"]
)
def test_the_shots_observation_passes_the_env_checker(env_id: str) -> None:
    env = gym.make(env_id, observation="shots")
    check_env(env.unwrapped, skip_render_check=True)
    obs, _ = env.reset(seed=0)
    for _ in range(3):
        obs, *_ = env.step(env.action_space.sample())
        assert env.observation_space.contains(obs)


def test_an_unknown_observation_is_refused_by_name() -> None:
    with pytest.raises(ValueError, match="observation must be one of"):
        gym.make("pool_env/OneBall-v1", observation="pixels")


def test_the_baselines_read_the_balls_and_ignore_the_shot_features() -> None:
    """The ghost-ball agent plays the same shots whether or not the features follow."""
    from agents.baselines.ghost_ball import GhostBallAgent

    plain = gym.make("pool_env/OneBallRoll-v1")
    shots = gym.make("pool_env/OneBallRoll-v1", observation="shots")
    for seed in range(10):
        a, _ = plain.reset(seed=seed)
        b, _ = shots.reset(seed=seed)
        expected, _ = GhostBallAgent(plain).predict(a)
        np.testing.assert_array_equal(GhostBallAgent(shots).predict(b)[0], expected)
        # Decoded from the observation alone (no env state to read), it aims the same.
        blind = GhostBallAgent(shots)
        blind.source.env = None
        np.testing.assert_allclose(blind.predict(b)[0], expected, atol=1e-4)


def test_the_first_row_agent_plays_row_zero_and_needs_the_shots() -> None:
    from agents.baselines.shot_row import ShotRowAgent

    env = gym.make("pool_env/OneBall-v1", observation="shots")
    agent = ShotRowAgent(env)
    for seed in range(20):
        obs, _ = env.reset(seed=seed)
        action, _ = agent.predict(obs)
        row = rows(env, obs)[0]
        expected = (row[COLUMN["aim"]], row[COLUMN["speed"]]) if row[0] else (0.0, 1.0)
        np.testing.assert_array_equal(action, np.array([*expected, 0.0, 0.0], np.float32))
    with pytest.raises(ValueError, match="observation='shots'"):
        ShotRowAgent(gym.make("pool_env/OneBall-v1"))
