"""The games, one :class:`~pool_env.game.rulesets.base.Ruleset` each, by their config value.

:func:`pool_env.game.config.make_config` looks ``game`` up in :data:`RULESETS` and the
:class:`~pool_env.game.config.GameConfig` carries the ruleset (``config.ruleset``); the
step, the observation and the ``info`` ask it wherever games differ
(:mod:`pool_env.game.rulesets.base` lists the steps). Modules: :mod:`.base` (the
interface), :mod:`.solitaire`, :mod:`.wpa` (9-ball and 8-ball).
"""

from __future__ import annotations

from pool_env.game.rulesets.base import Outcome, Ruleset
from pool_env.game.rulesets.solitaire import Solitaire
from pool_env.game.rulesets.wpa import EIGHT, NINE

__all__ = ["RULESETS", "Outcome", "Ruleset", "ruleset_for"]

#: Every game by its config value (``gym.make(..., game=...)``), in the order of the
#: kernels' game codes (``params[GAME]``).
RULESETS: dict[str, Ruleset] = {r.name: r for r in (Solitaire(), NINE, EIGHT)}


def ruleset_for(game: object) -> Ruleset:
    """The ruleset named ``game``.

    Raises:
        ValueError: For a name that is no game.
    """
    ruleset = RULESETS.get(game) if isinstance(game, str) else None
    if ruleset is None:
        raise ValueError(f"game must be one of {list(RULESETS)}, got {game!r}")
    return ruleset
