"""The fronts' own arguments: seeds, reset masks, render modes (``ValueError`` naming each).

What the decision process takes (actions, options, the config) is checked in
:mod:`pool_env.game.checks`; what only a Gymnasium front takes is checked here, once for
every front, so that the same bad input gets the same message from each.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import parse_count


def check_seeds(seed: object, n: int) -> list[int | None]:
    """One seed per table, as ``SyncVectorEnv.reset``: ``None``, ``seed + i``, or a list.

    Raises:
        ValueError: Unless ``seed`` is ``None``, a non-negative integer, or ``n`` of them
            (each ``None`` or a non-negative integer).
    """
    if seed is None:
        return [None] * n
    if _is_int(seed):
        return [check_seed(seed) + i for i in range(n)]
    seeds = list(seed) if isinstance(seed, list | tuple | np.ndarray) else None
    if seeds is None or len(seeds) != n:
        raise ValueError(f"seed must be None, an int or {n} seeds (one per table), got {seed!r}")
    return [None if s is None else check_seed(s) for s in seeds]


def _is_int(value: object) -> bool:
    return isinstance(value, int | np.integer) and not isinstance(value, bool | np.bool_)


def check_seed(value: object) -> int:
    """A seed: a non-negative integer (``ValueError`` otherwise)."""
    if not _is_int(value) or int(value) < 0:  # type: ignore[call-overload]
        raise ValueError(f"a seed must be None or a non-negative integer, got {value!r}")
    return int(value)  # type: ignore[call-overload]


def check_reset_mask(mask: object, n: int) -> NDArray[np.intp]:
    """The tables of ``options["reset_mask"]``, checked as ``SyncVectorEnv`` checks it."""
    if not isinstance(mask, np.ndarray) or mask.dtype != np.bool_ or mask.shape != (n,):
        raise ValueError(f"options['reset_mask'] must be a ({n},) numpy bool array, got {mask!r}")
    if not mask.any():
        raise ValueError("options['reset_mask'] must select at least one table")
    return np.flatnonzero(mask)


def check_render(render_mode: object, modes: list[str], width: object) -> int:
    """The render mode (one of ``modes`` or ``None``) and the frame width (>= 64 px)."""
    if render_mode is not None and render_mode not in modes:
        raise ValueError(f"render_mode must be one of {modes} or None, got {render_mode!r}")
    out = parse_count("render_width", width) or 800
    if out < 64:
        raise ValueError(f"render_width must be at least 64 pixels, got {width!r}")
    return out
