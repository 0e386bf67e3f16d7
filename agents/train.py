"""Train an SB3 agent on a pool environment; a thin command line over ``agents.training``.

Three names for one command: ``python train.py`` in a clone, ``python -m agents.train`` or
the console script ``pool-env-train`` wherever the package is installed (the hyperparameter
file ships with it). With no arguments it trains PPO on ``pool_env/OneBall-v1`` (the spin
table, one ball, the env's own action: aim, speed and cue tip) with the env's ``"shots"``
observation and the hyperparameters of ``agents/training/hyperparams.yml`` (800k steps over
the native vector env, under five minutes on two cores with the first compile), then
prints its pot rate next to random, the best constant action, the geometry played exactly
(``first-row``) and the ghost-ball agent on the same layouts, and the climb from the
untrained policy's evaluation to the last. ``--recipe candidates`` on ``pool_env/OneBallRoll-v1`` is
the earlier default: PPO picking and refining ghost-ball candidate shots
(:mod:`agents.learned.candidates`), skilled from its first evaluation because the
candidates carry the geometry. Each run writes
``runs/<env>/<algo>_s<seed>_<steps>_<time>/``: config.yaml, command.txt, model.zip,
evaluation.md/.json, curve.csv, learning_curve.png and tensorboard logs (tb/).

With ``--backend rllib`` it trains PPO on Ray RLlib instead
(:mod:`agents.integrations.rllib_train`): EnvRunners sample in parallel, each with its own
batch of tables, on this machine or on every node of the Ray cluster that ``RAY_ADDRESS`` names.

Examples::

    python train.py
    python train.py --env pool_env/OneBallRoll-v1 --recipe candidates
    python train.py --backend rllib --env-runners 2 --timesteps 50000
    python train.py --algo sac --timesteps 300000
    python train.py --timesteps 1000000 --seed 1 --set learning_rate=lin_1e-3 n_epochs=20
    tensorboard --logdir runs
"""

from __future__ import annotations

import argparse
import sys
from typing import Any

# Light imports only: the trainer (stable-baselines3, torch, Ray) loads after the first line
# printed, which says what the command waits for.
from agents.learned.pretrained import ALGO_CLASSES
from agents.training.hyperparams import VEC_KINDS, WARM_STARTS
from pool_env.extras import require

#: What ``python train.py`` trains on with no ``--env``.
DEFAULT_ENV = "pool_env/OneBall-v1"


def parse_sets(items: list[str]) -> dict[str, Any]:
    """``["key=value", ...]`` to a dict; values are parsed as YAML data (never evaluated)."""
    yaml = require("yaml", "train", "python train.py")
    out: dict[str, Any] = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key:
            raise ValueError(f"--set expects key=value, got {item!r}")
        out[key] = yaml.safe_load(value)
    return out


