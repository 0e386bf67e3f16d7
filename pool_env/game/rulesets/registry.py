"""Every game by its config value: the one list a new game joins."""

from __future__ import annotations

from pool_env.game.rulesets.base import Ruleset
from pool_env.game.rulesets.solitaire import Solitaire
from pool_env.game.rulesets.wpa import EIGHT, NINE, TEN

#: Every game by its config value (``gym.make(..., game=...)``), in the order of the
#: kernels' game codes (``params[GAME]``).
RULESETS: dict[str, Ruleset] = {r.name: r for r in (Solitaire(), NINE, EIGHT, TEN)}


def ruleset_for(game: object) -> Ruleset:
    """The ruleset named ``game``.

    Raises:
        ValueError: For a name that is no game.
    """
    ruleset = RULESETS.get(game) if isinstance(game, str) else None
    if ruleset is None:
        raise ValueError(f"game must be one of {list(RULESETS)}, got {game!r}")
    return ruleset
