"""One step of the decision process over B tables: the single source of truth.

``step(config, state, tables, actions)`` plays one shot on each of ``tables``:

1. decode each action into a shot and add execution noise (:mod:`.kernels.actions`);
2. simulate the shots to rest (:mod:`pool_env.sim`: one table through its single-shot
   entry, whose fixed cost is a third of the batch call's; several through the batch);
3. apply the outcomes by the rules (:func:`pool_env.game.rules.judge`): balls that
   dropped, re-spotting, rewards, episode ends.

``reset(config, state, tables, options)`` lays out new episodes and ``observe`` encodes
observations. :class:`pool_env.PoolEnv` is these with B = 1, :class:`pool_env.PoolVectorEnv`
with B = N; neither holds game logic.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import check_options
from pool_env.game.config import CUE, GameConfig
from pool_env.game.contact import read_first
from pool_env.game.kernels import params as kp
from pool_env.game.kernels import wpa
from pool_env.game.kernels.actions import executed_rule_shots, executed_shots, place_in_hand
from pool_env.game.kernels.layout import sample_layouts
from pool_env.game.kernels.observe import encode_observations, encode_rule_observations
from pool_env.game.rack import check_rack, rack_option
from pool_env.game.rules import (
    CLEARED,
    FIRST_BALL,
    POTTED_BITS,
    RESPOT,
    RESPOT_TAKEN,
    SCRATCH,
    SPOT_TAKEN,
    TERMINATED,
    TRUNCATED,
    judge,
    judge_rules,
)
from pool_env.game.scenes import check_layout, free_spot
from pool_env.game.state import GameState
from pool_env.sim.batch import (
    PARALLEL_FROM,
    available_cpus,
    simulate_batch,
    simulate_batch_threads,
)
from pool_env.sim.result import ShotResult
from pool_env.sim.simulate import simulate
from pool_env.sim.table import Table

_NO_CONTACT = np.full((1, 2), -1, dtype=np.int64)
_NO_CONTACT.setflags(write=False)


class StepResult:
    """What one step did; row ``k`` of each array is table ``tables[k]``.

    The rules' results are kept as the few arrays the kernels returned (one array costs
    about a microsecond to hand over); the named columns are views into them.

    Attributes:
        tables: ``(K,)`` the tables that shot.
        rewards: ``(K,)`` float64.
        flags: ``(K, 5)`` booleans, columns named in :mod:`pool_env.game.rules`.
        hits: ``(K, 2)`` integers: potted bits and the first ball hit.
        shots: ``(K, 2)`` the executed ``(angle, speed)``; ``(K, 4)`` on a spin table:
            and the executed tip ``(a, b)``.
        pocketed: ``(K, M)`` the simulator's pocket per ball (-1: none), columns ``balls``.
        balls: ``(M,)`` ball number of each column of the simulator's results.
        shot: The :class:`~pool_env.ShotResult` of a one-table step (its rows are
            ``balls``), else ``None``.
    """

    __slots__ = ("_capped", "_n_events", "balls", "flags", "hits", "pocketed", "rewards", "shot",
                 "shots", "tables")  # fmt: skip

    def __init__(
        self,
        tables: NDArray[np.intp],
        rewards: NDArray[np.float64],
        flags: NDArray[np.bool_],
        hits: NDArray[np.int64],
        shots: NDArray[np.float64],
        outcome: _Outcome,
    ) -> None:
        self.tables, self.rewards, self.flags, self.hits, self.shots = (
            tables, rewards, flags, hits, shots
        )  # fmt: skip
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


class _Outcome(NamedTuple):
    final: NDArray[np.float64]
    pocketed: NDArray[np.int64]
    first: NDArray[np.int64]
    cushions: NDArray[np.int64]
    order: NDArray[np.int64]
    n_events: NDArray[np.int64] | None  # None: read from shot
    capped: NDArray[np.bool_] | None
    balls: NDArray[np.intp]
    shot: ShotResult | None


def step(
    config: GameConfig,
    state: GameState,
    tables: NDArray[np.intp],
    actions: NDArray[np.float64],
    record: bool = False,
    parallel: bool | None = None,
) -> StepResult:
    """Play one shot on each of ``tables`` and apply the outcomes to ``state``.

    Args:
        config: The fixed model.
        state: The tables, updated in place.
        tables: ``(K,)`` distinct tables that shoot.
        actions: ``(K, 2)`` checked actions (:func:`pool_env.game.checks.check_actions`).
        record: Keep the trajectories of a one-table step (for rendering).
        parallel: Split a batch over the CPUs (``None``: from ``PARALLEL_FROM`` shots).

    Returns:
        The :class:`StepResult`.
    """
    table = config.table
    if config.rules:
        return _step_rules(config, state, tables, actions, record, parallel)
    shots, states = executed_shots(
        config.params, actions, tables, state.positions, state.on_table, state.ptrs
    )
    velocities, spins = split_states(states)
    out = _simulate(table, state, tables, velocities, spins, record, parallel)
    rewards, flags, hits = judge(
        config.params, table.pockets, tables, out.balls, state.positions, state.on_table,
        state.shots, out.final, out.pocketed, out.first,
    )  # fmt: skip
    if flags[:, SPOT_TAKEN].any():  # rare: something covers the head spot
        for k in np.flatnonzero(flags[:, SPOT_TAKEN]).tolist():
            _place(config, state, int(tables[k]), CUE, None)
    return StepResult(tables, rewards, flags, hits, shots, out)


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


def _place(
    config: GameConfig,
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
        config.table, state.positions[b], occupied, target, behind_head_string=behind
    )


def place_cue_balls(
    config: GameConfig, state: GameState, tables: NDArray[np.intp], actions: NDArray[np.float64]
) -> None:
    """Under rules: put each cue ball in hand where its action asks, or the nearest free point.

    The first part of a rules step, and of :func:`pool_env.game.codec.decode_action`.
    """
    rack = state.rack
    unplaced = place_in_hand(
        config.params, config.table.pockets, actions, tables, state.positions, state.on_table,
        rack,
    )  # fmt: skip
    if unplaced.any():  # the requested point is covered: the nearest free one
        for k in np.flatnonzero(unplaced).tolist():
            b = int(tables[k])
            target = state.positions[b, CUE].copy()
            _place(config, state, b, CUE, target, bool(rack[b, wpa.BEHIND]))


def _step_rules(
    config: GameConfig,
    state: GameState,
    tables: NDArray[np.intp],
    actions: NDArray[np.float64],
    record: bool,
    parallel: bool | None,
) -> StepResult:
    """:func:`step` under the 9-ball or 8-ball rules (``Box(5)`` actions, spin ``Box(7)``)."""
    table, params, rack = config.table, config.params, state.rack
    place_cue_balls(config, state, tables, actions)
    shots, states, called = executed_rule_shots(
        params, table.pockets, actions, tables, state.positions, state.on_table, state.ptrs,
        rack,
    )  # fmt: skip
    velocities, spins = split_states(states)
    out = _simulate(table, state, tables, velocities, spins, record, parallel)
    crossed = read_first(
        table, params, int(params[kp.GAME]), state.positions, state.on_table, rack, tables,
        out.balls, velocities, spins, out.first, out.shot,
    )  # fmt: skip
    rewards, flags, hits = judge_rules(
        params, table.pockets, tables, out.balls, state.positions, state.on_table,
        state.shots, rack, out.final, out.pocketed, out.first, out.cushions, out.order, called,
        crossed,
    )  # fmt: skip
    if flags[:, RESPOT_TAKEN].any():  # something covers the foot spot
        foot = params[[kp.FOOT_X, kp.FOOT_Y]].copy()
        for k in np.flatnonzero(flags[:, RESPOT_TAKEN]).tolist():
            _place(config, state, int(tables[k]), int(hits[k, RESPOT]), foot)
    if flags[:, SPOT_TAKEN].any():
        for k in np.flatnonzero(flags[:, SPOT_TAKEN]).tolist():
            _place(config, state, int(tables[k]), CUE, None)
    return StepResult(tables, rewards, flags, hits, shots, out)


def _simulate(
    table: Table,
    state: GameState,
    tables: NDArray[np.intp],
    vel: NDArray[np.float64],
    spins: NDArray[np.float64] | None,
    record: bool,
    parallel: bool | None,
) -> _Outcome:
    """The shots to rest: ``simulate`` for one table (the balls on it), else the batch.

    ``spins`` are the ``(K, N, 3)`` angular velocities of a spin table (``None`` on a roll
    table, which takes none). The simulator copies what it is given, so the state's
    arrays are passed as they are.
    """
    n_shots, n_balls = vel.shape[:2]
    spin = spins
    if n_shots == 1:
        b = tables[0]
        pos, on = state.positions[b], state.on_table[b]
        balls = on.nonzero()[0]
        if balls.shape[0] == n_balls:
            ang = None if spin is None else spin[0]
            shot = simulate(table, pos, vel[0], record=record, angular_velocities=ang)
        else:
            ang = None if spin is None else spin[0, balls]
            shot = simulate(table, pos[balls], vel[0, balls], record=record, angular_velocities=ang)
        contact = shot.first_contact
        first = _NO_CONTACT if contact is None else np.array([contact], dtype=np.int64)
        final, pocketed = shot.positions, shot.pocketed
        return _Outcome(
            final[None], pocketed[None], first, shot.cushions_after_contact[None],
            shot.pocket_order[None], None, None, balls, shot,
        )  # fmt: skip
    every = n_shots == state.n_tables
    pos = state.positions if every else state.positions[tables]
    on = state.on_table if every else state.on_table[tables]
    if parallel is None:
        parallel = n_shots >= PARALLEL_FROM
    threads = available_cpus() if parallel else 1
    if threads > 1:
        result = simulate_batch_threads(table, pos, vel, on, threads, angular_velocities=spin)
    else:
        result = simulate_batch(table, pos, vel, active=on, parallel=False, angular_velocities=spin)
    return _Outcome(
        result.positions, result.pocketed, result.first_contact,
        result.cushions_after_contact, result.pocket_order, result.n_events,
        result.hit_event_cap, np.arange(n_balls), None,
    )  # fmt: skip


def reset(
    config: GameConfig,
    state: GameState,
    tables: NDArray[np.intp],
    options: dict[str, Any] | None = None,
    option_names: tuple[str, ...] = ("positions", "on_table"),
) -> None:
    """Start new episodes on ``tables``: layouts from the scene, or from ``options``.

    Args:
        config: The fixed model.
        state: The tables (their generators must be set), updated in place.
        tables: ``(K,)`` distinct tables to reset.
        options: ``positions`` (``(N, 2)`` for every table, or ``(B, N, 2)``) and an
            optional ``on_table`` (``(N,)`` or ``(B, N)``); checked before anything changes.
        option_names: The option names the caller accepts (for the error message).

    Raises:
        ValueError: On bad options, naming them; the state is then unchanged.
    """
    if config.rules and "rules" not in option_names:
        option_names = (*option_names, "rules")
    options = check_options(options)
    rack = None
    if config.rules:
        rack = rack_option(config, options.pop("rules", None), rack_scene=not options)
    if options:
        positions, on_table = option_layouts(config, options, tables, state.n_tables, option_names)
        if rack is not None:
            check_rack(config, rack, on_table)
        state.positions[tables], state.on_table[tables] = positions, on_table
    else:
        if rack is not None:
            check_rack(config, rack, np.ones((1, config.n_balls), dtype=np.bool_))
        _lay_out(config, state, tables)
        state.on_table[tables] = True
    state.shots[tables] = 0
    if rack is not None:
        state.rack[tables] = rack


def _lay_out(config: GameConfig, state: GameState, tables: NDArray[np.intp]) -> None:
    """The scene's layouts for ``tables``."""
    scene = config.scene
    if scene.fixed is not None:
        state.positions[tables] = scene.fixed
    elif scene.n_new:
        sample_layouts(
            config.params, config.table.pockets, tables, state.positions, state.ptrs,
            scene.placed, scene.box, scene.fallback,
        )  # fmt: skip
    else:  # a callable scene: Python, one table at a time
        generators = state.ensure_generators()
        for b in tables.tolist():
            layout = scene.spec(config.table, generators[b])  # type: ignore[operator]
            state.positions[b] = check_layout(config.table, layout, config.n_balls)


