"""Candidate actions under the rules: K actions from one table, played side by side.

The game layer's batched rollout, for a search player or a lookahead: each candidate plays
on its own copy of the table (positions, rack state, shot count and the table's generator,
whose bit state is copied, so every candidate draws the execution noise the real step
would draw next), through the one :func:`~pool_env.game.step.step`; the simulator runs
them as one batch (:func:`pool_env.sim.simulate_batch_threads` from
:data:`~pool_env.sim.batch.PARALLEL_FROM` candidates on). Candidate ``k`` ends exactly as
``step(config, state, [table], actions[k:k + 1])`` would leave the table, bit for bit; the
given state is never changed.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.game.config import GameConfig
from pool_env.game.state import GameState, new_state
from pool_env.game.step import StepResult, step

__all__ = ["candidates_state", "rollout_actions"]


def candidates_state(state: GameState, table: int, k: int) -> GameState:
    """``k`` copies of ``state``'s table ``table``, each with a copy of its generator.

    Raises:
        ValueError: On a table index out of range, ``k < 1``, or a table never seeded (its
            noise would not be the real step's).
    """
    if not 0 <= table < state.n_tables:
        raise ValueError(f"table must be in [0, {state.n_tables}), got {table!r}")
    if k < 1:
        raise ValueError(f"at least one candidate action is needed, got {k}")
    rng = state.generators[table]
    if rng is None:
        raise ValueError(f"table {table} has no generator yet: reset it first")
    copies = new_state(k, state.positions.shape[1], state.rack.shape[1])
    copies.positions[...] = state.positions[table]
    copies.on_table[...] = state.on_table[table]
    copies.shots[...] = state.shots[table]
    copies.rack[...] = state.rack[table]
    bits = rng.bit_generator.state
    for c in range(k):
        twin = np.random.Generator(type(rng.bit_generator)())
        twin.bit_generator.state = bits
        copies.use_generator(c, twin, state.seeds[table])
    return copies


def rollout_actions(
    config: GameConfig,
    state: GameState,
    table: int,
    actions: NDArray[np.float64],
    parallel: bool | None = None,
) -> tuple[StepResult, GameState]:
    """Play each of ``actions`` from table ``table`` of ``state``, on a copy each.

    Args:
        config: The game.
        state: The tables; left as it is.
        table: The table the candidates start from.
        actions: ``(K, config.action_size)`` checked actions
            (:func:`pool_env.game.checks.check_actions`).
        parallel: As :func:`~pool_env.game.step.step` (``None``: from ``PARALLEL_FROM``).

    Returns:
        The :class:`~pool_env.game.step.StepResult` (row ``k``: candidate ``k``) and the
        ``K`` tables after the candidates, as a new :class:`GameState`.
    """
    copies = candidates_state(state, table, actions.shape[0])
    tables = np.arange(actions.shape[0], dtype=np.intp)
    return step(config, copies, tables, actions, parallel=parallel), copies
