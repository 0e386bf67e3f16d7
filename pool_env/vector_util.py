"""Plumbing of :class:`pool_env.vector.PoolVectorEnv`: arguments, generators and scenes.

Everything here is per batch, never per table in Python on the hot path: the scene's
layouts are drawn by :func:`pool_env.game.kernels.vector.sample_layouts` from constants laid
out exactly as the Python scene code (:mod:`pool_env.scenes`) uses them.
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env import scenes
from pool_env.game.kernels import vector as kv
from pool_env.sim.layouts import break_scene, head_spot
from pool_env.sim.table import Table

#: Exponent read at run time by the kernels (see :mod:`pool_env.game.kernels.vector`).
TWO = np.array([2.0])


@dataclass(frozen=True)
class SceneKernel:
    """A scene's layouts as batched kernel calls, with the constants of the scene code.

    Attributes:
        circles: ``(P, 3)`` capture circles ``(x, y, (radius + clearance)^2)``.
        bounds: ``(x_low, x_high, y_low, y_high)`` allowed for ball centres.
        spot: The head spot, where a potted cue ball goes back.
        reach2: Squared distance a re-spotted ball keeps from the others.
        min_d2: Squared distance between sampled balls.
        n_new: Balls drawn per layout (0: not a sampled scene).
        placed: ``(M, 2)`` fixed balls of a sampled layout (a rack), after the drawn ones.
        box: Where the drawn balls go.
        fixed: The layout of a fixed scene, else ``None``.
    """

    circles: NDArray[np.float64]
    bounds: NDArray[np.float64]
    spot: NDArray[np.float64]
    reach2: float
    min_d2: float
    n_new: int
    placed: NDArray[np.float64]
    box: NDArray[np.float64]
    fixed: NDArray[np.float64] | None

    def lay_out(
        self, tables: NDArray[np.intp], positions: NDArray[np.float64], ptrs: NDArray[np.uintp]
    ) -> None:
        """Draw new layouts for ``tables`` into ``positions`` (``n_new > 0`` scenes)."""
        failed = kv.sample_layouts(
            tables, positions, ptrs, self.n_new, self.placed, self.box, self.circles,
            self.min_d2, TWO, scenes._MAX_TRIES,
        )  # fmt: skip
        if (failed >= 0).any():
            k = int(np.argmax(failed >= 0))
            raise ValueError(
                f"table {int(tables[k])}: cannot lay out the scene: no free place for ball "
                f"{int(failed[k])} after {scenes._MAX_TRIES} random tries"
            )


def scene_kernel(table: Table, scene: scenes.SceneSpec, n_objects: int) -> SceneKernel:
    """The :class:`SceneKernel` of a scene (as parsed by ``scenes.make_sampler``)."""
    r = table.ball_radius
    reach = 2.0 * r + scenes.CLEARANCE
    bounds = np.array([r, table.length - r, r, table.width - r])
    n_new, placed, box, fixed = 0, np.zeros((0, 2)), bounds, None
    if isinstance(scene, str) and scene in ("one_ball", "random"):
        n_new = n_objects + 1  # scenes.sample_uniform over the whole table
    elif isinstance(scene, str):  # a break: the cue ball drawn in the kitchen, off the rack
        rack = break_scene(table, "nine" if scene == "nine_ball" else "eight")
        n_new, placed, box = 1, np.ascontiguousarray(rack[1:]), np.array(scenes.kitchen_box(table))
    elif not callable(scene):
        fixed = np.array(scene, dtype=np.float64)
    return SceneKernel(
        circles=np.array(scenes._capture_circles(table), dtype=np.float64).reshape(-1, 3),
        bounds=bounds,
        spot=head_spot(table),
        reach2=reach * reach,  # as scenes.free_spot
        min_d2=(2.0 * r + scenes.CLEARANCE) ** 2,  # as scenes.sample_uniform
        n_new=n_new,
        placed=placed,
        box=box,
        fixed=fixed,
    )


def generator_addresses(rng: np.random.Generator) -> tuple[int, int, int]:
    """``(state, next_double, next_uint64)`` addresses of a generator's bit generator."""
    c = rng.bit_generator.ctypes
    as_int = ctypes.cast  # function pointers -> their addresses
    return (
        int(c.state_address),
        int(as_int(c.next_double, ctypes.c_void_p).value or 0),
        int(as_int(c.next_uint64, ctypes.c_void_p).value or 0),
    )


