"""Three-cushion (UMB) as a ruleset: each player's own cue ball, points, innings, a match.

The rules are :func:`.rules.judge_rows` (numpy, vectorised over the tables that shot: a
carom's rule is a few comparisons on the simulator's per-ball rows, no compiled code is
needed). The action is ``(aim, speed)`` then the spin table's tip: the tip decides the
game (english and follow shape the cue ball's path off the cushions), so the roll table
is refused. Player 1's cue ball is the yellow (ball 1): its shots are decoded by the
shared strike on the tables with columns 0 and 1 swapped, so aim (cut and relative aim
at the nearest ball too) and noise are the shared ones.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import is_integer, parse_bool
from pool_env.game.games.three_cushion import section as sc
from pool_env.game.games.three_cushion.layout import break_scene, frozen, starting_layout
from pool_env.game.games.three_cushion.rules import judge_rows
from pool_env.game.games.three_cushion.section import REWARD_TERMS, ThreeCushionRules
from pool_env.game.kernels.actions import executed_shots
from pool_env.game.kernels.outcome import (
    FIRST_BALL,
    N_FLAGS,
    N_HITS,
    TERMINATED,
    TRUNCATED,
)
from pool_env.game.ruleset import (
    Executed,
    Judged,
    Outcome,
    Ruleset,
    RulesSection,
    Setup,
    Turn,
)
from pool_env.game.shots import ShotConstraints
from pool_env.game.state import GameState

if TYPE_CHECKING:
    from pool_env.game.config import GameConfig

#: The judge's integer columns after the shared ones.
(POINT, CUSHIONS, SECOND_BALL, FOUL, STRIKER, WINNER, RESPOTTED, TURN_OVER, SCORE_0,
 SCORE_1, INNINGS_0, INNINGS_1, N_THREE_HITS) = range(N_HITS, N_HITS + 13)  # fmt: skip

#: The ``info`` keys the game adds (:meth:`ThreeCushion.info_columns`).
INFO_KEYS = (
    "point", "cushions", "second_ball", "foul", "striker", "winner", "respotted",
    "turn_over", "score_0", "score_1", "innings_0", "innings_1",
)  # fmt: skip

#: The observation's features after the balls, each in ``[-1, 1]``, from the viewer's seat.
FEATURES = ("yellow", "to_shoot", "own_score", "other_score", "innings", "run", "break")

#: RGB of the white, the yellow and the red, and of the carom cloth (a tournament blue).
BALL_COLOURS = ((245, 245, 240), (240, 200, 40), (200, 30, 30))
CLOTH = (30, 90, 170)

#: The game's scene: the UMB starting position, white to break.
BREAK_SCENE = "three_cushion"

ROLL_REFUSAL = (
    "three-cushion is played on the spin level only (model='spin'): the cue ball's path "
    "off the cushions is decided by its english and follow, which the roll level has not"
)


class ThreeCushion(Ruleset):
    """Three-cushion (``game="three_cushion"``) on ``Table.preset("carom")``."""

    name = "three_cushion"
    spin_only = ROLL_REFUSAL
    rack_width = sc.N_RACK
    section = ThreeCushionRules
    reward_terms = REWARD_TERMS
    scenes: ClassVar[dict[str, Any]] = {BREAK_SCENE: break_scene}
    ball_colours = BALL_COLOURS
    cloth = CLOTH
    info_keys = INFO_KEYS

    # -- configuration and reset ----------------------------------------------------------

    def parse_section(self, section: RulesSection) -> ThreeCushionRules:
        """The section checked: ``target`` >= 1, ``inning_limit`` >= 0, a bool."""
        if not isinstance(section, ThreeCushionRules):
            raise ValueError(
                f"game={self.name!r} takes a ThreeCushionRules section, got {section!r}"
            )
        if not is_integer(section.target) or section.target < 1:
            raise ValueError(f"target must be a positive integer, got {section.target!r}")
        if not is_integer(section.inning_limit) or section.inning_limit < 0:
            raise ValueError(
                "inning_limit must be a non-negative integer (0: none), got "
                f"{section.inning_limit!r}"
            )
        return ThreeCushionRules(
            game=section.game,
            target=int(section.target),
            inning_limit=int(section.inning_limit),
            equalizing_inning=parse_bool("equalizing_inning", section.equalizing_inning),
        )

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """Refuse the roll level, a table with pockets, a scene not of three balls, "shots"."""
        if not setup.table.has_spin:
            raise ValueError(f"model='roll': {ROLL_REFUSAL}")  # a roll Table given
        if setup.table.n_pockets != 0:
            raise ValueError(
                "game='three_cushion' is played on a pocketless carom table: "
                "table=Table.preset('carom')"
            )
        if setup.scene.n_objects != 2:
            raise ValueError(
                "game='three_cushion' needs three balls (white, yellow, red), got a scene "
                f"with {setup.scene.n_objects + 1}"
            )
        if setup.observation == "shots":
            raise ValueError(
                "observation='shots' is no three-cushion observation: its features are "
                "the ghost-ball shot of the reference ball into each pocket, and a carom "
                "has no pocket and no ghost-ball shot (a point is a path off three "
                "cushions to both object balls); use observation='balls'"
            )
        if setup.end_on_miss:
            raise ValueError("end_on_miss is solitaire's: a three-cushion inning ends at a miss")
        self.parse_section(setup.rules)
        return super().configure(setup)

    def start(self, turn: Turn, given: Any, rack_scene: bool, on_table: NDArray[np.bool_]) -> None:
        """White to play; the opening shot (the red first) from the starting position.

        ``options["rules"]`` (``given``) is a dict as :meth:`state_dict` gives, or a row;
        without it a layout given at reset is white's first inning, not a break. Called
        before the layout lands (the reset checks first); a frozen cue ball is then
        re-spotted by :meth:`settle_layout`.
        """
        config, state, tables = turn
        if not np.all(on_table):
            raise ValueError(
                "three-cushion keeps its three balls on the table: on_table must be all "
                f"True, got {on_table[~np.all(on_table, axis=1)][0].tolist()}"
            )
        row = self.state_row(config, given)
        if given is None:
            row[sc.BREAKING] = rack_scene and config.scene.spec is break_scene
        state.rack[tables] = row

    def settle_layout(self, turn: Turn) -> None:
        """A striker's cue ball frozen in the layout laid out: re-spotted (UMB art. 27).

        What a carom referee does when a player comes to the table with his ball touching
        another, whether after a shot or in a layout given at reset
        (``options["positions"]``, a scene): the balls go to the starting position, the
        striker's ball on the head string. ``PoolEnv.positions`` shows where they went.
        """
        config, state, tables = turn
        self._respot_frozen(config, state, tables)

    # -- one step -------------------------------------------------------------------------

    def shoot(self, turn: Turn, actions: NDArray[np.float64]) -> Executed:
        """The shared strike on each striker's own cue ball (yellow: columns 0 and 1 swapped)."""
        config, state, tables = turn
        yellow = self.cue_columns(state)[tables] == 1
        local = np.arange(tables.shape[0])
        pos = state.positions[tables]
        pos[yellow] = pos[yellow][:, [1, 0, 2]]
        targets = self.aim_references(state)[tables]
        targets[yellow] = targets[yellow][:, [1, 0, 2]]
        shots, states = executed_shots(
            config.params, actions, local, pos, targets, state.ptrs[tables]
        )
        states[yellow] = states[yellow][:, [1, 0, 2]]
        return Executed(shots, states, None)

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        """The rules over the striker's cue ball's rows; a frozen next cue ball re-spotted."""
        config, state, tables = turn
        k = tables.shape[0]
        rows = np.arange(k)
        balls = out.balls
        state.positions[tables[:, None], balls[None, :]] = out.final
        state.shots[tables] += 1
        rack = state.rack[tables]
        striker = rack[:, sc.SHOOTER].copy()
        column = np.searchsorted(balls, striker)
        pair = out.first
        other = np.where(pair[:, 0] == column, pair[:, 1], pair[:, 0])
        first = np.where(pair[:, 0] >= 0, balls[np.maximum(other, 0)], -1)
        second_col = out.second_hit[rows, column]
        second = np.where(second_col >= 0, balls[np.maximum(second_col, 0)], -1)
        cushions = out.cushions_at_second[rows, column]
        rules = config.rules
        verdict = judge_rows(
            rack, first, second, cushions, rules.target, rules.inning_limit,
            rules.equalizing_inning, config.players,
        )  # fmt: skip
        state.rack[tables] = rack
        # a finished match's balls stay where they stopped: its final observation shows them
        playing = ~verdict.terminated
        respotted = np.zeros(k, dtype=np.bool_)
        respotted[playing] = self._respot_frozen(config, state, tables[playing])
        scales = config.rewards
        point = verdict.point * scales["point"]
        foul = verdict.foul * scales["foul"]
        values = np.stack([point + foul, point, foul], axis=1)
        flags = np.zeros((k, N_FLAGS), dtype=np.bool_)
        flags[:, TERMINATED] = verdict.terminated
        limit = config.shot_limit
        flags[:, TRUNCATED] = (limit > 0) & (state.shots[tables] >= limit)
        hits = np.zeros((k, N_THREE_HITS), dtype=np.int64)
        hits[:, FIRST_BALL], hits[:, POINT], hits[:, CUSHIONS] = first, verdict.point, cushions
        hits[:, SECOND_BALL], hits[:, FOUL], hits[:, STRIKER] = second, verdict.foul, striker
        hits[:, WINNER], hits[:, RESPOTTED] = rack[:, sc.WINNER], respotted
        hits[:, TURN_OVER] = verdict.turn_over
        hits[:, SCORE_0 : INNINGS_1 + 1] = rack[:, sc.SCORE_0 : sc.INNINGS_0 + 2]
        return Judged(values, flags, hits)

    def _respot_frozen(
        self, config: GameConfig, state: GameState, tables: NDArray[np.intp]
    ) -> NDArray[np.bool_]:
        """Re-spot the tables whose next cue ball touches a ball (UMB art. 27); which did."""
        shooter = state.rack[tables, sc.SHOOTER]
        touching = frozen(state.positions[tables], shooter, config.table.ball_radius)
        for k in np.flatnonzero(touching).tolist():
            state.positions[tables[k]] = starting_layout(config.table, int(shooter[k]))
        return touching

    # -- observation and info -------------------------------------------------------------

    def observe(
        self, config: GameConfig, state: GameState, viewers: NDArray[np.int64] | None
    ) -> NDArray[np.float32]:
        """The balls, then :data:`FEATURES` from each viewer's seat (default: the striker)."""
        balls = super().observe(config, state, viewers)
        rack = state.rack
        shooter = rack[:, sc.SHOOTER]
        viewer = shooter if viewers is None else np.asarray(viewers)
        rows = np.arange(rack.shape[0])
        rules = config.rules
        innings_scale = rules.inning_limit if rules.inning_limit > 0 else rules.target
        features = np.stack(
            [
                np.where(viewer == 1, 1.0, -1.0),
                np.where(viewer == shooter, 1.0, -1.0),
                rack[rows, sc.SCORE_0 + viewer] / rules.target,
                rack[rows, sc.SCORE_0 + 1 - viewer] / rules.target,
                rack[rows, sc.INNINGS_0 + viewer] / innings_scale,
                rack[:, sc.RUN] / rules.target,
                np.where(rack[:, sc.BREAKING] != 0, 1.0, -1.0),
            ],
            axis=1,
        )
        return np.concatenate([balls, np.clip(features, -1.0, 1.0).astype(np.float32)], axis=1)

    def observation_width(self, n_balls: int) -> int:
        """``3 N`` ball entries, then :data:`FEATURES`."""
        return 3 * n_balls + len(FEATURES)

    def obs_layout(self, n_balls: int) -> dict[str, slice]:
        """The balls, then one entry per name of :data:`FEATURES`."""
        layout = super().obs_layout(n_balls)
        for k, name in enumerate(FEATURES):
            layout[name] = slice(3 * n_balls + k, 3 * n_balls + k + 1)
        return layout

    def aim_references(
        self, state: GameState, viewers: NDArray[np.int64] | None = None
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls cut and relative aim refer to: the red alone on the break."""
        refer = state.on_table.copy()
        refer[state.rack[:, sc.BREAKING] != 0, :2] = False
        return refer

    def cue_columns(self, state: GameState) -> NDArray[np.int64]:
        """``(B,)`` each striker's cue ball: 0 the white (player 0), 1 the yellow (a copy)."""
        return state.rack[:, sc.SHOOTER].copy()

    def constraints(self, config: GameConfig, observation: NDArray[Any]) -> ShotConstraints:
        """Any first ball (a carom may start on either object ball; the break: the red)."""
        obs = np.asarray(observation)
        layout = self.obs_layout(config.n_balls)
        breaking = bool(obs[layout["break"]][0] > 0.5)
        yellow = bool(obs[layout["yellow"]][0] > 0.5)
        first = (2,) if breaking else ((0, 2) if yellow else (1, 2))
        return ShotConstraints(first_balls=first, speed_range=config.speed_range, breaking=breaking)

    def info_columns(self, hits: NDArray[np.int64]) -> dict[str, NDArray[Any]]:
        """:attr:`info_keys` over ``hits``' rows (``foul``: ``"break_not_red"`` or ``""``)."""
        columns: dict[str, NDArray[Any]] = {
            "point": hits[:, POINT] != 0,
            "cushions": hits[:, CUSHIONS],
            "second_ball": hits[:, SECOND_BALL],
            "foul": np.where(hits[:, FOUL] != 0, "break_not_red", "").astype(object),
            "striker": hits[:, STRIKER],
            "winner": hits[:, WINNER],
            "respotted": hits[:, RESPOTTED] != 0,
            "turn_over": hits[:, TURN_OVER] != 0,
        }
        for key, col in (("score_0", SCORE_0), ("score_1", SCORE_1),
                         ("innings_0", INNINGS_0), ("innings_1", INNINGS_1)):  # fmt: skip
            columns[key] = hits[:, col]
        return columns

    # -- the game state as a dict ----------------------------------------------------------

    def state_dict(self, row: NDArray[np.int64]) -> dict[str, Any]:
        """A rack row as a dict (``PoolEnv.rack``, ``options["rules"]``)."""
        return {
            "shooter": int(row[sc.SHOOTER]),
            "score": (int(row[sc.SCORE_0]), int(row[sc.SCORE_1])),
            "innings": (int(row[sc.INNINGS_0]), int(row[sc.INNINGS_1])),
            "run": int(row[sc.RUN]),
            "breaking": bool(row[sc.BREAKING]),
            "equalizing": bool(row[sc.EQUALIZING]),
            "winner": int(row[sc.WINNER]),
        }

    def state_row(
        self, config: GameConfig, given: Any, on_table: NDArray[np.bool_] | None = None
    ) -> NDArray[np.int64]:
        """The rack row of ``given``: a dict as :meth:`state_dict` gives, a row, or ``None``.

        ``None``: white to play its first inning, nothing scored.
        """
        row = np.zeros(sc.N_RACK, dtype=np.int64)
        row[sc.INNINGS_0], row[sc.WINNER] = 1, -1
        if given is None:
            return row
        if isinstance(given, dict):
            unknown = sorted(set(given) - set(self.state_dict(row)))
            if unknown:
                raise ValueError(
                    f"unknown three-cushion state key(s) {unknown}; the keys are "
                    f"{sorted(self.state_dict(row))}"
                )
            merged = {**self.state_dict(row), **given}
            shooter = merged["shooter"]
            if shooter not in (0, 1) or isinstance(shooter, bool):
                raise ValueError(f"shooter must be 0 or 1, got {shooter!r}")
            for key in ("score", "innings"):
                if not isinstance(merged[key], list | tuple) or len(merged[key]) != 2:
                    raise ValueError(
                        f"{key} must be a pair (player 0's, player 1's), got {merged[key]!r}"
                    )
            values = [shooter, *merged["score"], *merged["innings"], merged["run"],
                      merged["breaking"], merged["equalizing"], merged["winner"]]  # fmt: skip
            array = np.array(values)
        else:
            array = np.asarray(given)
        if array.shape != (sc.N_RACK,) or not np.all(array == np.round(array)):
            raise ValueError(f"a three-cushion state row is {sc.N_RACK} integers, got {given!r}")
        row = array.astype(np.int64)
        if np.any(row[: sc.WINNER] < 0) or row[sc.SHOOTER] > 1 or not -1 <= row[sc.WINNER] <= 2:
            raise ValueError(
                "a three-cushion state has shooter 0 or 1, counts >= 0 and winner -1, 0, 1 "
                f"or 2 (a draw), got {given!r}"
            )
        return row

    def shooters(self, state: GameState) -> NDArray[np.int64]:
        """``(B,)`` the player to strike on each table (a copy)."""
        return state.rack[:, sc.SHOOTER].copy()


#: The ruleset, registered as ``"three_cushion"``.
THREE_CUSHION = ThreeCushion()
