"""What a simulated outcome is worth to the player who shot it: the leaves of the rack searches.

A *leaf value* maps ``B`` layouts, from the side of the player about to shoot, to that
player's chance to win the rack (or, in run-out mode, to run it out):
``leaf(positions, on_table, in_hand, fouls[, targets]) -> (B,)``; ``targets`` are the
shooter's legal first balls, given off 9-ball (8-ball's groups and the 8: the rack rows after
the step say them, :func:`next_targets`). :class:`LogisticLeaf` wraps the 12-column logistic
(:class:`agents.learned.layout_value.LayoutValue`), :class:`SetLeaf` the
permutation-invariant network of :mod:`agents.learned.set_value` (9-ball only).

:func:`outcome_values` turns a batch of simulated shots (the rules' results and the layouts
they leave) into values for the shooter, by the rules: a won rack is 1 and a lost one 0; a
shot that keeps the table is worth the leaf value of what it leaves; in run-out mode a miss
or a foul is worth 0, against an opponent it is worth one minus the opponent's leaf value
(with ball in hand after a foul). :class:`agents.learned.lookahead.LookaheadAgent` and
:class:`agents.learned.search_player.SearchPlayer` both value their outcomes with it.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from agents.learned.layout_value import LayoutValue, layout_features
from agents.learned.legal_sets import target_sets
from agents.learned.set_value import SetValue
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER
from pool_env.game.geometry import PocketMouths
from pool_env.game.ruleset import Ruleset
from pool_env.game.step import StepResult
from pool_env.sim import Table


class LeafValue(Protocol):
    """The shooter's chance to win (or run out) from ``B`` layouts."""

    def __call__(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        in_hand: NDArray[np.bool_],
        fouls: NDArray[np.int64],
        targets: NDArray[np.int64] | None = None,
    ) -> NDArray[np.float64]:
        """``(B,)`` chances of ``(B, N, 2)`` layouts, ``(B, N)`` flags, ``(B,)``, ``(B, 2)``.

        ``targets``: ``(B, T)`` the shooter's legal first balls padded with -1
        (:func:`~agents.learned.legal_sets.target_sets`); ``None``: the ball on (9-ball).
        """
        ...


class LogisticLeaf:
    """The logistic layout value as a leaf value: its features, then the model.

    Args:
        value: The fitted :class:`LayoutValue`.
        table: The table.
        mouths: Its pockets.
        sigma: The aim error (rad) the features' pot chances are taken at.
        game: The game the layouts are of (:func:`layout_features`' ``game``).
    """

    def __init__(
        self,
        value: LayoutValue,
        table: Table,
        mouths: PocketMouths,
        sigma: float,
        game: str = "nine",
    ) -> None:
        self.value, self.table, self.mouths, self.sigma = value, table, mouths, sigma
        self.game = game

    def __call__(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        in_hand: NDArray[np.bool_],
        fouls: NDArray[np.int64],
        targets: NDArray[np.int64] | None = None,
    ) -> NDArray[np.float64]:
        """As :class:`LeafValue`."""
        feats = layout_features(
            self.table, self.mouths, positions, on_table, in_hand, fouls, self.sigma,
            targets, self.game,
        )  # fmt: skip
        return self.value(feats)


class SetLeaf:
    """The set network as a leaf value: 9-ball's (fitted on 9-ball layouts, the ball on).

    Called with ``targets`` (another game's legal balls) it refuses: its inputs have no
    place for them.

    Args:
        net: The fitted :class:`SetValue`.
        table: The table.
        mouths: Its pockets.
        sigma: The aim error (rad) its inputs' pot chances are taken at.
    """

    def __init__(self, net: SetValue, table: Table, mouths: PocketMouths, sigma: float) -> None:
        self.net, self.table, self.mouths, self.sigma = net, table, mouths, sigma

    def __call__(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        in_hand: NDArray[np.bool_],
        fouls: NDArray[np.int64],
        targets: NDArray[np.int64] | None = None,
    ) -> NDArray[np.float64]:
        """As :class:`LeafValue`.

        Raises:
            ValueError: Given ``targets``: the set network values 9-ball layouts only.
        """
        if targets is not None:
            raise ValueError(
                "the set network (SetLeaf) values 9-ball layouts only (the ball on); "
                "10-ball and 8-ball use the logistic layout value"
            )
        return self.net.value(
            self.table, self.mouths, positions, on_table, in_hand, fouls, self.sigma
        )


def next_targets(
    ruleset: Ruleset, racks: NDArray[np.int64], left: NDArray[np.bool_], kept: NDArray[np.bool_]
) -> NDArray[np.int64]:
    """``(S, T)`` the legal balls of whoever shoots next after ``S`` simulated shots.

    The shooter (seat 0, as the players' model racks are built) when it kept the table,
    else the opponent (seat 1), read from the rack rows after the step by the rules' own
    view (:meth:`~pool_env.game.ruleset.Ruleset.legal_first_balls`: 8-ball's groups as the
    shot decided them), padded with -1 (:func:`~agents.learned.legal_sets.target_sets`).
    """
    viewers = np.where(kept, 0, 1).astype(np.int64)
    return target_sets(ruleset.legal_first_balls(racks, left, viewers))


def outcome_values(
    leaf: LeafValue,
    runout: bool,
    result: StepResult,
    after: NDArray[np.float64],
    left: NDArray[np.bool_],
    fouls: tuple[int, int],
    racks: NDArray[np.int64] | None = None,
    ruleset: Ruleset | None = None,
) -> NDArray[np.float64]:
    """``(S,)`` each simulated shot's value to its shooter (module doc).

    Args:
        leaf: The leaf value.
        runout: Run-out mode (a miss or a foul ends the rack: worth 0).
        result: The rules' results of ``S`` shots (:meth:`GameModel.play`).
        after: ``(S, N, 2)`` the layouts they leave.
        left: ``(S, N)`` the balls left.
        fouls: The shooter's and the opponent's successive fouls before the shot (0..2).
        racks: ``(S, N_RACK)`` the rack rows after the shots (:meth:`GameModel.play_racks`),
            with ``ruleset``: the leaf is then given the next shooter's legal balls
            (:func:`next_targets`). ``None``: the leaf reads the ball on (9-ball).
        ruleset: The game's ruleset (``config.ruleset``), with ``racks``.
    """
    hits = result.hits
    foul = hits[:, FOUL] != 0
    keeps = ~foul & (hits[:, KEEPS] != 0)
    winner = hits[:, WINNER]
    value = np.where(winner == 0, 1.0, 0.0)
    open_rack = winner < 0
    mine, theirs = (min(int(f), 2) for f in fouls)
    rows = np.flatnonzero(open_rack & keeps if runout else open_rack)
    if not rows.size:
        return value
    kept = keeps[rows]
    mine_after = np.where(foul[rows], min(mine + 1, 2), 0)  # a legal shot clears them
    # Whoever shoots next: the shooter again (its fouls cleared), or the opponent.
    shooter_fouls = np.stack([np.zeros_like(mine_after), np.full_like(mine_after, theirs)], 1)
    opponent_fouls = np.stack([np.full_like(mine_after, theirs), mine_after], 1)
    next_fouls = np.where(kept[:, None], shooter_fouls, opponent_fouls)
    hand = ~kept & foul[rows]
    if racks is None or ruleset is None:
        chance = leaf(after[rows], left[rows], hand, next_fouls)
    else:
        targets = next_targets(ruleset, racks[rows], left[rows], kept)
        chance = leaf(after[rows], left[rows], hand, next_fouls, targets)
    value[rows] = np.where(kept, chance, 1.0 - chance)
    return value
