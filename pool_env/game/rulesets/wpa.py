"""WPA 9-ball, 10-ball and 8-ball: one ruleset for the family, the game as its parameter.

The games run the same compiled kernels, which branch on the game code themselves
(:func:`pool_env.game.kernels.wpa.judge_rack` and
:func:`~pool_env.game.kernels.wpa.legal_targets` read ``params[GAME]``): the cue ball in
hand (:func:`pool_env.game.kernels.actions.place_in_hand`), the shot with its calls
(:func:`~pool_env.game.kernels.actions.executed_rule_shots`), the first
contact as the rules read it (:func:`pool_env.game.contact.read_first`), the rules
(:func:`pool_env.game.rules.judge_rules`) and the rule observation
(:func:`pool_env.game.kernels.observe.encode_rule_observations`). What differs in Python
is a name, a code, the number of object balls, the money ball and the action's own
columns (10-ball's called ball; 9-ball and 10-ball's option: push-out or hand back), so the
games are instances of :class:`WpaGame` (:data:`NINE`, :data:`TEN`, :data:`EIGHT`), not
files that would repeat each other.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import parse_bool, parse_float, parse_range
from pool_env.game.components import unit_component
from pool_env.game.contact import read_first
from pool_env.game.kernels import params as kp
from pool_env.game.kernels import wpa
from pool_env.game.kernels.actions import executed_rule_shots, place_in_hand
from pool_env.game.kernels.observe import (
    OPTION_FEATURES,
    RULE_FEATURES,
    encode_rule_observations,
    legal_balls,
)
from pool_env.game.kernels.wpa import FOUL_NAMES, LOSS_NAMES
from pool_env.game.rules import (
    BALL_ON,
    CUE,
    FOUL,
    KEEPS,
    LOSS,
    PLAY,
    RESPOT,
    RESPOT_TAKEN,
    WINNER,
    judge_rules,
)
from pool_env.game.rulesets.base import (
    ConfigView,
    Executed,
    Judged,
    Outcome,
    RuleOptions,
    Ruleset,
    RulesSection,
    place_free,
)
from pool_env.game.scenes import ScenePlan
from pool_env.game.shots import Shot, ShotConstraints
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

#: The keys 9-ball and 10-ball add (they have the option): ``push_out`` (the shot was
#: played as a push-out) and ``handed_back`` (the step used the option to hand the table
#: back: no shot was played).
OPTION_KEYS: tuple[str, ...] = ("push_out", "handed_back")

#: Default break speed range (m/s) of the rules' break shot: a pro breaks at 11-13 m/s,
#: amateurs lower (Dr. Dave's "typical speeds" FAQ; ``docs/physics.md``).
DEFAULT_BREAK_SPEED_RANGE = (8.0, 12.0)

_FOULS = np.array(FOUL_NAMES, dtype=object)


@dataclass(frozen=True)
class WpaRules(RulesSection):
    """The rules section of 9-ball and 8-ball.

    Attributes:
        game: ``"nine"``, ``"ten"`` or ``"eight"``.
        end_on_foul: A foul, or a legal shot that does not keep the table, ends the
            episode (run-out mode); else play goes on (practice mode).
        break_speed_range: Speeds (m/s) of ``action[1] = -1`` and ``+1`` on a break.
        reward_foul: Reward of a foul.
        reward_win: Reward of a won rack (a lost rack gives ``-reward_win``).
    """

    game: str = "nine"
    end_on_foul: bool = False
    break_speed_range: tuple[float, float] = DEFAULT_BREAK_SPEED_RANGE
    reward_foul: float = -1.0
    reward_win: float = 1.0


_LOSSES = np.array(LOSS_NAMES, dtype=object)


class WpaGame(Ruleset):
    """A WPA game: 9-ball (``game="nine"``), 10-ball (``"ten"``) or 8-ball (``"eight"``).

    The action is ``(aim, speed, cue x, cue y, pocket)``, then 10-ball's called ball, then
    the option (9-ball and 10-ball: ``> 0`` declares a push-out, or hands the table back),
    then a spin table's tip.

    Args:
        name: The config value.
        code: The kernels' game code (:data:`pool_env.game.kernels.wpa.NINE`, ...).
        n_objects: The object balls of the game's rack, numbered as the game's.
        calls_ball: Each shot calls a ball (10-ball): the action has a ball column.
        has_option: The push-out and the opponent's option: the action has an option column.
    """

    has_rack = True
    section = WpaRules

    def __init__(
        self, name: str, code: int, n_objects: int, calls_ball: bool, has_option: bool
    ) -> None:
        self.name, self.code, self.n_objects = name, code, n_objects
        self.calls_ball, self.has_option = calls_ball, has_option
        self.money_ball = wpa.MONEY_BALLS[code]  # not the kernel: no compile at import
        self.ball_column = 5 if calls_ball else -1
        self.option_column = 5 + int(calls_ball) if has_option else -1
        self.action_width = 5 + int(calls_ball) + int(has_option)
        self.info_keys = RULE_KEYS + (OPTION_KEYS if has_option else ())
        self.features = RULE_FEATURES + (OPTION_FEATURES if has_option else ())

    def observation_width(self, n_balls: int) -> int:
        """``3 N`` ball entries, ``N - 1`` legal-ball flags and the rule features."""
        return 3 * n_balls + n_balls - 1 + len(self.features)

    def obs_layout(self, n_balls: int) -> dict[str, slice]:
        """The balls, the legal-ball flags, then one part per rule feature.

        ``"legal"`` holds balls ``1..N-1`` (may the viewer hit it first), and each name of
        :data:`~pool_env.game.kernels.observe.RULE_FEATURES` (9-ball and 10-ball: and of
        ``OPTION_FEATURES``) its own entry.
        """
        layout = super().obs_layout(n_balls)
        base = 4 * n_balls - 1
        layout["legal"] = slice(3 * n_balls, base)
        for k, name in enumerate(self.features):
            layout[name] = slice(base + k, base + k + 1)
        return layout

    def constraints(self, config: ConfigView, observation: NDArray[Any]) -> ShotConstraints:
        """The viewer's legal first balls, ball in hand and its box, the break, the calls.

        And in 9-ball and 10-ball whether the viewer may push out, or hand the table back.
        """
        obs = np.asarray(observation)
        layout = self.obs_layout(config.n_balls)
        names = RULE_FEATURES[:4] + (OPTION_FEATURES if self.has_option else ())
        flag = {name: bool(obs[layout[name]][0] > 0.5) for name in names}
        first = tuple(int(j) for j in np.flatnonzero(obs[layout["legal"]] > 0.5) + 1)
        params = config.params
        box = None
        if flag["ball_in_hand"]:
            x_high = params[kp.HEAD_X] if flag["behind_head_string"] else params[kp.X_HIGH]
            box = (
                (float(params[kp.X_LOW]), float(x_high)),
                (float(params[kp.Y_LOW]), float(params[kp.Y_HIGH])),
            )
        breaking = flag["break"]
        return ShotConstraints(
            first_balls=first,
            speed_range=config.break_speed_range if breaking else config.speed_range,
            ball_in_hand=flag["ball_in_hand"],
            behind_head_string=flag["ball_in_hand"] and flag["behind_head_string"],
            placement=box,
            breaking=breaking,
            call_pocket=not breaking and (self.calls_ball or (self.code == wpa.EIGHT
                                                             and first == (8,))),
            push_out=flag.get("push_out", False),
            call_ball=self.calls_ball and not breaking,
            option=flag.get("option", False),
        )  # fmt: skip

    def first_balls_after(self, on_after: NDArray[np.bool_], potted: int) -> tuple[int, ...]:
        """The legal first balls of the next shot if the shooter keeps the table.

        9-ball and 10-ball: the lowest ball left. 8-ball: what is left of the potted ball's
        group (which an open table then assigns), the 8 once that is empty, nothing after
        the 8.
        """
        left = [j for j in range(1, on_after.shape[0]) if on_after[j]]
        if self.code != wpa.EIGHT:
            return tuple(left[:1])
        if potted == 8:
            return ()
        group = [j for j in left if (j < 8) == (potted < 8) and j != 8]
        return tuple(group or [j for j in left if j == 8])

    def placed_cue(self, state: GameState) -> tuple[float, float] | None:
        """Where table 0's cue ball stands if it was in hand, else ``None``."""
        if not state.rack[0, wpa.IN_HAND]:
            return None
        return float(state.positions[0, CUE, 0]), float(state.positions[0, CUE, 1])

    def encode(
        self,
        config: ConfigView,
        shot: Shot,
        state: GameState,
        out: NDArray[np.float64],
        clip: bool,
    ) -> tuple[float, float]:
        """The placement (cue ball in hand), the calls, the option; the shot's speed range.

        Raises:
            ValueError: On a call the game has not (a ball outside 10-ball), a ball that is
                not one of the game's, or a push-out or hand-back the rack does not offer.
        """
        row = state.rack[0]
        if row[wpa.IN_HAND] and shot.cue is not None:
            out[2], out[3] = self.encode_placement(config, shot.cue, bool(row[wpa.BEHIND]), clip)
            state.positions[0, CUE] = shot.cue  # the aim refers from where the cue ball will be
        out[4] = encode_pocket(config.table, shot.pocket)
        if self.calls_ball:
            ball = shot.ball
            if ball is None:  # the ball on: the lowest on the table
                on = np.flatnonzero(state.on_table[0, 1:]) + 1
                ball = int(on[0]) if on.size else 1
            out[self.ball_column] = encode_ball(self.n_objects, ball)
        elif shot.ball is not None:
            raise ValueError(f"game={self.name!r} calls no ball: Shot.ball must be None")
        declared = {"push_out": (shot.push_out, wpa.PUSH_OUT),
                    "pass_back": (shot.pass_back, wpa.OPTION)}  # fmt: skip
        for name, (wanted, column) in declared.items():
            if wanted and (not self.has_option or not row[column]):
                raise ValueError(f"Shot.{name}: the rules offer none on this shot")
        if self.has_option:
            out[self.option_column] = 1.0 if shot.push_out or shot.pass_back else -1.0
        return config.break_speed_range if row[wpa.BREAKING] else config.speed_range

    def encode_placement(
        self, config: ConfigView, cue: Any, behind: bool, clip: bool
    ) -> tuple[float, float]:
        """``action[2]`` and ``action[3]``: the placement box (behind the head string or not).

        Raises:
            ValueError: On a point outside the box (without ``clip``).
        """
        params = config.params
        x, y = (float(v) for v in np.asarray(cue, dtype=np.float64).reshape(2))
        x_high = params[kp.HEAD_X] if behind else params[kp.X_HIGH]
        return (
            unit_component("cue x", x, params[kp.X_LOW], x_high, clip),
            unit_component("cue y", y, params[kp.Y_LOW], params[kp.Y_HIGH], clip),
        )

    def parse_rules(self, section: RulesSection) -> RuleOptions:
        """Check the :class:`WpaRules` (``ValueError``, naming the first bad one)."""
        assert isinstance(section, WpaRules)
        return RuleOptions(
            parse_bool("end_on_foul", section.end_on_foul),
            parse_range("break_speed_range", section.break_speed_range, 0.0),
            (parse_float("reward_foul", section.reward_foul),
             parse_float("reward_win", section.reward_win)),
        )  # fmt: skip

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
        out[[kp.BALL_COLUMN, kp.OPTION_COLUMN]] = self.ball_column, self.option_column
        out[kp.TIP_COLUMN] = self.action_width
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
        """:func:`~pool_env.game.kernels.actions.executed_rule_shots`; extra: the calls."""
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

    def aim_references(
        self, state: GameState, viewers: NDArray[np.int64] | None = None
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls each viewer (``None``: each shooter) may hit first."""
        if viewers is None:
            viewers = state.rack[:, wpa.SHOOTER]
        return legal_balls(self.code, state.on_table, state.rack, viewers)

    def table_info(self, hits: list[int], info: dict[str, Any]) -> None:
        """:data:`RULE_KEYS` as Python scalars."""
        info["foul"] = FOUL_NAMES[hits[FOUL]]
        info["legal"] = hits[FOUL] == 0
        info["loss"] = LOSS_NAMES[hits[LOSS]]
        info["turn_over"] = hits[FOUL] != 0 or hits[KEEPS] == 0
        for key, (_, column, _) in RULE_COLUMNS.items():
            info[key] = hits[column]
        if self.has_option:
            info["push_out"] = hits[PLAY] == wpa.PUSHED_OUT
            info["handed_back"] = hits[PLAY] == wpa.HANDED_BACK

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
        if self.has_option:
            for key, play in (("push_out", wpa.PUSHED_OUT), ("handed_back", wpa.HANDED_BACK)):
                flags = np.zeros(n_envs, dtype=np.bool_)
                flags[tables] = hits[:, PLAY] == play
                info[key], info[f"_{key}"] = flags, present.copy()


def encode_pocket(table: Table, pocket: int) -> float:
    """The action component (``action[4]``) that calls ``pocket``: the middle of its bin.

    Raises:
        ValueError: If the table has no pocket ``pocket``.
    """
    n_pockets = table.n_pockets
    if not 0 <= pocket < n_pockets:
        raise ValueError(f"pocket must be in 0..{n_pockets - 1}, got {pocket!r}")
    return (2.0 * pocket + 1.0) / n_pockets - 1.0


def encode_ball(n_objects: int, ball: int) -> float:
    """The action component that calls object ball ``ball`` (10-ball): the middle of its bin.

    Raises:
        ValueError: If ``ball`` is not one of the ``n_objects`` object balls.
    """
    if (
        isinstance(ball, bool)
        or not isinstance(ball, int | np.integer)
        or not (1 <= ball <= n_objects)
    ):
        raise ValueError(f"the called ball must be in 1..{n_objects}, got {ball!r}")
    return (2.0 * (ball - 1) + 1.0) / n_objects - 1.0


#: 9-ball: nine object balls, the 9 wins; the push-out.
NINE = WpaGame("nine", wpa.NINE, 9, calls_ball=False, has_option=True)

#: 10-ball: ten object balls, called shots (ball and pocket), the 10 wins; the push-out.
TEN = WpaGame("ten", wpa.TEN, 10, calls_ball=True, has_option=True)

#: 8-ball: fifteen object balls, solids and stripes, the 8 wins.
EIGHT = WpaGame("eight", wpa.EIGHT, 15, calls_ball=False, has_option=False)
