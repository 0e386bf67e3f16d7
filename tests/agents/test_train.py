"""train.py end to end on a tiny budget, hyperparameter parsing, vectorized env kinds."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest
import yaml

import train
from agents.evaluation.evaluate import evaluate_agent, load_model
from agents.train import first_line
from agents.training import hyperparams
from agents.training.paired import paired_clean
from agents.training.run_config import ALGOS, TrainConfig, resolve_config
from agents.training.train_lib import make_vec
from pool_env import ENV_IDS

TINY = [
    "--timesteps", "512", "--n-envs", "2", "--eval-freq", "256", "--eval-episodes", "10",
    "--final-episodes", "20", "--no-progress",
]  # fmt: skip


def test_train_py_writes_a_complete_run_folder(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert (
        train.main([*TINY, "--runs", str(tmp_path), "--set", "n_steps=128", "batch_size=64"]) == 0
    )
    printed = capsys.readouterr().out
    # The first line says what the command waits for (the trainer, the compile); the
    # warm-up comes before training; the last lines set the run beside the baselines.
    assert printed.splitlines()[0] == first_line("pool_env/OneBall-v1", "ppo", "sb3")
    assert "simulator compiles" in printed.splitlines()[0]
    assert printed.index("Ready in") < printed.index("pots per shot: ppo")
    assert all(f"| {name} " in printed for name in ("random", "ghost", "first-row"))
    # 512 steps: the best-constant scan (729 actions x 20 episodes) would outweigh them
    assert "| best-const " not in printed and "best-const left out" in printed
    (run,) = (tmp_path / "OneBall-v1").iterdir()
    for name in ("config.yaml", "command.txt", "model.zip", "evaluation.md", "evaluation.json",
                 "curve.csv", "learning_curve.png"):  # fmt: skip
        assert (run / name).is_file(), name
    assert any((run / "tb").rglob("events.out.tfevents.*"))
    config = yaml.safe_load((run / "config.yaml").read_text())
    assert config["algo"] == "ppo" and config["n_timesteps"] == 512
    assert config["algo_kwargs"]["n_steps"] == 128
    assert config["env_kwargs"] == {"observation": "shots"} and config["wrapper"] is None
    report = json.loads((run / "evaluation.json").read_text())
    # The "shots" observation adds its trivial policy (row 0 played exactly) to the
    # baselines; the spin entry leaves the (slow) search out.
    assert set(report["results"]) == {"ppo (this run)", "random", "ghost", "first-row"}
    assert report["process_seconds"] > 0.0
    assert report["total_seconds"] <= report["process_seconds"]
    assert report["results"]["ghost"]["pots_per_shot"][0] >= 0.8
    assert report["best_const_action"] is None and report["trained_steps"] == 512
    curve = (run / "curve.csv").read_text().splitlines()
    assert len(curve) >= 3  # header, start, end
    # The climb is printed from the curve's first and last points, and names the plot.
    first, last = (float(line.split(",")[2]) for line in (curve[1], curve[-1]))
    climb = next(line for line in printed.splitlines() if line.startswith("Learning:"))
    assert f"{first:.1%} untrained" in climb and f"{last:.1%} after" in climb
    assert str(run / "learning_curve.png") in climb
    _assert_saved_model_is_the_evaluated_one(run, "ppo (this run)")


def test_the_candidates_recipe_and_its_paired_comparison(tmp_path: Path) -> None:
    args = ["--env", "pool_env/OneBallRoll-v1", "--recipe", "candidates"]
    assert train.main([*TINY, *args, "--runs", str(tmp_path), "--set", "n_steps=128"]) == 0
    (run,) = (tmp_path / "OneBallRoll-v1").iterdir()
    report = json.loads((run / "evaluation.json").read_text())
    config = yaml.safe_load((run / "config.yaml").read_text())
    assert (config["recipe"], config["wrapper"]) == ("candidates", "ghost_candidates")
    assert {"ppo (this run)", "first-row", "search"} <= set(report["results"])
    assert report["results"]["first-row"]["pots_per_shot"][0] >= 0.8
    assert report["results"]["search"]["pots_per_shot"][0] >= 0.9
    # The paired comparison replays the report's layouts: the same two clean rates, and a
    # difference that is the discordant layouts' balance.
    paired = paired_clean(str(run / "model.zip"), 20, report["final_seed"])
    assert paired["model"] == report["results"]["ppo (this run)"]["clean_pot_rate"][0]
    assert paired["first_row"] == report["results"]["first-row"]["clean_pot_rate"][0]
    balance = paired["model_only"] - paired["first_row_only"]
    assert paired["diff"][0] * 20 == pytest.approx(balance)


def _assert_saved_model_is_the_evaluated_one(run: Path, name: str) -> None:
    """model.zip, evaluated again on the report's seeds, gives the report's figures exactly."""
    report = json.loads((run / "evaluation.json").read_text())
    again = evaluate_agent(
        str(run / "model.zip"), report["env_id"], report["episodes"], report["final_seed"]
    )
    for key, (value, _, _) in report["results"][name].items():
        assert again[key].value == value, key


def test_sac_runs(tmp_path: Path) -> None:
    argv = [*TINY, "--algo", "sac", "--runs", str(tmp_path), "--no-baselines", "--eval-freq", "0"]
    assert train.main([*argv, "--set", "learning_starts=64", "gradient_steps=1"]) == 0
    (run,) = (tmp_path / "OneBall-v1").iterdir()
    model = load_model(run / "model.zip")
    assert type(model).__name__ == "SAC" and model.num_timesteps == 512
    assert model._n_updates > 0  # it trained after learning_starts, not only collected
    _assert_saved_model_is_the_evaluated_one(run, "sac (this run)")


def test_subproc_vec_env_steps() -> None:
    config = TrainConfig(n_envs=2, vec="subproc")
    env = make_vec(config)
    try:
        env.reset()
        obs, _, dones, _ = env.step(env.action_space.sample()[None].repeat(2, 0))
        assert obs.shape == (2, 6) and dones.all()  # OneBall: one shot per episode
    finally:
        env.close()


def test_native_vec_missing_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "agents.vec.native_vec", None)  # as if not installed
    with pytest.raises(ImportError, match="native_vec"):
        make_vec(TrainConfig(n_envs=2, vec="native"))


def test_every_hyperparameter_entry_resolves() -> None:
    data = yaml.safe_load(hyperparams.DEFAULT_PATH.read_text())
    for env_id, entries in data.items():
        for key, entry in entries.items():
            algo, _, recipe = key.partition("-")  # "ppo" or a named recipe "ppo-candidates"
            assert algo in ALGOS
            run, kwargs = hyperparams.split(entry)
            hyperparams.to_sb3(kwargs)
            # "default" serves the ids without an entry of their own.
            env = next(i for i in ENV_IDS if i not in data) if env_id == "default" else env_id
            config = resolve_config(env, algo, {}, recipe=recipe or None)
            assert config.n_timesteps == run["n_timesteps"]


def test_schedules_and_bad_values() -> None:
    kwargs = hyperparams.to_sb3({"learning_rate": "lin_1e-3", "policy_kwargs": {
        "activation_fn": "relu"}})  # fmt: skip
    assert kwargs["learning_rate"](1.0) == pytest.approx(1e-3)
    assert kwargs["learning_rate"](0.5) == pytest.approx(5e-4)
    with pytest.raises(ValueError, match="schedule"):
        hyperparams.to_sb3({"learning_rate": "exp_1e-3"})
    with pytest.raises(ValueError, match="activation"):
        hyperparams.to_sb3({"policy_kwargs": {"activation_fn": "nope"}})
    with pytest.raises(SystemExit):
        train.main(["--set", "novalue"])


def test_a_schedule_stops_at_zero_past_the_end() -> None:
    """SB3's progress runs below 0 in a last rollout that overshoots the step count."""
    schedule = hyperparams.to_sb3({"learning_rate": "lin_1e-3"})["learning_rate"]
    assert schedule(-0.01) == 0.0
    assert schedule(0.0) == 0.0


