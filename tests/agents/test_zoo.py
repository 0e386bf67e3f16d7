"""RL Zoo files: generated from hyperparams.yml (no drift), and zoo reads and trains with them."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from agents.integrations.zoo import ZOO_ALGOS, ZOO_DIR, zoo_entry, zoo_file_text
from agents.training import hyperparams
from pool_env.envs.registration import ENV_IDS

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("algo", ZOO_ALGOS)
def test_shipped_zoo_files_are_what_hyperparams_yml_generates(algo: str) -> None:
    assert (ZOO_DIR / f"{algo}.yml").read_text() == zoo_file_text(algo), (
        "agents/integrations/zoo is out of date: run python -m agents.integrations.zoo"
    )


@pytest.mark.parametrize("algo", ZOO_ALGOS)
def test_every_id_has_its_entry_with_the_algorithm_arguments(algo: str) -> None:
    data = yaml.safe_load((ZOO_DIR / f"{algo}.yml").read_text())
    assert set(data) == set(ENV_IDS)
    for env_id in ENV_IDS:
        run, algo_kwargs = hyperparams.split(hyperparams.load(env_id, algo))
        entry = data[env_id]
        policy = algo_kwargs.pop("policy_kwargs", None)
        assert {k: entry[k] for k in algo_kwargs} == algo_kwargs
        if isinstance(entry.get("policy_kwargs"), str):
            # An activation is a class: zoo evaluates the string with torch.nn as nn, and it
            # must give what train.py builds from the same entry.
            import torch

            built = eval(entry["policy_kwargs"], {"nn": torch.nn, "dict": dict})
            assert built == hyperparams.to_sb3({"policy_kwargs": policy})["policy_kwargs"]
        else:
            assert entry.get("policy_kwargs") == policy
        assert entry["n_timesteps"] == run["n_timesteps"]
        assert entry["n_envs"] == run["n_envs"]
        # Keys zoo does not know would reach the SB3 constructor and fail there.
        assert not set(entry) & {"vec", "eval_freq", "eval_episodes", "wrapper", "final_baselines"}


def test_a_wrapper_becomes_a_zoo_env_wrapper(tmp_path: Path) -> None:
    path = tmp_path / "hp.yml"
    ppo = {"n_timesteps": 10, "wrapper": "pocket_features", "vec": "native"}
    path.write_text(yaml.safe_dump({"default": {"ppo": ppo}}))
    entry = zoo_entry("pool_env/OneBallRoll-v1", "ppo", path)
    assert entry == {"n_timesteps": 10, "env_wrapper": "agents.learned.features.PocketFeatures"}
    path.write_text(yaml.safe_dump({"default": {"ppo": {"wrapper": "mystery"}}}))
    with pytest.raises(ValueError, match="mystery"):
        zoo_entry("pool_env/OneBallRoll-v1", "ppo", path)


def test_zoo_trains_ppo_with_the_shipped_file(tmp_path: Path) -> None:
    # Found, not imported: importing rl_zoo3 patches Gymnasium's TimeLimit for the whole
    # process (rl_zoo3.gym_patches), and every later test would see its info key.
    if importlib.util.find_spec("rl_zoo3") is None:
        pytest.skip("needs the zoo extra: pip install -e '.[zoo]'")
    command = [
        sys.executable, "-m", "rl_zoo3.train", "--algo", "ppo", "--env", "pool_env/OneBallRoll-v1",
        "--gym-packages", "pool_env", "-conf", "agents/integrations/zoo/ppo.yml", "-n", "2048",
        "--num-threads", "1", "-f", str(tmp_path), "--eval-freq", "-1", "--seed", "0",
    ]  # fmt: skip
    done = subprocess.run(command, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    run = tmp_path / "ppo" / "pool_env-OneBallRoll-v1_1"
    assert (run / "pool_env-OneBallRoll-v1.zip").is_file()
    saved = yaml.unsafe_load((run / "pool_env-OneBallRoll-v1" / "config.yml").read_text())
    # Zoo used the file's values, not its own defaults (gamma 0.99, n_steps 2048).
    assert dict(saved)["gamma"] == 0.0
    assert (
        dict(saved)["n_steps"]
        == hyperparams.load("pool_env/OneBallRoll-v1", "ppo")["n_steps"]
        == 64
    )
    assert "total_timesteps" in done.stdout
