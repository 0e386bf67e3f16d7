"""Solitaire, as one package: its ruleset, its compiled rule and its parameter tail.

The game registers under ``"solitaire"`` (:mod:`pool_env.game.registry`): every
solitaire id (``Pool``, ``OneBall``, ``NineBall``, ``EightBall``) plays it.
"""

from __future__ import annotations

from pool_env.game.games.solitaire.game import REWARD_TERMS, Solitaire

#: The one solitaire ruleset.
SOLITAIRE = Solitaire()

#: The rulesets this package registers, by name.
GAMES = {SOLITAIRE.name: SOLITAIRE}

__all__ = ["GAMES", "REWARD_TERMS", "SOLITAIRE", "Solitaire"]
