"""The games, one :class:`~pool_env.game.rulesets.base.Ruleset` each, by their config value.

:func:`pool_env.game.config.make_config` looks ``game`` up in :data:`RULESETS` and the
:class:`~pool_env.game.config.GameConfig` carries the ruleset (``config.ruleset``); the
step, the observation and the ``info`` ask it wherever games differ
(:mod:`pool_env.game.rulesets.base` lists the steps). Modules: :mod:`.base` (the
interface), :mod:`.solitaire`, :mod:`.wpa` (9-ball and 8-ball), :mod:`.registry` (every
game by name).
"""

from __future__ import annotations

from pool_env.game.rulesets.base import Outcome, Ruleset
from pool_env.game.rulesets.registry import RULESETS, ruleset_for

__all__ = ["RULESETS", "Outcome", "Ruleset", "ruleset_for"]
