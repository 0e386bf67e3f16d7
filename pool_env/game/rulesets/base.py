"""The interface of a ruleset: what a game decides in one step, as one strategy object.

:func:`pool_env.game.step.step` has one path, the same for every game; at each point where
games differ it asks ``config.ruleset`` (a :class:`Ruleset`). The compiled kernels stay
numba functions; a ruleset only chooses which of them run and with which arrays, so one
step costs a few Python method calls more than a hard-wired path, and allocates nothing
more. One step, in order:

1. :meth:`Ruleset.place`: the cue ball in hand goes where the action asks;
2. :meth:`Ruleset.execute`: the actions decoded into shots, with execution noise;
3. the simulator plays the shots to rest (the same for every game: :mod:`.step`);
4. :meth:`Ruleset.judge`: the outcome applied to the state by the rules (rewards, flags);
5. :meth:`Ruleset.fix_spots`: the rare re-spots the compiled rules could not finish;
6. :meth:`Ruleset.observe` and the ``info`` columns (:meth:`Ruleset.table_info`,
   :meth:`Ruleset.batch_info`).

A new game is a new subclass in its own module of this package and a name in
:data:`pool_env.game.rulesets.RULESETS` (``docs/architecture.md`` walks through 10-ball).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple, Protocol

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels.observe import encode_observations
from pool_env.game.rules import CUE, SPOT_TAKEN
from pool_env.game.scenes import ScenePlan, free_spot
from pool_env.game.shots import Shot, ShotConstraints
from pool_env.game.state import GameState
from pool_env.sim.result import ShotResult
from pool_env.sim.table import Table


class Outcome(NamedTuple):
    """The simulator's answer for the tables that shot; row ``k`` is ``tables[k]``.

    Attributes:
        final: ``(K, M, 2)`` final positions, columns ``balls``.
        pocketed: ``(K, M)`` pocket of each ball, -1 for none.
        first: ``(K, 2)`` result columns of the first ball-ball impact, -1 for none.
        cushions: ``(K, M)`` each ball's cushion impacts after the first contact.
        order: ``(K, M)`` the order the balls dropped, -1 if they did not.
        n_events: ``(K,)`` simulator events, or ``None``: read from ``shot``.
        capped: ``(K,)`` a shot reached the event cap, or ``None``: read from ``shot``.
        balls: ``(M,)`` ball number of each column.
        shot: The :class:`~pool_env.ShotResult` of a one-table step, else ``None``.
    """

    final: NDArray[np.float64]
    pocketed: NDArray[np.int64]
    first: NDArray[np.int64]
    cushions: NDArray[np.int64]
    order: NDArray[np.int64]
    n_events: NDArray[np.int64] | None
    capped: NDArray[np.bool_] | None
    balls: NDArray[np.intp]
    shot: ShotResult | None


#: What :meth:`Ruleset.execute` returns: ``(shots, states, extra)``: the executed shots
#: ``(K, 2)`` (spin ``(K, 4)``), the initial ball states ``(K, N, 2)`` (spin ``(K, N, 5)``)
#: and what the ruleset's own judge needs besides (the WPA games' calls; ``None``: nothing).
Executed = tuple[NDArray[np.float64], NDArray[np.float64], Any]

#: What :meth:`Ruleset.judge` returns: ``(rewards, flags, hits)``, columns named in
#: :mod:`pool_env.game.rules`.
Judged = tuple[NDArray[np.float64], NDArray[np.bool_], NDArray[np.int64]]


@dataclass(frozen=True)
class RulesSection:
    """A game's section of the config (:mod:`pool_env.game.sections`): its name alone here.

    A game with options of its own subclasses it (:class:`~.wpa.WpaRules`) and names the
    subclass as its :attr:`Ruleset.section`.

    Attributes:
        game: The game (``"solitaire"``, ``"nine"``, ``"ten"``, ``"eight"``).
    """

    game: str = "solitaire"


class RuleOptions(NamedTuple):
    """A rules section parsed: what :class:`~pool_env.game.config.GameConfig` keeps of it."""

    end_on_foul: bool
    break_speed_range: tuple[float, float]
    rule_rewards: tuple[float, float]


class ConfigView(Protocol):
    """What a ruleset reads of a :class:`~pool_env.game.config.GameConfig` (which holds it)."""

    @property
    def table(self) -> Table: ...  # noqa: D102

    @property
    def params(self) -> NDArray[np.float64]: ...  # noqa: D102

    @property
    def n_balls(self) -> int: ...  # noqa: D102

    @property
    def speed_range(self) -> tuple[float, float]: ...  # noqa: D102

    @property
    def break_speed_range(self) -> tuple[float, float]: ...  # noqa: D102


class Ruleset:
    """A game: the steps of the decision process where games differ.

    Subclasses set the class attributes and override what their game does differently;
    the defaults here are solitaire's where a step has nothing to do (no ball in hand, no
    observation or ``info`` beyond the balls').

    Attributes:
        name: The config value naming the game (``GameConfig.game``, ``gym.make(...,
            game=name)``).
        code: The game's code in the kernels (``params[GAME]``).
        has_rack: Whether each table keeps a rack state (``GameState.rack``: turns, fouls,
            ball in hand), read by ``PoolEnv.rack`` and ``options["rules"]``.
        action_width: Action components before a spin table's two tip components.
        info_keys: The ``info`` keys this game adds to every step's.
        section: The game's section of the config (its rule options and their defaults).
    """

    name: str = ""
    code: int = 0
    has_rack: bool = False
    action_width: int = 2
    info_keys: tuple[str, ...] = ()
    section: type[RulesSection] = RulesSection

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r})"

    def observation_width(self, n_balls: int) -> int:
        """Observation entries for ``n_balls`` balls (the cue ball included): ``3 N``."""
        return 3 * n_balls

    def obs_layout(self, n_balls: int) -> dict[str, slice]:
        """Where each part of an observation lies: here ``"balls"``, ``(x, y, on_table)`` each.

        Ball ``j``'s entries are ``obs[layout["balls"]][3 j : 3 j + 3]``.
        """
        return {"balls": slice(0, 3 * n_balls)}

    def constraints(self, config: ConfigView, observation: NDArray[Any]) -> ShotConstraints:
        """What the next shot may do, read from one observation: any ball on the table."""
        on = np.asarray(observation)[self.obs_layout(config.n_balls)["balls"]][2::3] > 0.5
        first = tuple(int(j) for j in np.flatnonzero(on[1:]) + 1)
        return ShotConstraints(first_balls=first, speed_range=config.speed_range)

    def first_balls_after(self, on_after: NDArray[np.bool_], potted: int) -> tuple[int, ...]:
        """The legal first balls of the next shot if the shooter keeps the table.

        ``potted`` dropped and ``on_after`` are the balls left: here every object ball left.
        """
        return tuple(int(j) for j in np.flatnonzero(on_after[1:]) + 1)

    def placed_cue(self, state: GameState) -> tuple[float, float] | None:
        """Where table 0's cue ball was placed in hand by :meth:`place`: never here."""
        return None

    def encode(
        self,
        config: ConfigView,
        shot: Shot,
        state: GameState,
        out: NDArray[np.float64],
        clip: bool,
    ) -> tuple[float, float]:
        """Write the game's own action components of ``shot`` (none here) into ``out``.

        Also moves table 0's cue ball of ``state`` to where the shot places it, so that
        the aim refers from there.

        Returns:
            The speed range of this shot's speed component.
        """
        return config.speed_range

    def encode_placement(
        self, config: ConfigView, cue: Any, behind: bool, clip: bool
    ) -> tuple[float, float]:
        """The action components that place the cue ball in hand at ``cue``.

        Raises:
            ValueError: Always here: this game has no ball in hand.
        """
        raise ValueError("the cue ball is placed in hand under rules (game='nine', 'ten', 'eight')")

    def parse_rules(self, section: RulesSection) -> RuleOptions:
        """Check and parse the game's section: no options here (no fouls, no break)."""
        return RuleOptions(False, (0.0, 0.0), (0.0, 0.0))

    def check(
        self, scene: ScenePlan, table: Table, end_on_miss: bool, end_on_foul: bool, players: int
    ) -> None:
        """Refuse arguments the game cannot play (``ValueError``, naming them)."""

    def rule_params(
        self,
        params: NDArray[np.float64],
        table: Table,
        players: int,
        end_on_foul: bool,
        break_speed_range: tuple[float, float],
        rule_rewards: tuple[float, float],
    ) -> NDArray[np.float64]:
        """The kernel parameters with the game's entries set (read-only): as they are here."""
        return params

    def place(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        actions: NDArray[np.float64],
    ) -> None:
        """Put each cue ball in hand where its action asks: no ball in hand here."""

    def execute(
        self,
        params: NDArray[np.float64],
        pockets: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        actions: NDArray[np.float64],
    ) -> Executed:
        """The shots the actions play, with execution noise (see :data:`Executed`)."""
        raise NotImplementedError

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
        """Apply the outcomes to ``state`` by the rules (see :data:`Judged`).

        ``velocities`` and ``spins`` are the shots' initial states (a rule may replay a
        shot from them); ``extra`` is the third item :meth:`execute` returned.
        """
        raise NotImplementedError

    def fix_spots(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        tables: NDArray[np.intp],
        flags: NDArray[np.bool_],
        hits: NDArray[np.int64],
    ) -> None:
        """Finish the re-spots the compiled rules left: the cue ball of ``SPOT_TAKEN`` rows.

        Rare (something covers the head spot): the cue ball goes to the free point nearest
        to it.
        """
        if flags[:, SPOT_TAKEN].any():
            for k in np.flatnonzero(flags[:, SPOT_TAKEN]).tolist():
                place_free(table, state, int(tables[k]), CUE, None)

    def observe(
        self,
        table: Table,
        params: NDArray[np.float64],
        state: GameState,
        viewers: NDArray[np.int64] | None,
    ) -> NDArray[np.float32]:
        """``(B, obs)`` observations of every table: per ball ``(x, y, on_table)``."""
        return encode_observations(state.positions, state.on_table, table.length, table.width)

    def aim_references(
        self, state: GameState, viewers: NDArray[np.int64] | None = None
    ) -> NDArray[np.bool_]:
        """``(B, N)``: the balls relative and cut aim may refer to: here every ball on.

        Under rules, the balls each viewer (``None``: each table's shooter) may hit first.
        A fresh array.
        """
        return state.on_table.copy()

    def table_info(self, hits: list[int], info: dict[str, Any]) -> None:
        """Add the game's keys to a one-table ``info`` from its ``hits`` row: none here."""

    def batch_info(
        self,
        hits: NDArray[np.int64],
        rows: NDArray[np.bool_] | slice,
        tables: NDArray[np.intp],
        n_envs: int,
        present: NDArray[np.bool_],
        info: dict[str, Any],
    ) -> None:
        """Add the game's keys to a vector ``info`` (Gymnasium's layout): none here.

        Args:
            hits: ``(K, C)`` the step's integer results.
            rows: The rows reported (a mask over ``K``, or every row).
            tables: ``(K',)`` the tables of those rows.
            n_envs: Number of tables.
            present: ``(n_envs,)`` the reported tables (each key's mask is a copy).
            info: The dict to add to.
        """


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
