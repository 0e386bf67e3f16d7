"""The ghost-ball features and candidate actions on an SB3 ``VecEnv`` (``--vec native``).

The ``gym.Env`` wrappers of the same features and actions are
:class:`agents.learned.features.GhostBallFeatures` and
:class:`agents.learned.candidates.GhostCandidates`, which the evaluation envs use; both
compute the features with :class:`agents.learned.features.GhostShotFeatures` and decode with
:func:`agents.learned.candidates.decode_candidates`.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray
from stable_baselines3.common.vec_env import VecEnv, VecEnvWrapper
from stable_baselines3.common.vec_env.base_vec_env import VecEnvStepReturn

from agents.baselines.base import env_spec
from agents.learned.candidates import candidate_space, decode_candidates
from agents.learned.features import GhostShotFeatures
from agents.learned.position_rows import PositionRowFeatures, decode_position, position_space

__all__ = ["GhostCandidatesVecEnv", "GhostFeaturesVecEnv", "PositionCandidatesVecEnv"]


class GhostFeaturesVecEnv(VecEnvWrapper):
    """The SB3 ``VecEnv`` counterpart of :class:`GhostBallFeatures` (``--vec native``).

    It appends the same features to every observation, terminal observations included, so
    that the native vector env (all tables in one compiled call) trains on what a
    ``GhostBallFeatures`` env evaluates on.

    Args:
        venv: A ``VecEnv`` of ``PoolEnv`` tables (e.g. :class:`agents.vec.native_vec.NativeVecEnv`).
    """

    def __init__(self, venv: VecEnv) -> None:
        self.ghost_features = GhostShotFeatures(env_spec(venv))
        raw = venv.observation_space.shape[0]
        space = gym.spaces.Box(-1.0, 1.0, (raw + self.ghost_features.size,), np.float32)
        super().__init__(venv, observation_space=space)

    def _append(self, observations: NDArray[np.float32]) -> NDArray[np.float32]:
        extra = self.ghost_features.of_observations(observations)
        return np.concatenate([observations, extra], axis=1)

    def reset(self) -> NDArray[np.float32]:
        """Reset every table; observations with their features."""
        return self._append(self.venv.reset())

    def step_wait(self) -> VecEnvStepReturn:
        """Step every table; observations (and terminal ones) with their features."""
        obs, rewards, dones, infos = self.venv.step_wait()
        ended = [i for i, info in enumerate(infos) if "terminal_observation" in info]
        if ended:  # one batch for all of them (one shot per episode: often every table)
            final = self._append(np.stack([infos[i]["terminal_observation"] for i in ended]))
            for i, row in zip(ended, final, strict=True):
                infos[i]["terminal_observation"] = row
        return self._append(obs), rewards, dones, infos


class GhostCandidatesVecEnv(VecEnvWrapper):
    """The SB3 ``VecEnv`` counterpart of :class:`agents.learned.candidates.GhostCandidates`.

    Observations with their ghost-ball features (:class:`GhostFeaturesVecEnv`); actions are
    candidate actions, decoded on each table's last observation. After an episode ends the
    vector env has already reset that table, so the last observation is the new episode's.

    Args:
        venv: A ``VecEnv`` of ``PoolEnv`` tables, without the features wrapper.
    """

    def __init__(self, venv: VecEnv) -> None:
        features = GhostFeaturesVecEnv(venv)
        self.ghost_features = features.ghost_features
        self.n_rows = self.ghost_features.mouths.n
        super().__init__(features, action_space=candidate_space(self.n_rows))
        self._last: NDArray[np.float32] | None = None

    def reset(self) -> NDArray[np.float32]:
        """Reset every table; observations with their features."""
        obs = self.venv.reset()
        self._last = obs.copy()  # the caller's array is its own
        return obs

    def step_async(self, actions: NDArray[np.floating]) -> None:
        """Decode the candidate actions and step the tables with the env actions."""
        if self._last is None:
            raise RuntimeError("call reset() before step()")
        self.venv.step_async(decode_candidates(self._last, actions, self.n_rows))

    def step_wait(self) -> VecEnvStepReturn:
        """Step every table; observations (and terminal ones) with their features."""
        obs, rewards, dones, infos = self.venv.step_wait()
        self._last = obs.copy()
        return obs, rewards, dones, infos


class PositionCandidatesVecEnv(VecEnvWrapper):
    """The SB3 ``VecEnv`` counterpart of :class:`agents.learned.position_rows.PositionCandidates`.

    Observations with the candidate strikes' rows appended (terminal observations too);
    actions are preferences, decoded on each table's last observation with
    :func:`agents.learned.position_rows.decode_position`. After an episode ends the vector
    env has already reset that table, so the last observation is the new episode's.

    Args:
        venv: A ``VecEnv`` of spin ``PoolEnv`` tables.
    """

    def __init__(self, venv: VecEnv) -> None:
        self.position_rows = PositionRowFeatures(venv)
        self.n_rows = self.position_rows.n_rows
        raw = venv.observation_space.shape[0]
        space = gym.spaces.Box(-1.0, 1.0, (raw + self.position_rows.size,), np.float32)
        super().__init__(venv, observation_space=space, action_space=position_space())
        self._last: NDArray[np.float32] | None = None

    def _append(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        raw = np.asarray(observations, dtype=np.float32)
        return np.concatenate([raw, self.position_rows.of_observations(raw)], axis=1)

    def reset(self) -> NDArray[np.float32]:
        """Reset every table; observations with their rows."""
        obs = self._append(self.venv.reset())
        self._last = obs.copy()  # the caller's array is its own
        return obs

    def step_async(self, actions: NDArray[np.floating]) -> None:
        """Decode the preferences and step the tables with the env actions."""
        if self._last is None:
            raise RuntimeError("call reset() before step()")
        self.venv.step_async(decode_position(self._last, actions, self.n_rows)[0])

    def step_wait(self) -> VecEnvStepReturn:
        """Step every table; observations (and terminal ones) with their rows."""
        obs, rewards, dones, infos = self.venv.step_wait()
        for info in infos:
            if "terminal_observation" in info:
                info["terminal_observation"] = self._append(info["terminal_observation"][None])[0]
        obs = self._append(obs)
        self._last = obs.copy()
        return obs, rewards, dones, infos
