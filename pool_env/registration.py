"""Gymnasium registration of the pool environments (idempotent: safe to call again)."""

from __future__ import annotations

from typing import Any

import gymnasium as gym

ENTRY_POINT = "pool_env.env:PoolEnv"

#: ``gymnasium.make_vec(id, num_envs=n)`` builds this batched env (one compiled call per
#: step for all tables); ``vectorization_mode="sync"`` / ``"async"`` still wrap PoolEnvs.
VECTOR_ENTRY_POINT = "pool_env.vector:PoolVectorEnv"

#: id -> (make() keyword arguments, max_episode_steps).
ENV_IDS: dict[str, tuple[dict[str, Any], int]] = {
    # The configurable one: 3 random object balls by default; every argument via make().
    "pool_env/Pool-v0": ({}, 50),
    # One shot per episode (a miss ends it, a pot clears the table): a clean contextual
    # bandit whose success rate is the pot rate. end_on_miss=False makes it multi-shot.
    "pool_env/OneBall-v0": ({"scene": "one_ball", "end_on_miss": True}, 10),
    # Break, then keep shooting until the table is clear: 50 shots is ~5 a ball.
    "pool_env/NineBall-v0": ({"scene": "nine_ball"}, 50),
    "pool_env/EightBall-v0": ({"scene": "eight_ball"}, 80),
    # The games under their rules (pool_env.game.kernels.wpa), one agent at the table:
    # fouls, ball in hand (Box(5) actions), a break at break speed; the episode ends when
    # the rack is won or lost (end_on_foul=True: at the first foul or missed turn).
    "pool_env/NineBallGame-v0": ({"scene": "nine_ball", "game": "nine"}, 100),
    "pool_env/EightBallGame-v0": ({"scene": "eight_ball", "game": "eight"}, 150),
}


def register_envs() -> None:
    """Register every id of :data:`ENV_IDS` that is not registered yet."""
    for env_id, (kwargs, max_steps) in ENV_IDS.items():
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point=ENTRY_POINT,
                vector_entry_point=VECTOR_ENTRY_POINT,
                kwargs=kwargs,
                max_episode_steps=max_steps,
            )


#: The ids played under the 9-ball or 8-ball rules (``Box(5)`` actions); the others are
#: solitaire (``Box(2)``).
GAME_IDS: tuple[str, ...] = tuple(k for k, (kw, _) in ENV_IDS.items() if "game" in kw)
