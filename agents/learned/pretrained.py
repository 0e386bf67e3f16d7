"""Pretrained agents in one line: ``agents.load("models/ppo_oneball.zip")``.

A model trained by ``train.py`` saw the environment through a wrapper (``ghost_features``
appends the ghost-ball shot into each pocket; the OneBall PPO default ``ghost_candidates``
also acts by picking one of those shots and refining it, :mod:`agents.learned.candidates`), so
SB3's ``PPO.load(path).predict(obs)`` on the environment's own observation fails on the
shape, or returns a candidate action rather than the env's.
:func:`load` reads the model's saved run config (``<stem>_config.yaml`` or ``config.yaml``
beside it: env id, ``env_kwargs``, ``wrapper``) and returns a :class:`PretrainedPolicy`
whose ``predict`` applies that wrapper's features to the raw observation first and, for
candidate actions, decodes the model's action to the env's. Both are functions of the
observation alone, so nothing but the observation is needed.

The committed models and their evaluations sit together in ``models/``:
``ppo_oneball.zip`` (PPO, 200k steps on ``pool_env/OneBallRoll-v1``), its settings
``ppo_oneball_config.yaml`` and its re-evaluation ``ppo_oneball_eval.md``.

Examples:
    >>> import agents, gymnasium as gym
    >>> policy = agents.load("models/ppo_oneball.zip")
    >>> policy.env_id, policy.wrapper
    ('pool_env/OneBallRoll-v1', 'ghost_candidates')
    >>> env = policy.make_env()  # gym.make(env_id, **env_kwargs), no wrapper
    >>> obs, _ = env.reset(seed=50000)
    >>> action, _ = policy.predict(obs, deterministic=True)
    >>> action.shape
    (2,)
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import batch_obs, decode_observation
from agents.learned.candidates import decode_candidates
from agents.learned.envs import make_env
from agents.learned.position_rows import decode_position
from pool_env.extras import require

__all__ = ["ALGO_CLASSES", "PretrainedPolicy", "algo_class", "load", "load_model", "model_config"]

#: The SB3 algorithms by the name used in ``hyperparams.yml``, on the command line and in a
#: model's file name: their class names in ``stable_baselines3``.
ALGO_CLASSES = {"ppo": "PPO", "sac": "SAC", "a2c": "A2C", "td3": "TD3"}


def algo_class(name: str) -> Any:
    """The SB3 algorithm class of ``name`` (a key of :data:`ALGO_CLASSES`).

    Raises:
        ValueError: On an unknown name.
    """
    if name not in ALGO_CLASSES:
        raise ValueError(f"unknown algorithm {name!r}: use one of {list(ALGO_CLASSES)}")
    # stable-baselines3 (and torch) come with the train extra: imported only when a model is
    # loaded or built, so that the baselines and their evaluation run on the core install.
    stable_baselines3 = require("stable_baselines3", "train", "a saved SB3 model")
    return getattr(stable_baselines3, ALGO_CLASSES[name])


def model_config(path: str | Path) -> dict[str, Any]:
    """The saved run config of a model: ``config.yaml`` beside it or ``<stem>_config.yaml``."""
    yaml = require("yaml", "train", "a saved model's config")

    path = Path(path)
    for candidate in (path.with_name(f"{path.stem}_config.yaml"), path.parent / "config.yaml"):
        if candidate.is_file():
            return yaml.safe_load(candidate.read_text()) or {}
    return {}


def load_model(path: str | Path, algo: str | None = None) -> Any:
    """Load an SB3 model; the algorithm from ``algo``, the saved config, or the file name.

    Raises:
        FileNotFoundError: If there is no model file.
        ValueError: If the algorithm cannot be told or is unknown.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no model file {path}")
    algo = algo or model_config(path).get("algo")
    if algo is None:
        algo = next((name for name in ALGO_CLASSES if name in path.name.lower()), None)
    if algo is None:
        raise ValueError(
            f"cannot tell the algorithm of {path}: pass algo= (one of {list(ALGO_CLASSES)})"
        )
    return algo_class(algo).load(str(path), device="cpu")


