"""What defines a training run: its config, the algorithms by name, and their resolution.

:class:`TrainConfig` is everything a run is made of (saved as its ``config.yaml``);
:func:`resolve_config` builds one from ``hyperparams.yml`` and the command line's
overrides; :data:`ALGOS` holds the algorithms by the name used in both.
:mod:`agents.training.train_lib` trains one.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from stable_baselines3.common.base_class import BaseAlgorithm

from agents.learned.pretrained import ALGO_CLASSES, algo_class
from agents.training import hyperparams

#: Algorithms by the name used in ``hyperparams.yml`` and on the command line.
ALGOS: dict[str, type[BaseAlgorithm]] = {name: algo_class(name) for name in ALGO_CLASSES}

#: Baselines of the final evaluation, in the order printed (see :mod:`agents.evaluation.evaluate`).
FINAL_BASELINES = ("random", "best-const", "ghost", "search")


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
        final_episodes: Episodes of the final evaluation (model and baselines).
        baselines: Evaluate the baselines next to the model.
        final_baselines: Which (:data:`FINAL_BASELINES` by default): the spin entries leave
            out the search, whose 1000 episodes take over two minutes there.
        progress_bar: Show SB3's progress bar.
        policy: SB3 policy name.
        env_kwargs: ``gymnasium.make`` keyword arguments.
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
    final_episodes: int = 1000
    baselines: bool = True
    final_baselines: list[str] = field(default_factory=lambda: list(FINAL_BASELINES))
    progress_bar: bool = True
    policy: str = "MlpPolicy"
    env_kwargs: dict[str, Any] = field(default_factory=dict)
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
    (:func:`agents.training.hyperparams.load`).
    """
    if algo not in ALGOS:
        raise ValueError(f"unknown algorithm {algo!r}: use one of {list(ALGOS)}")
    run, algo_kwargs = hyperparams.split(hyperparams.load(env_id, algo, path, recipe))
    algo_kwargs.update(overrides.pop("algo_kwargs", None) or {})
    fields = {**run, **{k: v for k, v in overrides.items() if v is not None}}
    return TrainConfig(env_id=env_id, algo=algo, recipe=recipe, algo_kwargs=algo_kwargs, **fields)
