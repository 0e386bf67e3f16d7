"""The interface of a game: what a game decides, as one strategy object over one context.

:func:`pool_env.game.step.step` has one path, the same for every game; at each point where
games differ it asks ``config.ruleset`` (a :class:`Ruleset`), handing it one
:class:`Turn` (the config, the tables' state, the tables that shoot) rather than loose
arrays. The compiled kernels stay numba functions in the game's own package; a ruleset
only chooses which of them run and with which arrays. A game decides, in this order:

1. :meth:`Ruleset.configure` (once, when an env is made): its rules section checked
   against the scene, the table and the players, and its tail of the kernel parameters
   (its rule options and reward scales);
2. :meth:`Ruleset.start` (each reset): the per-table game state an episode starts from
   (``GameState.rack``, :attr:`Ruleset.rack_width` integers a table; none in solitaire);
3. :meth:`Ruleset.shoot` (each step): the actions decoded into struck shots, the cue
   ball in hand placed first, with execution noise (one compiled call, but for the rare
   covered placement);
4. the simulator plays the shots to rest (the same for every game: :mod:`.step`);
5. :meth:`Ruleset.judge`: the outcome applied to the state by the rules (rewards and
   their terms, ends, re-spots);
6. :meth:`Ruleset.observe` and :meth:`Ruleset.info_columns`: what the agent sees, and
   what the step's ``info`` adds.

The rest serves players and the codec, read-only: :meth:`Ruleset.obs_layout`,
:meth:`Ruleset.constraints`, :meth:`Ruleset.first_balls_after`,
:meth:`Ruleset.legal_first_balls`,
:meth:`Ruleset.aim_references`, :meth:`Ruleset.cue_columns`, :meth:`Ruleset.encode` and
the game state as a dict
(:meth:`Ruleset.state_dict`, :meth:`Ruleset.state_row`, :meth:`Ruleset.shooters`).

A game is a package of its own under :mod:`pool_env.game.games` (or anywhere: a user's
package), made known by :func:`pool_env.game.registry.register_game`;
``docs/own_game.md`` builds one.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels.actions import executed_shots
from pool_env.game.kernels.observe import encode_observations
from pool_env.game.kernels.outcome import (
    CLEARED,
    CUE,
    FIRST_BALL,
    N_FLAGS,
    N_HITS,
    POTTED_BITS,
    REWARD,
    SCRATCH,
    SPOT_TAKEN,
    TERMINATED,
    TRUNCATED,
    settle_rows,
)
from pool_env.game.kernels.params import TAIL_SIZE
from pool_env.game.shots import Shot, ShotConstraints
from pool_env.game.spots import free_spot
from pool_env.game.state import GameState
from pool_env.game.turns import (
    Executed,
    GameConfig,
    Judged,
    Outcome,
    RulesSection,
    Setup,
    Turn,
)
from pool_env.sim.table import Table


class Ruleset:
    """A game: the steps of the decision process where games differ.

    Subclasses set the class attributes and override what their game does differently;
    the defaults here are what a game without ball in hand, game state or observation of
    its own does (solitaire's).

    Attributes:
        name: The game's registered name (``gym.make(..., game=name)``).
        rack_width: Integers of game state each table keeps (``GameState.rack``: turns,
            fouls, ball in hand...); 0 for none.
        action_width: Action components before a spin table's two tip components.
        info_keys: The ``info`` keys this game adds to every step's.
        section: The game's section of the config (its rule options and their defaults).
        reward_terms: The game's reward terms and their default scales, in the order of
            the judge's values; each step reports each term, scaled, as
            ``info["reward_<term>"]``, and the reward is their sum.
        scenes: The game's own starting layouts by name, each a fixed ``(N, 2)`` layout or
            a callable ``(table, rng) -> (N, 2)`` (cue ball first), which ``scene=<name>``
            picks on this game's tables (the shared ones are :data:`pool_env.SCENES`).
        spin_only: Empty, or why the game is played on the spin level only: then
            ``model="roll"`` is refused with this reason before any table is made.
        ball_colours: The game's balls in pictures: one RGB triple (0-255) per ball column
            (ball 0 first), drawn plain, without numbers or stripes (snooker's reds and
            colours, carom's white, yellow and red); ``None``: pool balls by number.
        cloth: The cloth's RGB triple in pictures (carom's blue); ``None``: pool green.
    """

    name: str = ""
    rack_width: int = 0
    action_width: int = 2
    info_keys: tuple[str, ...] = ()
    section: type[RulesSection] = RulesSection
    reward_terms: Mapping[str, float] = {}
    scenes: Mapping[str, Any] = {}
    spin_only: str = ""
    ball_colours: tuple[tuple[int, int, int], ...] | None = None
    cloth: tuple[int, int, int] | None = None

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r})"

    @property
    def has_rack(self) -> bool:
        """Whether each table keeps a game state (``PoolEnv.rack``, ``options["rules"]``)."""
        return self.rack_width > 0

    # -- configuration and reset ----------------------------------------------------------

    def configure(self, setup: Setup) -> NDArray[np.float64]:
        """Check the game's arguments and give its tail of the kernel parameters.

        Returns:
            ``(TAIL_SIZE,)`` float64 (:mod:`pool_env.game.kernels.params`: entries from
            ``TAIL`` on, named in the game's package).

        Raises:
            ValueError: On arguments the game cannot play, naming them.
        """
        return np.zeros(TAIL_SIZE)

    def parse_section(self, section: RulesSection) -> RulesSection:
        """The rules section with its values checked and parsed (``ValueError`` if bad)."""
        return section

    def variant(self, section: RulesSection) -> Ruleset:
        """The ruleset that plays the parsed ``section`` (by default this one).

        A game whose section has an option that changes its spaces returns the ruleset of
        those spaces (WPA's ``push_out=False``: no option column, no option features).
        """
        return self

    def start(self, turn: Turn, given: Any, rack_scene: bool, on_table: NDArray[np.bool_]) -> None:
        """Set the game state ``turn.tables`` start from (``options["rules"]``: ``given``).

        Args:
            turn: The reset tables.
            given: ``options["rules"]`` (``None``: the game's default start).
            rack_scene: The layout is the scene's named rack (a break follows).
            on_table: ``(K, N)`` the balls each table starts with, for the checks.

        Raises:
            ValueError: On a given state the game cannot start from (state unchanged).
        """
        if given is not None:
            raise ValueError(f"game={self.name!r} takes no options['rules']")
        turn.state.rack[turn.tables] = 0  # a game that keeps state starts from zeros

    def settle_layout(self, turn: Turn) -> None:
        """Apply the game's rules to the layouts just laid out on ``turn.tables``: none here.

        Called by every reset after the layouts land (the scene's or ``options``'), once
        :meth:`start` has checked them: a game may move balls its rules do not let stand
        (three-cushion re-spots a frozen cue ball). It must not fail.
        """

    # -- one step -------------------------------------------------------------------------

    def shoot(self, turn: Turn, actions: NDArray[np.float64]) -> Executed:
        """The shots the actions play (the cue ball in hand placed first), with noise.

        Here the shared decoding (:func:`pool_env.game.kernels.actions.executed_shots`):
        aim and speed, relative and cut aim at the nearest ball on the table, each table's
        noise, the strike of the table's level; no calls.

        It may change only the cue balls in hand (placed) and the tables' generators (the
        noise drawn): the step saves both before and puts them back if the simulator then
        refuses a shot (:mod:`pool_env.game.kernels.undo`), so a failed step changes nothing.
        """
        state = turn.state
        shots, states = executed_shots(
            turn.config.params, actions, turn.tables, state.positions, state.on_table,
            state.ptrs,
        )  # fmt: skip
        return Executed(shots, states, None)

    def judge(self, turn: Turn, out: Outcome, executed: Executed) -> Judged:
        """Apply the outcomes to ``turn.state`` by the rules, re-spots finished."""
        raise NotImplementedError

    def observe(
        self, config: GameConfig, state: GameState, viewers: NDArray[np.int64] | None
    ) -> NDArray[np.float32]:
        """``(B, obs)`` observations of every table: per ball ``(x, y, on_table)``.

        Every table is observed (no ``Turn``: an observation is made twice a step, and
        the context would cost a tenth of a cheap step's game layer).
        """
        table = config.table
        return encode_observations(state.positions, state.on_table, table.length, table.width)

    def info_columns(self, hits: NDArray[np.int64]) -> dict[str, NDArray[Any]]:
        """The game's ``info`` keys as one array over ``hits``' rows each: none here.

        Each array's dtype is the key's (``bool``, ``int64``; ``object`` for names or
        ``None``); :mod:`pool_env.game.info` turns them into the one-table dict or
        Gymnasium's vector layout.
        """
        return {}

    def info_row(self, hits: list[int]) -> dict[str, Any]:
        """The game's ``info`` keys of one table, as Python scalars (``PoolEnv.step``).

        Here :meth:`info_columns` of that one row; a game may answer faster from the
        list (the WPA games do). ``tests/envs/test_vector.py`` holds the two to the same
        values: the vector env equals a ``SyncVectorEnv`` of ``PoolEnv``'s bit for bit.
        """
        columns = self.info_columns(np.array([hits], dtype=np.int64))
        return {key: column.tolist()[0] for key, column in columns.items()}

    # -- views for players and the codec ---------------------------------------------------

    def observation_width(self, n_balls: int) -> int:
        """Observation entries for ``n_balls`` balls (the cue ball included): ``3 N``."""
        return 3 * n_balls

    def obs_layout(self, n_balls: int) -> dict[str, slice]:
        """Where each part of an observation lies: here ``"balls"``, ``(x, y, on_table)`` each.

        Ball ``j``'s entries are ``obs[layout["balls"]][3 j : 3 j + 3]``.
        """
        return {"balls": slice(0, 3 * n_balls)}

    def constraints(self, config: GameConfig, observation: NDArray[Any]) -> ShotConstraints:
        """What the next shot may do, read from one observation: any ball on the table."""
        on = np.asarray(observation)[self.obs_layout(config.n_balls)["balls"]][2::3] > 0.5
        first = tuple(int(j) for j in np.flatnonzero(on[1:]) + 1)
        return ShotConstraints(first_balls=first, speed_range=config.speed_range)

    def first_balls_after(self, on_after: NDArray[np.bool_], potted: int) -> tuple[int, ...]:
        """The legal first balls of the next shot if the shooter keeps the table.

        ``potted`` dropped and ``on_after`` are the balls left: here every object ball left.
        """
        return tuple(int(j) for j in np.flatnonzero(on_after[1:]) + 1)

    def legal_first_balls(
        self,
        rack: NDArray[np.int64],
        on_table: NDArray[np.bool_],
        viewers: NDArray[np.int64] | None = None,
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the object balls each viewer may hit first, from rack rows, batched.

        The batched twin of :meth:`constraints`' ``first_balls`` for players that search
        simulated outcomes (their rack rows after a step): here every object ball on.

        Args:
            rack: ``(B, rack_width)`` rack-state rows (none here: ``(B, 0)``).
            on_table: ``(B, N)`` which balls are on the table.
            viewers: ``(B,)`` whose legal balls (``None``: each row's shooter).

        Returns:
            A fresh ``(B, N)`` bool array; the cue ball's column is False.
        """
        out = np.array(on_table, dtype=np.bool_, ndmin=2)
        out[:, 0] = False
        return out

    def aim_references(
        self, state: GameState, viewers: NDArray[np.int64] | None = None
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls relative and cut aim may refer to: here every ball on.

        Under rules, the balls each viewer (``None``: each table's shooter) may hit first.
        A fresh array.
        """
        return state.on_table.copy()

    def cue_columns(self, state: GameState) -> NDArray[np.int64]:
        """``(B,)`` the column of the ball each table's striker strikes: 0 here.

        A game where each player has a cue ball of his own (three-cushion: the yellow is
        player 1's) answers the striker's; the codec aims from that ball. A fresh array.
        """
        return np.zeros(state.n_tables, dtype=np.int64)

    def encode(
        self, config: GameConfig, shot: Shot, state: GameState, out: NDArray[np.float64],
        clip: bool,
    ) -> tuple[float, float]:  # fmt: skip
        """Write the game's own action components of ``shot`` (none here) into ``out``.

        Also moves table 0's cue ball of ``state`` to where the shot places it, so that
        the aim refers from there.

        Returns:
            The speed range of this shot's speed component.
        """
        return config.speed_range

    def encode_placement(
        self, config: GameConfig, cue: Any, behind: bool, clip: bool
    ) -> tuple[float, float]:
        """The action components that place the cue ball in hand at ``cue``.

        Raises:
            ValueError: Always here: this game has no ball in hand.
        """
        raise ValueError(
            f"game={self.name!r} has no cue ball in hand: the cue ball is placed in hand "
            "under rules (game='nine', 'ten', 'eight')"
        )

    def encode_ball(self, config: GameConfig, ball: int) -> float:
        """The action component that calls object ball ``ball``.

        Raises:
            ValueError: Here: this game calls no ball.
        """
        raise ValueError(f"game={self.name!r} calls no ball (10-ball does)")

    def decoded_shot(self, row: list[float], calls: Any, tip: tuple[float, float],
                     cue: tuple[float, float] | None) -> Shot:  # fmt: skip
        """The :class:`Shot` of one executed row and its calls (:func:`.codec.decode_action`)."""
        return Shot(angle=row[0], speed=row[1], tip=tip, cue=cue)

    def placed_cue(self, state: GameState) -> tuple[float, float] | None:
        """Where table 0's cue ball was placed in hand by :meth:`shoot`: never here."""
        return None

    def state_dict(self, row: NDArray[np.int64]) -> dict[str, Any]:
        """A table's game state as a dict (``PoolEnv.rack``).

        Raises:
            ValueError: Here: this game keeps no state.
        """
        raise ValueError(f"game={self.name!r} keeps no rack state")

    def state_row(
        self, config: GameConfig, given: Any, on_table: NDArray[np.bool_] | None = None
    ) -> NDArray[np.int64]:
        """A table's game state row from a dict (:meth:`state_dict`'s), a row or ``None``.

        ``on_table`` (``(N,)``, the layout the row goes with) lets a game whose state
        follows the balls read them (snooker's phase); the others ignore it.
        """
        if given is not None:
            raise ValueError(
                f"rack is for the rules ids (a game with a rack state), not game={self.name!r}"
            )
        return np.zeros(self.rack_width, dtype=np.int64)

    def shooters(self, state: GameState) -> NDArray[np.int64]:
        """``(B,)`` the player to shoot on each table: always 0 here (one player)."""
        return np.zeros(state.n_tables, dtype=np.int64)


class Settled(NamedTuple):
    """What :func:`settle_shots` found; row ``k`` is ``tables[k]``.

    Attributes:
        potted: ``(K, N)`` the object balls each shot potted (the cue ball's column False).
        scratch: ``(K,)`` the cue ball dropped (it is back on the table already).
        first: ``(K,)`` the first ball the cue ball hit, -1 for none.
        bits: ``(K,)`` the potted object balls as bits (ball ``j``: bit ``j - 1``).
    """

    potted: NDArray[np.bool_]
    scratch: NDArray[np.bool_]
    first: NDArray[np.int64]
    bits: NDArray[np.int64]


def settle_shots(turn: Turn, out: Outcome) -> Settled:
    """Apply the simulator's outcome to the tables: what a judge does before its rules.

    The balls move to where they stopped, potted ones leave the table, each table's shot
    is counted, and a scratched cue ball goes back on the head spot (or, when that is
    covered, on the free point nearest it). One compiled call over every row
    (:func:`pool_env.game.kernels.outcome.settle_rows`), the rare covered spot in Python.
    """
    config, state, tables = turn
    potted, scratch, first, bits, taken = settle_rows(
        config.params, config.table.pockets, tables, out.balls, state.positions,
        state.on_table, state.shots, out.final, out.pocketed, out.first,
    )  # fmt: skip
    if taken.any():
        for k in np.flatnonzero(taken).tolist():
            place_free(config.table, state, int(tables[k]), CUE, None)
    return Settled(potted, scratch, first, bits)


def place_free(
    table: Table,
    state: GameState,
    b: int,
    ball: int,
    target: NDArray[np.float64] | None,
    behind: bool = False,
) -> None:
    """Move ``ball`` of table ``b`` to the free point nearest ``target`` (head spot: None)."""
    occupied = state.on_table[b].copy()
    occupied[ball] = False
    state.positions[b, ball] = free_spot(
        table, state.positions[b], occupied, target, behind_head_string=behind
    )


def place_cue_balls(turn: Turn, flags: NDArray[np.bool_]) -> None:
    """Finish the cue balls the compiled rules left on a covered head spot (rare).

    The cue ball of each ``SPOT_TAKEN`` row goes to the free point nearest the head spot.
    """
    taken = flags[:, SPOT_TAKEN]
    # One table (every PoolEnv step) reads its flag: numpy's any() costs a microsecond.
    if not (taken[0] if taken.shape[0] == 1 else taken.any()):
        return
    for k in np.flatnonzero(taken).tolist():
        place_free(turn.config.table, turn.state, int(turn.tables[k]), CUE, None)


__all__ = [
    "CLEARED",
    "FIRST_BALL",
    "N_FLAGS",
    "N_HITS",
    "POTTED_BITS",
    "REWARD",
    "SCRATCH",
    "SPOT_TAKEN",
    "TERMINATED",
    "TRUNCATED",
    "Executed",
    "Judged",
    "Outcome",
    "RulesSection",
    "Ruleset",
    "Settled",
    "Setup",
    "Turn",
    "place_cue_balls",
    "place_free",
    "settle_shots",
]
