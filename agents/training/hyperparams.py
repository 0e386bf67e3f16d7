"""Hyperparameters as data: ``hyperparams.yml`` keyed by env id, then algorithm.

As in rl-baselines3-zoo, but parsed without ``eval``: learning-rate schedules are written
``"lin_3e-4"`` (linear decay to 0), activation functions by name, and every other value is
plain YAML. Keys that configure the run rather than the algorithm are split off
(:data:`RUN_KEYS`). An env id without an entry uses the ``default`` entry.
"""

from __future__ import annotations

import copy
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pool_env.extras import require

#: Vectorized environment kinds (``--vec``; the run key ``vec``).
VEC_KINDS = ("dummy", "subproc", "native")

#: The hyperparameter file shipped with the package.
DEFAULT_PATH = Path(__file__).with_name("hyperparams.yml")

#: Keys of an entry that configure the run, not the SB3 algorithm's constructor.
RUN_KEYS = (
    "n_timesteps",
    "n_envs",
    "vec",
    "policy",
    "env_kwargs",
    "train_rewards",
    "warm_start",
    "wrapper",
    "eval_freq",
    "eval_episodes",
    "final_baselines",
)

#: The warm starts by name (the run key ``warm_start``, :mod:`agents.training.warm_start`):
#: ``"first-row"`` fits the policy's action to row 0 of the ``"shots"`` observation.
WARM_STARTS = ("first-row",)

#: Activation functions by name (``policy_kwargs.activation_fn``) and their ``torch.nn`` class.
ACTIVATION_CLASSES = {
    "tanh": "Tanh", "relu": "ReLU", "elu": "ELU", "leaky_relu": "LeakyReLU", "silu": "SiLU",
}  # fmt: skip
ACTIVATIONS = tuple(ACTIVATION_CLASSES)


def entry_key(algo: str, recipe: str | None = None) -> str:
    """The key of an entry under its env id: ``algo``, or ``<algo>-<recipe>`` for a named one."""
    return algo if recipe is None else f"{algo}-{recipe}"


def load(
    env_id: str, algo: str, path: str | Path | None = None, recipe: str | None = None
) -> dict[str, Any]:
    """The entry for ``env_id`` and ``algo`` (or the ``default`` entry), as plain data.

    ``recipe`` names another entry of the id (``ppo-candidates``): a second way to train
    the same algorithm there, which the ``default`` entry never supplies.

    Raises:
        KeyError: If neither the id nor ``default`` has an entry for ``algo`` (with a
            recipe: if the id has no such entry).
    """
    yaml = require("yaml", "train", "the hyperparameter file")
    data = yaml.safe_load(Path(path or DEFAULT_PATH).read_text()) or {}
    key = entry_key(algo, recipe)
    for env_key in (env_id,) if recipe else (env_id, "default"):
        if key in (data.get(env_key) or {}):
            return copy.deepcopy(data[env_key][key])
    if recipe:
        named = sorted(k for k in data.get(env_id) or {} if "-" in k)
        raise KeyError(f"no recipe {key!r} for {env_id!r} in {path or DEFAULT_PATH}: {named}")
    raise KeyError(f"no hyperparameters for {algo!r} under {env_id!r} or 'default' in {path}")


def split(entry: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """``(run settings, algorithm keyword arguments)`` of an entry."""
    run = {k: entry[k] for k in RUN_KEYS if k in entry}
    algo = {k: v for k, v in entry.items() if k not in RUN_KEYS}
    return run, algo


def linear_schedule(initial: float) -> Callable[[float], float]:
    """SB3 schedule: ``initial`` at the start, falling linearly to 0 at the end, then 0.

    SB3's progress runs below 0 in the last rollout when the step count is not a multiple
    of the rollout's size (``1 - steps / total``); unclipped, that last update's learning
    rate is negative and Adam climbs the loss (a 300k-step PPO run on OneBall-v1 fell from
    81% to 62% pots in that one update).
    """

    def schedule(progress_remaining: float) -> float:
        return max(progress_remaining, 0.0) * initial

    return schedule


def to_sb3(kwargs: dict[str, Any]) -> dict[str, Any]:
    """Turn the data form of algorithm arguments into SB3 objects (schedules, activations).

    Raises:
        ValueError: On an unknown schedule or activation name.
    """
    import torch  # only when an algorithm is built

    out = copy.deepcopy(kwargs)
    for key in ("learning_rate", "clip_range"):
        value = out.get(key)
        if isinstance(value, str):
            try:  # YAML 1.1 reads "1e-3" (no dot) as a string
                out[key] = float(value)
                continue
            except ValueError:
                pass
            kind, _, number = value.partition("_")
            if kind != "lin" or not number:
                raise ValueError(f"{key}: unknown schedule {value!r}: use a number or 'lin_<x>'")
            out[key] = linear_schedule(float(number))
    policy_kwargs = out.get("policy_kwargs")
    if policy_kwargs and isinstance(policy_kwargs.get("activation_fn"), str):
        name = policy_kwargs["activation_fn"]
        if name not in ACTIVATION_CLASSES:
            raise ValueError(f"unknown activation_fn {name!r}: use one of {ACTIVATIONS}")
        policy_kwargs["activation_fn"] = getattr(torch.nn, ACTIVATION_CLASSES[name])
    return out
