"""The values a game's methods take and give: the context of a step and its results.

:mod:`pool_env.game.ruleset` (the interface) re-exports them; a game imports them from
there.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, NamedTuple, Protocol

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import SpeedCeiling
from pool_env.game.frozen import freeze_fields
from pool_env.game.scenes import ScenePlan
from pool_env.game.state import GameState
from pool_env.sim.result import ShotResult
from pool_env.sim.table import Table


class GameConfig(Protocol):
    """What a game reads of the parsed config (:class:`pool_env.game.config.GameConfig`).

    A protocol, so that this module, below the config, names no module above it.
    """

    @property
    def table(self) -> Table:
        """The table."""

    @property
    def params(self) -> NDArray[np.float64]:
        """The kernel parameters: the shared head and the game's tail."""

    @property
    def rules(self) -> RulesSection:
        """The game's rules section, checked."""

    @property
    def rewards(self) -> Mapping[str, float]:
        """The reward scales by term."""

    @property
    def players(self) -> int:
        """1 or 2."""

    @property
    def shot_limit(self) -> int:
        """Shots after which an episode is truncated (0: never)."""

    @property
    def n_balls(self) -> int:
        """Balls of a layout, the cue ball included."""

    @property
    def speed_range(self) -> tuple[float, float]:
        """Speeds (m/s) of ``action[1] = -1`` and ``+1``."""

    @property
    def scene(self) -> ScenePlan:
        """The parsed scene."""

    @property
    def ruleset(self) -> Any:
        """The game's :class:`~pool_env.game.ruleset.Ruleset`."""


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
        velocities: ``(K, N, 2)`` the shots' initial velocities (a rule may replay a shot).
        spins: ``(K, N, 3)`` their angular velocities on a spin table, else ``None``.
        second_hit: ``(K, M)`` result column of the second distinct ball each ball
            touched, -1 for none.
        cushions_at_second: ``(K, M)`` each ball's cushion impacts from the shot's start up
            to its second distinct ball contact, -1 for none.
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
    velocities: NDArray[np.float64]
    spins: NDArray[np.float64] | None
    second_hit: NDArray[np.int64]
    cushions_at_second: NDArray[np.int64]


class Turn(NamedTuple):
    """The one context a game's step methods take: who shoots, on what, under which config.

    Attributes:
        config: The fixed model (its sections, table and kernel parameters).
        state: The tables, changed in place by the step.
        tables: ``(K,)`` the tables that shoot (or that are observed or reset).
    """

    config: GameConfig
    state: GameState
    tables: NDArray[np.intp]


class Executed(NamedTuple):
    """What :meth:`Ruleset.shoot` returns.

    Attributes:
        shots: ``(K, 2)`` the executed ``(angle, speed)``; ``(K, 4)`` on a spin table: and
            the executed tip ``(a, b)``.
        states: ``(K, N, 2)`` initial velocities; ``(K, N, 5)`` on a spin table: and
            angular velocities.
        calls: What the game's own judge needs besides (the WPA games' calls), or ``None``.
    """

    shots: NDArray[np.float64]
    states: NDArray[np.float64]
    calls: Any


class Judged(NamedTuple):
    """What :meth:`Ruleset.judge` returns; row ``k`` is ``tables[k]``.

    Attributes:
        values: ``(K, 1 + T)`` floats: the reward (column
            :data:`~pool_env.game.kernels.outcome.REWARD`), then each of the game's ``T``
            reward terms scaled (:attr:`Ruleset.reward_terms`' order); the reward is their sum.
        flags: ``(K, F)`` booleans, the shared columns first
            (:mod:`pool_env.game.kernels.outcome`), then the game's.
        hits: ``(K, H)`` integers, the shared columns first, then the game's.
    """

    values: NDArray[np.float64]
    flags: NDArray[np.bool_]
    hits: NDArray[np.int64]


@dataclass(frozen=True)
class RulesSection:
    """A game's section of the config (:mod:`pool_env.game.sections`): its name alone here.

    A game with options of its own subclasses it (as the WPA games' ``WpaRules``) and
    names the subclass as its :attr:`Ruleset.section`.

    A bare ``RulesSection(game=name)`` names the game alone: a config takes it as the
    game's own section at its defaults (:func:`pool_env.game.sections.game_section`).
    Every field is frozen when the section is made (:func:`pool_env.game.frozen.freeze`:
    a list or array given is copied), so a subclass that defines its own
    ``__post_init__`` calls this one.

    Attributes:
        game: The game's registered name (``"solitaire"``, ``"nine"``, ...).
    """

    game: str = "solitaire"

    def __post_init__(self) -> None:
        freeze_fields(self)


class Setup(NamedTuple):
    """What :meth:`Ruleset.configure` is given: the parsed sections it may check and read.

    Attributes:
        table: The parsed table.
        scene: The parsed scene.
        rules: The game's rules section, as given (the game checks it).
        rewards: The reward scales by term, checked finite numbers.
        end_on_miss: The task section's ``end_on_miss``.
        players: 1 or 2, the front's.
        action_width: The game's action columns (the tip columns follow on a spin table).
        speeds: What a speed range's top may be on this table with this noise: a game
            checks its own ranges with it (``speeds.check(name, given, high)``).
    """

    table: Table
    scene: ScenePlan
    rules: RulesSection
    rewards: Mapping[str, float]
    end_on_miss: bool
    players: int
    action_width: int
    speeds: SpeedCeiling
