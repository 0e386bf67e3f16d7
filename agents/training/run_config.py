"""What defines a training run: its config, the algorithms by name, and their resolution.

:class:`TrainConfig` is everything a run is made of (saved as its ``config.yaml``);
:func:`resolve_config` builds one from ``hyperparams.yml`` and the command line's
overrides; :data:`ALGOS` holds the algorithms by the name used in both.
:mod:`agents.training.train_lib` trains one.
"""

from __future__ import annotations

import difflib
import inspect
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from stable_baselines3.common.base_class import BaseAlgorithm

from agents.evaluation.players import is_game
from agents.learned.envs import make_env
from agents.learned.pretrained import ALGO_CLASSES, algo_class
from agents.training import hyperparams

#: Algorithms by the name used in ``hyperparams.yml`` and on the command line.
ALGOS: dict[str, type[BaseAlgorithm]] = {name: algo_class(name) for name in ALGO_CLASSES}

#: Baselines of the final evaluation, in the order printed (see :mod:`agents.evaluation.evaluate`).
FINAL_BASELINES = ("random", "best-const", "ghost", "search")

#: The final baselines of a game id (a rack by the rules) without its own entry: a constant
#: action means nothing over a rack, and the search takes about 2 s a 9-ball rack (half an
#: hour for 1000): ``python -m agents.evaluate --agent search`` measures it apart.
GAME_BASELINES = ("random", "ghost")

#: Constructor arguments the trainer passes itself: not for ``--set``.
TRAINER_ARGS = ("self", "policy", "env", "seed", "device", "verbose", "tensorboard_log")

#: The option of ``train.py`` that sets a run key or a trainer's argument.
RUN_FLAGS = {
    "n_timesteps": "--timesteps", "n_envs": "--n-envs", "vec": "--vec", "seed": "--seed",
    "eval_freq": "--eval-freq", "eval_episodes": "--eval-episodes", "wrapper": "--wrapper",
    "env_kwargs": "--env-kwargs", "train_rewards": "--train-rewards",
    "warm_start": "--warm-start",
    "tensorboard_log": "--runs (tb/ in the run folder)",
}  # fmt: skip


@dataclass
class TrainConfig:
    """Everything that defines a run (saved as the run's ``config.yaml``).

    Attributes:
        env_id: Registered environment id.
        algo: Key of :data:`ALGOS`.
        recipe: The named entry of ``hyperparams.yml`` it came from (``None``: the
            algorithm's own entry).
        seed: Seed of the algorithm and of the training envs.
        n_timesteps: Environment steps to train for.
        n_envs: Parallel environments.
        vec: One of :data:`~agents.training.hyperparams.VEC_KINDS`.
        threads: Torch threads.
        eval_freq: Environment steps between evaluations (0: none during training).
        eval_episodes: Episodes per periodic evaluation.
        final_episodes: Episodes of the final evaluation (model and baselines); ``None``:
            sized to the run (:func:`agents.training.train_lib.final_episodes`).
        baselines: Evaluate the baselines next to the model.
        final_baselines: Which (:data:`FINAL_BASELINES` by default, :data:`GAME_BASELINES`
            on a game id): the spin entries leave out the search, whose 1000 episodes take
            over two minutes there.
        progress_bar: Show SB3's progress bar.
        policy: SB3 policy name.
        env_kwargs: ``gymnasium.make`` keyword arguments.
        train_rewards: Reward scales of the training envs only, by the env's term name
            (``{scratch: -3.0}`` trains on ``reward_scratch=-3.0``): a training-time reward
            term. The periodic and final evaluations play ``env_kwargs`` alone, so they
            score the env's own reward (:func:`training_env_kwargs`).
        warm_start: Before RL, fit the policy's deterministic action to a baseline's
            (:data:`agents.training.hyperparams.WARM_STARTS`: ``"first-row"``), or ``None``.
        wrapper: Observation wrapper name (see :mod:`agents.learned.envs`), or ``None``.
        algo_kwargs: Algorithm keyword arguments in their data form (``hyperparams.yml``).
    """

    env_id: str = "pool_env/OneBallRoll-v1"
    algo: str = "ppo"
    recipe: str | None = None
    seed: int = 0
    n_timesteps: int = 100_000
    n_envs: int = 8
    vec: str = "dummy"
    threads: int = 1
    eval_freq: int = 50_000
    eval_episodes: int = 500
    final_episodes: int | None = None
    baselines: bool = True
    final_baselines: list[str] = field(default_factory=lambda: list(FINAL_BASELINES))
    progress_bar: bool = True
    policy: str = "MlpPolicy"
    env_kwargs: dict[str, Any] = field(default_factory=dict)
    train_rewards: dict[str, float] = field(default_factory=dict)
    warm_start: str | None = None
    wrapper: str | None = None
    algo_kwargs: dict[str, Any] = field(default_factory=dict)


