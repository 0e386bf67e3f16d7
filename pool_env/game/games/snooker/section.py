"""Snooker's section of the config, and its reward terms."""

from __future__ import annotations

from dataclasses import dataclass

from pool_env.game.ruleset import RulesSection

#: The reward terms and their default scales, in the judge's order (the WPA games' names,
#: snooker's meanings): ``pot`` per point the striker scores, ``foul`` per penalty point
#: the striker's foul gives the opponent, ``win`` for the frame won (lost: minus the
#: scale; 0 by default: the points already say who leads). ``pool_env/SnookerBreak-v1``
#: sets ``foul`` to 0: its reward is the points of the break.
REWARD_TERMS: dict[str, float] = {"pot": 1.0, "foul": -1.0, "win": 0.0}


@dataclass(frozen=True)
class SnookerRules(RulesSection):
    """The rules section of snooker.

    Attributes:
        game: ``"snooker"``.
        end_on_foul: The episode is one visit to the table: it ends when the turn would
            pass (a foul, or a stroke that scores nothing), or the frame is decided
            (``pool_env/SnookerBreak-v1``). Else the frame goes on, the turn passing.
    """

    game: str = "snooker"
    end_on_foul: bool = False
