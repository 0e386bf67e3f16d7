"""RandomAgent: uniform actions, the floor every learner must clear."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import BaselineAgent


class RandomAgent(BaselineAgent):
    """Uniformly random actions in the environment's action box, with SB3's ``predict``.

    Args:
        env: The environment (``gym.Env`` or SB3 ``VecEnv``): only its action space is read.
        seed: Seed of the agent's own generator (independent of the environment's).
    """

    def __init__(self, env: Any, seed: int | None = None) -> None:
        space = env.action_space
        self.low = np.asarray(space.low, dtype=np.float32)
        self.high = np.asarray(space.high, dtype=np.float32)
        self.rng = np.random.default_rng(seed)

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """Uniform actions, one per observation."""
        shape = (observations.shape[0], *self.low.shape)
        return self.rng.uniform(self.low, self.high, size=shape).astype(np.float32)


class ConstantAgent(BaselineAgent):
    """Always the same action: the floor a learner must clear when one shot fits most layouts.

    On ``OneBallRoll-v1`` with the default ``cut`` aim, action ``(0, 1)`` (a full hit as hard as
    possible) pots often: the object ball runs around the low-friction table until some
    pocket's capture circle takes it. A policy that only learned that has learned no aiming.

    Args:
        env: The environment (unused; for the common constructor).
        action: The action, in ``[-1, 1]^2`` (``[-1, 1]^4`` on a spin env).
    """

    def __init__(self, env: Any, action: tuple[float, ...] = (0.0, 1.0)) -> None:
        self.action = np.asarray(action, dtype=np.float32)

    def act(self, observations: NDArray[np.floating]) -> NDArray[np.float32]:
        """The constant action, once per observation."""
        return np.tile(self.action, (observations.shape[0], 1))
