"""Solitaire: one player pots every object ball, in any order and any pocket.

The rule itself is :func:`pool_env.game.rules.judge` (compiled; its module docstring
states it). No ball in hand, no rack state, the ``Box(2)`` action (spin: ``Box(4)``) and
the balls-only observation: the :class:`~pool_env.game.rulesets.base.Ruleset` defaults.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels.actions import executed_shots
from pool_env.game.rules import judge
from pool_env.game.rulesets.base import Executed, Judged, Outcome, Ruleset
from pool_env.game.scenes import ScenePlan
from pool_env.game.state import GameState
from pool_env.sim.table import Table


class Solitaire(Ruleset):
    """The solitaire ruleset (``game="solitaire"``, every registered solitaire id)."""

    name = "solitaire"
    code = 0

    def check(
        self, scene: ScenePlan, table: Table, end_on_miss: bool, end_on_foul: bool, players: int
    ) -> None:
        """Refuse the rule games' arguments: ``end_on_foul`` and two players."""
        if end_on_foul or players != 1:
            raise ValueError("end_on_foul and players need a rules game: 'nine', 'ten' or 'eight'")

    def execute(
        self,
        params: NDArray[np.float64],
        pockets: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        actions: NDArray[np.float64],
    ) -> Executed:
        """:func:`pool_env.game.kernels.actions.executed_shots`; nothing extra."""
        shots, states = executed_shots(
            params, actions, tables, state.positions, state.on_table, state.ptrs
        )
        return shots, states, None

    def judge(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        out: Outcome,
        velocities: NDArray[np.float64],
        spins: NDArray[np.float64] | None,
        extra: Any,
    ) -> Judged:
        """:func:`pool_env.game.rules.judge`."""
        return judge(
            params, table.pockets, tables, out.balls, state.positions, state.on_table,
            state.shots, out.final, out.pocketed, out.first,
        )  # fmt: skip
