"""One step of the decision process over B tables: the single source of truth.

``step(config, state, tables, actions)`` plays one shot on each of ``tables``:

1. place each cue ball in hand and decode each action into a shot with execution noise
   (the game's ruleset: :meth:`~pool_env.game.ruleset.Ruleset.shoot`), what these change
   saved first (:meth:`~pool_env.game.state.GameState.hold`) and put back if the step
   fails before 3;
2. simulate the shots to rest (:mod:`pool_env.sim`: one table through its single-shot
   entry, whose fixed cost is a third of the batch call's; several through the batch);
3. apply the outcomes by the rules (:meth:`~pool_env.game.ruleset.Ruleset.judge`): balls
   that dropped, re-spotting, rewards and their terms, episode ends.

One path for every game: where games differ, ``config.ruleset`` (:mod:`.ruleset`) decides.

``reset(config, state, tables, options)`` (from :mod:`.reset`) lays out new episodes and
``observe`` encodes observations. :class:`pool_env.PoolEnv` is these with B = 1,
:class:`pool_env.PoolVectorEnv` with B = N; neither holds game logic.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.game.config import GameConfig
from pool_env.game.kernels.outcome import (
    CLEARED,
    FIRST_BALL,
    POTTED_BITS,
    REWARD,
    SCRATCH,
    TERMINATED,
    TRUNCATED,
)
from pool_env.game.reset import option_layouts, reset
from pool_env.game.ruleset import Judged, Outcome, Ruleset, Turn
from pool_env.game.shot_features import shot_feature_batch
from pool_env.game.state import GameState
from pool_env.sim.batch import PARALLEL_FROM, available_cpus, run_batch_arrays
from pool_env.sim.simulate import simulate_checked_arrays
from pool_env.sim.table import Table

__all__ = ["StepResult", "observe", "option_layouts", "reset", "step"]

#: The first contact of a shot that touched no ball: ``(-1, -1)``.
_NO_CONTACT = (-1, -1)


class StepResult:
    """What one step did; row ``k`` of each array is table ``tables[k]``.

    The rules' results are kept as the few arrays the kernels returned (one array costs
    about a microsecond to hand over); the named columns are views into them.

    Attributes:
        tables: ``(K,)`` the tables that shot.
        values: ``(K, 1 + T)`` float64: the reward, then the game's ``T`` reward terms,
            scaled (:attr:`~pool_env.game.ruleset.Ruleset.reward_terms`).
        flags: ``(K, F)`` booleans, the shared columns of
            :mod:`pool_env.game.kernels.outcome` first, then the game's.
        hits: ``(K, H)`` integers: potted bits and the first ball hit, then the game's (the
            WPA games: the foul, the ball on, ...).
        shots: ``(K, 2)`` the executed ``(angle, speed)``; ``(K, 4)`` on a spin table:
            and the executed tip ``(a, b)``.
        pocketed: ``(K, M)`` the simulator's pocket per ball (-1: none), columns ``balls``.
        balls: ``(M,)`` ball number of each column of the simulator's results.
        shot: The :class:`~pool_env.ShotResult` of a one-table step (its rows are
            ``balls``), else ``None``.
        ruleset: The game's ruleset (it reads its own ``info`` columns).
    """

    __slots__ = ("_capped", "_n_events", "balls", "flags", "hits", "pocketed", "rewards",
                 "ruleset", "shot", "shots", "tables", "values")  # fmt: skip

    def __init__(
        self,
        tables: NDArray[np.intp],
        judged: Judged,
        shots: NDArray[np.float64],
        outcome: Outcome,
        ruleset: Ruleset,
    ) -> None:
        self.tables, self.shots = tables, shots
        self.values, self.flags, self.hits = judged
        self.rewards = judged.values[:, REWARD]  # (K,) the sum of each row's terms
        self.ruleset = ruleset
        self.pocketed, self.balls, self.shot = outcome.pocketed, outcome.balls, outcome.shot
        self._n_events, self._capped = outcome.n_events, outcome.capped

    @property
    def terminated(self) -> NDArray[np.bool_]:
        """``(K,)`` the episode ended by the rules."""
        return self.flags[:, TERMINATED]

    @property
    def truncated(self) -> NDArray[np.bool_]:
        """``(K,)`` the episode reached its shot limit."""
        return self.flags[:, TRUNCATED]

    @property
    def cleared(self) -> NDArray[np.bool_]:
        """``(K,)`` the table is cleared (``info["is_success"]``)."""
        return self.flags[:, CLEARED]

    @property
    def scratch(self) -> NDArray[np.bool_]:
        """``(K,)`` the cue ball dropped."""
        return self.flags[:, SCRATCH]

    @property
    def potted_bits(self) -> NDArray[np.int64]:
        """``(K,)`` bit ``j - 1`` set for each object ball ``j`` potted."""
        return self.hits[:, POTTED_BITS]

    @property
    def first_contact(self) -> NDArray[np.int64]:
        """``(K,)`` the first ball the cue ball hit, -1 for none."""
        return self.hits[:, FIRST_BALL]

    @property
    def angle(self) -> NDArray[np.float64]:
        """``(K,)`` executed directions (radians from +x)."""
        return self.shots[:, 0]

    @property
    def speed(self) -> NDArray[np.float64]:
        """``(K,)`` executed speeds (m/s)."""
        return self.shots[:, 1]

    @property
    def n_events(self) -> NDArray[np.int64]:
        """``(K,)`` simulator events."""
        if self._n_events is None:
            self._n_events = np.array([self.shot.n_events], dtype=np.int64)  # type: ignore[union-attr]
        return self._n_events

    @property
    def hit_event_cap(self) -> NDArray[np.bool_]:
        """``(K,)`` a shot reached the simulator's event cap."""
        if self._capped is None:
            self._capped = np.array([self.shot.hit_event_cap])  # type: ignore[union-attr]
        return self._capped


