"""Ray RLlib: the env creator in every worker, hyperparameters translated, PPO iterations."""

from __future__ import annotations

import csv
import json
import os
from pathlib import Path

import numpy as np
import pytest

ray = pytest.importorskip(
    "ray", reason="needs the rllib extra (ray[rllib]): pip install -e '.[rllib]'"
)
pytest.importorskip("ray.rllib", reason="needs the rllib extra: pip install -e '.[rllib]'")

from gymnasium.vector import AutoresetMode  # noqa: E402

from agents.integrations.rllib_env import make_env, register  # noqa: E402
from agents.integrations.rllib_train import (  # noqa: E402
    RLlibRun,
    build_config,
    fit,
    resolve_run,
    rllib_training_kwargs,
)
from agents.training import hyperparams  # noqa: E402
from pool_env.envs.vector import PoolVectorEnv  # noqa: E402

ONE = "pool_env/OneBallRoll-v1"


def test_make_env_gives_the_native_vector_env_in_next_step_mode() -> None:
    env = make_env({"num_envs": 4, "env_kwargs": {"aim": "relative"}}, env_id=ONE)
    assert isinstance(env, PoolVectorEnv)
    assert env.num_envs == 4
    assert env.config.aim == "relative"
    assert env.autoreset_mode == AutoresetMode.NEXT_STEP
    assert env.max_episode_steps == 10  # the id's TimeLimit, as gym.make(id)
    single = make_env({"env_id": ONE})
    assert single.spec.id == ONE
    with pytest.raises(ValueError, match="next-step"):
        make_env({"num_envs": 2, "env_kwargs": {"autoreset_mode": "SameStep"}}, env_id=ONE)
    with pytest.raises(ValueError, match="env id must be one of"):
        make_env({"num_envs": 2}, env_id="CartPole-v1")
    with pytest.raises(ValueError, match="not a pool_env id"):
        register("CartPole-v1")


def test_hyperparameters_translate_key_by_key() -> None:
    run, algo = hyperparams.split(hyperparams.load(ONE, "ppo"))
    kw = rllib_training_kwargs(algo, 300_000, run["n_envs"])
    # The OneBall entry: gamma 0, lambda 0, n_steps 64 x 64 envs, batch 512, 10 epochs, lr
    # annealed, no entropy bonus, relu 128x128.
    assert kw["gamma"] == 0.0
    assert kw["lambda_"] == 0.0
    assert kw["train_batch_size_per_learner"] == algo["n_steps"] * 64 == 4096
    assert kw["minibatch_size"] == algo["batch_size"] == 512
    assert kw["num_epochs"] == algo["n_epochs"] == 10
    # lin_1e-3: RLlib's piecewise-linear schedule from 1e-3 to 0 over the run's steps.
    assert algo["learning_rate"] == "lin_1e-3"
    assert kw["lr"] == [[0, pytest.approx(1e-3)], [300_000, 0.0]]
    assert kw["entropy_coeff"] == algo["ent_coef"] == 0.0
    assert kw["model"] == {"fcnet_hiddens": [128, 128], "fcnet_activation": "relu"}
    assert resolve_run(ONE, {}).sb3_n_envs == 64  # the file's n_envs sets the train batch


@pytest.fixture(scope="module")
def local_ray():  # type: ignore[no-untyped-def]
    if ray.is_initialized():
        ray.shutdown()
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    # tests/conftest.py set RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER=0: traffic stays on loopback.
    assert {n["NodeManagerAddress"] for n in ray.nodes()} == {"127.0.0.1"}
    yield
    ray.shutdown()


def test_ppo_trains_on_two_env_runners_with_the_plain_id(local_ray: None, tmp_path: Path) -> None:
    run = resolve_run(
        ONE,
        {
            "env_runners": 2,
            "n_envs": 16,
            "n_timesteps": 1,  # one iteration
            "final_episodes": 20,
            "baselines": False,
            "algo_kwargs": {"n_steps": 32, "batch_size": 128, "n_epochs": 1},  # 256 a batch
        },
    )
    assert isinstance(run, RLlibRun)
    algo = build_config(run).build_algo()
    try:
        # Each EnvRunner is its own process that never imported pool_env itself: the
        # creator registered the plain id there and built a 16-table PoolVectorEnv.
        found = algo.env_runner_group.foreach_env_runner(
            lambda r: (os.getpid(), type(r.env.unwrapped).__name__, r.env.unwrapped.num_envs),
            local_env_runner=False,
        )
        pids = {pid for pid, _, _ in found}
        assert len(pids) == 2
        assert os.getpid() not in pids
        assert {(name, n) for _, name, n in found} == {("PoolVectorEnv", 16)}
        before = [p.detach().clone() for p in algo.get_module().parameters()]
        steps = fit(algo, run, tmp_path)
        after = list(algo.get_module().parameters())
    finally:
        algo.stop()
    assert steps >= 256
    assert any(
        not np.allclose(b.numpy(), a.detach().numpy()) for b, a in zip(before, after, strict=True)
    )
    with (tmp_path / "progress.csv").open() as progress:
        rows = list(csv.DictReader(progress))
    assert len(rows) == 1
    # OneBallRoll-v1 is one shot per episode: every sampled step ends an episode.
    assert int(rows[0]["episodes"]) == int(rows[0]["env_steps"]) == steps
    assert -1.0 <= float(rows[0]["episode_return_mean"]) <= 1.0
    report = json.loads((tmp_path / "evaluation.json").read_text())
    assert report["episodes"] == 20
    assert set(report["results"]) == {"ppo (rllib)"}
    assert (tmp_path / "checkpoint").is_dir()
