"""Training on Stable-Baselines3: vectorized envs, periodic evaluation, a folder per run.

:func:`train` is everything ``train.py`` does: it resolves the hyperparameters of
``hyperparams.yml`` for the env id and algorithm, builds the vectorized environment, trains
with SB3's progress bar and tensorboard logging, evaluates every ``eval_freq`` steps (pot
rate, clean pots, scratches on fixed seeds), and writes into its run folder: ``config.yaml``,
``command.txt``, ``model.zip``, ``evaluation.md`` / ``evaluation.json`` (the model next to
the baselines on the same seeds: random, the best constant action, the geometric ghost-ball
agent and the simulator search), ``curve.csv`` and ``learning_curve.png`` (the baselines
drawn as horizontal lines). The kernels are compiled (or loaded from numba's cache) before
the clock starts, and periodic evaluations are timed apart, so the reported training time
is learning only. What defines a run (:class:`TrainConfig`, :func:`resolve_config`,
:data:`ALGOS`) is :mod:`agents.training.run_config`.
"""

from __future__ import annotations

import json
import time
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import asdict
from pathlib import Path

import numpy as np
import yaml
from stable_baselines3.common.base_class import BaseAlgorithm
from stable_baselines3.common.callbacks import BaseCallback, ProgressBarCallback
from stable_baselines3.common.env_util import make_vec_env
from stable_baselines3.common.off_policy_algorithm import OffPolicyAlgorithm
from stable_baselines3.common.on_policy_algorithm import OnPolicyAlgorithm
from stable_baselines3.common.type_aliases import TrainFrequencyUnit
from stable_baselines3.common.vec_env import (
    DummyVecEnv,
    SubprocVecEnv,
    VecEnv,
    VecEnvWrapper,
    VecMonitor,
)

from agents.evaluation.constant_scan import best_constant_agent, lattice_size
from agents.evaluation.episodes import run_episodes
from agents.evaluation.evaluate import evaluate_agent
from agents.evaluation.metrics import Estimate
from agents.evaluation.table import format_table, one_line
from agents.learned.candidates import FirstRowAgent
from agents.learned.envs import EnvFactory, make_env
from agents.training import hyperparams, runs
from agents.training.hyperparams import VEC_KINDS
from agents.training.run_config import ALGOS, TrainConfig, training_env_kwargs
from agents.training.run_config import FINAL_BASELINES as FINAL_BASELINES  # re-exported
from agents.training.run_config import resolve_config as resolve_config  # re-exported
from agents.training.vec_features import (
    GhostCandidatesVecEnv,
    GhostFeaturesVecEnv,
    PositionCandidatesVecEnv,
)
from agents.training.warm_start import LAYOUTS as WARM_LAYOUTS
from agents.training.warm_start import warm_start

#: Observation wrappers the native vector env can apply (by ``wrapper`` name): the same
#: features as the ``gym.Env`` wrapper of that name (:data:`agents.learned.envs.WRAPPERS`),
#: which the evaluation envs use.
NATIVE_WRAPPERS: dict[str, type[VecEnvWrapper]] = {
    "ghost_features": GhostFeaturesVecEnv,
    "ghost_candidates": GhostCandidatesVecEnv,
    "position_candidates": PositionCandidatesVecEnv,
}

#: Seeds of the periodic evaluation and of the final one: apart from each other, so that
#: nothing is tuned on the final numbers, and from the training envs' own streams.
EVAL_SEED = 20_000
FINAL_SEED = 10_000

#: Shots the best-constant scan may play: its episodes per action are this over the
#: lattice's size, at most the final evaluation's (81 actions on a roll id: 1000 each; 729
#: with a spin id's tip: 137 each, about 20 s, where 1000 each took minutes).
SCAN_SHOTS = 100_000

#: The final evaluation's episodes when the config leaves them to the run: one per
#: :data:`STEPS_PER_FINAL_EPISODE` steps trained, within ``[MIN, MAX]`` (runs of 200k steps
#: and more: 1000 episodes; a 16k-step smoke run: 100).
MIN_FINAL_EPISODES, MAX_FINAL_EPISODES = 100, 1000
STEPS_PER_FINAL_EPISODE = 200


