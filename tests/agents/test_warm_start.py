"""The first-row warm start: the policy's own action fitted to row 0 before RL."""

from __future__ import annotations

import numpy as np
import pytest
from stable_baselines3 import PPO

import train
from agents.evaluation.episodes import run_episodes
from agents.learned.envs import make_env
from agents.training.run_config import TrainConfig, resolve_config
from agents.training.train_lib import make_vec
from agents.training.warm_start import first_row_targets, fit_policy_mean, warm_start

ROLL = "pool_env/OneBallRoll-v1"


def _ppo(config: TrainConfig) -> PPO:
    from agents.training import hyperparams

    return PPO(config.policy, make_vec(config), seed=0, device="cpu",
               **hyperparams.to_sb3(config.algo_kwargs))  # fmt: skip


def test_the_fit_plays_row_0_on_the_roll_tables_own_action() -> None:
    config = resolve_config(ROLL, "ppo", {"n_envs": 8})
    model = _ppo(config)
    env = make_env(ROLL, config.env_kwargs)
    before = run_episodes(model, env, 200, seed=10_000).summary()["pots_per_shot"].value
    obs, actions = first_row_targets(ROLL, config.env_kwargs, 2048)
    assert actions.shape == (2048, 2) and np.all(np.abs(actions) <= 1.0)
    loss = fit_policy_mean(model, obs, actions, epochs=40)
    assert loss < 1e-3
    fresh, targets = first_row_targets(ROLL, config.env_kwargs, 300, seed=10_000)
    played, _ = model.predict(fresh, deterministic=True)
    assert np.median(np.abs(played[:, 0] - targets[:, 0])) < 0.01  # a pot window is ~0.09
    after = run_episodes(model, env, 200, seed=10_000).summary()["pots_per_shot"].value
    # Row 0 played exactly pots 96% of these layouts; the untrained policy about a fifth.
    assert before < 0.4 and after > 0.8
    env.close()


def test_an_unknown_warm_start_is_named() -> None:
    with pytest.raises(ValueError, match="warm_start 'last-row': use one of \\['first-row'\\]"):
        resolve_config(ROLL, "ppo", {"warm_start": "last-row"})
    config = resolve_config(ROLL, "ppo", {"n_envs": 8})
    with pytest.raises(ValueError, match="use one of"):
        warm_start(_ppo(config), "last-row", ROLL, config.env_kwargs)
    with pytest.raises(ValueError, match="observation='shots'"):
        first_row_targets(ROLL, {}, 4)  # the positions only: no row to fit
    with pytest.raises(ValueError, match="the wrapper 'ghost_candidates' changes it"):
        resolve_config(ROLL, "ppo", {"warm_start": "first-row"}, recipe="candidates")


def test_the_command_line_refuses_a_warm_start_on_a_wrapper(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        train.main(["--env", ROLL, "--wrapper", "ghost_candidates", "--no-baselines"])
    assert exit_info.value.code == 2  # the roll recipe warm-starts: not on another action
    assert "fits the env's own action" in capsys.readouterr().err
    # --warm-start none lifts the recipe's: the same command gets past every check.
    checked = []
    monkeypatch.setattr(
        "agents.training.train_lib.train", lambda config, root: checked.append(config)
    )
    argv = ["--env", ROLL, "--wrapper", "ghost_candidates", "--warm-start", "none"]
    assert train.main(argv) == 0
    assert checked[0].warm_start is None and checked[0].wrapper == "ghost_candidates"
