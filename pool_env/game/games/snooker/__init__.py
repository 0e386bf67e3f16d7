"""Snooker (WPBSA), as one package: everything the game owns.

Its ruleset (:mod:`.game`: :data:`SNOOKER`), rules section and reward terms
(:mod:`.section`), the table's markings and scenes (:mod:`.markings`), compiled rules
(:mod:`.rules`, with :mod:`.geometry`, over the frame state of :mod:`.rack_state`), the
step's kernels (:mod:`.judge`), observation (:mod:`.observe`), ``info`` keys (:mod:`.info`)
and its tail of the kernel parameters (:mod:`.params`). The game registers under
``"snooker"`` (:mod:`pool_env.game.registry`). Ball numbers: 0 the cue ball, 1-15 the
reds, 16 yellow, 17 green, 18 brown, 19 blue, 20 pink, 21 black.
"""

from __future__ import annotations

from pool_env.game.games.snooker.game import SNOOKER, Snooker
from pool_env.game.games.snooker.section import REWARD_TERMS, SnookerRules

#: The rulesets this package registers, by name.
GAMES = {SNOOKER.name: SNOOKER}

__all__ = ["GAMES", "REWARD_TERMS", "SNOOKER", "Snooker", "SnookerRules"]