def resolve_config(
    env_id: str,
    algo: str,
    overrides: dict[str, Any],
    path: str | Path | None = None,
    recipe: str | None = None,
) -> TrainConfig:
    """Merge ``hyperparams.yml`` (for ``env_id``/``algo``) with command-line overrides.

    ``overrides`` holds :class:`TrainConfig` fields (``None`` values are ignored) and an
    optional ``algo_kwargs`` dict merged over the file's; ``recipe`` picks a named entry
    (:func:`agents.training.hyperparams.load`). A game id whose entry names no final
    baselines gets :data:`GAME_BASELINES`.

    Raises:
        ValueError: On an unknown algorithm or warm start, or an algorithm argument its
            class does not take (:func:`check_algo_kwargs`; ``--set`` names the command line's).
        KeyError: As :func:`agents.training.hyperparams.load`.
    """
    if algo not in ALGOS:
        raise ValueError(f"unknown algorithm {algo!r}: use one of {list(ALGOS)}")
    run, algo_kwargs = hyperparams.split(hyperparams.load(env_id, algo, path, recipe))
    check_algo_kwargs(
        algo, algo_kwargs, f"the entry {algo!r} of {path or hyperparams.DEFAULT_PATH}"
    )
    given = overrides.pop("algo_kwargs", None) or {}
    check_algo_kwargs(algo, given, "--set")
    algo_kwargs.update(given)
    fields = {**run, **{k: v for k, v in overrides.items() if v is not None}}
    check_warm_start(fields.get("warm_start"), fields.get("wrapper"))
    if "final_baselines" not in fields and _is_game(env_id):
        fields["final_baselines"] = list(GAME_BASELINES)
    return TrainConfig(env_id=env_id, algo=algo, recipe=recipe, algo_kwargs=algo_kwargs, **fields)


def check_warm_start(name: str | None, wrapper: str | None) -> None:
    """Refuse an unknown warm start, or one on a wrapped env (it fits the env's own action).

    Raises:
        ValueError: Naming the warm start and the valid choices, or the wrapper.
    """
    if name is None:
        return
    if name not in hyperparams.WARM_STARTS:
        raise ValueError(f"warm_start {name!r}: use one of {list(hyperparams.WARM_STARTS)}")
    if wrapper:
        raise ValueError(
            f"warm_start {name!r} fits the env's own action; the wrapper {wrapper!r} changes "
            "it: use one or the other"
        )


def training_env_kwargs(config: TrainConfig) -> dict[str, Any]:
    """The ``gymnasium.make`` keywords of the training envs (the evaluations take env_kwargs).

    ``env_kwargs`` and :attr:`~TrainConfig.train_rewards` as ``reward_<term>`` keys (over
    the env_kwargs' own). The env checks the terms' names and values (a ``ValueError``
    naming the key).

    Raises:
        ValueError: When ``train_rewards`` is not a mapping of term names to numbers.

    Examples:
        >>> config = TrainConfig(env_kwargs={"observation": "shots"},
        ...                      train_rewards={"scratch": -3.0})
        >>> training_env_kwargs(config)
        {'observation': 'shots', 'reward_scratch': -3.0}
        >>> config.env_kwargs  # the evaluations' keywords, untouched
        {'observation': 'shots'}
    """
    rewards = config.train_rewards
    if not isinstance(rewards, dict):
        raise ValueError(
            f"train_rewards must map reward terms to scales (e.g. {{scratch: -3.0}}), "
            f"got {rewards!r}"
        )
    for term, scale in rewards.items():
        if not isinstance(term, str) or isinstance(scale, bool):
            raise ValueError(f"train_rewards {term!r}: {scale!r}: want a term name and a number")
        if not isinstance(scale, (int, float)):
            raise ValueError(f"train_rewards {term}: {scale!r} is not a number")
    return {**config.env_kwargs, **{f"reward_{t}": float(s) for t, s in rewards.items()}}


def algo_args(algo: str) -> list[str]:
    """The keyword arguments of ``algo``'s constructor a run may set (not :data:`TRAINER_ARGS`)."""
    params = inspect.signature(ALGOS[algo].__init__).parameters
    return [name for name in params if name not in TRAINER_ARGS and not name.startswith("_")]


def check_algo_kwargs(algo: str, kwargs: dict[str, Any], where: str) -> None:
    """Refuse an algorithm argument ``algo``'s class does not take, before anything runs.

    A run key (``n_envs``, ...) has its own flag and is named; any other key is checked
    against the constructor's signature, with the closest name.

    Raises:
        ValueError: ``--set n_step: PPO takes no 'n_step' (did you mean n_steps?); ...``.
    """
    valid = algo_args(algo)
    for key in kwargs:
        if key in valid:
            continue
        if key in hyperparams.RUN_KEYS or key in TRAINER_ARGS:
            how = RUN_FLAGS.get(key, "the hyperparameter file (--hyperparams)")
            raise ValueError(
                f"{where} {key}: a setting of the run, not an argument of {algo.upper()}: use {how}"
            )
        close = difflib.get_close_matches(key, valid, n=1)
        hint = f" (did you mean {close[0]}?)" if close else ""
        raise ValueError(
            f"{where} {key}: {algo.upper()} takes no {key!r}{hint}; its arguments: "
            f"{', '.join(valid)}"
        )


def _is_game(env_id: str) -> bool:
    """Whether ``env_id`` plays racks by the rules (False for an id Gymnasium cannot make)."""
    try:
        env = make_env(env_id)
    except ValueError:
        return False
    try:
        return is_game(env)
    finally:
        env.close()
