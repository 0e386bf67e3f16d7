"""The two-player AEC env: PettingZoo's API test, determinism, turns and wins by the rules."""

from __future__ import annotations

import math

import numpy as np
import pytest
from pettingzoo.test import api_test

from pool_env.multiagent import PoolDuelEnv, VersusPolicyEnv

TOWARD_CORNER = -3 * math.pi / 4


def _speed_action(env: PoolDuelEnv, speed: float) -> float:
    lo, hi = env.speed_range
    return 2.0 * (speed - lo) / (hi - lo) - 1.0


@pytest.mark.parametrize("game", ["nine", "eight"])
def test_pettingzoo_api(game: str) -> None:
    api_test(PoolDuelEnv(game, max_shots=40), num_cycles=100)


def _rollout(seed: int, shots: int = 12) -> list:
    env = PoolDuelEnv("nine", noise=(0.01, 0.05), max_shots=shots)
    env.reset(seed=seed)
    rng = np.random.default_rng(seed)
    trace = []
    for agent in env.agent_iter():
        obs, reward, term, trunc, info = env.last()
        action = None if term or trunc else rng.uniform(-1, 1, 5).astype(np.float32)
        trace.append((agent, obs.tobytes(), reward, info.get("foul")))
        env.step(action)
    return trace


def test_same_seed_same_game() -> None:
    assert _rollout(3) == _rollout(3)
    assert _rollout(3) != _rollout(4)


def test_a_break_that_touches_nothing_gives_the_opponent_ball_in_hand() -> None:
    env = PoolDuelEnv("nine", break_speed_range=(0.5, 10.0))
    env.reset(seed=0)
    # Observation: 3 x 10 ball entries, 9 legal-ball flags, then ball in hand (39), behind
    # the head string (40), break (41), open table (42), own fouls (43), opponent's (44).
    assert env.agent_selection == "player_0" and env.observe("player_0")[39] == 1.0
    # Cue ball placed in the kitchen, shot softly into the head rail: it never reaches the rack.
    r = env.table.ball_radius
    ax = 2 * (0.3 - r) / (env.table.length / 4 - r) - 1  # the break's placement: the kitchen
    env.step(np.array([-1.0, -1.0, ax, 0.0, 0.0], np.float32))
    assert env.infos["player_1"]["foul"] == "illegal_break"
    assert env.agent_selection == "player_1"
    obs = env.observe("player_1")
    assert obs[39] == 1.0 and obs[40] == 0.0  # ball in hand anywhere, not only the kitchen
    assert obs[44] == 0.5 and obs[43] == 0.0  # the opponent (player_0) has one foul in a row
    assert obs[45] == 1.0 and env.observe("player_0")[45] == 0.0  # player_1 shoots next


def test_the_nine_straight_in_wins_the_rack() -> None:
    env = PoolDuelEnv("nine")
    pos = np.array([[1.5, 0.6]] * 10)
    on = np.zeros(10, bool)
    on[[0, 9]] = True
    pos[0] = (0.45 / math.sqrt(2),) * 2
    pos[9] = (0.25 / math.sqrt(2),) * 2
    env.reset(seed=0, options={"positions": pos, "on_table": on})
    env.step(np.array([TOWARD_CORNER / math.pi, _speed_action(env, 1.5), 0, 0, 0], np.float32))
    assert env.infos["player_0"]["winner"] == "player_0"
    assert env.rewards == {"player_0": 1.0, "player_1": -1.0}
    assert all(env.terminations.values())


def test_reset_refuses_an_invalid_layout() -> None:
    env = PoolDuelEnv("nine")
    pos = np.array([[1.0, 0.6]] * 10)
    with pytest.raises(ValueError, match="overlap"):
        env.reset(options={"positions": pos})
    with pytest.raises(ValueError, match="keep the cue"):
        env.reset(options={"positions": pos, "on_table": np.zeros(10, bool)})


def test_versus_policy_env_passes_the_checkers() -> None:
    from gymnasium.utils.env_checker import check_env
    from stable_baselines3.common.env_checker import check_env as sb3_check_env

    check_env(VersusPolicyEnv(game="nine", max_shots=30), skip_render_check=True)
    sb3_check_env(VersusPolicyEnv(game="eight", max_shots=30), warn=True)


def test_versus_policy_rack_ends_with_the_opponents_win_or_the_agents() -> None:
    """A rack against a random opponent: the agent's return is the rack's result."""
    env = VersusPolicyEnv(game="nine", max_shots=400)
    env.reset(seed=1)
    total, done, rng = 0.0, False, np.random.default_rng(1)
    while not done:
        _, reward, term, trunc, _ = env.step(rng.uniform(-1, 1, 5).astype(np.float32))
        total += reward
        done = term or trunc
    winner = env.duel.rack["winner"]
    assert total == (0.0 if winner < 0 else (1.0 if winner == 0 else -1.0))
    with pytest.raises(ValueError, match="rack is over"):
        env.step(np.zeros(5, np.float32))
