"""Reset of the decision process: new episodes from the scene, or from reset options.

``reset(config, state, tables, options)`` lays out new episodes on ``tables`` (the scene's
layouts, or ``options["positions"]`` / ``on_table`` / the rules' ``options["rules"]``,
checked before anything changes). :mod:`pool_env.game.step` re-exports it beside ``step``
and ``observe``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import check_options
from pool_env.game.config import CUE, GameConfig
from pool_env.game.kernels.layout import sample_layouts
from pool_env.game.ruleset import Turn
from pool_env.game.scenes import check_layout
from pool_env.game.state import GameState
from pool_env.sim.layouts import shuffled_spots


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
    ruleset = config.ruleset
    if ruleset.has_rack and "rules" not in option_names:
        option_names = (*option_names, "rules")
    options = check_options(options)
    keeps_state = ruleset.has_rack  # a game without state between shots starts from none
    given = options.pop("rules", None) if keeps_state else None
    if options:
        positions, on_table = option_layouts(config, options, tables, state.n_tables, option_names)
        if keeps_state:  # checked before the layouts land
            ruleset.start(Turn(config, state, tables), given, False, on_table)
        state.positions[tables], state.on_table[tables] = positions, on_table
    else:
        if keeps_state:
            every_ball = np.ones((1, config.n_balls), dtype=np.bool_)
            ruleset.start(Turn(config, state, tables), given, True, every_ball)
        _lay_out(config, state, tables)
        state.on_table[tables] = True
    state.shots[tables] = 0
    ruleset.settle_layout(Turn(config, state, tables))  # the layouts have landed


def _lay_out(config: GameConfig, state: GameState, tables: NDArray[np.intp]) -> None:
    """The scene's layouts for ``tables``.

    A rack scene's cue ball is drawn first, then (``rack_order="random"``) the rack's order,
    each table from its own generator: the cue ball's spot does not depend on the order, and
    with ``rack_order="fixed"`` the cue ball's are the only draws.
    """
    scene = config.scene
    if scene.fixed is not None:
        state.positions[tables] = scene.fixed
    elif scene.n_new:
        sample_layouts(
            config.params, config.table.pockets, tables, state.positions, state.ptrs,
            scene.placed, scene.box, scene.fallback,
        )  # fmt: skip
        if scene.rack is not None:  # the rack's balls follow the drawn ones (row n_new on)
            for b, rng in zip(tables.tolist(), state.generators_of(tables), strict=True):
                state.positions[b, scene.n_new :] = scene.spots[shuffled_spots(scene.rack, rng)]
    else:  # a callable scene: Python, one table at a time
        generators = state.generators_of(tables)
        for b, rng in zip(tables.tolist(), generators, strict=True):
            layout = scene.spec(config.table, rng)  # type: ignore[operator]
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
