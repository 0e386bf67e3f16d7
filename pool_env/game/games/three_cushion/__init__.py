"""Three-cushion carom (UMB), as one package: everything the game owns.

Its ruleset (:mod:`.game`), rules section, reward terms and rack-state columns
(:mod:`.section`), rules (:mod:`.rules`) and starting position (:mod:`.layout`). The game
registers under ``"three_cushion"`` (:mod:`pool_env.game.registry`) and is played on
``Table.preset("carom")``, spin level only.
"""

from __future__ import annotations

from pool_env.game.games.three_cushion.game import THREE_CUSHION, ThreeCushion
from pool_env.game.games.three_cushion.section import REWARD_TERMS, ThreeCushionRules

#: The rulesets this package registers, by name.
GAMES = {THREE_CUSHION.name: THREE_CUSHION}

__all__ = ["GAMES", "REWARD_TERMS", "THREE_CUSHION", "ThreeCushion", "ThreeCushionRules"]
