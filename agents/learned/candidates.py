"""An action space of candidate shots: pick a ghost-ball feature row and refine it.

PPO on the env's own action (aim, speed) must put one Gaussian's mean on one pocket's aim,
and on the roll table it settles between two pockets' aims that both pot, where neither
does (results/oneball_scratches.md: the pot window is 0.09 of the action wide, the misses
between two rows). The ghost-ball features (:mod:`agents.learned.features`) already
hold, per pocket, the env action that plays the geometric shot. :class:`GhostCandidates`
makes the policy's action a choice among those rows plus a small residual:

``action = (s_0, ..., s_{K-1}, r_aim, r_speed)`` in ``[-1, 1]^(K + 2)``: the row played is
the valid row with the largest score ``s_k`` (the argmax of a Gaussian sample is a valid
stochastic policy over rows: PPO's likelihood ratio is the one of the continuous sample),
and the env action is that row's ``(aim, speed)`` plus ``(AIM_RESIDUAL r_aim,
SPEED_RESIDUAL r_speed)``, clipped to ``[-1, 1]``. The rows' actions are the env's own
action encoding (computed from the env's aim mode and ranges, :class:`GhostShotFeatures`),
so decoding needs nothing but the observation's feature columns: the same function
(:func:`decode_candidates`) serves the ``gym.Env`` wrapper, the native vector env
(:class:`agents.training.vec_features.GhostCandidatesVecEnv`) and a loaded model
(:mod:`agents.learned.pretrained`). With no valid row (no direct shot), the base is ``(0, 0)``:
a full hit on the reference ball at the middle speed, refined the same way.
"""

from __future__ import annotations

from typing import Any, SupportsFloat

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.learned.features import GhostBallFeatures, GhostShotFeatures

#: Scale of the aim residual, in action units (the aim action's range is 2). Row 0 played
#: exactly pots 93%; the misses a residual can fix (collision throw, the deceleration
#: model's error over long shots) move the aim by a few hundredths, and a scale of 0.05
#: keeps the initial exploration (std 0.37 x 0.05 = 0.018) well inside a pot's window.
AIM_RESIDUAL = 0.05

#: Scale of the speed residual, in action units: speed noise of sd 0.1 alone costs 22
#: points of pots (results/agents.md), so the refinement is kept as fine as the aim's.
SPEED_RESIDUAL = 0.1

#: Columns of a feature row (:class:`GhostShotFeatures`): valid flag, aim action, speed action.
_VALID, _AIM, _SPEED = 0, 2, 7


def decode_candidates(
    observations: NDArray[np.floating], actions: NDArray[np.floating], n_rows: int
) -> NDArray[np.float32]:
    """The env actions ``(B, 2)`` of candidate actions ``(B, n_rows + 2)``.

    Args:
        observations: ``(B, D + n_rows * PER_SHOT)`` observations with their ghost-ball
            features last (what :class:`GhostBallFeatures` returns).
        actions: ``(B, n_rows + 2)`` scores of the rows, then the aim and speed residuals.
        n_rows: Feature rows (pockets) per observation.

    Raises:
        ValueError: On shapes that do not fit ``n_rows``.
    """
    obs = np.asarray(observations, dtype=np.float64)
    act = np.clip(np.asarray(actions, dtype=np.float64), -1.0, 1.0)
    per = GhostShotFeatures.PER_SHOT
    if obs.ndim != 2 or act.ndim != 2 or act.shape != (obs.shape[0], n_rows + 2):
        raise ValueError(
            f"expected (B, D) observations and (B, {n_rows + 2}) actions, got "
            f"{obs.shape} and {act.shape}"
        )
    if obs.shape[1] < n_rows * per:
        raise ValueError(f"observations of size {obs.shape[1]} hold no {n_rows} feature rows")
    rows = obs[:, obs.shape[1] - n_rows * per :].reshape(len(obs), n_rows, per)
    valid = rows[..., _VALID] > 0.5
    pick = np.argmax(np.where(valid, act[:, :n_rows], -np.inf), axis=1)
    chosen = rows[np.arange(len(obs)), pick]
    any_valid = valid.any(axis=1)
    base_aim = np.where(any_valid, chosen[:, _AIM], 0.0)
    base_speed = np.where(any_valid, chosen[:, _SPEED], 0.0)
    aim = base_aim + AIM_RESIDUAL * act[:, n_rows]
    speed = base_speed + SPEED_RESIDUAL * act[:, n_rows + 1]
    return np.clip(np.stack([aim, speed], axis=1), -1.0, 1.0).astype(np.float32)


def candidate_space(n_rows: int) -> gym.spaces.Box:
    """The candidate action space: ``n_rows`` scores and two residuals in ``[-1, 1]``."""
    return gym.spaces.Box(-1.0, 1.0, (n_rows + 2,), np.float32)


class GhostCandidates(gym.Wrapper):
    """A ``PoolEnv`` seen through the ghost-ball features, acting by candidate shots.

    The observation is :class:`GhostBallFeatures`'s; the action is a candidate action
    (module docstring), decoded to the env's action from the last observation's rows. The
    env action played is in ``info["env_action"]``.

    Args:
        env: A (wrapped) ``PoolEnv`` without the features wrapper.
    """

    def __init__(self, env: gym.Env) -> None:
        features = GhostBallFeatures(env)
        super().__init__(features)
        self.ghost_features = features.ghost_features
        self.n_rows = self.ghost_features.mouths.n
        self.action_space = candidate_space(self.n_rows)
        self._last: NDArray[np.float32] | None = None

    def reset(self, **kwargs: Any) -> tuple[NDArray[np.float32], dict[str, Any]]:
        """Reset; the observation with its features."""
        obs, info = self.env.reset(**kwargs)
        self._last = np.array(obs, dtype=np.float32)
        return obs, info

    def step(
        self, action: NDArray[np.floating]
    ) -> tuple[NDArray[np.float32], SupportsFloat, bool, bool, dict[str, Any]]:
        """Decode the candidate action on the last observation and play it.

        Raises:
            RuntimeError: If called before ``reset``.
        """
        if self._last is None:
            raise RuntimeError("call reset() before step()")
        env_action = decode_candidates(self._last[None], np.asarray(action)[None], self.n_rows)[0]
        obs, reward, terminated, truncated, info = self.env.step(env_action)
        self._last = np.array(obs, dtype=np.float32)
        return obs, reward, terminated, truncated, {**info, "env_action": env_action}


class FirstRowAgent:
    """Plays feature row 0 exactly (the easiest ghost-ball shot): the trivial candidate policy.

    It acts on a :class:`GhostCandidates` env (SB3's ``predict`` signature): the score of
    row 0 highest, the residuals zero. A learner on the candidate actions must beat it.

    Args:
        n_rows: Feature rows (the env's ``n_rows``).
    """

    def __init__(self, n_rows: int) -> None:
        self.action = np.zeros(n_rows + 2, dtype=np.float32)
        self.action[0] = 1.0

    def predict(
        self,
        observation: NDArray[np.floating],
        state: Any = None,
        episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], Any]:
        """The row-0 action, once per observation (``(D,)`` or ``(B, D)``)."""
        obs = np.asarray(observation)
        if obs.ndim == 1:
            return self.action.copy(), state
        return np.tile(self.action, (obs.shape[0], 1)), state
