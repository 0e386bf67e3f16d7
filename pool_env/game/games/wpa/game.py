"""WPA 9-ball, 10-ball and 8-ball: one ruleset for the family, the game as its parameter.

The games run the same compiled kernels of this package, which branch on the game code
themselves (:func:`pool_env.game.games.wpa.rules.judge_rack` and
:func:`~pool_env.game.games.wpa.rack_state.legal_targets` read ``params[VARIANT]``): the
cue ball in hand and the shot with its calls (:mod:`.shots`), the first contact as the
rules read it (:mod:`.first_contact`), the rules (:mod:`.judge` over :mod:`.rules`) and the
rule observation (:mod:`.observe`). What differs in Python is a name, a code, the number of
object balls, the money ball and the action's own columns (10-ball's called ball; 9-ball
and 10-ball's option: push-out or hand back), so the games are instances of
:class:`WpaGame` (:data:`NINE`, :data:`TEN`, :data:`EIGHT`), not files that would repeat
each other.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import parse_bool, parse_range
from pool_env.game.components import ball_component, pocket_component, unit_component
from pool_env.game.games.wpa import params as wp
from pool_env.game.games.wpa import rack_state as wpa
from pool_env.game.games.wpa.first_contact import read_first
from pool_env.game.games.wpa.info import OPTION_KEYS, RULE_KEYS, info_columns, info_row
from pool_env.game.games.wpa.judge import RESPOT, RESPOT_TAKEN, judge_rules
from pool_env.game.games.wpa.observe import (
    OPTION_FEATURES,
    RULE_FEATURES,
    check_rule_observation,
    encode_rule_observations,
    legal_balls,
)
from pool_env.game.games.wpa.rack import check_rack, rack_dict, rack_of, rack_option
from pool_env.game.games.wpa.section import REWARD_TERMS, WpaRules
from pool_env.game.games.wpa.shots import (
    CALL_BALL,
    CALL_HAND_BACK,
    CALL_POCKET,
    CALL_PUSH_OUT,
    executed_rule_shots,
    placed_rule_shots,
)
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.outcome import CUE
from pool_env.game.ruleset import (
    Executed,
    Judged,
    Outcome,
    Ruleset,
    RulesSection,
    Setup,
    Turn,
    place_cue_balls,
    place_free,
)
from pool_env.game.shots import Shot, ShotConstraints
from pool_env.game.state import GameState
from pool_env.sim.layouts import foot_spot

if TYPE_CHECKING:
    from pool_env.game.config import GameConfig


class WpaGame(Ruleset):
    """A WPA game: 9-ball (``game="nine"``), 10-ball (``"ten"``) or 8-ball (``"eight"``).

    The action is ``(aim, speed, cue x, cue y, pocket)``, then 10-ball's called ball, then
    the option (9-ball and 10-ball: ``> 0`` declares a push-out, or hands the table back),
    then a spin table's tip.

    Args:
        name: The config value.
        code: The kernels' game code (:data:`pool_env.game.games.wpa.rack_state.NINE`, ...).
        n_objects: The object balls of the game's rack, numbered as the game's.
        calls_ball: Each shot calls a ball (10-ball): the action has a ball column.
        has_option: The push-out and the opponent's option: the action has an option column.
    """

    rack_width = wpa.N_RACK
    section = WpaRules
    reward_terms = REWARD_TERMS

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
        self._without_option: WpaGame | None = None

    # -- configuration and reset ----------------------------------------------------------

    def parse_section(self, section: RulesSection) -> WpaRules:
        """The :class:`WpaRules` checked (``ValueError``, naming the first bad one)."""
        if not isinstance(section, WpaRules):
            raise ValueError(f"game={self.name!r} takes a WpaRules section, got {section!r}")
        rotation = self.code != wpa.EIGHT
        push_out = (
            rotation if section.push_out is None else parse_bool("push_out", section.push_out)
        )
        if push_out and not rotation:
            raise ValueError(f"push_out=True: game={self.name!r} has no push-out")
        if not push_out and self.code == wpa.TEN:
            raise ValueError(
                "push_out=False: 10-ball's option also follows a pot without its call; only "
                "9-ball is played without the push-out (as pool_env/NineBallGame-v1)"
            )
        return WpaRules(
            game=section.game,
            end_on_foul=parse_bool("end_on_foul", section.end_on_foul),
            break_speed_range=parse_range("break_speed_range", section.break_speed_range, 0.0),
            push_out=push_out,
        )

    def variant(self, section: RulesSection) -> WpaGame:
        """This game, or its twin without the option when the parsed section says so.

        The option's column and features are part of the spaces, so the game without the
        push-out (``push_out=False``: 9-ball as ``-v1`` plays it) is a ruleset of its own.
        """
        if not self.has_option or getattr(section, "push_out", True):
            return self
        if self._without_option is None:
            self._without_option = WpaGame(
                self.name, self.code, self.n_objects, self.calls_ball, has_option=False
            )
        return self._without_option

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """Refuse what the game cannot play; give its tail of the kernel parameters.

        Refused: a scene of other balls, ``end_on_miss``, a table without pockets,
        ``end_on_foul`` with two players, and a ``break_speed_range`` whose top speed (with
        the noise) the simulator cannot strike (:class:`~pool_env.game.checks.SpeedCeiling`).

        The tail: the game code, the rule options, the head string and foot spot, the
        action's own columns and the reward scales (:mod:`pool_env.game.games.wpa.params`).
        """
        scene, table = setup.scene, setup.table
        if scene.n_objects != self.n_objects:
            raise ValueError(
                f"game={self.name!r} needs {self.n_objects} object balls numbered as the "
                f"game's, got a scene with {scene.n_objects}"
            )
        if setup.end_on_miss:
            raise ValueError("end_on_miss is solitaire's: under rules use end_on_foul")
        if table.n_pockets == 0:
            raise ValueError(f"game={self.name!r} needs a table with pockets")
        rules = self.parse_section(setup.rules)
        if rules.end_on_foul and setup.players == 2:
            # The run-out mode ends one agent's episode at its foul; in a rack of two
            # players a foul passes the table to the opponent, and the rack goes on.
            raise ValueError(
                "end_on_foul=True is the one-agent run-out mode: in a two-player rack "
                "(PoolDuelEnv, VersusPolicyEnv) a foul passes the table to the opponent "
                "with ball in hand, and the rack goes on; leave end_on_foul=False"
            )
        setup.speeds.check(
            "break_speed_range", setup.rules.break_speed_range, rules.break_speed_range[1]
        )
        return kp.game_tail(
            {
                wp.VARIANT: self.code,
                wp.END_ON_FOUL: float(rules.end_on_foul),
                wp.BREAK_LOW: rules.break_speed_range[0],
                wp.BREAK_HIGH: rules.break_speed_range[1],
                wp.HEAD_X: table.length / 4.0,
                wp.FOOT_X: foot_spot(table)[0],
                wp.FOOT_Y: foot_spot(table)[1],
                wp.BALL_COLUMN: self.ball_column,
                wp.OPTION_COLUMN: self.option_column,
                wp.W_POT: setup.rewards["pot"],
                wp.W_FOUL: setup.rewards["foul"],
                wp.W_WIN: setup.rewards["win"],
            }
        )

    def start(self, turn: Turn, given: Any, rack_scene: bool, on_table: NDArray[np.bool_]) -> None:
        """The rack state from ``options["rules"]`` (:func:`.rack.rack_option`), checked."""
        row = rack_option(turn.config, given, rack_scene)
        check_rack(turn.config, row, on_table)
        turn.state.rack[turn.tables] = row

    # -- one step -------------------------------------------------------------------------

    def shoot(self, turn: Turn, actions: NDArray[np.float64]) -> Executed:
        """Each cue ball in hand placed and every shot struck: :func:`.shots.placed_rule_shots`.

        One compiled call; a requested placement on a covered point (rare) goes to the
        nearest free one, and that row is decoded then.
        """
        config, state, tables = turn
        table, params = config.table, config.params
        rack, pockets = state.rack, table.pockets
        shots, states, calls, unplaced = placed_rule_shots(
            params, pockets, actions, tables, state.positions, state.on_table, state.ptrs, rack
        )
        if unplaced.any():  # the requested point is covered: the nearest free one
            rows = np.flatnonzero(unplaced)
            for k in rows.tolist():
                b = int(tables[k])
                target = state.positions[b, CUE].copy()
                place_free(table, state, b, CUE, target, bool(rack[b, wpa.BEHIND]))
            shots[rows], states[rows], calls[rows] = executed_rule_shots(
                params, pockets, actions[rows], tables[rows], state.positions,
                state.on_table, state.ptrs, rack, np.zeros(rows.size, dtype=np.bool_),
            )  # fmt: skip
        return Executed(shots, states, calls)

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        """The first contact settled (:func:`.first_contact.read_first`), then the rules.

        Then the rare re-spots the compiled rules could not finish: a re-spotted ball whose
        foot spot is covered first, then the cue ball's head spot.
        """
        config, state, tables = turn
        table, params, rack = config.table, config.params, state.rack
        crossed = read_first(
            table, params, self.code, state.positions, state.on_table, rack, tables,
            out.balls, out.velocities, out.spins, out.first, out.shot,
        )  # fmt: skip
        judged = Judged(*judge_rules(
            params, table.pockets, tables, out.balls, state.positions, state.on_table,
            state.shots, rack, out.final, out.pocketed, out.first, out.cushions, out.order,
            executed.calls, crossed,
        ))  # fmt: skip
        flags, hits = judged.flags, judged.hits
        respot = flags[:, RESPOT_TAKEN]
        if respot[0] if respot.shape[0] == 1 else respot.any():  # one table: no any() call
            foot = params[[wp.FOOT_X, wp.FOOT_Y]].copy()
            for k in np.flatnonzero(flags[:, RESPOT_TAKEN]).tolist():
                place_free(table, state, int(tables[k]), int(hits[k, RESPOT]), foot)
        place_cue_balls(turn, flags)
        return judged

    def observe(
        self, config: GameConfig, state: GameState, viewers: NDArray[np.int64] | None
    ) -> NDArray[np.float32]:
        """The rule observation from ``viewers``' seats (``None``: each table's shooter)."""
        if viewers is None:
            viewers = state.rack[:, wpa.SHOOTER]
        return encode_rule_observations(
            config.params, state.positions, state.on_table, state.rack, viewers,
            config.table.length, config.table.width,
        )  # fmt: skip

    def info_columns(self, hits: NDArray[np.int64]) -> dict[str, NDArray[Any]]:
        """:data:`.info.RULE_KEYS` (and the option's keys) over ``hits``' rows."""
        return info_columns(hits, self.has_option)

    def info_row(self, hits: list[int]) -> dict[str, Any]:
        """The same keys for one table, from its row as a list: no array made."""
        return info_row(hits, self.has_option)

    # -- views for players and the codec ---------------------------------------------------

    def observation_width(self, n_balls: int) -> int:
        """``3 N`` ball entries, ``N - 1`` legal-ball flags and the rule features."""
        return 3 * n_balls + n_balls - 1 + len(self.features)

    def obs_layout(self, n_balls: int) -> dict[str, slice]:
        """The balls, the legal-ball flags, then one part per rule feature.

        ``"legal"`` holds balls ``1..N-1`` (may the viewer hit it first), and each name of
        :data:`~pool_env.game.games.wpa.observe.RULE_FEATURES` (9-ball and 10-ball: and of
        ``OPTION_FEATURES``) its own entry.
        """
        layout = super().obs_layout(n_balls)
        base = 4 * n_balls - 1
        layout["legal"] = slice(3 * n_balls, base)
        for k, name in enumerate(self.features):
            layout[name] = slice(base + k, base + k + 1)
        return layout

    def constraints(self, config: GameConfig, observation: NDArray[Any]) -> ShotConstraints:
        """The viewer's legal first balls, ball in hand and its box, the break, the calls.

        And in 9-ball and 10-ball whether the viewer may push out, or hand the table back.

        Raises:
            ValueError: On an observation whose rule part is not this game's
                (:func:`.observe.check_rule_observation`).
        """
        obs = np.asarray(observation)
        layout = self.obs_layout(config.n_balls)
        check_rule_observation(self.name, self.code, obs, layout)
        names = RULE_FEATURES[:4] + (OPTION_FEATURES if self.has_option else ())
        flag = {name: bool(obs[layout[name]][0] > 0.5) for name in names}
        first = tuple(int(j) for j in np.flatnonzero(obs[layout["legal"]] > 0.5) + 1)
        params = config.params
        box = None
        if flag["ball_in_hand"]:
            x_high = params[wp.HEAD_X] if flag["behind_head_string"] else params[kp.X_HIGH]
            box = (
                (float(params[kp.X_LOW]), float(x_high)),
                (float(params[kp.Y_LOW]), float(params[kp.Y_HIGH])),
            )
        breaking = flag["break"]
        return ShotConstraints(
            first_balls=first,
            speed_range=config.rules.break_speed_range if breaking else config.speed_range,
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

    def legal_first_balls(
        self,
        rack: NDArray[np.int64],
        on_table: NDArray[np.bool_],
        viewers: NDArray[np.int64] | None = None,
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls each viewer may hit first, by the rules' own kernel.

        :func:`~pool_env.game.games.wpa.observe.legal_balls` over rack rows (the rule
        observation's legal-ball flags, batched): the ball on in 9-ball and 10-ball; in
        8-ball the viewer's group, every ball but the 8 on an open table, the 8 once the
        group is cleared, any ball on the break.

        Args:
            rack: ``(B, N_RACK)`` rack-state rows (after a simulated step, say).
            on_table: ``(B, N)`` which balls are on the table.
            viewers: ``(B,)`` whose legal balls, 0 or 1 (``None``: each row's shooter).

        Raises:
            ValueError: On shapes that do not fit or a viewer that is not 0 or 1.
        """
        rows = np.ascontiguousarray(rack, dtype=np.int64)
        on = np.ascontiguousarray(on_table, dtype=np.bool_)
        if rows.ndim != 2 or on.ndim != 2 or rows.shape != (on.shape[0], wpa.N_RACK):
            raise ValueError(
                f"rack must be (B, {wpa.N_RACK}) and on_table (B, N), got {rows.shape} and "
                f"{on.shape}"
            )
        seats = rows[:, wpa.SHOOTER] if viewers is None else viewers
        seats = np.ascontiguousarray(np.broadcast_to(seats, (on.shape[0],)), dtype=np.int64)
        if ((seats != 0) & (seats != 1)).any():
            raise ValueError(f"viewers must be 0 or 1, got {np.unique(seats).tolist()}")
        return legal_balls(self.code, on, rows, seats)

    def placed_cue(self, state: GameState) -> tuple[float, float] | None:
        """Where table 0's cue ball stands if it was in hand, else ``None``."""
        if not state.rack[0, wpa.IN_HAND]:
            return None
        return float(state.positions[0, CUE, 0]), float(state.positions[0, CUE, 1])

    def encode(
        self,
        config: GameConfig,
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
        out[4] = pocket_component(config.table.n_pockets, shot.pocket)
        if self.calls_ball:
            ball = shot.ball
            if ball is None:  # the ball on: the lowest on the table
                on = np.flatnonzero(state.on_table[0, 1:]) + 1
                ball = int(on[0]) if on.size else 1
            out[self.ball_column] = ball_component(self.n_objects, ball)
        elif shot.ball is not None:
            raise ValueError(f"game={self.name!r} calls no ball: Shot.ball must be None")
        declared = {"push_out": (shot.push_out, wpa.PUSH_OUT),
                    "pass_back": (shot.pass_back, wpa.OPTION)}  # fmt: skip
        for name, (wanted, column) in declared.items():
            if wanted and (not self.has_option or not row[column]):
                raise ValueError(f"Shot.{name}: the rules offer none on this shot")
        if self.has_option:
            out[self.option_column] = 1.0 if shot.push_out or shot.pass_back else -1.0
        return config.rules.break_speed_range if row[wpa.BREAKING] else config.speed_range

    def encode_ball(self, config: GameConfig, ball: int) -> float:
        """The ball column's component that calls ``ball`` (10-ball): the middle of its bin.

        Raises:
            ValueError: In 9-ball and 8-ball (no ball is called), or for a ball not the game's.
        """
        if not self.calls_ball:
            return super().encode_ball(config, ball)
        return ball_component(self.n_objects, ball)

    def encode_placement(
        self, config: GameConfig, cue: Any, behind: bool, clip: bool
    ) -> tuple[float, float]:
        """``action[2]`` and ``action[3]``: the placement box (behind the head string or not).

        Raises:
            ValueError: On a point outside the box (without ``clip``).
        """
        params = config.params
        x, y = (float(v) for v in np.asarray(cue, dtype=np.float64).reshape(2))
        x_high = params[wp.HEAD_X] if behind else params[kp.X_HIGH]
        return (
            unit_component("cue x", x, params[kp.X_LOW], x_high, clip),
            unit_component("cue y", y, params[kp.Y_LOW], params[kp.Y_HIGH], clip),
        )

    def aim_references(
        self, state: GameState, viewers: NDArray[np.int64] | None = None
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls each viewer (``None``: each shooter) may hit first."""
        if viewers is None:
            viewers = state.rack[:, wpa.SHOOTER]
        return legal_balls(self.code, state.on_table, state.rack, viewers)

    def decoded_shot(self, row: list[float], calls: Any, tip: tuple[float, float],
                     cue: tuple[float, float] | None) -> Shot:  # fmt: skip
        """The :class:`Shot` of one executed row with its calls (pocket, ball, option)."""
        call = calls[0]
        return Shot(
            angle=row[0], speed=row[1], tip=tip, cue=cue, pocket=int(call[CALL_POCKET]),
            ball=int(call[CALL_BALL]) if call[CALL_BALL] > 0 else None,
            push_out=bool(call[CALL_PUSH_OUT]), pass_back=bool(call[CALL_HAND_BACK]),
        )  # fmt: skip

    def state_dict(self, row: NDArray[np.int64]) -> dict[str, Any]:
        """A rack-state row as the keys of ``options["rules"]`` and ``winner``."""
        return rack_dict(row)

    def state_row(
        self, config: GameConfig, given: Any, on_table: NDArray[np.bool_] | None = None
    ) -> NDArray[np.int64]:
        """The rack row of ``given``: a row, a dict as ``PoolEnv.rack`` gives, or ``None``."""
        return rack_of(config, given)

    def shooters(self, state: GameState) -> NDArray[np.int64]:
        """``(B,)`` the player to shoot on each table (a copy)."""
        return state.rack[:, wpa.SHOOTER].copy()


#: 9-ball: nine object balls, the 9 wins; the push-out.
NINE = WpaGame("nine", wpa.NINE, 9, calls_ball=False, has_option=True)

#: 10-ball: ten object balls, called shots (ball and pocket), the 10 wins; the push-out.
TEN = WpaGame("ten", wpa.TEN, 10, calls_ball=True, has_option=True)

#: 8-ball: fifteen object balls, solids and stripes, the 8 wins.
EIGHT = WpaGame("eight", wpa.EIGHT, 15, calls_ball=False, has_option=False)
