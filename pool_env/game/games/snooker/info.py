"""The ``info`` keys snooker adds to every step, read from the judge's integer results."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.games.snooker.judge import (
    BALL_ON,
    BREAK_AFTER,
    FOUL,
    FREE,
    NOMINATED,
    PENALTY,
    POINTS,
    SCORE_A,
    SCORE_B,
    TURN_OVER,
    WINNER_AFTER,
)
from pool_env.game.games.snooker.rack_state import FOUL_NAMES

#: The keys: ``foul`` (None or its name), ``penalty`` (points given to the opponent),
#: ``points`` (scored by the striker), ``ball_on`` (1: a red; a colour's number; 0: a
#: colour not named), ``nominated`` (the colour nominated or taken as free ball, -1: none),
#: ``free_ball`` (the stroke was a free ball), ``turn_over``, ``break`` (the striker's
#: break after the stroke), ``score_0`` and ``score_1`` (after it), ``winner`` (-1 while
#: the frame goes on).
RULE_KEYS: tuple[str, ...] = (
    "foul", "penalty", "points", "ball_on", "nominated", "free_ball", "turn_over", "break",
    "score_0", "score_1", "winner",
)  # fmt: skip

_FOULS = np.array(FOUL_NAMES, dtype=object)
_INTS = {"penalty": PENALTY, "points": POINTS, "ball_on": BALL_ON, "nominated": NOMINATED,
         "break": BREAK_AFTER, "score_0": SCORE_A, "score_1": SCORE_B,
         "winner": WINNER_AFTER}  # fmt: skip


def info_row(hits: list[int]) -> dict[str, Any]:
    """:func:`info_columns` of one table's row, as Python scalars."""
    row: dict[str, Any] = {"foul": FOUL_NAMES[hits[FOUL]]}
    row.update({key: hits[column] for key, column in _INTS.items()})
    row["free_ball"] = hits[FREE] != 0
    row["turn_over"] = hits[TURN_OVER] != 0
    return {key: row[key] for key in RULE_KEYS}


def info_columns(hits: NDArray[np.int64]) -> dict[str, NDArray[Any]]:
    """:data:`RULE_KEYS` over ``hits``' rows."""
    columns: dict[str, NDArray[Any]] = {"foul": _FOULS[hits[:, FOUL]]}
    columns.update({key: hits[:, column].copy() for key, column in _INTS.items()})
    columns["free_ball"] = hits[:, FREE] != 0
    columns["turn_over"] = hits[:, TURN_OVER] != 0
    return {key: columns[key] for key in RULE_KEYS}