class PretrainedPolicy:
    """An SB3 model with the observation wrapper it was trained behind.

    ``predict`` takes the environment's own observations (``(D,)`` or ``(B, D)``; already
    wrapped ones, of the model's input size, pass through unchanged) and has SB3's
    signature, so it works with ``evaluate_policy`` and :func:`agents.run_episodes`.

    Args:
        model: The loaded SB3 model.
        config: The model's saved run config (``env_id``, ``env_kwargs``, ``wrapper``, ...).

    Raises:
        ValueError: If the config names no ``env_id`` or an unknown wrapper.
    """

    def __init__(self, model: Any, config: dict[str, Any]) -> None:
        if not config.get("env_id"):
            raise ValueError("the model's config names no env_id")
        self.model = model
        self.config = dict(config)
        self.env_id: str = str(config["env_id"])
        self.env_kwargs: dict[str, Any] = dict(config.get("env_kwargs") or {})
        self.wrapper: str | None = config.get("wrapper") or None
        # The wrapped env computes the features; it is never stepped.
        self._features_env = make_env(self.env_id, self.env_kwargs, self.wrapper)
        self._raw_size = int(self._features_env.unwrapped.observation_space.shape[0])
        self._model_size = int(model.observation_space.shape[0])

    def make_env(self, **kwargs: Any) -> gym.Env:
        """``gymnasium.make(env_id, **env_kwargs, **kwargs)``: the env the model plays, unwrapped.

        Args:
            **kwargs: More ``gymnasium.make`` keywords (e.g. ``render_mode``).
        """
        return gym.make(self.env_id, **{**self.env_kwargs, **kwargs})

    def features(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The model's input for ``(B, D)`` raw observations: the wrapper's features appended.

        Raises:
            ValueError: If the rows are neither the env's nor the model's size.
        """
        obs = np.asarray(observations, dtype=np.float32)
        size = obs.shape[1]
        if size == self._model_size:
            return obs
        if size != self._raw_size:
            raise ValueError(
                f"observations of size {size}: {self.env_id} gives {self._raw_size}, "
                f"the model takes {self._model_size}"
            )
        if self.wrapper is None:
            return obs
        env = self._features_env
        if self.wrapper in ("ghost_features", "ghost_candidates"):
            extra = env.ghost_features.of_observations(obs)
        elif self.wrapper == "position_candidates":  # the spin ghost agent's strikes as rows
            extra = env.position_rows.of_observations(obs)
        else:  # pocket_features reads a layout: decode it from each observation
            table = env.unwrapped.config.table
            extra = np.stack([env.features(*decode_observation(row, table)) for row in obs])
        return np.concatenate([obs, extra.astype(np.float32)], axis=1)

    def predict(
        self,
        observation: Any,
        state: tuple[NDArray[Any], ...] | None = None,
        episode_start: NDArray[np.bool_] | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], tuple[NDArray[Any], ...] | None]:
        """Actions for the env's observation ``(D,)`` or a batch ``(B, D)`` (SB3's signature).

        Args:
            observation: One observation or a batch, raw or already wrapped.
            state: Recurrent state, passed to the model.
            episode_start: Passed to the model.
            deterministic: The policy's mean action (True, the default here) or a sample.

        Returns:
            ``(actions, state)``: the env's actions, ``(A,)`` or ``(B, A)`` (a candidate-action
            model's decoded, :mod:`agents.learned.candidates`; a position-candidates
            model's, :mod:`agents.learned.position_rows`).
        """
        obs, single = batch_obs(observation)
        inputs = self.features(obs)
        actions, state = self.model.predict(
            inputs, state, episode_start, deterministic=deterministic
        )
        if self.wrapper == "ghost_candidates":  # a candidate action: the env's action of it
            actions = decode_candidates(inputs, actions, self._features_env.n_rows)
        elif self.wrapper == "position_candidates":  # a preference: the strike it picks
            actions = decode_position(inputs, actions, self._features_env.n_rows)[0]
        return (actions[0] if single else actions), state


def load(path: str | Path, algo: str | None = None) -> PretrainedPolicy:
    """Load an SB3 model saved by ``train.py`` with the wrapper of its saved config.

    Args:
        path: The model ``.zip``; its config is ``<stem>_config.yaml`` or ``config.yaml``
            in the same folder (a run folder has the latter).
        algo: The SB3 algorithm (``"ppo"``, ``"sac"``, ...); default: the config's, else
            the file name's.

    Returns:
        A :class:`PretrainedPolicy` with SB3's ``predict`` on the env's own observations.

    Raises:
        FileNotFoundError: If there is no model file.
        ValueError: If there is no config beside it or the algorithm cannot be told.

    Examples:
        >>> import agents
        >>> agents.load("models/ppo_oneball.zip").model.__class__.__name__
        'PPO'
    """
    path = Path(path)
    config = model_config(path)
    if not path.is_file():
        raise FileNotFoundError(f"no model file {path}")
    if not config:
        raise ValueError(
            f"no saved config beside {path} ({path.stem}_config.yaml or config.yaml): "
            "it says which env and observation wrapper the model was trained on"
        )
    return PretrainedPolicy(load_model(path, algo or config.get("algo")), config)
