"""What the commands print: the steps trained, the final evaluation's size, the table, the noise."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import train
from agents.baselines.random_agent import RandomAgent
from agents.evaluation.evaluate import main, run_episodes
from agents.evaluation.noise_flag import noise_label, parse_noise
from agents.evaluation.table import format_table
from agents.learned.envs import make_env
from agents.training import hyperparams
from agents.training.run_config import ALGOS, GAME_BASELINES, TrainConfig, resolve_config
from agents.training.train_lib import (
    StepsBar,
    final_episodes,
    make_vec,
    trained_steps,
)


def test_the_bar_and_the_count_are_the_steps_sb3_trains() -> None:
    config = TrainConfig(env_id="pool_env/OneBallRoll-v1", n_envs=2, vec="dummy")
    env = make_vec(config)
    model = ALGOS["ppo"]("MlpPolicy", env, n_steps=64, batch_size=64, n_epochs=1, seed=0)
    steps = trained_steps(model, 100)
    assert steps == 128  # one rollout of 64 steps on each of 2 envs
    bar = StepsBar(steps)
    model.learn(100, callback=[bar])
    env.close()
    assert model.num_timesteps == steps
    assert bar.pbar.total == steps and bar.pbar.n == steps  # never past its total


def test_the_final_evaluation_is_sized_to_the_run() -> None:
    config = TrainConfig()
    assert final_episodes(config, 16_384) == 100  # a smoke run: a short evaluation
    assert final_episodes(config, 100_000) == 500
    assert final_episodes(config, 802_816) == 1000  # the default run's figures unchanged
    config.final_episodes = 7
    assert final_episodes(config, 802_816) == 7


def test_a_game_id_gets_the_game_baselines() -> None:
    game = resolve_config("pool_env/NineBallGame-v1", "ppo", {})
    assert game.final_baselines == list(GAME_BASELINES) == ["random", "ghost"]
    assert "best-const" in resolve_config("pool_env/NineBall-v1", "ppo", {}).final_baselines


def test_set_keys_are_checked_against_the_algorithm() -> None:
    with pytest.raises(
        ValueError, match=r"--set n_step: PPO takes no 'n_step' \(did you mean n_steps"
    ):
        resolve_config("pool_env/OneBall-v1", "ppo", {"algo_kwargs": {"n_step": 64}})
    with pytest.raises(ValueError, match=r"--set n_envs: a setting of the run.*--n-envs"):
        resolve_config("pool_env/OneBall-v1", "ppo", {"algo_kwargs": {"n_envs": 4}})
    # Every key of the shipped file is one its algorithm takes.
    assert resolve_config("pool_env/OneBall-v1", "sac", {}).algo_kwargs["buffer_size"] > 0
    assert hyperparams.RUN_KEYS  # the run keys are named apart


def _rows(env_id: str, episodes: int = 30) -> dict:
    env = make_env(env_id, {"observation": "shots"} if "OneBall" in env_id else None)
    rows = {"random": run_episodes(RandomAgent(env, seed=0), env, episodes, 10_000).summary()}
    env.close()
    return rows


def test_a_one_shot_table_leaves_out_the_columns_that_repeat() -> None:
    table = format_table(_rows("pool_env/OneBallRoll-v1"), 30)
    head = table.splitlines()[0]
    assert "pots/shot" in head and "clean pots/shot" in head and "scratch/shot" in head
    for label in ("clear rate", "run-out rate", "pots/turn", "shots/episode"):
        assert label not in head
    assert "clear rate (= pots/shot)" in table and "shots/episode (1)" in table
    many = format_table(_rows("pool_env/NineBallRoll-v1", 3), 3)  # several shots a rack
    assert "pots/turn" in many.splitlines()[0] and "repeat" not in many


def test_first_row_is_explained_where_it_is_printed() -> None:
    rows = _rows("pool_env/OneBallRoll-v1", 5)
    assert "first-row:" not in format_table(rows, 5)
    rows["first-row"] = rows["random"]
    assert "first-row: the observation's easiest ghost-ball shot" in format_table(rows, 5)


def test_a_short_run_says_what_it_trains_and_how_to_skip_the_evaluation(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    args = ["--timesteps", "100", "--n-envs", "2", "--eval-freq", "64", "--eval-episodes", "5",
            "--runs", str(tmp_path), "--set", "n_steps=64", "batch_size=64"]  # fmt: skip
    assert train.main(args) == 0  # the progress bar on: the periodic lines still print
    out = capsys.readouterr().out
    assert (
        "training 128 steps (100 asked: PPO trains whole rollouts of 64 steps on each of 2" in out
    )
    periodic = [line for line in out.splitlines() if line.strip().endswith("]") and "steps" in line]
    assert [line.split()[0] for line in periodic] == ["0", "64", "128"]
    assert all("pots/shot" in line for line in periodic)
    assert "Final evaluation: 100 episodes each" in out
    assert "--final-episodes N" in out and "--no-baselines" in out
    assert "best-const left out: its scan would play" in out  # 729 actions x 100 > 128 steps
    assert "after 128 steps" in out


def test_evaluate_plays_the_game_ids_at_the_field_noise(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert (
        main(["--env", "pool_env/NineBallGameRoll-v2", "--agent", "random", "--episodes", "1"]) == 0
    )
    assert "noise fastfiz (FastFiz x1, the field's)" in capsys.readouterr().out.splitlines()[0]
    args = ["--env", "pool_env/NineBallGameRoll-v2", "--agent", "random", "--episodes", "1"]
    assert main([*args, "--noise", "none"]) == 0
    assert "noise none (exact shots)" in capsys.readouterr().out.splitlines()[0]
    assert main(["--agent", "random", "--episodes", "1"]) == 0  # not a game id: the env's own
    assert "noise none (exact shots)" in capsys.readouterr().out.splitlines()[0]
    assert parse_noise("fastfiz:5") == ("fastfiz", 5.0) and parse_noise("0") is None


def test_evaluate_help_lists_the_players(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit):
        main(["--help"])
    text = " ".join(capsys.readouterr().out.split())
    for word in ("ghost", "const:a0,a1", "best-const", ".zip", ".npz", ".yaml", "search player",
                 "fastfiz on the game ids"):  # fmt: skip
        assert word in text, word


def test_a_long_run_keeps_the_best_constant_scan(capsys: pytest.CaptureFixture[str]) -> None:
    from agents.training.train_lib import _final_evaluation

    config = resolve_config("pool_env/OneBallRoll-v1", "ppo", {"progress_bar": False})
    env = make_env(config.env_id, config.env_kwargs)
    agent = RandomAgent(env, seed=0)
    env.close()
    rows, action = _final_evaluation(config, agent, 5, steps=1_000_000)  # 81 x 5 shots
    assert "best-const" in rows and action is not None
    grid = np.linspace(-1.0, 1.0, 9).tolist()
    assert all(v in grid for v in action)
    out = capsys.readouterr().out
    assert "left out" not in out and "best-const scan (5 episodes each): 81 actions" in out
    rows, action = _final_evaluation(config, agent, 5, steps=400)  # the scan: 405 > 400
    assert "best-const" not in rows and action is None
    assert "its scan would play 405 shots, more than the 400 trained" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("noise", "label"),
    [
        (None, "none (exact shots)"),
        ("fastfiz", "fastfiz (FastFiz x1, the field's)"),
        (("fastfiz", 5.0), "fastfiz:5 (FastFiz x5)"),
        ((0.003, 0.05), "sigmas 0.003, 0.05"),
        ([0.003, 0.05], "sigmas 0.003, 0.05"),  # --env-kwargs "{noise: [...]}" is a list
    ],
)
def test_the_header_names_the_noise_in_force(noise: object, label: str) -> None:
    assert noise_label(noise) == label


def test_the_best_constant_note_gives_every_component_of_the_action() -> None:
    from agents.training.train_lib import _best_const_note

    note = _best_const_note([0.25, -0.5, 0.125, -1.0])  # a spin id's aim, speed and tip
    assert "(+0.25, -0.50, +0.12, -1.00)" in note and "9 x 9" not in note
    assert _best_const_note(None) == ""
