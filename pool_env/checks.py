"""Checks of environment arguments: each error is a ``ValueError`` that names the argument."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from pool_env.sim.table import Table


def parse_table(table: Table | dict[str, Any] | None) -> Table:
    """A :class:`Table`, the ``Table(**dict)`` of a dict (a config file), or the default."""
    if table is None:
        return Table()
    if isinstance(table, Table):
        return table
    if isinstance(table, dict):
        try:
            return Table(**table)
        except TypeError as exc:
            raise ValueError(f"table: {exc}") from None
    raise ValueError(
        f"table must be a pool_env.Table, a dict of Table arguments or None, got {table!r}"
    )


def parse_float(name: str, value: object) -> float:
    """A finite number."""
    try:
        out = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return out


def parse_range(name: str, value: object, minimum: float | None) -> tuple[float, float]:
    """A pair ``(low, high)`` of finite numbers with ``low <= high`` (and ``low >= minimum``)."""
    try:
        low, high = (parse_float(name, v) for v in value)  # type: ignore[union-attr]
    except (TypeError, ValueError) as exc:
        raise ValueError(
            f"{name} must be a pair (low, high) of finite numbers, got {value!r}"
        ) from exc
    if not low <= high or (minimum is not None and low < minimum):
        floor = "" if minimum is None else f" and low >= {minimum}"
        raise ValueError(f"{name} must have low <= high{floor}, got {value!r}")
    return low, high


def parse_noise(value: object) -> tuple[float, float] | None:
    """Noise sigmas ``(angle, speed)``, both >= 0; ``None`` when off (or both 0)."""
    if value is None:
        return None
    try:
        angle, speed = (parse_float("noise", v) for v in value)  # type: ignore[union-attr]
    except (TypeError, ValueError) as exc:
        raise ValueError(f"noise must be a pair (sigma_angle, sigma_speed), got {value!r}") from exc
    if angle < 0.0 or speed < 0.0:
        raise ValueError(f"noise sigmas must be >= 0, got {value!r}")
    return None if angle == speed == 0.0 else (angle, speed)


def parse_bool(name: str, value: object) -> bool:
    """A real boolean (not a truthy string)."""
    if not isinstance(value, bool | np.bool_):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


def parse_count(name: str, value: object) -> int | None:
    """A positive integer, or ``None``."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise ValueError(f"{name} must be a positive integer or None, got {value!r}")
    return int(value)
