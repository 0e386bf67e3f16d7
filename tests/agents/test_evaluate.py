"""Evaluation: statistics, confidence intervals, the command line, loading a saved model."""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import pool_env  # noqa: F401
from agents.baselines.random_agent import ConstantAgent
from agents.evaluation.evaluate import evaluate_agent, load_model, main, run_episodes
from agents.evaluation.metrics import mean_ci, ratio_ci, wilson

ONE = "pool_env/OneBallRoll-v1"


def test_wilson_interval_known_values() -> None:
    est = wilson(50, 100)
    assert est.value == 0.5
    assert est.low == pytest.approx(0.4038, abs=1e-4)
    assert est.high == pytest.approx(0.5962, abs=1e-4)
    zero = wilson(0, 20)
    assert zero.low == 0.0 and 0.0 < zero.high < 0.2


def test_ratio_ci_is_wilson_for_one_shot_episodes() -> None:
    pots = np.array([1, 0, 1, 1, 0, 1])
    assert ratio_ci(pots, np.ones(6)) == wilson(4, 6)


def test_ratio_ci_clusters_by_episode() -> None:
    pots, shots = np.array([3.0, 0.0, 5.0, 1.0]), np.array([4.0, 2.0, 5.0, 3.0])
    est = ratio_ci(pots, shots)
    assert est.value == pytest.approx(9 / 14)
    assert est.low < est.value < est.high
    m = mean_ci(np.array([1.0, 2.0, 3.0]))
    assert m.value == 2.0 and m.high - m.value == pytest.approx(1.96 / math.sqrt(3), 1e-3)


def test_run_episodes_counts_shots_pots_and_scratches() -> None:
    env = gym.make(ONE)
    log = run_episodes(ConstantAgent(env, (0.0, 1.0)), env, 50, seed=0)
    assert log.shots == [1] * 50  # OneBall: one shot per episode
    assert all(c <= p for c, p in zip(log.clean, log.pots, strict=True))
    for pots, clean, scratch, reward in zip(
        log.pots, log.clean, log.scratches, log.rewards, strict=True
    ):
        assert reward == pots - scratch
        assert clean == (pots > 0 and not scratch)
    stats = log.summary()
    assert stats["pots_per_turn"].value == stats["pots_per_shot"].value


def test_multi_shot_episodes_count_turns() -> None:
    env = gym.make("pool_env/PoolRoll-v1", n_balls=2, max_shots=5)
    agent = ConstantAgent(env, (0.0, -0.5))
    log = run_episodes(agent, env, 5, seed=0)
    # Replay the episodes and count by the rule: a shot that pots nothing or scratches
    # ends the turn, and the episode's end ends the last one.
    expected_shots, expected_turns = [], []
    for k in range(5):
        obs, _ = env.reset(seed=k)
        outcomes = []
        while True:
            obs, _, terminated, truncated, info = env.step(agent.predict(obs)[0])
            outcomes.append(not info["potted"] or info["scratch"])
            if terminated or truncated:
                break
        expected_shots.append(len(outcomes))
        expected_turns.append(sum(outcomes) + (not outcomes[-1]))
    assert log.shots == expected_shots
    assert log.turns == expected_turns
    assert log.turns != log.shots  # some turn had more than one shot: the case is tested


def test_cli_prints_a_table(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    out = tmp_path / "eval.md"
    argv = ["--env", ONE, "--agent", "random", "ghost", "--episodes", "30", "--seed", "5"]
    assert main([*argv, "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "| random |" in text and "| ghost |" in text and "pots/shot" in text
    assert "| ghost |" in out.read_text()


def test_saved_model_loads_and_evaluates(tmp_path: Path) -> None:
    from stable_baselines3 import PPO

    env = gym.make(ONE)
    model = PPO("MlpPolicy", env, n_steps=64, batch_size=32, n_epochs=1, gamma=0.0, seed=0)
    model.learn(64)
    path = tmp_path / "ppo_tiny.zip"
    model.save(path)
    loaded = load_model(path)
    assert isinstance(loaded, PPO)
    stats = evaluate_agent(str(path), ONE, 20, seed=0)
    # The loaded model plays exactly as the one in memory on the same layouts.
    direct = run_episodes(model, gym.make(ONE), 20, seed=0).summary()
    assert {k: v.value for k, v in stats.items()} == {k: v.value for k, v in direct.items()}
    assert main(["--env", ONE, "--agent", str(path), "--episodes", "10"]) == 0


def test_unknown_agent_is_a_clear_error() -> None:
    with pytest.raises(ValueError, match="unknown agent"):
        evaluate_agent("nonsense", ONE, 1, seed=0)
    with pytest.raises(FileNotFoundError):
        load_model("missing_ppo.zip")


def test_best_constant_scan_keeps_the_best_of_the_grid() -> None:
    from agents.evaluation.constant_scan import scan_constant_actions

    env = gym.make(ONE)
    scan = scan_constant_actions(env, grid=3, episodes=40, seed=100)
    assert len(scan.table) == 9 and {a for a, _ in scan.table} >= {(0.0, 1.0), (-1.0, -1.0)}
    assert scan.pots_per_shot.value == max(rate for _, rate in scan.table)
    replay = run_episodes(ConstantAgent(env, scan.action), env, 40, seed=100).summary()
    assert replay["pots_per_shot"].value == scan.pots_per_shot.value
    full_hit = dict(scan.table)[(0.0, 1.0)]
    assert scan.pots_per_shot.value >= full_hit
    with pytest.raises(ValueError, match="grid"):
        scan_constant_actions(env, grid=1)


def test_cli_names_every_baseline(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["--env", ONE, "--agent", "best-const", "search", "--episodes", "10", "--seed", "5"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "| best-const (" in text and "| search |" in text