def step(
    config: GameConfig,
    state: GameState,
    tables: NDArray[np.intp],
    actions: NDArray[np.float64],
    record: bool = False,
    parallel: bool | None = None,
) -> StepResult:
    """Play one shot on each of ``tables`` and apply the outcomes to ``state``.

    Transactional: until the rules apply the outcomes nothing is kept. The game's
    :meth:`~pool_env.game.ruleset.Ruleset.shoot` may move only the cue balls (placing a
    ball in hand, which only a game with a rack state has) and draw the noise; when it
    or the simulator raises (a shot the simulator refuses),
    :meth:`~pool_env.game.state.GameState.undo` puts both back on every table, and the
    error propagates with the state as it was. The judge must not fail.

    Args:
        config: The fixed model.
        state: The tables, updated in place (unchanged when this raises).
        tables: ``(K,)`` distinct tables that shoot.
        actions: ``(K, config.action_size)`` checked actions
            (:func:`pool_env.game.checks.check_actions`).
        record: Keep the trajectories of a one-table step (for rendering).
        parallel: Split a batch over the CPUs (``None``: from ``PARALLEL_FROM`` shots).

    Returns:
        The :class:`StepResult`.
    """
    ruleset = config.ruleset
    turn = Turn(config, state, tables)
    # Before the simulation, a step changes the generators (noise drawn) and the cue
    # balls in hand (placed), which a game keeps in its rack state; without either there
    # is nothing to save, and a cheap step pays nothing.
    saves = config.noise is not None or ruleset.rack_width > 0
    held = state.hold(tables) if saves else None
    try:
        executed = ruleset.shoot(turn, actions)
        velocities, spins = split_states(executed.states)
        out = _simulate(config.table, state, tables, velocities, spins, record, parallel)
    except BaseException:
        # A shot the simulator refuses (or an interrupt) changes nothing: the cue balls
        # placed in hand and the noise drawn are put back, on every table of the batch.
        if saves:
            state.undo(tables, held)
        raise
    judged = ruleset.judge(turn, out, executed)
    return StepResult(tables, judged, executed.shots, out, ruleset)