def build_parser() -> argparse.ArgumentParser:
    """The command line (every option defaults to the hyperparameter file's value)."""
    p = argparse.ArgumentParser(
        description=__doc__.split("\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter
    )
    p.add_argument("--env", default=DEFAULT_ENV, help="registered env id")
    p.add_argument(
        "--backend", default="sb3", choices=("sb3", "rllib"), help="trainer (rllib: PPO only)"
    )
    p.add_argument("--env-runners", type=int, default=2, help="rllib: EnvRunner actors")
    p.add_argument("--address", help="rllib: Ray cluster address (default: RAY_ADDRESS or local)")
    p.add_argument("--algo", default="ppo", choices=sorted(ALGO_CLASSES))
    p.add_argument(
        "--recipe",
        help="a named entry of the hyperparameter file, <algo>-<recipe> under the env id "
        "(e.g. candidates: PPO picking ghost-ball candidate shots on pool_env/OneBallRoll-v1)",
    )
    p.add_argument("--timesteps", type=int, help="training steps (default: from the YAML)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument(
        "--n-envs", type=int, help="parallel envs (default: YAML; rllib: 64 tables per runner)"
    )
    p.add_argument(
        "--vec", choices=VEC_KINDS, help="vectorized env kind (default: YAML, else dummy)"
    )
    p.add_argument("--threads", type=int, default=1, help="torch threads (1 is fastest here)")
    p.add_argument("--eval-freq", type=int, help="steps between evaluations (0: none)")
    p.add_argument("--eval-episodes", type=int, help="episodes per periodic evaluation")
    p.add_argument(
        "--final-episodes",
        type=int,
        help="episodes of the final evaluation, the model's and each baseline's (default: "
        "sized to the run, a hundredth of the steps trained, 100 to 1000)",
    )
    p.add_argument(
        "--no-baselines",
        action="store_true",
        help="skip the baselines of the final evaluation (random, best-const, ghost, ...)",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--aim", help="env aim mode override (cut, relative, absolute)")
    p.add_argument(
        "--env-kwargs", help='gymnasium.make kwargs as YAML, e.g. "{noise: [0.003, 0.05]}"'
    )
    p.add_argument(
        "--train-rewards",
        help='reward scales of the training envs only, as YAML, e.g. "{scratch: -3.0}" '
        "(reward_scratch -3 while training; every evaluation plays the env's own reward)",
    )
    p.add_argument(
        "--warm-start",
        choices=(*WARM_STARTS, "none"),
        help="before RL, fit the policy's action to this baseline's (first-row: row 0 of "
        'the "shots" observation, played exactly; none: no warm start, over the recipe\'s)',
    )
    p.add_argument(
        "--wrapper",
        help="wrapper: ghost_candidates (the candidates recipe: features and candidate-shot "
        "actions), ghost_features (SAC's), pocket_features, none",
    )
    p.add_argument("--hyperparams", help="YAML file (default: agents/training/hyperparams.yml)")
    p.add_argument("--runs", default="runs", help="parent folder of run folders")
    p.add_argument("--set", nargs="*", default=[], metavar="KEY=VALUE", help="algorithm kwargs")
    return p


def first_line(env_id: str, algo: str, backend: str) -> str:
    """What the command is about to do, and what it waits for before training starts."""
    trainer = "Ray RLlib" if backend == "rllib" else "Stable-Baselines3"
    return (
        f"Training {algo.upper()} ({trainer}) on {env_id}. First the trainer loads and the "
        "simulator compiles what it needs for this machine (tens of seconds, on the first "
        "run only, and none after `python -m pool_env.precompile`: later runs load it from "
        "the disk cache in about a second)."
    )


#: Options that count something: each must be at least this (``--eval-freq 0``: none).
MINIMUMS = {
    "timesteps": 1, "n_envs": 1, "threads": 1, "eval_freq": 0, "eval_episodes": 1,
    "final_episodes": 1, "env_runners": 1,
}  # fmt: skip


def main(argv: list[str] | None = None) -> int:
    """Parse, check, resolve the config, train; print the final comparison.

    Every value is checked before the trainer loads (the env id, its keyword arguments,
    the wrapper) or before anything trains (``--set`` against the algorithm's
    constructor): a bad one exits with status 2 and one line naming it (``parser.error``).
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    for name, least in MINIMUMS.items():
        value = getattr(args, name)
        if value is not None and value < least:
            parser.error(f"--{name.replace('_', '-')} must be >= {least}, got {value}")
    if args.backend == "rllib":
        require("ray.rllib", "rllib", "python train.py --backend rllib")
    else:
        require("stable_baselines3", "train", "python train.py")
    try:
        algo_kwargs = parse_sets(args.set)
    except ValueError as exc:
        parser.error(str(exc))
    yaml = require("yaml", "train", "python train.py")
    extra = _yaml_mapping(parser, yaml, "--env-kwargs", args.env_kwargs or None) or {}
    train_rewards = _yaml_mapping(parser, yaml, "--train-rewards", args.train_rewards)
    if args.aim:
        extra["aim"] = args.aim
    wrapper = None if args.wrapper in (None, "none") else args.wrapper
    _check_env(parser, args.env, extra, wrapper)
    print(first_line(args.env, args.algo, args.backend), flush=True)
    if args.backend == "rllib":
        return _train_rllib(parser, args, algo_kwargs, extra)
    overrides: dict[str, Any] = {
        "seed": args.seed,
        "n_timesteps": args.timesteps,
        "n_envs": args.n_envs,
        "vec": args.vec,
        "threads": args.threads,
        "eval_freq": args.eval_freq,
        "eval_episodes": args.eval_episodes,
        "final_episodes": args.final_episodes,
        "baselines": not args.no_baselines,
        "progress_bar": not args.no_progress,
        "train_rewards": train_rewards,
        "warm_start": None if args.warm_start == "none" else args.warm_start,
        "algo_kwargs": algo_kwargs,
    }
    from agents.training import hyperparams
    from agents.training.run_config import (
        check_warm_start,
        resolve_config,
        training_env_kwargs,
    )
    from agents.training.train_lib import NATIVE_WRAPPERS, train

    try:
        config = resolve_config(args.env, args.algo, overrides, args.hyperparams, args.recipe)
        hyperparams.to_sb3(config.algo_kwargs)  # schedules and activations by name
    except KeyError as exc:
        parser.error(str(exc.args[0]))
    except ValueError as exc:
        parser.error(str(exc))
    config.env_kwargs = {**config.env_kwargs, **extra}
    if args.warm_start == "none":
        config.warm_start = None
    if args.wrapper:
        config.wrapper = wrapper
        native_ok = config.wrapper is None or config.wrapper in NATIVE_WRAPPERS
        if config.vec == "native" and not native_ok and not args.vec:
            config.vec = "dummy"  # the native vector env cannot apply this Python wrapper
    _check_env(parser, config.env_id, config.env_kwargs, config.wrapper)  # with the entry's
    try:  # the training envs' keywords too: a reward term the env has not is named
        train_kwargs = training_env_kwargs(config)
        check_warm_start(config.warm_start, config.wrapper)  # after --wrapper's override
    except ValueError as exc:
        parser.error(str(exc))
    _check_env(parser, config.env_id, train_kwargs, config.wrapper)
    train(config, root=args.runs)
    return 0


def _yaml_mapping(
    parser: argparse.ArgumentParser, yaml: Any, flag: str, text: str | None
) -> dict[str, Any] | None:
    """The YAML mapping ``text`` of option ``flag`` (``None`` when not given); else exit 2."""
    if text is None:
        return None
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError as exc:
        parser.error(f"{flag} {text!r} is not YAML: {' '.join(str(exc).split())}")
    if not isinstance(value, dict):
        parser.error(f"{flag} must be a YAML mapping, got {text!r}")
    return value


def _check_env(
    parser: argparse.ArgumentParser, env_id: str, env_kwargs: dict[str, Any], wrapper: str | None
) -> None:
    """Make the env once, as the run will: an unknown id, key, value or wrapper exits 2."""
    from agents.learned.envs import make_env  # Gymnasium and pool_env: no trainer yet

    try:
        make_env(env_id, env_kwargs, wrapper).close()
    except ValueError as exc:
        parser.error(str(exc))


def _train_rllib(
    parser: argparse.ArgumentParser,
    args: argparse.Namespace,
    algo_kwargs: dict[str, Any],
    env_kwargs: dict[str, Any],
) -> int:
    """``--backend rllib``: PPO on Ray RLlib with the same hyperparameter file."""
    if args.algo != "ppo":
        parser.error("--backend rllib trains PPO only")
    if args.vec or args.wrapper or args.recipe or args.train_rewards or args.warm_start:
        parser.error(
            "--backend rllib always samples the native vector env with its own entry: no "
            "--vec/--wrapper/--recipe/--train-rewards/--warm-start"
        )
    overrides: dict[str, Any] = {
        "seed": args.seed,
        "n_timesteps": args.timesteps,
        "env_runners": args.env_runners,
        "n_envs": args.n_envs,
        "threads": args.threads,
        "final_episodes": args.final_episodes,
        "baselines": not args.no_baselines,
        "env_kwargs": env_kwargs,
        "algo_kwargs": algo_kwargs,
    }
    from agents.integrations.rllib_train import resolve_run
    from agents.integrations.rllib_train import train as train_rllib

    try:
        run = resolve_run(args.env, overrides, args.hyperparams)
    except (KeyError, ValueError) as exc:
        parser.error(str(exc))
    train_rllib(run, root=args.runs, address=args.address)
    return 0


if __name__ == "__main__":
    sys.exit(main())
