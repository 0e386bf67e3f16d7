"""The shooter's legal balls and rack row as the search players need them, batched.

A search over simulated outcomes values each layout from the side of whoever shoots next,
and off 9-ball that player's legal first balls are not "the lowest ball": 8-ball's group,
the 8 once it is cleared, every ball but the 8 on an open table. The rules say them
(:meth:`pool_env.game.ruleset.Ruleset.legal_first_balls` over rack rows); this module
turns them into what the values and the candidates take (:func:`target_sets`: ``(B, T)``
ball numbers padded with -1, as :func:`pool_env.game.geometry.ghost_shots` takes targets),
and builds the rack rows the game model shoots from: from the viewer's observation
(:func:`observed_row`) and back from a layout's legal balls (:func:`shooter_racks`: the
8-ball group they imply), with the shooter in seat 0.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.learned.layout_value import observed_rack
from pool_env import GameConfig, obs_layout, shot_constraints
from pool_env.game.games.wpa import rack_row
from pool_env.game.games.wpa.rack_state import GROUP_0, GROUP_1, OPEN, SOLIDS, STRIPES


def target_sets(legal: NDArray[np.bool_]) -> NDArray[np.int64]:
    """``(B, T)`` the legal balls of ``(B, N)`` flags, ascending, padded with -1.

    ``T`` is the most legal balls of any row (at least 1); the cue ball (column 0) is
    never one.
    """
    flags = np.array(legal, dtype=np.bool_, ndmin=2)
    flags[:, 0] = False
    n = flags.shape[1]
    width = max(int(flags.sum(axis=1).max(initial=0)), 1)
    order = np.sort(np.where(flags, np.arange(n), n), axis=1)[:, :width]
    return np.where(order < n, order, -1).astype(np.int64)


def group_of_targets(on_table: NDArray[np.bool_], targets: NDArray[np.int64]) -> NDArray[np.int64]:
    """``(B,)`` the 8-ball group (``OPEN``, ``SOLIDS``, ``STRIPES``) legal balls imply.

    Solids only: solids; stripes only: stripes; both: an open table; the 8 alone: the group
    that is cleared (solids if no solid is left, else stripes).
    """
    on = np.asarray(on_table, dtype=np.bool_)
    t = np.asarray(targets, dtype=np.int64)
    legal = t >= 0
    solid = (legal & (t >= 1) & (t <= 7)).any(axis=1)
    stripe = (legal & (t >= 9)).any(axis=1)
    cleared = np.where(on[:, 1:8].any(axis=1), STRIPES, SOLIDS)
    return np.where(solid & stripe, OPEN, np.where(solid, SOLIDS, np.where(stripe, STRIPES,
                                                                            cleared)))  # fmt: skip


def shooter_racks(
    game: str, on_table: NDArray[np.bool_], targets: NDArray[np.int64], fouls: tuple[int, int]
) -> NDArray[np.int64]:
    """``(B, N_RACK)`` rack rows to shoot from: the shooter in seat 0, ``fouls``, its group.

    In 8-ball the groups are those the legal balls imply (:func:`group_of_targets`, the
    opponent the other one); the other games have none (the legal ball is the lowest).
    """
    row = rack_row({"fouls": (min(int(fouls[0]), 2), min(int(fouls[1]), 2))})
    rows = np.tile(row, (np.shape(on_table)[0], 1))
    if game == "eight":
        mine = group_of_targets(on_table, targets)
        rows[:, GROUP_0] = mine
        rows[:, GROUP_1] = np.where(mine == OPEN, OPEN, SOLIDS + STRIPES - mine)
    return rows


def observed_row(obs: NDArray[np.floating], config: GameConfig | Any) -> NDArray[np.int64]:
    """The rack row a model plays the viewer's next shot from, read from its observation.

    The viewer in seat 0 with its successive fouls and the opponent's (at most 2), and in
    8-ball the groups (the observation's open-table flag and legal balls; on the break
    the table is open). No ball in hand: the player places the cue ball first.
    """
    layout = obs_layout(config)
    own, other = observed_rack(obs, config)[2]
    row = rack_row({"fouls": (min(own, 2), min(other, 2))})
    if config.game == "eight" and float(obs[layout["open_table"]][0]) < 0.5:
        rules = shot_constraints(config, obs)
        if not rules.breaking:
            on = np.asarray(obs)[layout["balls"]][2::3] > 0.5
            first = np.array([list(rules.first_balls) or [-1]], dtype=np.int64)
            mine = int(group_of_targets(on[None], first)[0])
            row[GROUP_0], row[GROUP_1] = mine, SOLIDS + STRIPES - mine
    return row
