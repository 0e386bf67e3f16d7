"""The ``info`` keys the WPA games add to every step, read from the judge's integer results."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.games.wpa.judge import BALL_ON, FOUL, KEEPS, LOSS, PLAY, WINNER
from pool_env.game.games.wpa.rack_state import FOUL_NAMES, HANDED_BACK, LOSS_NAMES, PUSHED_OUT

#: Every key a step adds under rules: ``foul`` (None or its name), ``legal``, ``loss``
#: (None or why the shooter lost the rack), ``turn_over`` (a foul, or a legal shot that
#: does not keep the table: with two players the opponent would come to the table), the
#: ball on before the shot (-1: not a single ball, 8-ball before the group is cleared) and
#: the winner (-1 while undecided; integers rather than None, so that Gymnasium's vector
#: info has one dtype per key).
RULE_KEYS: tuple[str, ...] = ("foul", "legal", "loss", "turn_over", "ball_on", "winner")

#: The keys 9-ball and 10-ball add (they have the option): ``push_out`` (the shot was
#: played as a push-out) and ``handed_back`` (the step used the option to hand the table
#: back: no shot was played).
OPTION_KEYS: tuple[str, ...] = ("push_out", "handed_back")

_FOULS = np.array(FOUL_NAMES, dtype=object)
_LOSSES = np.array(LOSS_NAMES, dtype=object)


def info_row(hits: list[int], has_option: bool) -> dict[str, Any]:
    """:func:`info_columns` of one table's row, as Python scalars.

    No array is made: a ``PoolEnv`` step builds this dict on every shot.
    """
    foul = hits[FOUL]
    row: dict[str, Any] = {
        "foul": FOUL_NAMES[foul],
        "legal": foul == 0,
        "loss": LOSS_NAMES[hits[LOSS]],
        "turn_over": foul != 0 or hits[KEEPS] == 0,
        "ball_on": hits[BALL_ON],
        "winner": hits[WINNER],
    }
    if has_option:
        row["push_out"] = hits[PLAY] == PUSHED_OUT
        row["handed_back"] = hits[PLAY] == HANDED_BACK
    return row


def info_columns(hits: NDArray[np.int64], has_option: bool) -> dict[str, NDArray[Any]]:
    """:data:`RULE_KEYS` (and :data:`OPTION_KEYS` with the option) over ``hits``' rows."""
    codes = hits[:, FOUL]
    columns: dict[str, NDArray[Any]] = {
        "foul": _FOULS[codes],
        "legal": codes == 0,
        "loss": _LOSSES[hits[:, LOSS]],
        "turn_over": (codes != 0) | (hits[:, KEEPS] == 0),
        "ball_on": hits[:, BALL_ON],
        "winner": hits[:, WINNER],
    }
    if has_option:
        columns["push_out"] = hits[:, PLAY] == PUSHED_OUT
        columns["handed_back"] = hits[:, PLAY] == HANDED_BACK
    return columns
