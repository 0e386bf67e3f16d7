"""WPA 9-ball and 8-ball: one ruleset for the family, the game as its parameter.

Both games run the same compiled kernels, which branch on the game code themselves
(:func:`pool_env.game.kernels.wpa.judge_rack` and
:func:`~pool_env.game.kernels.wpa.legal_targets` read ``params[GAME]``): the cue ball in
hand (:func:`pool_env.game.kernels.actions.place_in_hand`), the ``Box(5)`` shot with a
called pocket (:func:`~pool_env.game.kernels.actions.executed_rule_shots`), the first
contact as the rules read it (:func:`pool_env.game.contact.read_first`), the rules
(:func:`pool_env.game.rules.judge_rules`) and the rule observation
(:func:`pool_env.game.kernels.observe.encode_rule_observations`). What differs in Python
is a name, a code and the number of object balls, so the two games are two instances of
:class:`WpaGame` (:data:`NINE`, :data:`EIGHT`), not two files that would repeat each other.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.contact import read_first
from pool_env.game.kernels import params as kp
from pool_env.game.kernels import wpa
from pool_env.game.kernels.actions import executed_rule_shots, place_in_hand
from pool_env.game.kernels.observe import N_RULE_FEATURES, encode_rule_observations
from pool_env.game.kernels.wpa import FOUL_NAMES, LOSS_NAMES
from pool_env.game.rules import (
    BALL_ON,
    CUE,
    FOUL,
    KEEPS,
    LOSS,
    RESPOT,
    RESPOT_TAKEN,
    WINNER,
    judge_rules,
)
from pool_env.game.rulesets.base import Executed, Judged, Outcome, Ruleset, place_free
from pool_env.game.scenes import ScenePlan
from pool_env.game.state import GameState
from pool_env.sim.layouts import foot_spot
from pool_env.sim.table import Table

#: The rules' integer ``info`` keys: the ball on before the shot (-1: not a single ball,
#: 8-ball before the group is cleared) and the winner (-1 while undecided; integers rather
#: than None, so that Gymnasium's vector info has one dtype per key).
RULE_COLUMNS: dict[str, tuple[str, int, type]] = {
    "ball_on": ("hits", BALL_ON, np.int64),
    "winner": ("hits", WINNER, np.int64),
}

#: Every key a step adds under rules: ``foul`` (None or its name), ``legal``, ``loss``
#: (None or why the shooter lost the rack), ``turn_over`` (a foul, or a legal shot that
#: does not keep the table: with two players the opponent would come to the table) and
#: :data:`RULE_COLUMNS`.
RULE_KEYS: tuple[str, ...] = ("foul", "legal", "loss", "turn_over", *RULE_COLUMNS)

_FOULS = np.array(FOUL_NAMES, dtype=object)
_LOSSES = np.array(LOSS_NAMES, dtype=object)


class WpaGame(Ruleset):
    """A WPA game: 9-ball (``game="nine"``) or 8-ball (``game="eight"``).

    Args:
        name: The config value.
        code: The kernels' game code (:data:`pool_env.game.kernels.wpa.NINE`, ``EIGHT``).
        n_objects: The object balls of the game's rack, numbered as the game's.
    """

    has_rack = True
    action_width = 5
    info_keys = RULE_KEYS

    def __init__(self, name: str, code: int, n_objects: int) -> None:
        self.name, self.code, self.n_objects = name, code, n_objects

    def observation_width(self, n_balls: int) -> int:
        """``3 N`` ball entries, ``N - 1`` legal-ball flags and the rule features."""
        return 3 * n_balls + n_balls - 1 + N_RULE_FEATURES

    def check(
        self, scene: ScenePlan, table: Table, end_on_miss: bool, end_on_foul: bool, players: int
    ) -> None:
        """Refuse a scene of other balls, ``end_on_miss`` and a table without pockets."""
        if scene.n_objects != self.n_objects:
            raise ValueError(
                f"game={self.name!r} needs {self.n_objects} object balls numbered as the "
                f"game's, got a scene with {scene.n_objects}"
            )
        if end_on_miss:
            raise ValueError("end_on_miss is solitaire's: under rules use end_on_foul")
        if table.n_pockets == 0:
            raise ValueError(f"game={self.name!r} needs a table with pockets")

    def rule_params(
        self,
        params: NDArray[np.float64],
        table: Table,
        players: int,
        end_on_foul: bool,
        break_speed_range: tuple[float, float],
        rule_rewards: tuple[float, float],
    ) -> NDArray[np.float64]:
        """A read-only copy of ``params`` with the rules' entries set."""
        out = params.copy()
        out[kp.GAME] = self.code
        out[kp.PLAYERS] = players
        out[kp.END_ON_FOUL] = float(end_on_foul)
        out[[kp.BREAK_LOW, kp.BREAK_HIGH]] = break_speed_range
        out[[kp.W_FOUL, kp.W_WIN]] = rule_rewards
        out[kp.HEAD_X] = table.length / 4.0
        out[[kp.FOOT_X, kp.FOOT_Y]] = foot_spot(table)
        out.setflags(write=False)
        return out

    def place(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        actions: NDArray[np.float64],
    ) -> None:
        """Each cue ball in hand where its action asks, or on the nearest free point.

        The first part of a step, and of :func:`pool_env.game.codec.decode_action`.
        """
        rack = state.rack
        unplaced = place_in_hand(
            params, table.pockets, actions, tables, state.positions, state.on_table, rack
        )
        if unplaced.any():  # the requested point is covered: the nearest free one
            for k in np.flatnonzero(unplaced).tolist():
                b = int(tables[k])
                target = state.positions[b, CUE].copy()
                place_free(table, state, b, CUE, target, bool(rack[b, wpa.BEHIND]))

    def execute(
        self,
        params: NDArray[np.float64],
        pockets: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        actions: NDArray[np.float64],
    ) -> Executed:
        """:func:`~pool_env.game.kernels.actions.executed_rule_shots`; extra: the called pockets."""
        return executed_rule_shots(
            params, pockets, actions, tables, state.positions, state.on_table, state.ptrs,
            state.rack,
        )  # fmt: skip

    def judge(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        out: Outcome,
        velocities: NDArray[np.float64],
        spins: NDArray[np.float64] | None,
        extra: Any,
    ) -> Judged:
        """The first contact settled (:func:`~pool_env.game.contact.read_first`), then the rules."""
        rack = state.rack
        crossed = read_first(
            table, params, self.code, state.positions, state.on_table, rack, tables,
            out.balls, velocities, spins, out.first, out.shot,
        )  # fmt: skip
        return judge_rules(
            params, table.pockets, tables, out.balls, state.positions, state.on_table,
            state.shots, rack, out.final, out.pocketed, out.first, out.cushions, out.order,
            extra, crossed,
        )  # fmt: skip

    def fix_spots(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        flags: NDArray[np.bool_],
        hits: NDArray[np.int64],
    ) -> None:
        """A re-spotted ball whose foot spot is covered first, then the cue ball's spot."""
        if flags[:, RESPOT_TAKEN].any():
            foot = params[[kp.FOOT_X, kp.FOOT_Y]].copy()
            for k in np.flatnonzero(flags[:, RESPOT_TAKEN]).tolist():
                place_free(table, state, int(tables[k]), int(hits[k, RESPOT]), foot)
        super().fix_spots(table, params, state, tables, flags, hits)

    def observe(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        viewers: NDArray[np.int64] | None,
    ) -> NDArray[np.float32]:
        """The rule observation from ``viewers``' seats (``None``: each table's shooter)."""
        if viewers is None:
            viewers = state.rack[:, wpa.SHOOTER]
        return encode_rule_observations(
            params, state.positions, state.on_table, state.rack, viewers, table.length,
            table.width,
        )  # fmt: skip

    def table_info(self, hits: list[int], info: dict[str, Any]) -> None:
        """:data:`RULE_KEYS` as Python scalars."""
        info["foul"] = FOUL_NAMES[hits[FOUL]]
        info["legal"] = hits[FOUL] == 0
        info["loss"] = LOSS_NAMES[hits[LOSS]]
        info["turn_over"] = hits[FOUL] != 0 or hits[KEEPS] == 0
        for key, (_, column, _) in RULE_COLUMNS.items():
            info[key] = hits[column]

    def batch_info(
        self,
        hits: NDArray[np.int64],
        rows: NDArray[np.bool_] | slice,
        tables: NDArray[np.intp],
        n_envs: int,
        present: NDArray[np.bool_],
        info: dict[str, Any],
    ) -> None:
        """:data:`RULE_KEYS` as arrays over the tables, each with its mask."""
        hits = hits[rows]
        codes = hits[:, FOUL]
        fouls = np.full(n_envs, None, dtype=object)
        fouls[tables] = _FOULS[codes]
        legal = np.zeros(n_envs, dtype=np.bool_)
        legal[tables] = codes == 0
        losses = np.full(n_envs, None, dtype=object)
        losses[tables] = _LOSSES[hits[:, LOSS]]
        turn_over = np.zeros(n_envs, dtype=np.bool_)
        turn_over[tables] = (codes != 0) | (hits[:, KEEPS] == 0)
        for key, values in (("foul", fouls), ("legal", legal), ("loss", losses),
                            ("turn_over", turn_over)):  # fmt: skip
            info[key], info[f"_{key}"] = values, present.copy()
        for key, (_, column, dtype) in RULE_COLUMNS.items():
            values = np.zeros(n_envs, dtype=dtype)
            values[tables] = hits[:, column]
            info[key], info[f"_{key}"] = values, present.copy()


#: 9-ball: nine object balls, the 9 wins.
NINE = WpaGame("nine", wpa.NINE, 9)

#: 8-ball: fifteen object balls, solids and stripes, the 8 wins.
EIGHT = WpaGame("eight", wpa.EIGHT, 15)
