"""The env creator RLlib calls in every EnvRunner: pool ids by their plain name, in any worker.

RLlib's EnvRunners are separate processes, on this machine or on other nodes, that never ran
the driver's ``import pool_env``; ``config.environment("pool_env/OneBallRoll-v1")`` alone fails
there with ``NamespaceNotFound``. :func:`register` registers :func:`make_env` under the plain
id with Ray's registry (shared by every worker of the cluster); RLlib then calls it in each
EnvRunner, where it imports the package (which registers the ids) before making the env.

With ``gym_env_vectorize_mode="vector_entry_point"`` RLlib passes ``num_envs`` and
:func:`make_env` returns one :class:`~pool_env.envs.vector.PoolVectorEnv`: all the runner's
tables step in one compiled call.

Autoreset: RLlib 2.60's ``SingleAgentEnvRunner`` implements only Gymnasium's next-step
autoreset (it records the observation of the step after an episode ends as the next
episode's first observation), so the tables run in ``NEXT_STEP`` mode and one-shot episodes
cost two vector steps each (measured: 0.5 episodes per vector step per table; the SB3
adapter, :mod:`agents.vec.native_vec`, runs same-step: 1.0). Another mode is refused rather
than silently corrupting the episodes.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from typing import Any

import gymnasium as gym
from gymnasium.vector import AutoresetMode


def make_env(
    config: Mapping[str, Any], env_id: str | None = None
) -> gym.Env | gym.vector.VectorEnv:
    """Make a pool env in an EnvRunner (the RLlib env creator).

    Args:
        config: RLlib's ``EnvContext``: ``env_kwargs`` (``gymnasium.make`` keyword
            arguments), ``env_id`` unless given, and, from RLlib in ``vector_entry_point``
            mode, ``num_envs``.
        env_id: The pool_env id (:func:`register` binds it).

    Returns:
        A ``PoolVectorEnv`` of ``num_envs`` tables (next-step autoreset), or one
        ``gymnasium.make`` env when RLlib asks for a single env.

    Raises:
        ValueError: Without ``env_id``, with a non-pool id, or with another autoreset mode.
    """
    import pool_env  # noqa: F401  (registers the ids in this worker process)
    from pool_env.envs.registration import ENV_IDS

    env_id = env_id or config.get("env_id")
    if env_id not in ENV_IDS:
        raise ValueError(f"the env id must be one of {list(ENV_IDS)}, got {env_id!r}")
    kwargs = dict(config.get("env_kwargs") or {})
    mode = AutoresetMode(kwargs.pop("autoreset_mode", AutoresetMode.NEXT_STEP))
    if mode != AutoresetMode.NEXT_STEP:
        raise ValueError(
            "RLlib's EnvRunner implements next-step autoreset only; got autoreset_mode="
            f"{mode.value!r}"
        )
    num_envs = config.get("num_envs")
    if num_envs is None:
        return gym.make(env_id, **kwargs)
    return gym.make_vec(
        env_id, num_envs=int(num_envs), vectorization_mode="vector_entry_point", **kwargs
    )


def register(env_id: str) -> None:
    """Register :func:`make_env` with Ray under ``env_id`` (call in the driver, before build).

    Raises:
        ValueError: If ``env_id`` is not a pool_env id.
    """
    from ray.tune.registry import register_env  # the rllib extra: only when registering

    from pool_env.envs.registration import ENV_IDS

    if env_id not in ENV_IDS:
        raise ValueError(f"{env_id!r} is not a pool_env id: use one of {list(ENV_IDS)}")
    register_env(env_id, functools.partial(make_env, env_id=env_id))
