"""Gymnasium's generators for the tables: each table draws as ``gym.Env.reset(seed=)`` makes it.

The decision process (:class:`pool_env.game.state.GameState`) draws from whatever generator
each table holds; a front gives it one here, as Gymnasium makes it, so that table ``i`` of
:class:`~pool_env.PoolVectorEnv` seeded with ``s`` plays exactly as :class:`~pool_env.PoolEnv`
reset with ``seed=s``.
"""

from __future__ import annotations

import numpy as np
from gymnasium.utils import seeding

from pool_env.game.state import GameState


def seed_table(state: GameState, table: int, seed: int | None) -> None:
    """Give ``table`` a new generator, as ``gymnasium.Env.reset(seed=seed)`` makes one."""
    rng, used = seeding.np_random(seed)
    state.use_generator(table, rng, used)


def seeded_generators(state: GameState) -> list[np.random.Generator]:
    """Every table's generator, making random ones (seed ``None``) for tables never seeded."""
    for i, rng in enumerate(state.generators):
        if rng is None:
            seed_table(state, i, None)
    return state.generators  # type: ignore[return-value]
