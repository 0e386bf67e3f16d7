"""The game's own step on copies of one position: what a planner with the true model sees.

:class:`GameModel` holds a batch of tables of an env's config (:class:`pool_env.GameConfig`)
and plays candidate actions from one position on them through :func:`pool_env.game.step.step`,
the function every front steps with: the same decoding, execution noise, simulation and
rules. Each table draws its execution noise from its own generator; :meth:`GameModel.play`
gives the ``m``-th sample of every candidate the same noise (common random numbers), so
that candidates are compared on the same errors and their differences are not the noise's.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.game.config import GameConfig
from pool_env.game.games.wpa.rack_state import IN_HAND
from pool_env.game.state import GameState
from pool_env.game.step import StepResult, step


class GameModel:
    """A batch of model tables of ``config``, grown on demand.

    Args:
        config: The env's config (its rules, table and execution noise).
        seed: Seed of the noise samples.
    """

    def __init__(self, config: GameConfig, seed: int = 0) -> None:
        if not config.ruleset.has_rack:
            raise ValueError("GameModel plays the rules' game ids (game='nine' or 'eight')")
        self.config = config
        self.rng = np.random.default_rng(seed)
        self.state: GameState = config.new_state(0)

    def _reserve(self, tables: int) -> None:
        """At least ``tables`` tables, each with its own generator."""
        have = self.state.n_tables
        if tables <= have:
            return
        grown = self.config.new_state(tables)
        for b in range(tables):
            grown.use_generator(b, np.random.Generator(np.random.PCG64(b)))
        self.state = grown

    def play(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        rack: NDArray[np.int64],
        actions: NDArray[np.float64],
        samples: int,
        parallel: bool | None = False,
    ) -> tuple[StepResult, NDArray[np.float64], NDArray[np.bool_]]:
        """Play each of ``C`` actions ``samples`` times from one position.

        Args:
            positions: ``(N, 2)`` ball centres (the cue ball where it will be struck).
            on_table: ``(N,)`` which balls are on the table.
            rack: ``(N_RACK,)`` the rack state to shoot from (no ball in hand: the cue
                ball is placed already).
            actions: ``(C, A)`` env actions (the config's width).
            samples: Plays of each action; sample ``m`` of every action draws the same
                execution noise.
            parallel: Split the batch over the CPUs (``None``: the step's own threshold).

        Returns:
            ``(result, positions, on_table)``: the step's :class:`StepResult` over the
            ``C * samples`` tables (action ``c``'s samples are rows ``c * samples ..``), and
            copies of the tables' positions ``(C * samples, N, 2)`` and flags after it.

        Raises:
            ValueError: On a rack state with ball in hand or actions of the wrong width.
        """
        acts = np.asarray(actions, dtype=np.float64)
        c = acts.shape[0] if acts.ndim == 2 else 0
        return self.play_layouts(
            np.broadcast_to(positions, (c, *np.shape(positions))),
            np.broadcast_to(on_table, (c, *np.shape(on_table))),
            np.broadcast_to(rack, (c, *np.shape(rack))),
            acts, samples, parallel,
        )  # fmt: skip

    def play_layouts(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        racks: NDArray[np.int64],
        actions: NDArray[np.float64],
        samples: int,
        parallel: bool | None = None,
        common_noise: bool = True,
    ) -> tuple[StepResult, NDArray[np.float64], NDArray[np.bool_]]:
        """Play ``C`` actions, each from its own position, ``samples`` times each.

        Args:
            positions: ``(C, N, 2)`` each action's ball centres (the cue ball placed).
            on_table: ``(C, N)`` which balls are on the table.
            racks: ``(C, N_RACK)`` the rack states to shoot from (no ball in hand).
            actions: ``(C, A)`` env actions (the config's width).
            samples: Plays of each action; sample ``m`` of every action draws the same
                execution noise.
            parallel: Split the batch over the CPUs (``None``: the step's own threshold).
            common_noise: Give sample ``m`` of every action the same noise. Without it each
                table's generator goes on with its own stream (still seeded, and cheaper:
                setting thousands of generator states costs more than a batch of shots).

        Returns:
            As :meth:`play`.

        Raises:
            ValueError: On shapes that do not fit, a rack state with ball in hand or
                actions of the wrong width.
        """
        return self.play_racks(
            positions, on_table, racks, actions, samples, parallel, common_noise
        )[:3]

    def play_racks(
        self,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        racks: NDArray[np.int64],
        actions: NDArray[np.float64],
        samples: int,
        parallel: bool | None = None,
        common_noise: bool = True,
    ) -> tuple[StepResult, NDArray[np.float64], NDArray[np.bool_], NDArray[np.int64]]:
        """:meth:`play_layouts`, with a copy of the rack rows after the step too.

        The rows say what the rules made of each outcome beyond the balls: who shoots
        next, ball in hand, the fouls and 8-ball's groups (a shot on an open table decides
        them), from which the next shooter's legal balls are read
        (:meth:`pool_env.game.ruleset.Ruleset.legal_first_balls`).

        Returns:
            ``(result, positions, on_table, racks)``: as :meth:`play`, and ``(C * samples,
            N_RACK)`` rack rows after the step.

        Raises:
            ValueError: As :meth:`play_layouts`.
        """
        acts = np.asarray(actions, dtype=np.float64)
        if acts.ndim != 2 or acts.shape[1] != self.config.action_size:
            raise ValueError(f"actions must be (C, {self.config.action_size}), got {acts.shape}")
        c, n_balls = acts.shape[0], self.config.n_balls
        if np.shape(positions) != (c, n_balls, 2) or np.shape(on_table) != (c, n_balls):
            raise ValueError(
                f"positions must be ({c}, {n_balls}, 2) and on_table ({c}, {n_balls}), got "
                f"{np.shape(positions)} and {np.shape(on_table)}"
            )
        if np.asarray(racks)[:, IN_HAND].any():
            raise ValueError("place the cue ball first: the model plays from a placed cue ball")
        if samples < 1:
            raise ValueError(f"samples must be >= 1, got {samples}")
        n = c * samples
        self._reserve(n)
        state = self.state
        tables = np.arange(n)
        state.positions[:n] = np.repeat(positions, samples, axis=0)
        state.on_table[:n] = np.repeat(on_table, samples, axis=0)
        state.rack[:n] = np.repeat(racks, samples, axis=0)
        state.shots[:n] = 0
        if common_noise:
            noise = [np.random.PCG64(s).state for s in self.rng.integers(2**63, size=samples)]
            for b in range(n):
                state.generators[b].bit_generator.state = noise[b % samples]  # type: ignore[union-attr]
        result = step(
            self.config, state, tables, np.repeat(acts, samples, axis=0), parallel=parallel
        )
        after = state.positions[:n].copy(), state.on_table[:n].copy(), state.rack[:n].copy()
        return result, *after
