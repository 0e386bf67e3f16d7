"""Three-cushion's section of the config, its reward terms and its rack-state columns."""

from __future__ import annotations

from dataclasses import dataclass

from pool_env.game.ruleset import RulesSection

#: UMB's match distance for the World Championship and World Cups (50 points since 2020;
#: 40 before), the default point target.
DEFAULT_TARGET = 50
#: UMB's inning limit of a 50-point match (0: no limit).
DEFAULT_INNING_LIMIT = 50

#: The reward terms and their default scales, in the judge's order: per point (a valid
#: carom), and a foul (UMB: a foul scores nothing and ends the inning, no penalty).
REWARD_TERMS: dict[str, float] = {"point": 1.0, "foul": 0.0}

#: The rack state's columns: who strikes (0 white, 1 yellow), each player's points and
#: innings begun, the points of the current inning, 1 on the opening shot, 1 in the second
#: player's equalizing inning, and the winner (-1 undecided, 0 or 1, 2 a draw).
(SHOOTER, SCORE_0, SCORE_1, INNINGS_0, INNINGS_1, RUN, BREAKING, EQUALIZING, WINNER,
 N_RACK) = range(10)  # fmt: skip

#: The winner column's value of a drawn match.
DRAW = 2


@dataclass(frozen=True)
class ThreeCushionRules(RulesSection):
    """The rules section of three-cushion (UMB).

    Attributes:
        game: ``"three_cushion"``.
        target: Points that win the match (a positive integer).
        inning_limit: Innings per player after which the match ends on points (0: none).
        equalizing_inning: When the first player reaches the target, the second plays one
            more inning to equal the innings (UMB; a draw if it reaches the target too).
    """

    game: str = "three_cushion"
    target: int = DEFAULT_TARGET
    inning_limit: int = DEFAULT_INNING_LIMIT
    equalizing_inning: bool = True
