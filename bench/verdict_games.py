"""Our games' verdicts of a :class:`~bench.verdict_shots.Case`, through their envs.

:func:`game_judge` returns ``judge(case, outcome)``: the verdict (the form of
:mod:`bench.verdict_rules`) our game's own rules give the shot, on our physics
(``outcome=None``) or on a given outcome (pooltool's, so that the rules are compared on
identical outcomes), or ``None`` while the games are not in this tree.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from bench.verdict_outcomes import Summary
from bench.verdict_shots import Case

Judge = Callable[[Case, Summary | None], dict[str, Any]]


def game_judge() -> Judge | None:
    """The judge of our games, or ``None`` if ``snooker`` and ``three_cushion`` are missing."""
    from pool_env.game.registry import BUILTIN

    if not {"snooker", "three_cushion"} <= set(BUILTIN):
        return None
    raise NotImplementedError("the games' envs are to be wired here once they land")
