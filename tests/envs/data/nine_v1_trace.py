"""Play the 9-ball ids on fixed seeds and random actions: the trace that pins ``-v1``.

``pool_env/NineBallGame-v1`` and ``NineBallGameRoll-v1`` are 9-ball as it was played
before the push-out (which came with ``-v2``). This script plays both ids on fixed seeds with
actions drawn from a seeded generator and records every step's observation, reward and
ending. ``nine_v1_trace.npz`` beside it was written by this script on commit ``097e0ad``
(the last commit before the push-out)::

    git worktree add --detach /tmp/prepush 097e0ad
    cd /tmp/prepush && python /path/to/tests/envs/data/nine_v1_trace.py /path/to/out.npz

``tests/envs/test_id_versions.py`` plays the same on the current code and asserts equality,
bit for bit. The script uses only what both versions have (``gymnasium.make``, ``reset``,
``step``), so it runs unchanged on either.
"""

from __future__ import annotations

import sys
from typing import Any

import numpy as np

#: The ids, their seeds and the steps played per seed (episodes restart when they end).
IDS = ("pool_env/NineBallGameRoll-v1", "pool_env/NineBallGame-v1")
SEEDS = (3, 11, 29)
STEPS = 12


def play(env_id: str) -> dict[str, Any]:
    """Every step's observation, reward, terminated and truncated on ``env_id``."""
    import gymnasium as gym

    import pool_env  # noqa: F401  (registers the ids)

    observations, rewards, endings = [], [], []
    for seed in SEEDS:
        env = gym.make(env_id)
        rng = np.random.default_rng(seed)
        obs, _ = env.reset(seed=seed)
        observations.append(obs)
        low, high = env.action_space.low, env.action_space.high
        for _ in range(STEPS):
            action = rng.uniform(low, high).astype(env.action_space.dtype)
            obs, reward, terminated, truncated, _ = env.step(action)
            observations.append(obs)
            rewards.append(reward)
            endings.append((terminated, truncated))
            if terminated or truncated:
                obs, _ = env.reset()
                observations.append(obs)
        env.close()
    return {
        "observations": np.array(observations, dtype=np.float32),
        "rewards": np.array(rewards, dtype=np.float64),
        "endings": np.array(endings, dtype=np.bool_),
    }


def trace() -> dict[str, np.ndarray]:
    """The trace of every id of :data:`IDS`, keyed ``"<id>/<field>"``."""
    out: dict[str, np.ndarray] = {}
    for env_id in IDS:
        for key, value in play(env_id).items():
            out[f"{env_id}/{key}"] = value
    return out


if __name__ == "__main__":
    np.savez_compressed(sys.argv[1], **trace())
