"""Solitaire: one player pots every object ball, in any order and any pocket.

The rule itself is :func:`pool_env.game.games.solitaire.rules.judge` (compiled; its module
docstring states it). No ball in hand, no rack state, the ``Box(2)`` action (spin:
``Box(4)``) and the balls-only observation: the :class:`~pool_env.game.ruleset.Ruleset`
defaults.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.game.games.solitaire import params as sp
from pool_env.game.games.solitaire.rules import judge
from pool_env.game.kernels.params import game_tail
from pool_env.game.ruleset import (
    Executed,
    Judged,
    Outcome,
    Ruleset,
    Setup,
    Turn,
    place_cue_balls,
)

#: Solitaire's reward terms and their default scales, in the judge's order: per object
#: ball potted, a scratch, a shot that touches no ball, and the shaping potential's change
#: (:func:`pool_env.game.kernels.observe.potential`; 0: none).
REWARD_TERMS: dict[str, float] = {"pot": 1.0, "scratch": -1.0, "no_contact": 0.0, "shaping": 0.0}


class Solitaire(Ruleset):
    """The solitaire ruleset (``game="solitaire"``, every registered solitaire id)."""

    name = "solitaire"
    reward_terms = REWARD_TERMS

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """Refuse two players; the tail: ``end_on_miss`` and the reward scales."""
        if setup.players != 1:
            raise ValueError("players need a rules game: 'nine', 'ten' or 'eight'")
        scales = zip((sp.W_POT, sp.W_SCRATCH, sp.W_NO_CONTACT, sp.W_SHAPING), REWARD_TERMS,
                     strict=True)  # fmt: skip
        values = {index: setup.rewards[term] for index, term in scales}
        return game_tail({sp.END_ON_MISS: float(setup.end_on_miss), **values})

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        """:func:`pool_env.game.games.solitaire.rules.judge`, then a covered head spot."""
        state = turn.state
        judged = Judged(*judge(
            turn.config.params, turn.config.table.pockets, turn.tables, out.balls,
            state.positions, state.on_table, state.shots, out.final, out.pocketed, out.first,
        ))  # fmt: skip
        place_cue_balls(turn, judged.flags)
        return judged