def option_layouts(
    config: GameConfig,
    options: dict[str, Any],
    tables: NDArray[np.intp],
    n_envs: int,
    option_names: tuple[str, ...] = ("positions", "on_table"),
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Layouts from ``options["positions"]`` (and ``on_table``), checked.

    Returns:
        ``(K, N, 2)`` positions and ``(K, N)`` on-table flags for ``tables``.

    Raises:
        ValueError: Naming the bad option (and the table, for a batch).
    """
    unknown = set(options) - set(option_names)
    if unknown:
        names = ", ".join(repr(name) for name in option_names)
        raise ValueError(f"unknown reset options {sorted(unknown)}: use {names}")
    if "positions" not in options:
        raise ValueError("options['on_table'] needs options['positions']")
    n = config.n_balls
    shapes = f"({n}, 2)" if n_envs == 1 else f"({n}, 2) or ({n_envs}, {n}, 2)"
    try:
        pos = np.array(options["positions"], dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"options['positions'] must be numbers of shape {shapes}: {exc}") from None
    if pos.shape == (n, 2):
        pos = np.broadcast_to(pos, (tables.size, n, 2)).copy()
    elif pos.shape == (n_envs, n, 2) and n_envs > 1:
        pos = pos[tables]
    else:
        raise ValueError(f"options['positions'] must have shape {shapes}, got {pos.shape}")
    on = np.ones((tables.size, n), dtype=np.bool_)
    if options.get("on_table") is not None:
        given = np.array(options["on_table"])
        flags = f"({n},)" if n_envs == 1 else f"({n},) or ({n_envs}, {n})"
        if given.dtype.kind not in "biu":
            raise ValueError(f"options['on_table'] must be {flags} booleans, got {given!r}")
        given = given.astype(np.bool_)
        if given.shape == (n,):
            on[:] = given
        elif given.shape == (n_envs, n) and n_envs > 1:
            on = given[tables]
        else:
            raise ValueError(f"options['on_table'] must have shape {flags}, got {given.shape}")
        if not on[:, CUE].all():
            raise ValueError("options['on_table'] must keep the cue (0) on the table")
        if not on[:, 1:].any(axis=1).all():
            raise ValueError("options['on_table'] leaves no object ball on the table")
    # Every row must be finite, a ball off the table included: its row is kept as where it
    # was captured (``positions`` reads it back), so NaN would reach the caller.
    bad = ~np.isfinite(pos).all(axis=2)
    if bad.any():
        k, ball = (int(v) for v in np.argwhere(bad)[0])
        where = "" if n_envs == 1 else f"table {int(tables[k])}: "
        raise ValueError(
            f"{where}options['positions'] row {ball} is not finite ({pos[k, ball].tolist()}): "
            "every row needs a finite point, a ball off the table included (any point will do)"
        )
    for k in range(tables.size):
        try:
            check_layout(config.table, pos[k][on[k]])
        except ValueError as exc:
            where = "" if n_envs == 1 else f"table {int(tables[k])}: "
            raise ValueError(f"{where}options['positions']: {exc}") from None
    return pos, on


def observe(
    config: GameConfig, state: GameState, viewers: NDArray[np.int64] | None = None
) -> NDArray[np.float32]:
    """``(B, obs)`` observations of every table (see :class:`pool_env.PoolEnv`).

    Under rules, ``viewers`` (``(B,)``, default: each table's shooter) says whose
    perspective the rule features take (the two-player front observes for each agent).
    """
    if config.rules:
        if viewers is None:
            viewers = state.rack[:, wpa.SHOOTER]
        return encode_rule_observations(
            config.params, state.positions, state.on_table, state.rack, viewers,
            config.table.length, config.table.width,
        )  # fmt: skip
    return encode_observations(
        state.positions, state.on_table, config.table.length, config.table.width
    )