def test_a_named_recipe_is_its_own_entry() -> None:
    candidates = resolve_config("pool_env/OneBallRoll-v1", "ppo", {}, recipe="candidates")
    assert (candidates.recipe, candidates.wrapper) == ("candidates", "ghost_candidates")
    own = resolve_config("pool_env/OneBallRoll-v1", "ppo", {})
    assert own.recipe is None and own.wrapper is None
    assert own.env_kwargs == {"observation": "shots"}
    with pytest.raises(KeyError, match="ppo-nothing"):
        resolve_config("pool_env/OneBallRoll-v1", "ppo", {}, recipe="nothing")
    with pytest.raises(SystemExit):
        train.main(["--recipe", "nothing", "--no-baselines"])


@pytest.mark.parametrize(
    ("env_id", "algo", "recipe", "wrapper"),
    [
        ("pool_env/OneBallRoll-v1", "ppo", "candidates", "ghost_candidates"),
        ("pool_env/OneBall-v1", "ppo", None, None),
        ("pool_env/OneBall-v1", "sac", None, None),
    ],
)
def test_default_recipe_trains_on_what_its_evaluation_sees(
    env_id: str, algo: str, recipe: str | None, wrapper: str | None
) -> None:
    """The OneBall recipes on the native vector env see and act as their eval env does."""
    from agents.learned.envs import make_env

    config = resolve_config(env_id, algo, {"n_envs": 2}, recipe=recipe)
    assert (config.vec, config.wrapper) == ("native", wrapper)
    venv = make_vec(config)
    env = make_env(config.env_id, config.env_kwargs, config.wrapper)
    try:
        obs = venv.reset()
        expected, _ = env.reset(seed=config.seed)
        assert venv.observation_space == env.observation_space
        assert venv.action_space == env.action_space
        np.testing.assert_array_equal(obs[0], expected)
        assert expected[6] == 1.0  # a direct shot exists on this layout: its row is filled
    finally:
        venv.close()
        env.close()
