"""Vector envs for plain Gymnasium loops and CleanRL-style scripts, same-step autoreset.

A pool episode is often one shot (``OneBallRoll-v1``: always). With Gymnasium's default
next-step autoreset, the step after an episode ends is a reset that ignores its action: half
of all vector steps are no-ops (0.5 episodes per table per step, measured in
``tests/agents/test_gym_vec.py``). Same-step autoreset resets a finished table inside the step that
ends it (its last observation goes to ``info["final_obs"]``): 1.0 episode per table per step.
:func:`make_vec` builds the native vector env that way.

:func:`make_cleanrl_envs` is CleanRL's ``ppo_continuous_action.py`` env stack as Gymnasium
vector wrappers around that env, with two changes that same-step autoreset needs on
Gymnasium 1.2.2 (the version Ray RLlib pins):

* its vector ``RecordEpisodeStatistics`` counts episodes the next-step way (with same-step
  autoreset it reports every one-shot episode as return 0, length 0; fixed in Gymnasium
  1.4), so episodes are recorded by :class:`SameStepEpisodeStatistics`, which writes the
  same ``info["episode"]`` keys;
* its vector observation wrappers refuse same-step envs (they would not transform
  ``final_obs``), so ``NormalizeObservation`` and the observation clip are left out: pool
  observations are already scaled to ``[-1, 1]``.
"""

from __future__ import annotations

import time
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv, VectorWrapper
from gymnasium.wrappers import vector as vw

import pool_env  # noqa: F401  (registers the ids)


def make_vec(
    env_id: str,
    num_envs: int,
    autoreset_mode: AutoresetMode | str = AutoresetMode.SAME_STEP,
    **env_kwargs: Any,
) -> VectorEnv:
    """``num_envs`` tables of ``env_id`` in one native vector env, same-step by default.

    Args:
        env_id: A pool_env id.
        num_envs: Tables.
        autoreset_mode: Gymnasium's autoreset mode (same-step: no reset no-op steps).
        **env_kwargs: ``gymnasium.make`` keyword arguments of the tables.

    Returns:
        The :class:`~pool_env.envs.vector.PoolVectorEnv`.
    """
    return gym.make_vec(
        env_id,
        num_envs=num_envs,
        vectorization_mode="vector_entry_point",
        autoreset_mode=AutoresetMode(autoreset_mode),
        **env_kwargs,
    )


class SameStepEpisodeStatistics(VectorWrapper):
    """Episode return, length and time of a same-step vector env, CleanRL's way.

    When tables end an episode, ``info["episode"]`` holds ``"r"``, ``"l"``, ``"t"`` arrays
    over the tables (0 where none ended) and ``info["_episode"]`` the mask: the layout of
    Gymnasium's ``RecordEpisodeStatistics``, counted for same-step autoreset (the step that
    ends an episode is its last, the next step is the new episode's first).

    Raises:
        ValueError: If the env does not autoreset same-step.
    """

    def __init__(self, env: VectorEnv) -> None:
        super().__init__(env)
        if env.metadata.get("autoreset_mode") != AutoresetMode.SAME_STEP:
            raise ValueError(
                "SameStepEpisodeStatistics needs autoreset_mode SAME_STEP, got "
                f"{env.metadata.get('autoreset_mode')}; use gymnasium's RecordEpisodeStatistics"
            )
        self.episode_returns = np.zeros(self.num_envs)
        self.episode_lengths = np.zeros(self.num_envs, dtype=np.int64)
        self.episode_starts = np.zeros(self.num_envs)

    def reset(self, **kwargs: Any) -> tuple[Any, dict[str, Any]]:
        """Reset the env and the running statistics."""
        obs, info = self.env.reset(**kwargs)
        self.episode_returns[:] = 0.0
        self.episode_lengths[:] = 0
        self.episode_starts[:] = time.perf_counter()
        return obs, info

    def step(self, actions: Any) -> tuple[Any, Any, Any, Any, dict[str, Any]]:
        """Step; add ``info["episode"]`` for the tables whose episode ended."""
        obs, rewards, terminated, truncated, info = self.env.step(actions)
        self.episode_returns += rewards
        self.episode_lengths += 1
        dones = np.logical_or(terminated, truncated)
        if dones.any():
            now = time.perf_counter()
            info = dict(info)
            info["episode"] = {
                "r": np.where(dones, self.episode_returns, 0.0),
                "l": np.where(dones, self.episode_lengths, 0),
                "t": np.where(dones, np.round(now - self.episode_starts, 6), 0.0),
            }
            info["_episode"] = dones
            self.episode_returns[dones] = 0.0
            self.episode_lengths[dones] = 0
            self.episode_starts[dones] = now
        return obs, rewards, terminated, truncated, info


def make_cleanrl_envs(
    env_id: str, num_envs: int, gamma: float, clip: float = 10.0, **env_kwargs: Any
) -> VectorEnv:
    """CleanRL ``ppo_continuous_action.py``'s env stack on same-step native tables.

    Innermost first: episode statistics (raw rewards), ``ClipAction``,
    ``NormalizeReward(gamma)``, rewards clipped to ``[-clip, clip]`` (observations are
    already in ``[-1, 1]``: see the module docstring).

    Args:
        env_id: A pool_env id.
        num_envs: Tables.
        gamma: The discount (``NormalizeReward`` scales by the discounted return's spread).
        clip: Reward clip.
        **env_kwargs: ``gymnasium.make`` keyword arguments of the tables.

    Returns:
        The wrapped vector env (``envs.step`` as CleanRL calls it).
    """
    envs: VectorEnv = SameStepEpisodeStatistics(make_vec(env_id, num_envs, **env_kwargs))
    envs = vw.ClipAction(envs)
    envs = vw.NormalizeReward(envs, gamma=gamma)
    return vw.TransformReward(envs, lambda reward: np.clip(reward, -clip, clip))
