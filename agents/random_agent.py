"""RandomAgent: uniform actions, the floor every learner must clear."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.state import batch_obs


class RandomAgent:
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

    def predict(
        self,
        observation: Any,
        state: tuple[NDArray[Any], ...] | None = None,
        episode_start: NDArray[np.bool_] | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], tuple[NDArray[Any], ...] | None]:
        """Random actions, one per observation (``deterministic`` is ignored: it is random).

        Args:
            observation: One observation ``(D,)`` or a batch ``(B, D)``.
            state: Recurrent state (unused, returned as is).
            episode_start: Unused.
            deterministic: Unused.

        Returns:
            ``(actions, state)``: ``(2,)`` or ``(B, 2)`` float32 actions.
        """
        obs, single = batch_obs(observation)
        shape = (obs.shape[0], *self.low.shape)
        actions = self.rng.uniform(self.low, self.high, size=shape).astype(np.float32)
        return (actions[0] if single else actions), state


class ConstantAgent:
    """Always the same action: the floor a learner must clear when one shot fits most layouts.

    On ``OneBall-v0`` with the default ``cut`` aim, action ``(0, 1)`` (a full hit as hard as
    possible) pots often: the object ball runs around the low-friction table until some
    pocket's capture circle takes it. A policy that only learned that has learned no aiming.

    Args:
        env: The environment (unused; for the common constructor).
        action: The action, in ``[-1, 1]^2``.
    """

    def __init__(self, env: Any, action: tuple[float, float] = (0.0, 1.0)) -> None:
        self.action = np.asarray(action, dtype=np.float32)

    def predict(
        self,
        observation: Any,
        state: tuple[NDArray[Any], ...] | None = None,
        episode_start: NDArray[np.bool_] | None = None,
        deterministic: bool = True,
    ) -> tuple[NDArray[np.float32], tuple[NDArray[Any], ...] | None]:
        """The constant action, once per observation (SB3's signature)."""
        obs, single = batch_obs(observation)
        actions = np.tile(self.action, (obs.shape[0], 1))
        return (actions[0] if single else actions), state
