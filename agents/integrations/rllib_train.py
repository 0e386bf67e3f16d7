"""PPO on Ray RLlib (``python train.py --backend rllib``): the scale-out path.

Sampling runs in ``env_runners`` EnvRunner actors, each stepping ``n_envs`` tables in one
:class:`~pool_env.envs.vector.PoolVectorEnv` (``gym_env_vectorize_mode="vector_entry_point"``);
the learner (one, in the driver) updates the policy on their batches. ``ray.init()`` starts
a local Ray on this machine, or joins the cluster that ``RAY_ADDRESS`` (or ``--address``)
names, so the same command trains on one machine or many: more EnvRunners sample in
parallel across the nodes; the single learner does not scale out.

The hyperparameters are the SB3 ones of ``agents/training/hyperparams.yml`` (PPO entry of the env
id), translated by :func:`rllib_training_kwargs`: the same file drives both backends.
A run writes ``runs/<env>/rllib_ppo_s<seed>_<steps>_<time>/``: ``config.yaml``,
``command.txt``, ``progress.csv`` (per iteration), ``checkpoint/`` and ``evaluation.md`` /
``.json`` (the trained policy next to the baselines, on the seeds ``train.py`` uses).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from numpy.typing import NDArray

from agents.evaluation.evaluate import evaluate_agent
from agents.evaluation.table import format_table, one_line
from agents.integrations.rllib_env import register
from agents.training import hyperparams, runs

#: SB3 PPO's defaults: what an entry that does not set a key means (RLlib's differ).
SB3_PPO_DEFAULTS: dict[str, Any] = {
    "learning_rate": 3e-4,
    "n_steps": 2048,
    "batch_size": 64,
    "n_epochs": 10,
    "gamma": 0.99,
    "gae_lambda": 0.95,
    "clip_range": 0.2,
    "ent_coef": 0.0,
    "vf_coef": 0.5,
    "max_grad_norm": 0.5,
}

#: SB3 PPO key -> RLlib ``PPOConfig.training`` key, for the keys that map one to one.
RLLIB_KEYS = {
    "gamma": "gamma",
    "gae_lambda": "lambda_",
    "n_epochs": "num_epochs",
    "batch_size": "minibatch_size",
    "clip_range": "clip_param",
    "ent_coef": "entropy_coeff",
    "vf_coef": "vf_loss_coeff",
    "max_grad_norm": "grad_clip",
}

#: SB3 ``policy_kwargs`` that RLlib's default PPO model has no counterpart for and that the
#: RLlib run goes without: its Gaussian's log std is a network output, not a parameter with
#: an initial value.
SB3_ONLY_POLICY_KWARGS = ("log_std_init",)

#: Seeds of the final evaluation (the SB3 path's, so the tables compare).
FINAL_SEED = 10_000


@dataclass
class RLlibRun:
    """Everything that defines an RLlib run (saved as the run's ``config.yaml``).

    Attributes:
        env_id: A pool_env id.
        seed: Seed of the algorithm and of the EnvRunners' tables.
        n_timesteps: Environment steps to sample (whole iterations: at least this many).
        env_runners: EnvRunner actors (0: sample in the driver).
        n_envs: Tables per EnvRunner (one ``PoolVectorEnv``).
        threads: Torch threads of the driver (the learner).
        final_episodes: Episodes of the final evaluation (0: none).
        baselines: Evaluate random, constant and ghost-ball next to the policy.
        env_kwargs: ``gymnasium.make`` keyword arguments.
        algo_kwargs: SB3 PPO keyword arguments (``hyperparams.yml``'s data form).
        sb3_n_envs: The file's ``n_envs``: one SB3 rollout (``n_steps`` x this) is one
            RLlib train batch.
    """

    env_id: str = "pool_env/OneBallRoll-v1"
    seed: int = 0
    n_timesteps: int = 300_000
    env_runners: int = 2
    n_envs: int = 64
    threads: int = 1
    final_episodes: int = 1000
    baselines: bool = True
    env_kwargs: dict[str, Any] = field(default_factory=dict)
    algo_kwargs: dict[str, Any] = field(default_factory=dict)
    sb3_n_envs: int = 8


def resolve_run(env_id: str, overrides: dict[str, Any], path: str | Path | None = None) -> RLlibRun:
    """The PPO entry of ``hyperparams.yml`` for ``env_id`` with command-line overrides.

    ``n_envs`` is not taken from the file (its value is SB3's number of envs, which sets
    the train batch); ``None`` overrides are ignored and ``algo_kwargs`` is merged over the
    file's.

    Raises:
        ValueError: On a negative ``env_runners``, a non-positive ``n_envs``, or algorithm
            keys RLlib's PPO cannot take.
    """
    run, algo_kwargs = hyperparams.split(hyperparams.load(env_id, "ppo", path))
    algo_kwargs.update(overrides.pop("algo_kwargs", None) or {})
    fields = {k: v for k, v in overrides.items() if v is not None}
    fields.setdefault("n_timesteps", run.get("n_timesteps", RLlibRun.n_timesteps))
    env_kwargs = {**(run.get("env_kwargs") or {}), **(fields.pop("env_kwargs", None) or {})}
    fields.setdefault("sb3_n_envs", int(run.get("n_envs", RLlibRun.sb3_n_envs)))
    if fields.get("env_runners", 0) < 0:
        raise ValueError(f"env_runners must be >= 0, got {fields['env_runners']}")
    if fields.get("n_envs", 1) < 1:
        raise ValueError(f"n_envs (tables per EnvRunner) must be >= 1, got {fields['n_envs']}")
    # Bad keys fail here, at the entry point, not later inside Ray's workers.
    rllib_training_kwargs(algo_kwargs, fields["n_timesteps"], fields["sb3_n_envs"])
    return RLlibRun(env_id=env_id, env_kwargs=env_kwargs, algo_kwargs=algo_kwargs, **fields)


def rllib_training_kwargs(
    algo_kwargs: dict[str, Any], n_timesteps: int, sb3_n_envs: int = 8
) -> dict[str, Any]:
    """SB3 PPO keyword arguments (data form) as ``PPOConfig.training`` keyword arguments.

    SB3's defaults fill the keys the entry leaves out. One SB3 rollout (``n_steps`` per env
    times ``sb3_n_envs`` envs) is one RLlib train batch; ``"lin_<x>"`` becomes a linear
    learning-rate schedule to 0 at ``n_timesteps``; there is no KL penalty (SB3 has none);
    ``policy_kwargs`` may give ``net_arch`` (a list) and ``activation_fn``; the keys of
    :data:`SB3_ONLY_POLICY_KWARGS` are left out.

    Raises:
        ValueError: On a key RLlib's PPO has no counterpart for, or a bad value.
    """
    kw = {**SB3_PPO_DEFAULTS, **algo_kwargs}
    policy_kwargs = dict(kw.pop("policy_kwargs", None) or {})
    for key in SB3_ONLY_POLICY_KWARGS:
        policy_kwargs.pop(key, None)
    out: dict[str, Any] = {rllib: kw.pop(sb3) for sb3, rllib in RLLIB_KEYS.items()}
    out["train_batch_size_per_learner"] = int(kw.pop("n_steps")) * int(sb3_n_envs)
    out["lr"] = _learning_rate(kw.pop("learning_rate"), n_timesteps)
    out["kl_coeff"] = 0.0
    out["use_kl_loss"] = False
    if kw:
        raise ValueError(f"PPO keys without an RLlib counterpart: {sorted(kw)}")
    net_arch = policy_kwargs.pop("net_arch", [64, 64])
    activation = policy_kwargs.pop("activation_fn", "tanh")
    if policy_kwargs:
        raise ValueError(
            f"policy_kwargs keys without an RLlib counterpart: {sorted(policy_kwargs)}"
        )
    if not (isinstance(net_arch, list) and all(isinstance(u, int) and u > 0 for u in net_arch)):
        raise ValueError(f"net_arch must be a list of layer sizes, got {net_arch!r}")
    if activation not in hyperparams.ACTIVATIONS:
        raise ValueError(
            f"unknown activation_fn {activation!r}: use one of {hyperparams.ACTIVATIONS}"
        )
    out["model"] = {"fcnet_hiddens": net_arch, "fcnet_activation": activation}
    return out


def _learning_rate(value: Any, n_timesteps: int) -> float | list[list[float]]:
    if isinstance(value, str):
        kind, _, number = value.partition("_")
        if kind == "lin" and number:
            return [[0, float(number)], [int(n_timesteps), 0.0]]
        try:
            return float(value)  # YAML 1.1 reads "1e-3" (no dot) as a string
        except ValueError:
            raise ValueError(f"learning_rate: unknown schedule {value!r}") from None
    return float(value)


def build_config(run: RLlibRun) -> Any:
    """The RLlib ``PPOConfig`` of ``run`` (registers the env creator with Ray first)."""
    # Ray (the rllib extra) is heavy: imported when a run is configured, not with this module.
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig

    register(run.env_id)
    training = rllib_training_kwargs(run.algo_kwargs, run.n_timesteps, run.sb3_n_envs)
    model = training.pop("model")
    return (
        PPOConfig()
        .environment(run.env_id, env_config={"env_kwargs": dict(run.env_kwargs)})
        .env_runners(
            num_env_runners=run.env_runners,
            num_envs_per_env_runner=run.n_envs,
            gym_env_vectorize_mode="vector_entry_point",
            num_cpus_per_env_runner=1,
        )
        .learners(num_learners=0)  # one learner, in the driver
        .training(**training)
        .rl_module(model_config=DefaultModelConfig(vf_share_layers=False, **model))
        .debugging(seed=run.seed)
    )


class RLlibPolicy:
    """A trained RLlib module with SB3's ``predict``, for :func:`agents.run_episodes`.

    The deterministic action is the mean of the Gaussian, clipped to the action box (what
    RLlib's module-to-env connector sends to the env).
    """

    def __init__(self, module: Any) -> None:
        self.module = module

    def predict(
        self, obs: NDArray[np.float32], state: Any = None, episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], None]:  # fmt: skip
        """The action for one observation (``deterministic=False`` samples the Gaussian)."""
        import torch  # heavy (the rllib extra): only when the policy acts

        with torch.no_grad():
            batch = {"obs": torch.as_tensor(np.asarray(obs, dtype=np.float32)[None])}
            logits = self.module.forward_inference(batch)["action_dist_inputs"]
            dist = self.module.get_inference_action_dist_cls().from_logits(logits)
            action = (dist.to_deterministic() if deterministic else dist).sample()
        return np.clip(action.numpy()[0], -1.0, 1.0).astype(np.float32), None


def train(run: RLlibRun, root: str | Path = "runs", address: str | None = None) -> Path:
    """Train PPO on RLlib, evaluate, write the run folder; return its path.

    Args:
        run: The run (see :func:`resolve_run`).
        root: Parent folder of run folders.
        address: Ray cluster to join; ``None``: ``RAY_ADDRESS`` if set, else a local Ray.

    Returns:
        The run folder.
    """
    import ray  # heavy (the rllib extra): only when a run starts

    out = runs.run_folder(root, run.env_id, "rllib_ppo", run.seed, run.n_timesteps)
    started_here = not ray.is_initialized()
    if started_here:
        ray.init(address=address)
    algo = build_config(run).build_algo()
    try:
        fit(algo, run, out)
    finally:
        algo.stop()
        if started_here:
            ray.shutdown()
    return out


def fit(algo: Any, run: RLlibRun, out: Path) -> int:
    """Train a built algorithm for ``run.n_timesteps`` and write ``out``'s files.

    Returns:
        The environment steps sampled (whole iterations).
    """
    import torch  # heavy (the rllib extra): only when a run starts

    # The learner's small MLP: torch's default of one thread per core makes the threads
    # fight each other and the EnvRunners on a small machine (15-20x slower measured with
    # SB3); Ray already starts each 1-CPU EnvRunner with OMP_NUM_THREADS=1.
    torch.set_num_threads(run.threads)
    (out / "config.yaml").write_text(yaml.safe_dump(asdict(run), sort_keys=False))
    runs.write_command(out)
    t0 = time.perf_counter()
    lines = ["iteration,env_steps,seconds,episode_return_mean,episodes"]
    steps = 0
    while steps < run.n_timesteps:
        result = algo.train()
        runners = result["env_runners"]
        steps = int(runners["num_env_steps_sampled_lifetime"])
        ret = float(runners.get("episode_return_mean", math.nan))
        seconds = time.perf_counter() - t0
        lines.append(
            f"{result['training_iteration']},{steps},{seconds:.1f},{ret:.4f},"
            f"{int(runners.get('num_episodes', 0))}"
        )
        print(f"iteration {result['training_iteration']:>4}  {steps:>9,} steps  "
              f"{seconds:6.0f} s  return {ret:+.3f}", flush=True)  # fmt: skip
    train_seconds = time.perf_counter() - t0
    (out / "progress.csv").write_text("\n".join(lines) + "\n")
    algo.save_to_path(str((out / "checkpoint").resolve()))
    _evaluate(run, RLlibPolicy(algo.get_module()), out, steps, train_seconds)
    return steps


def _evaluate(run: RLlibRun, policy: RLlibPolicy, out: Path, steps: int, seconds: float) -> None:
    """The final table: the policy next to the baselines on the same seeds."""
    report = {"env_id": run.env_id, "backend": "rllib", "n_timesteps": steps,
              "train_seconds": round(seconds, 1)}  # fmt: skip
    text = f"# PPO (RLlib) on {run.env_id}, {steps:,} steps\n\n"
    text += f"Command: `{(out / 'command.txt').read_text().strip()}`\n\n"
    if run.final_episodes > 0:
        n, kw = run.final_episodes, run.env_kwargs
        rows = {"ppo (rllib)": evaluate_agent("ppo (rllib)", run.env_id, n, FINAL_SEED, kw,
                                              None, agent=policy)}  # fmt: skip
        if run.baselines:
            for name in ("random", "const", "ghost"):
                rows[name] = evaluate_agent(name, run.env_id, n, FINAL_SEED, kw, None)
        table = format_table(rows, n)
        report["final_seed"], report["episodes"] = FINAL_SEED, n
        report["results"] = {
            agent: {k: [e.value, e.low, e.high] for k, e in stats.items()}
            for agent, stats in rows.items()
        }
        text += table + "\n\n"
        print(f"\nPPO (RLlib) on {run.env_id} after {steps:,} steps\n{table}\n\n{one_line(rows)}")
    text += f"Training {seconds:.0f} s with {run.env_runners} EnvRunners x {run.n_envs} tables.\n"
    (out / "evaluation.json").write_text(json.dumps(report, indent=2) + "\n")
    (out / "evaluation.md").write_text(text)
    print(f"\nTraining took {seconds:.0f} s. Run folder: {out}")
