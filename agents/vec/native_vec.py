"""Stable-Baselines3 ``VecEnv`` over :class:`pool_env.PoolVectorEnv` (``--vec native``).

All tables step in one compiled call instead of one Python call (``DummyVecEnv``) or one
process (``SubprocVecEnv``) per environment. The adapter follows SB3's conventions: a
finished table is reset within the step (the vector env runs in ``SAME_STEP`` autoreset
mode), its last observation is ``infos[i]["terminal_observation"]``, and every info has
``"TimeLimit.truncated"``. Given the same seed and actions it returns what a ``DummyVecEnv``
of ``gymnasium.make(env_id)`` environments returns (rewards as float32, as there).

``VecMonitor`` (episode statistics) and ``VecNormalize`` go on top as on any ``VecEnv``;
:func:`make_native_vec_env` adds neither, so that the caller wraps exactly once.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.vector import AutoresetMode
from numpy.typing import NDArray
from stable_baselines3.common.vec_env import VecEnv
from stable_baselines3.common.vec_env.base_vec_env import VecEnvIndices, VecEnvStepReturn

import pool_env  # noqa: F401  (registers the ids and their vector entry point)
from pool_env import ENV_IDS, PoolVectorEnv
from pool_env.envs.registration import VECTOR_ENTRY_POINT
from pool_env.game.info import info_keys

#: Attributes that hold one value per table: ``get_attr`` returns each table's own.
PER_TABLE = frozenset({"positions", "on_table", "shots", "np_random", "np_random_seed"})


class NativeVecEnv(VecEnv):
    """SB3 ``VecEnv`` adapter of a :class:`~pool_env.PoolVectorEnv`.

    Args:
        env: The vector env; it must use ``AutoresetMode.SAME_STEP``.

    Raises:
        ValueError: If ``env`` resets finished tables in another mode.
    """

    def __init__(self, env: PoolVectorEnv) -> None:
        if env.autoreset_mode != AutoresetMode.SAME_STEP:
            raise ValueError(
                "NativeVecEnv needs a PoolVectorEnv with autoreset_mode=SAME_STEP (SB3 resets "
                f"finished environments within the step), got {env.autoreset_mode}"
            )
        self.env = env  # before VecEnv.__init__, which reads render_mode through get_attr
        # PoolEnv's step info keys, in its order: every id's, the spin ids' tip, the game's
        # reward terms, then the game's own (9-ball's and 10-ball's push-out and option).
        self._info_keys = info_keys(env.config.ruleset, env.config.spin)
        self._actions: NDArray[Any] | None = None
        super().__init__(env.num_envs, env.single_observation_space, env.single_action_space)

    def reset(self) -> NDArray[np.float32]:
        """Reset every table with the seeds of :meth:`seed` and options of ``set_options``."""
        seeds = None if all(s is None for s in self._seeds) else list(self._seeds)
        options = self._options[0] if self._options else {}
        if any(o != options for o in self._options):
            raise ValueError("NativeVecEnv takes one set of reset options for all tables")
        obs, _ = self.env.reset(seed=seeds, options=dict(options) or None)
        self.reset_infos = [{} for _ in range(self.num_envs)]
        self._reset_seeds()
        self._reset_options()
        return obs

    def step_async(self, actions: NDArray[Any]) -> None:
        """Keep the actions for :meth:`step_wait`."""
        self._actions = actions

    def step_wait(self) -> VecEnvStepReturn:
        """One shot on every table; finished tables are reset, SB3-style."""
        if self._actions is None:
            raise RuntimeError("call step_async(actions) before step_wait()")
        obs, rewards, terminated, truncated, info = self.env.step(self._actions)
        self._actions = None
        dones = terminated | truncated
        final = info.get("final_info", {})
        columns = []
        keys = [key for key in self._info_keys if key in info or key in final]
        for key in keys:  # each table's info is in the top level or, if it ended, final
            if key in info and key in final:
                columns.append(np.where(info[f"_{key}"], info[key], final[key]).tolist())
            else:
                columns.append((info[key] if key in info else final[key]).tolist())
        keys.append("TimeLimit.truncated")
        columns.append((truncated & ~terminated).tolist())
        infos = [dict(zip(keys, values, strict=True)) for values in zip(*columns, strict=True)]
        if dones.any():
            final_obs = info["final_obs"]
            for i in np.flatnonzero(dones).tolist():
                infos[i]["terminal_observation"] = final_obs[i]
        return obs, rewards.astype(np.float32), dones, infos

    def close(self) -> None:
        """Close the vector env."""
        self.env.close()

    def get_attr(self, attr_name: str, indices: VecEnvIndices = None) -> list[Any]:
        """The vector env's attribute, once per table (each table's own for per-table ones)."""
        value = getattr(self.env, attr_name)
        tables = self._get_indices(indices)
        if attr_name in PER_TABLE:
            return [value[i] for i in tables]
        return [value for _ in tables]

    def set_attr(self, attr_name: str, value: Any, indices: VecEnvIndices = None) -> None:
        """Set an attribute shared by all tables (a subset of tables cannot differ)."""
        if len(list(self._get_indices(indices))) != self.num_envs:
            raise ValueError("the tables of a NativeVecEnv share their attributes: set all")
        setattr(self.env, attr_name, value)

    def env_method(
        self, method_name: str, *method_args: Any, indices: VecEnvIndices = None, **kwargs: Any
    ) -> list[Any]:
        """Only ``render`` (one frame per table): the tables have no methods of their own."""
        if method_name != "render":
            raise NotImplementedError(f"NativeVecEnv cannot call {method_name!r} per table")
        frames = self.env.render()
        return [None if frames is None else frames[i] for i in self._get_indices(indices)]

    def env_is_wrapped(
        self, wrapper_class: type[gym.Wrapper], indices: VecEnvIndices = None
    ) -> list[bool]:
        """No table is wrapped (``VecMonitor`` goes around the whole ``VecEnv``)."""
        return [False for _ in self._get_indices(indices)]

    def get_images(self) -> Sequence[NDArray[np.uint8] | None]:
        """One frame per table (``render_mode="rgb_array"``)."""
        frames = self.env.render()
        return [None] * self.num_envs if frames is None else list(frames)


def make_native_vec_env(
    env_id: str, n_envs: int, seed: int, env_kwargs: dict | None = None
) -> VecEnv:
    """SB3 ``VecEnv`` of ``n_envs`` tables of ``env_id``, all stepped in one compiled call.

    The counterpart of ``make_vec_env(env_id, n_envs, seed, env_kwargs=...)`` with a
    ``DummyVecEnv``: table ``i`` is seeded with ``seed + i`` at the first reset, and the
    tables are the id's ``PoolEnv`` with its ``TimeLimit``. No ``Monitor``: wrap the result
    in ``VecMonitor`` (and ``VecNormalize``) as needed.

    Args:
        env_id: A registered pool_env id (``"pool_env/OneBallRoll-v1"``).
        n_envs: Number of tables.
        seed: Seed of table 0 (``None``: random).
        env_kwargs: ``PoolEnv`` keyword arguments, as for ``gymnasium.make``.

    Returns:
        The ``VecEnv`` (a :class:`NativeVecEnv`).

    Raises:
        ValueError: If ``env_id`` is not a pool_env id.
    """
    name = env_id.split(":", 1)[-1]  # "pool_env:pool_env/X" names the module to import
    if name not in gym.registry or gym.spec(name).vector_entry_point != VECTOR_ENTRY_POINT:
        raise ValueError(f"{env_id!r} is not a pool_env id: use one of {list(ENV_IDS)}")
    kwargs = {**(env_kwargs or {}), "autoreset_mode": AutoresetMode.SAME_STEP}
    env = gym.make_vec(name, num_envs=n_envs, vectorization_mode="vector_entry_point", **kwargs)
    vec_env = NativeVecEnv(env)  # type: ignore[arg-type]
    vec_env.seed(seed)
    return vec_env