def seed_list(seed: int | list[int | None] | None, n: int) -> list[int | None]:
    """One seed per table, as ``SyncVectorEnv.reset``: ``None``, ``seed + i``, or the list."""
    if seed is None:
        return [None] * n
    if isinstance(seed, int | np.integer) and not isinstance(seed, bool):
        return [int(seed) + i for i in range(n)]
    seeds = list(seed)
    if len(seeds) != n:
        raise ValueError(f"seed must be None, an int or {n} seeds (one per table), got {seed!r}")
    return seeds


def check_reset_mask(mask: object, n: int) -> NDArray[np.intp]:
    """The tables of ``options["reset_mask"]``, checked as ``SyncVectorEnv`` checks it."""
    if not isinstance(mask, np.ndarray) or mask.dtype != np.bool_ or mask.shape != (n,):
        raise ValueError(f"options['reset_mask'] must be a ({n},) numpy bool array, got {mask!r}")
    if not mask.any():
        raise ValueError("options['reset_mask'] must select at least one table")
    return np.flatnonzero(mask)


def as_actions(actions: ArrayLike, n: int) -> NDArray[np.floating]:
    """Actions as a ``(n, 2)`` float array (float32 kept: ``PoolEnv`` decodes it as given)."""
    a = actions if isinstance(actions, np.ndarray) else None
    if a is None or a.dtype not in (np.float32, np.float64):
        try:
            a = np.asarray(actions, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"actions must be a ({n}, 2) array of numbers: {exc}") from None
    if a.shape != (n, 2):
        raise ValueError(f"actions must have shape ({n}, 2), got {a.shape}")
    return a


def object_rows(rows: NDArray[Any], tables: NDArray[np.intp], n: int) -> NDArray[np.object_]:
    """An object array holding ``rows[i]`` for each table ``i`` (``None`` elsewhere)."""
    out = np.full(n, None, dtype=object)
    # Assigning a list of arrays would broadcast them into a 2-D block; fromiter keeps each
    # row as one object, without a Python loop.
    out[tables] = np.fromiter(iter(rows[tables]), dtype=object, count=tables.size)
    return out


def option_layouts(
    table: Any, options: dict[str, Any], tables: NDArray[np.intp], n: int, n_envs: int
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Layouts from ``options["positions"]`` (and ``on_table``), checked like ``PoolEnv``'s."""
    unknown = set(options) - {"positions", "on_table"}
    if unknown:
        raise ValueError(
            f"unknown reset options {sorted(unknown)}: use 'positions', 'on_table', 'reset_mask'"
        )
    if "positions" not in options:
        raise ValueError("options['on_table'] needs options['positions']")
    pos = np.array(options["positions"], dtype=np.float64)
    if pos.shape == (n, 2):
        pos = np.broadcast_to(pos, (tables.size, n, 2)).copy()
    elif pos.shape == (n_envs, n, 2):
        pos = pos[tables]
    else:
        raise ValueError(
            f"options['positions'] must have shape ({n}, 2) or ({n_envs}, {n}, 2), got {pos.shape}"
        )
    on = np.ones((tables.size, n), dtype=np.bool_)
    if options.get("on_table") is not None:
        given = np.array(options["on_table"], dtype=bool)
        if given.shape == (n,):
            on[:] = given
        elif given.shape == (n_envs, n):
            on = given[tables]
        else:
            raise ValueError(f"options['on_table'] must have shape ({n},) or ({n_envs}, {n})")
        if not on[:, 0].all():
            raise ValueError("options['on_table'] must keep the cue (0) on the table")
    for k in range(tables.size):
        try:
            scenes.check_layout(table, pos[k][on[k]])
        except ValueError as exc:
            raise ValueError(f"table {int(tables[k])}: {exc}") from None
    return pos, on