def split_states(
    states: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Initial velocities ``(K, N, 2)`` and, on a spin table, angular velocities ``(K, N, 3)``.

    The kernels hand back one array (``(K, N, 5)`` on a spin table): a roll step thus
    costs what it did.
    """
    if states.shape[2] == 2:
        return states, None
    return np.ascontiguousarray(states[:, :, :2]), np.ascontiguousarray(states[:, :, 2:])


def _simulate(
    table: Table,
    state: GameState,
    tables: NDArray[np.intp],
    vel: NDArray[np.float64],
    spins: NDArray[np.float64] | None,
    record: bool,
    parallel: bool | None,
) -> Outcome:
    """The shots to rest: ``simulate`` for one table (the balls on it), else the batch.

    ``spins`` are the ``(K, N, 3)`` angular velocities of a spin table (``None`` on a roll
    table, which takes none). The simulator never writes its inputs, so the state's
    arrays are passed as they are; one table goes through
    :func:`~pool_env.sim.simulate.simulate_checked_arrays` (the state holds the kernel's
    arrays already; the scene is still validated in the compiled call).
    """
    n_shots, n_balls = vel.shape[:2]
    spin = spins
    if n_shots == 1:
        b = tables[0]
        pos, on = state.positions[b], state.on_table[b]
        balls = on.nonzero()[0]
        if balls.shape[0] == n_balls:
            ang = None if spin is None else spin[0]
            shot = simulate_checked_arrays(table, pos, vel[0], ang, record)
        else:
            ang = None if spin is None else spin[0, balls]
            shot = simulate_checked_arrays(table, pos[balls], vel[0, balls], ang, record)
        contact = shot.first_contact
        # A fresh writable array either way: a read-only one for the misses gave the rules'
        # kernels a second signature, compiled on a process's first miss.
        first = np.array([_NO_CONTACT if contact is None else contact], dtype=np.int64)
        final, pocketed = shot.positions, shot.pocketed
        return Outcome(
            final[None], pocketed[None], first, shot.cushions_after_contact[None],
            shot.pocket_order[None], None, None, balls, shot, vel, spins,
            shot.second_hit[None], shot.cushions_at_second[None],
        )  # fmt: skip
    every = n_shots == state.n_tables
    pos = state.positions if every else state.positions[tables]
    on = state.on_table if every else state.on_table[tables]
    if parallel is None:
        parallel = n_shots >= PARALLEL_FROM
    threads = available_cpus() if parallel else 1
    result = run_batch_arrays(table, pos, vel, spin, on, threads)  # the state's arrays as they are
    return Outcome(
        result.positions, result.pocketed, result.first_contact,
        result.cushions_after_contact, result.pocket_order, result.n_events,
        result.hit_event_cap, np.arange(n_balls), None, vel, spins, result.second_hit,
        result.cushions_at_second,
    )  # fmt: skip


def observe(
    config: GameConfig, state: GameState, viewers: NDArray[np.int64] | None = None
) -> NDArray[np.float32]:
    """``(B, obs)`` observations of every table (see :class:`pool_env.PoolEnv`).

    The ruleset's :meth:`~pool_env.game.ruleset.Ruleset.observe`. Under the WPA
    rules, ``viewers`` (``(B,)``, default: each table's shooter) says whose perspective
    the rule features take (the two-player front observes for each agent). With
    ``observation="shots"`` the ghost-ball shot features follow
    (:mod:`pool_env.game.shot_features`), on each viewer's reference ball.
    """
    ruleset = config.ruleset
    obs = ruleset.observe(config, state, viewers)
    if config.task.observation != "shots":
        return obs
    refer = ruleset.aim_references(state, viewers)
    shots = shot_feature_batch(
        config.table, config.params, config.aim_range, config.speed_range, state.positions,
        state.on_table, refer,
    )  # fmt: skip
    return np.concatenate([obs, shots], axis=1)
