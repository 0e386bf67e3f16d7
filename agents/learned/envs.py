"""Making environments for training and evaluation: one id, keyword arguments, a wrapper.

A run's environment is data: ``env_id``, ``env_kwargs`` (``gymnasium.make`` keyword
arguments) and ``wrapper`` (a name from :data:`WRAPPERS` or ``None``), so that the same
environment is rebuilt for evaluation from a saved config.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable
from typing import Any

import gymnasium as gym

import pool_env  # registers the ids
from agents.learned.candidates import GhostCandidates
from agents.learned.features import GhostBallFeatures, PocketFeatures
from agents.learned.position_rows import PositionCandidates

#: Wrappers by name (``wrapper:`` in ``hyperparams.yml``): observation features, and
#: ``ghost_candidates``, which also makes the action a candidate shot
#: (:mod:`agents.learned.candidates`), and ``position_candidates``, whose action picks one
#: of the spin ghost-ball agent's strikes (:mod:`agents.learned.position_rows`).
WRAPPERS: dict[str, Callable[[gym.Env], gym.Env]] = {
    "pocket_features": PocketFeatures,
    "ghost_features": GhostBallFeatures,
    "ghost_candidates": GhostCandidates,  # the features, and candidate shots as the action
    # the spin ghost agent's strikes as rows, the action a preference among them
    "position_candidates": PositionCandidates,
}


def worker_id(env_id: str) -> str:
    """The id to make in a subprocess: ``"pool_env:pool_env/X"`` imports the package first."""
    if ":" in env_id or not env_id.startswith("pool_env/"):
        return env_id
    return f"pool_env:{env_id}"


def check_env_id(env_id: str) -> None:
    """Refuse an id Gymnasium does not know, naming the closest pool_env id and all of them.

    Any registered id passes (another package's too, or ``"module:Id"`` to import first);
    the ids listed are pool_env's current ones (:data:`pool_env.ENV_IDS`).

    Raises:
        ValueError: ``unknown env id 'pool_env/NineBall-v9' (did you mean ...?): ...``.
    """
    if ":" in env_id or env_id in gym.registry:  # "module:Id": Gymnasium imports it first
        return
    ids = list(pool_env.ENV_IDS)
    close = difflib.get_close_matches(env_id, ids, n=1, cutoff=0.6)
    hint = f" (did you mean {close[0]}?)" if close else ""
    raise ValueError(f"unknown env id {env_id!r}{hint}: the pool_env ids are {', '.join(ids)}")


def make_env(
    env_id: str,
    env_kwargs: dict[str, Any] | None = None,
    wrapper: str | None = None,
) -> gym.Env:
    """``gymnasium.make(env_id, **env_kwargs)`` with the named wrapper applied.

    Raises:
        ValueError: On an unknown env id (:func:`check_env_id`) or wrapper name, or the
            env's own refusal of a keyword argument.
    """
    check_env_id(env_id)
    if wrapper and wrapper not in WRAPPERS:
        raise ValueError(f"unknown wrapper {wrapper!r}: use one of {sorted(WRAPPERS)}")
    env = gym.make(worker_id(env_id), **(env_kwargs or {}))
    return WRAPPERS[wrapper](env) if wrapper else env


class EnvFactory:
    """A picklable ``() -> gym.Env`` for vectorized envs (subprocess workers rebuild it)."""

    def __init__(
        self, env_id: str, env_kwargs: dict[str, Any] | None = None, wrapper: str | None = None
    ) -> None:
        self.env_id = env_id
        self.env_kwargs = dict(env_kwargs or {})
        self.wrapper = wrapper

    def __call__(self) -> gym.Env:
        """A new environment."""
        return make_env(self.env_id, self.env_kwargs, self.wrapper)