def trained_steps(model: BaseAlgorithm, n_timesteps: int) -> int:
    """The steps ``model.learn(n_timesteps)`` trains: whole rollouts, not ``n_timesteps``.

    SB3 collects a rollout of ``n_steps`` on each of the ``n_envs`` envs before it checks
    the count (PPO with 2048 x 8 trains 16,384 steps when 100 are asked); an off-policy
    algorithm ``train_freq`` steps of every env (one env step where it counts episodes).
    """
    if isinstance(model, OnPolicyAlgorithm):
        batch = model.n_steps * model.n_envs
    elif isinstance(model, OffPolicyAlgorithm) and model.train_freq.unit == TrainFrequencyUnit.STEP:
        batch = model.train_freq.frequency * model.n_envs
    else:
        batch = model.n_envs
    return -(-n_timesteps // batch) * batch


def final_episodes(config: TrainConfig, steps: int) -> int:
    """The final evaluation's episodes: the config's, or sized to the ``steps`` trained."""
    if config.final_episodes is not None:
        return config.final_episodes
    return min(MAX_FINAL_EPISODES, max(MIN_FINAL_EPISODES, steps // STEPS_PER_FINAL_EPISODE))


class StepsBar(ProgressBarCallback):
    """SB3's progress bar, its total the steps that will be trained (:func:`trained_steps`).

    SB3's own counts to the steps asked, so a run of 800,000 ended at 802,816/800,000.
    """

    def __init__(self, total: int) -> None:
        super().__init__()
        self.total = total

    def _on_training_start(self) -> None:
        from stable_baselines3.common import callbacks  # its tqdm: rich's, or None
        from tqdm import TqdmExperimentalWarning

        with warnings.catch_warnings():  # SB3's bar: tqdm's rich front is "experimental"
            warnings.simplefilter("ignore", TqdmExperimentalWarning)
            self.pbar = callbacks.tqdm(total=self.total - self.model.num_timesteps)


@contextmanager
def progress(bar: bool, what: str, total: int, unit: str) -> Iterator[Callable[[int], object]]:
    """Show the progress of ``total`` ``unit``s of work: a bar, or a line at the start and end.

    Yields:
        The ``update(n)`` to call as the work goes.
    """
    t0 = time.perf_counter()
    if bar:
        from tqdm import tqdm

        with tqdm(total=total, desc=what, unit=unit, leave=True) as pbar:
            yield pbar.update
        return
    print(f"{what}: {total:,} {unit}s ...", flush=True)
    yield lambda n: None
    print(f"{what}: done in {time.perf_counter() - t0:.0f} s", flush=True)


def make_vec(config: TrainConfig, n_envs: int | None = None, seed: int | None = None) -> VecEnv:
    """The training ``VecEnv`` of ``config`` (episode statistics monitored).

    Its envs take :func:`~agents.training.run_config.training_env_kwargs` (the recipe's
    training-time reward terms included); the evaluations build theirs from
    ``config.env_kwargs`` alone.

    Raises:
        ValueError: On an unknown kind, or a wrapper the native kind cannot apply.
        ImportError: For ``native`` when ``agents.vec.native_vec`` is not installed.
    """
    n = n_envs or config.n_envs
    seed = config.seed if seed is None else seed
    if config.vec == "native":
        if config.wrapper and config.wrapper not in NATIVE_WRAPPERS:
            raise ValueError(
                f"--vec native applies only the wrappers {sorted(NATIVE_WRAPPERS)}, not "
                f"{config.wrapper!r}; use --vec dummy"
            )
        try:  # optional: the native adapter is the one VecEnv this module does not need
            from agents.vec.native_vec import make_native_vec_env
        except ImportError as exc:
            raise ImportError(
                "--vec native needs agents/vec/native_vec.py (make_native_vec_env), which is not "
                f"available here ({exc}); use --vec dummy or --vec subproc"
            ) from exc
        kwargs = training_env_kwargs(config)
        venv = VecMonitor(make_native_vec_env(config.env_id, n, seed, kwargs or None))
        return NATIVE_WRAPPERS[config.wrapper](venv) if config.wrapper else venv
    if config.vec not in VEC_KINDS:
        raise ValueError(f"--vec must be one of {VEC_KINDS}, got {config.vec!r}")
    factory = EnvFactory(config.env_id, training_env_kwargs(config), config.wrapper)
    cls = SubprocVecEnv if config.vec == "subproc" else DummyVecEnv
    return make_vec_env(factory, n_envs=n, seed=seed, vec_env_cls=cls)


class PeriodicEval(BaseCallback):
    """Evaluate the model every ``eval_freq`` steps on fixed seeds; log and keep the curve.

    Args:
        config: The run's config (which env to build).
        history: List the results are appended to: ``(timesteps, seconds, summary)``, the
            seconds of wall time since the process started, periodic evaluations excluded.
    """

    def __init__(self, config: TrainConfig, history: list[tuple[int, float, dict]]) -> None:
        super().__init__()
        self.config = config
        self.history = history
        self.env = make_env(config.env_id, config.env_kwargs, config.wrapper)
        self.next_eval = 0
        self.eval_seconds = 0.0  # spent evaluating, to keep out of the training time

    def _evaluate(self) -> None:
        # The point's time: wall seconds since the process started (what a user waits from
        # typing the command), less the evaluations so far, which a run without them skips.
        seconds = runs.process_seconds() - self.eval_seconds
        t0 = time.perf_counter()
        summary = run_episodes(self.model, self.env, self.config.eval_episodes, EVAL_SEED).summary()
        self.eval_seconds += time.perf_counter() - t0
        self.history.append((self.num_timesteps, seconds, summary))
        for key in ("pots_per_shot", "clean_pot_rate", "scratch_rate", "episode_reward"):
            self.logger.record(f"eval/{key}", summary[key].value)
        self.logger.dump(self.num_timesteps)
        print(eval_line(self.num_timesteps, self.history[-1][1], summary), flush=True)

    def _on_training_start(self) -> None:
        self._evaluate()  # the untrained policy: the curve's first point
        self.next_eval = self.num_timesteps + self.config.eval_freq

    def _on_step(self) -> bool:
        if self.num_timesteps >= self.next_eval:
            self._evaluate()
            self.next_eval += self.config.eval_freq
        return True

    def _on_training_end(self) -> None:
        if not self.history or self.history[-1][0] != self.num_timesteps:
            self._evaluate()
        self.env.close()


def eval_line(steps: int, seconds: float, summary: dict[str, Estimate]) -> str:
    """A periodic evaluation in one line: the pot rate (a game id: racks won too)."""
    won = f"  racks won {summary['clear_rate']}" if "fouls_per_shot" in summary else ""
    return (
        f"{steps:>9,} steps {seconds:6.0f} s  pots/shot {summary['pots_per_shot']}  "
        f"clean {summary['clean_pot_rate']}  scratch {summary['scratch_rate']}{won}"
    )


def run_folder(root: str | Path, config: TrainConfig) -> Path:
    """A new folder ``root/<env>/<algo>_s<seed>_<steps>_<time>`` for one run."""
    return runs.run_folder(root, config.env_id, config.algo, config.seed, config.n_timesteps)


def warm_up(config: TrainConfig) -> float:
    """Compile (or load from numba's cache) every kernel a run uses; return the seconds.

    One step of a throwaway training env and of an evaluation env, with their own seeds,
    so the run's own environments and random streams are untouched.
    """
    t0 = time.perf_counter()
    vec = make_vec(config, n_envs=1, seed=config.seed + 1_000_003)
    vec.reset()
    vec.step(np.zeros((1, *vec.action_space.shape), dtype=np.float32))
    vec.close()
    env = make_env(config.env_id, config.env_kwargs, config.wrapper)
    env.reset(seed=0)
    env.step(np.zeros(env.action_space.shape, dtype=np.float32))
    env.close()
    return time.perf_counter() - t0


def train(config: TrainConfig, root: str | Path = "runs", quiet: bool = False) -> Path:
    """Train, evaluate and write a run folder; return its path.

    Args:
        config: The run (see :func:`~agents.training.run_config.resolve_config`).
        root: Parent folder of run folders.
        quiet: Print nothing but the final table.

    Returns:
        The run folder.
    """
    import torch  # heavy (the train extra): only when a run starts

    # Why one thread: the policy is a small MLP, and torch's default (one thread per core)
    # spends more on synchronising threads than on the matrix products; on the 2-core
    # machine third-party trainers left at the default ran 15-20x slower (34-52 steps/s
    # against ~730; RL Zoo 61 fps against 628 with --num-threads 1, measured).
    torch.set_num_threads(config.threads)
    t0 = time.perf_counter()
    out = run_folder(root, config)
    (out / "config.yaml").write_text(yaml.safe_dump(asdict(config), sort_keys=False))
    runs.write_command(out)

    compile_seconds = warm_up(config)
    env = make_vec(config)
    model = ALGOS[config.algo](
        config.policy,
        env,
        seed=config.seed,
        device="cpu",
        verbose=0,
        tensorboard_log=str(out / "tb"),
        **hyperparams.to_sb3(config.algo_kwargs),
    )
    steps = trained_steps(model, config.n_timesteps)
    if not quiet:
        print(f"Ready in {compile_seconds:.1f} s; {steps_line(model, config, steps)}", flush=True)
    if config.warm_start:
        t_warm = time.perf_counter()
        loss = warm_start(model, config.warm_start, config.env_id, config.env_kwargs)
        if not quiet:
            print(
                f"Warm start {config.warm_start!r}: the policy's action fitted to it on "
                f"{WARM_LAYOUTS:,} layouts in {time.perf_counter() - t_warm:.0f} s (mean "
                f"squared error {loss:.2g})",
                flush=True,
            )
    history: list[tuple[int, float, dict]] = []
    callback = PeriodicEval(config, history) if config.eval_freq > 0 else None
    callbacks: list[BaseCallback] = [c for c in (callback,) if c is not None]
    if config.progress_bar:
        callbacks.append(StepsBar(steps))
    t_train = time.perf_counter()
    model.learn(config.n_timesteps, callback=callbacks)
    eval_seconds = callback.eval_seconds if callback is not None else 0.0
    train_seconds = time.perf_counter() - t_train - eval_seconds
    env.close()
    model.save(out / "model.zip")

    n_final = final_episodes(config, steps)
    rows, best_const = _final_evaluation(config, model, n_final, steps)
    from agents.training.plots import learning_curve  # matplotlib only now

    _write_curve(out, history)
    learning_curve(out / "learning_curve.png", history, rows, config)
    total = time.perf_counter() - t0
    table = format_table(rows, n_final)
    report = {
        "env_id": config.env_id,
        "algo": config.algo,
        "n_timesteps": config.n_timesteps,
        "trained_steps": steps,
        "train_seconds": round(train_seconds, 1),
        "periodic_eval_seconds": round(eval_seconds, 1),
        "compile_seconds": round(compile_seconds, 1),
        "total_seconds": round(total, 1),
        "process_seconds": round(runs.process_seconds(), 1),
        "best_const_action": best_const,
        "final_seed": FINAL_SEED,
        "episodes": n_final,
        "results": {agent: _as_dict(stats) for agent, stats in rows.items()},
    }
    (out / "evaluation.json").write_text(json.dumps(report, indent=2) + "\n")
    (out / "evaluation.md").write_text(
        f"# {config.algo.upper()} on {config.env_id}, {steps:,} steps\n\n"
        f"Command: `{(out / 'command.txt').read_text().strip()}`\n\n{table}\n\n"
        f"Training {train_seconds:.0f} s (periodic evaluation {eval_seconds:.0f} s, compiling "
        f"{compile_seconds:.0f} s), total {total:.0f} s.{_best_const_note(best_const)}\n"
    )
    print(f"\n{config.algo.upper()} on {config.env_id} after {steps:,} steps")
    print(table)
    if best_const is not None:
        print(_best_const_note(best_const).strip())
    print("\n" + one_line(rows))
    if history:
        print(climb_line(history, out))
    if not quiet:
        print(
            f"\nTraining took {train_seconds:.0f} s (plus {eval_seconds:.0f} s of periodic "
            f"evaluation and {compile_seconds:.0f} s compiling; {total:.0f} s in all). "
            f"Run folder: {out}"
        )
    return out


def steps_line(model: BaseAlgorithm, config: TrainConfig, steps: int) -> str:
    """``training 16,384 steps (100 asked: ...)``: the steps that will be trained, and why."""
    if steps == config.n_timesteps:
        return f"training {steps:,} steps"
    if isinstance(model, OnPolicyAlgorithm):
        how = f"whole rollouts of {model.n_steps:,} steps on each of {model.n_envs} envs"
    else:
        how = f"steps of all {model.n_envs} envs at once"
    asked = f"{config.n_timesteps:,} asked: {config.algo.upper()} trains {how}"
    return f"training {steps:,} steps ({asked})"


def _final_evaluation(
    config: TrainConfig, model: BaseAlgorithm, n: int, steps: int
) -> tuple[dict[str, dict], list[float] | None]:
    """The model and (optionally) the final baselines on the same ``n`` final seeds.

    The baselines: ``config.final_baselines``
    (:data:`~agents.training.run_config.FINAL_BASELINES` by default); the best-constant
    scan is left out when it would play more shots than the ``steps`` trained (a short run:
    the scan would be most of the command's time). Each row shows its progress.

    Returns:
        The rows by agent name, and the best constant action (``None`` without it).
    """
    kw, wrap, bar = config.env_kwargs, config.wrapper, config.progress_bar
    probe = make_env(config.env_id, kw)
    scan_shots = lattice_size(probe) * max(1, min(n, SCAN_SHOTS // lattice_size(probe)))
    probe.close()
    names = list(config.final_baselines) if config.baselines else []
    skipped = ""
    if "best-const" in names and scan_shots > steps:
        names.remove("best-const")
        skipped = (
            f" best-const left out: its scan would play {scan_shots:,} shots, more than the "
            f"{steps:,} trained."
        )
    first_row = config.baselines and (
        ((kw or {}).get("observation") == "shots" and wrap is None) or wrap == "ghost_candidates"
    )
    listed = ", ".join([config.algo, *names, *(["first-row"] if first_row else [])])
    print(
        f"\nFinal evaluation: {n:,} episodes each of {listed} (--final-episodes N for another "
        f"number, --no-baselines for the model alone).{skipped}",
        flush=True,
    )

    def play(name: str, wrapper: str | None = None, agent: object = None) -> dict:
        with progress(bar, f"final: {name}", n, "episode") as update:
            return evaluate_agent(
                name, config.env_id, n, FINAL_SEED, kw, wrapper, agent=agent, progress=update
            )

    name = f"{config.algo} (this run)"
    rows = {name: play(name, wrap, model)}
    best_const = None
    for name in names:  # baselines read the raw observation: no wrapper, same layouts
        agent = None
        if name == "best-const":  # scanned on its own seeds, then evaluated on these
            scan_env = make_env(config.env_id, kw)
            size = lattice_size(scan_env)
            per_action = max(1, min(n, SCAN_SHOTS // size))
            what = f"best-const scan ({per_action:,} episodes each)"
            with progress(bar, what, size, "action") as update:
                agent = best_constant_agent(scan_env, episodes=per_action, progress=update)
            scan_env.close()
            best_const = [float(v) for v in agent.action]
        rows[name] = play(name, None, agent)
    if first_row and wrap is None:  # the "shots" observation's trivial policy
        rows["first-row"] = play("first-row")
    elif first_row:  # the trivial candidate policy: row 0, no residual
        probe = make_env(config.env_id, kw, wrap)
        agent = FirstRowAgent(probe.n_rows)
        probe.close()
        rows["first-row"] = play("first-row", wrap, agent)
    return rows, best_const


def climb_line(history: list[tuple[int, float, dict]], out: Path) -> str:
    """What training did, from the periodic evaluations: first and last, and the curve's file.

    The first evaluation is the untrained policy's, the last the trained one's (the same
    ``EVAL_SEED`` episodes, apart from the final table's).
    """
    (steps0, _, first), (steps1, seconds, last) = history[0], history[-1]
    start, end = first["pots_per_shot"], last["pots_per_shot"]
    return (
        f"Learning: pots per shot {start.value:.1%} untrained (step {steps0:,}), "
        f"{end.value:.1%} after {steps1:,} steps ({100 * (end.value - start.value):+.1f} "
        f"points, {seconds:.0f} s after the command started); the curve: "
        f"{out / 'learning_curve.png'} (data: curve.csv)"
    )


def _best_const_note(action: list[float] | None) -> str:
    if action is None:
        return ""
    # Every component: on a spin id the scan also crosses a grid of cue tips.
    values = ", ".join(f"{a:+.2f}" for a in action)
    return f" best-const: the action ({values}), the best of a grid scan of constant actions."


def _as_dict(stats: dict[str, Estimate]) -> dict[str, list[float]]:
    return {key: [est.value, est.low, est.high] for key, est in stats.items()}


def _write_curve(out: Path, history: list[tuple[int, float, dict]]) -> None:
    # clear_rate last: the readers of the first columns by position stay as they were.
    keys = ("pots_per_shot", "clean_pot_rate", "scratch_rate", "episode_reward", "clear_rate")
    lines = ["timesteps,seconds," + ",".join(keys)]
    for steps, seconds, summary in history:
        values = ",".join(f"{summary[k].value:.4f}" for k in keys)
        lines.append(f"{steps},{seconds:.1f},{values}")
    (out / "curve.csv").write_text("\n".join(lines) + "\n")
