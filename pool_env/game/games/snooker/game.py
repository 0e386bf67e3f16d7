"""Snooker (WPBSA), one ruleset over the compiled rules of this package.

The frame's state is a row of :mod:`.rack_state` per table; :mod:`.judge` strikes the
strokes and judges them by :mod:`.rules` (whose docstring lists every rule implemented and
every rule left out, with its section number); :mod:`.observe` shows the frame to a player.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import parse_bool
from pool_env.game.components import ball_component, unit_component
from pool_env.game.games.snooker import params as sp
from pool_env.game.games.snooker import rack_state as sk
from pool_env.game.games.snooker.info import RULE_KEYS, info_columns, info_row
from pool_env.game.games.snooker.judge import (
    N_NOMINATIONS,
    UNPLACED,
    judge_snooker,
    snooker_shots,
)
from pool_env.game.games.snooker.markings import COLOURS, N_BALLS, SCENES, markings
from pool_env.game.games.snooker.observe import RULE_FEATURES, encode_snooker_observations
from pool_env.game.games.snooker.rack import row_of, state_dict
from pool_env.game.games.snooker.section import REWARD_TERMS, SnookerRules
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
    place_free,
)
from pool_env.game.shots import Shot, ShotConstraints
from pool_env.game.state import GameState

if TYPE_CHECKING:
    from pool_env.game.config import GameConfig

#: The balls' colours (RGB, 0-255), by ball number: white, 15 reds, yellow, green, brown,
#: blue, pink, black.
BALL_COLOURS: tuple[tuple[int, int, int], ...] = (
    ((250, 250, 240),) + ((200, 20, 30),) * 15
    + ((250, 210, 30), (20, 140, 60), (120, 70, 30), (30, 80, 200), (250, 140, 170),
       (15, 15, 15))
)  # fmt: skip

#: The cloth (RGB): a snooker green.
CLOTH: tuple[int, int, int] = (30, 110, 50)


class Snooker(Ruleset):
    """Snooker (``game="snooker"``): a frame by the WPBSA rules (:mod:`.rules`).

    The action is ``(aim, speed, cue x, cue y, nomination)``, then a spin table's tip
    (:mod:`.judge` says how each is read).
    """

    name = "snooker"
    rack_width = sk.N_RACK
    action_width = 5
    info_keys = RULE_KEYS
    section = SnookerRules
    reward_terms = REWARD_TERMS
    scenes = SCENES
    ball_colours = BALL_COLOURS
    cloth = CLOTH

    # -- configuration and reset ----------------------------------------------------------

    def parse_section(self, section: RulesSection) -> SnookerRules:
        """The :class:`SnookerRules` checked (``ValueError`` naming a bad value)."""
        if not isinstance(section, SnookerRules):
            raise ValueError(f"game='snooker' takes a SnookerRules section, got {section!r}")
        return SnookerRules(end_on_foul=parse_bool("end_on_foul", section.end_on_foul))

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """Refuse what snooker cannot play; give its tail of the kernel parameters.

        Refused: a scene of other than 21 object balls, ``end_on_miss``, a table without
        pockets, ``end_on_foul`` with two players. The tail: the visit mode, the table's
        markings (:func:`.markings.markings`) and the reward scales.
        """
        table = setup.table
        if setup.scene.n_objects != N_BALLS - 1:
            raise ValueError(
                "game='snooker' needs 21 object balls numbered as snooker's (1-15 the reds, "
                f"16-21 yellow .. black), got a scene with {setup.scene.n_objects}: use "
                "scene='snooker' or scene='snooker_break'"
            )
        if setup.end_on_miss:
            raise ValueError("end_on_miss is solitaire's: under rules use end_on_foul")
        if table.n_pockets == 0:
            raise ValueError("game='snooker' needs a table with pockets")
        rules = self.parse_section(setup.rules)
        if rules.end_on_foul and setup.players == 2:
            raise ValueError(
                "end_on_foul=True is the one-visit mode (SnookerBreak): in a frame of two "
                "players a foul passes the table to the opponent; leave end_on_foul=False"
            )
        mark = markings(table)
        return kp.game_tail(
            {
                sp.END_ON_FOUL: float(rules.end_on_foul),
                sp.BAULK_X: mark.baulk_x,
                sp.D_RADIUS: mark.d_radius,
                sp.CENTRE_Y: mark.centre_y,
                sp.BLUE_X: mark.spots[3, 0],
                sp.PINK_X: mark.spots[4, 0],
                sp.BLACK_X: mark.spots[5, 0],
                sp.W_POINTS: setup.rewards["pot"],
                sp.W_PENALTY: setup.rewards["foul"],
                sp.W_WIN: setup.rewards["win"],
            }
        )

    def start(self, turn: Turn, given: Any, rack_scene: bool, on_table: NDArray[np.bool_]) -> None:
        """The frame state from ``options["rules"]`` (:func:`.rack.row_of`), checked.

        The scene's start: player 0 to play, the cue ball in hand in the D, a red on.
        From given positions: the cue ball where it lies (unless ``ball_in_hand``), a red
        on (the colours in order when no red is on the table).
        """
        row = row_of(given, _has_reds(on_table), in_hand=rack_scene)
        turn.state.rack[turn.tables] = row

    # -- one step -------------------------------------------------------------------------

    def shoot(self, turn: Turn, actions: NDArray[np.float64]) -> Executed:
        """Each cue ball in hand placed in the D, the nominations read, the strokes struck."""
        config, state, tables = turn
        shots, states, calls, unplaced = snooker_shots(
            config.params, config.table.pockets, actions, tables, state.positions,
            state.on_table, state.ptrs, state.rack,
        )  # fmt: skip
        if unplaced.any():
            raise ValueError("the D has no free point for the cue ball in hand")
        return Executed(shots, states, calls)

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        """The rules (:func:`.judge.judge_snooker`), then the rare placement left over.

        A colour with no room on its lines (or a cue ball with none in the D) goes to the
        free point nearest its spot (the D's middle).
        """
        config, state, tables = turn
        table = config.table
        judged = Judged(*judge_snooker(
            config.params, table.pockets, tables, out.balls, state.positions,
            state.on_table, state.shots, state.rack, out.final, out.pocketed, out.first,
            executed.calls, state.ptrs,
        ))  # fmt: skip
        left = judged.flags[:, UNPLACED]
        if left[0] if left.shape[0] == 1 else left.any():
            mark = markings(table)
            for k in np.flatnonzero(left).tolist():
                self._place_overlapping(table, state, int(tables[k]), mark)
        return judged

    @staticmethod
    def _place_overlapping(table: Any, state: GameState, b: int, mark: Any) -> None:
        """Move each ball that overlaps another to the free point nearest its own point."""
        pos, on = state.positions[b], state.on_table[b]
        reach = 2.0 * table.ball_radius
        for j in (*COLOURS, CUE):
            if not on[j]:
                continue
            gaps = np.hypot(*(pos[on] - pos[j]).T)
            if np.sum(gaps < reach) > 1:  # itself, and another
                target = (
                    mark.spots[j - COLOURS[0]]
                    if j
                    else np.array([mark.baulk_x - mark.d_radius / 2.0, mark.centre_y])
                )
                place_free(table, state, b, j, np.asarray(target, dtype=np.float64))

    def observe(
        self, config: GameConfig, state: GameState, viewers: NDArray[np.int64] | None
    ) -> NDArray[np.float32]:
        """The balls, the balls on, the frame's features from ``viewers``' seats."""
        if viewers is None:
            viewers = state.rack[:, sk.SHOOTER]
        table = config.table
        return encode_snooker_observations(
            state.positions, state.on_table, state.rack, viewers, table.length, table.width,
            table.ball_radius,
        )  # fmt: skip

    def info_columns(self, hits: NDArray[np.int64]) -> dict[str, NDArray[Any]]:
        """:data:`.info.RULE_KEYS` over ``hits``' rows."""
        return info_columns(hits)

    def info_row(self, hits: list[int]) -> dict[str, Any]:
        """The same keys for one table, from its row as a list."""
        return info_row(hits)

    # -- views for players and the codec ---------------------------------------------------

    def observation_width(self, n_balls: int) -> int:
        """``3 N`` ball entries, ``N - 1`` balls-on flags and the rule features."""
        return 4 * n_balls - 1 + len(RULE_FEATURES)

    def obs_layout(self, n_balls: int) -> dict[str, slice]:
        """The balls, the balls-on flags (``"legal"``), then one part per rule feature."""
        layout = super().obs_layout(n_balls)
        base = 4 * n_balls - 1
        layout["legal"] = slice(3 * n_balls, base)
        for k, name in enumerate(RULE_FEATURES):
            layout[name] = slice(base + k, base + k + 1)
        return layout

    def constraints(self, config: GameConfig, observation: NDArray[Any]) -> ShotConstraints:
        """The balls the viewer may play first, the cue ball in hand and the D's box.

        ``call_ball`` is set when a nomination counts: a colour on, or a free ball.

        Raises:
            ValueError: On an observation of another width.
        """
        obs = np.asarray(observation)
        width = self.observation_width(config.n_balls)
        if obs.shape != (width,):
            raise ValueError(f"a snooker observation has shape ({width},), got {obs.shape}")
        layout = self.obs_layout(config.n_balls)
        flag = {name: bool(obs[layout[name]][0] > 0.5) for name in RULE_FEATURES[:6]}
        first = tuple(int(j) for j in np.flatnonzero(obs[layout["legal"]] > 0.5) + 1)
        box = None
        if flag["ball_in_hand"]:
            p = config.params
            bx, r, cy = p[sp.BAULK_X], p[sp.D_RADIUS], p[sp.CENTRE_Y]
            box = ((float(bx - r), float(bx)), (float(cy - r), float(cy + r)))
        return ShotConstraints(
            first_balls=first,
            speed_range=config.speed_range,
            ball_in_hand=flag["ball_in_hand"],
            placement=box,
            call_ball=flag["colour_on"] or flag["free_ball"],
        )

    def first_balls_after(self, on_after: NDArray[np.bool_], potted: int) -> tuple[int, ...]:
        """The balls on next if the striker pots ``potted`` legally.

        A red: every colour left (one is nominated). A colour: the reds left, or with none
        the lowest colour left.
        """
        left = [j for j in range(1, on_after.shape[0]) if on_after[j]]
        colours = [j for j in left if j >= sk.FIRST_COLOUR]
        if potted < sk.FIRST_COLOUR:
            return tuple(colours)
        reds = [j for j in left if j < sk.FIRST_COLOUR]
        return tuple(reds or colours[:1])

    def aim_references(
        self, state: GameState, viewers: NDArray[np.int64] | None = None
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls on for each table's striker (a fresh array)."""
        out = np.zeros(state.on_table.shape, dtype=np.bool_)
        targets = np.empty(state.on_table.shape[1], dtype=np.bool_)
        for b in range(state.n_tables):
            sk.legal_targets(state.rack[b], state.on_table[b], targets)
            out[b] = targets
        return out

    def placed_cue(self, state: GameState) -> tuple[float, float] | None:
        """Where table 0's cue ball stands if it was in hand, else ``None``."""
        if not state.rack[0, sk.IN_HAND]:
            return None
        return float(state.positions[0, CUE, 0]), float(state.positions[0, CUE, 1])

    def encode(
        self, config: GameConfig, shot: Shot, state: GameState, out: NDArray[np.float64],
        clip: bool,
    ) -> tuple[float, float]:  # fmt: skip
        """The placement in the D (cue ball in hand) and the nomination (``Shot.ball``).

        Raises:
            ValueError: On a nomination that is not a colour (16 .. 21), or a placement
                outside the D (without ``clip``).
        """
        if state.rack[0, sk.IN_HAND] and shot.cue is not None:
            out[2], out[3] = self.encode_placement(config, shot.cue, False, clip)
            state.positions[0, CUE] = shot.cue  # the aim refers from where it will be
        out[4] = -1.0 + 1.0 / N_NOMINATIONS if shot.ball is None else self.encode_ball(
            config, shot.ball)  # fmt: skip
        return config.speed_range

    def encode_ball(self, config: GameConfig, ball: int) -> float:
        """The nomination component naming colour ``ball`` (16 .. 21): its bin's middle.

        Raises:
            ValueError: For a ball that is not a colour.
        """
        if ball not in COLOURS:
            raise ValueError(f"snooker nominates a colour, 16 (yellow) .. 21 (black), got {ball!r}")
        # bins: none, yellow .. black; ball_component's bins of 7 "balls" are the same
        return ball_component(N_NOMINATIONS, ball - sk.FIRST_COLOUR + 2)

    def encode_placement(
        self, config: GameConfig, cue: Any, behind: bool, clip: bool
    ) -> tuple[float, float]:
        """``action[2]`` and ``action[3]``: the point of the D (:func:`.markings.d_point`).

        Raises:
            ValueError: On a point outside the D (without ``clip``).
        """
        p = config.params
        bx, r, cy = float(p[sp.BAULK_X]), float(p[sp.D_RADIUS]), float(p[sp.CENTRE_Y])
        x, y = (float(v) for v in np.asarray(cue, dtype=np.float64).reshape(2))
        depth = unit_component("cue x (depth into the D)", bx - x, 0.0, r, clip)
        d = (depth + 1.0) / 2.0 * r
        half = float(np.sqrt(max(r * r - d * d, 0.0)))
        if half == 0.0:
            return depth, 0.0
        return depth, unit_component("cue y (across the D)", y - cy, -half, half, clip)

    def decoded_shot(self, row: list[float], calls: Any, tip: tuple[float, float],
                     cue: tuple[float, float] | None) -> Shot:  # fmt: skip
        """The :class:`Shot` of one executed row: the nominated colour as ``ball``."""
        colour = int(calls[0])
        return Shot(angle=row[0], speed=row[1], tip=tip, cue=cue,
                    ball=colour if colour > 0 else None)  # fmt: skip

    def state_dict(self, row: NDArray[np.int64]) -> dict[str, Any]:
        """A frame-state row as a dict (:func:`.rack.state_dict`)."""
        return state_dict(row)

    def state_row(
        self, config: GameConfig, given: Any, on_table: NDArray[np.bool_] | None = None
    ) -> NDArray[np.int64]:
        """The frame-state row of ``given`` (a dict, a row or ``None``).

        With ``on_table`` (``(N,)``, the codec's layout) the phase follows the balls as
        :meth:`start`'s does (the colours in order without reds; a red on refused there);
        without it, from the given phase (a red on by default).
        """
        if on_table is not None:
            return row_of(given, _has_reds(np.asarray(on_table)[None, :]), False)
        return (
            row_of(given, True, False)
            if given is None or not isinstance(given, dict)
            else row_of(given, given.get("phase", "red") != "in_order", False)
        )

    def shooters(self, state: GameState) -> NDArray[np.int64]:
        """``(B,)`` the player to shoot on each table (a copy)."""
        return state.rack[:, sk.SHOOTER].copy()


def _has_reds(on_table: NDArray[np.bool_]) -> bool:
    """Whether the ``(K, N)`` tables have reds: every one of them, or none (refused)."""
    reds = bool(on_table[:, 1:16].any(axis=1).all())
    if not (reds or not on_table[:, 1:16].any()):
        raise ValueError("options['on_table'] must give every table reds, or none")
    return reds


#: The one snooker ruleset.
SNOOKER = Snooker()
