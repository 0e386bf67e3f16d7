"""The rules of three-cushion (UMB), vectorised over the tables that shot (numpy).

UMB World Rules of Carom Billiard (edition of 1 January 1989, the articles the UMB's
current sports rules keep):

* art. 83 (three cushions): a point (a carom) when the striker's cue ball meets both object
  balls and has touched at least three cushions before it meets the second one (the
  simulator's ``second_hit`` and ``cushions_at_second`` of the cue ball: its own cushion
  impacts from the shot's start; one cushion hit three times counts three);
* art. 24 and 25: the striker plays on while scoring; a miss ends the inning and the
  opponent plays with his own cue ball (player 0 white, player 1 yellow);
* art. 23: the opening shot must hit the red first (direct attack), else a foul: no point,
  the inning ends (art. 41: a foul cancels the stroke's point; no penalty points);
* art. 29 and the UMB tournament rules: the match ends at the point target or at the
  inning limit (each player the same innings); when the first player reaches the target
  the second plays an equalizing inning, and the match is drawn if it reaches the target
  too (or if the scores are equal at the limit).

With one player (the ``ThreeCushion-v1`` task) the episode is one inning: it ends at the
first miss or foul (or at the target).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from pool_env.game.games.three_cushion.section import (
    BREAKING,
    DRAW,
    EQUALIZING,
    INNINGS_0,
    RUN,
    SCORE_0,
    SHOOTER,
    WINNER,
)

RED = 2
#: Cushion impacts a point needs before the second object ball (UMB art. 83).
CUSHIONS_NEEDED = 3


class Verdict(NamedTuple):
    """What the rules decided for each row (the rack rows are updated in place).

    Attributes:
        point: A valid carom, scored.
        foul: The opening shot did not hit the red first.
        turn_over: The inning ended (a miss, a foul, or the match's end).
        terminated: The match (one player: the inning) is over.
    """

    point: NDArray[np.bool_]
    foul: NDArray[np.bool_]
    turn_over: NDArray[np.bool_]
    terminated: NDArray[np.bool_]


def judge_rows(
    rack: NDArray[np.int64],
    first: NDArray[np.int64],
    second: NDArray[np.int64],
    cushions: NDArray[np.int64],
    target: int,
    inning_limit: int,
    equalizing: bool,
    players: int,
) -> Verdict:
    """Apply one shot per row to the rack rows ``rack`` (``(K, N_RACK)``, in place).

    Args:
        rack: The rack state of each table that shot (:mod:`.section`'s columns).
        first: ``(K,)`` the first ball the striker's cue ball met, -1 for none.
        second: ``(K,)`` the second distinct ball it met, -1 for none.
        cushions: ``(K,)`` its cushion impacts up to that second ball, -1 without one.
        target: Points that win.
        inning_limit: Innings per player (0: none).
        equalizing: The second player's equalizing inning.
        players: 1 (an episode is one inning) or 2 (a match).
    """
    rows = np.arange(rack.shape[0])
    s = rack[:, SHOOTER]
    foul = (rack[:, BREAKING] != 0) & (first != RED)
    point = ~foul & (second >= 0) & (cushions >= CUSHIONS_NEEDED)
    rack[rows, SCORE_0 + s] += point
    rack[:, RUN] = np.where(point, rack[:, RUN] + 1, 0)
    rack[:, BREAKING] = 0
    reached = point & (rack[rows, SCORE_0 + s] >= target)
    if players == 1:
        terminated = ~point | reached
        rack[:, WINNER] = np.where(reached, 0, rack[:, WINNER])
        return Verdict(point, foul, ~point, terminated)
    in_equalizing = rack[:, EQUALIZING] != 0
    scores = rack[:, SCORE_0 : SCORE_0 + 2]
    on_points = np.where(
        scores[:, 0] > scores[:, 1], 0, np.where(scores[:, 1] > scores[:, 0], 1, DRAW)
    )
    # The first player at the target: the second's equalizing inning, or the match.
    to_equalize = reached & (s == 0) & equalizing
    first_wins = reached & (s == 0) & (not equalizing)
    second_reaches = reached & (s == 1)
    missed = ~point
    failed_equalizing = missed & (s == 1) & in_equalizing
    at_limit = missed & (s == 1) & ~in_equalizing & (inning_limit > 0)
    at_limit &= rack[:, INNINGS_0 + 1] >= inning_limit
    winner = np.full(rows.shape[0], -1, dtype=np.int64)
    winner[first_wins | failed_equalizing] = 0
    winner[second_reaches] = np.where(in_equalizing, DRAW, 1)[second_reaches]
    winner[at_limit] = on_points[at_limit]
    terminated = winner >= 0
    rack[:, WINNER] = winner
    passes = (missed | to_equalize) & ~terminated
    other = 1 - s
    rack[:, SHOOTER] = np.where(passes, other, s)
    rack[rows, INNINGS_0 + other] += passes
    rack[:, RUN] = np.where(passes, 0, rack[:, RUN])
    rack[:, EQUALIZING] = np.where(to_equalize, 1, rack[:, EQUALIZING])
    return Verdict(point, foul, missed | terminated | to_equalize, terminated)
