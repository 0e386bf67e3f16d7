"""Checks of scalar arguments: real finite numbers, within the simulator's numeric limits.

Shared by :class:`~pool_env.sim.table.Table` and the entry points
(:mod:`pool_env.sim.inputs`); public so that the environment layer can give the same
messages. Each raises a ``ValueError`` that names the argument and, for a limit, the bound.
"""

from __future__ import annotations

import math
import numbers

import numpy as np


def real_number(name: str, value: object) -> float:
    """``value`` as a finite float: a real number (not a bool, string or complex)."""
    if type(value) is float and math.isfinite(value):  # the common case, fast
        return value
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    out = float(value)
    if not math.isfinite(out):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return out


def within(name: str, value: object, low: float, high: float, unit: str) -> float:
    """A real number in ``[low, high]`` (the simulator's limits for ``name``)."""
    out = real_number(name, value)
    if not low <= out <= high:
        raise ValueError(
            f"{name} must lie in [{low:g}, {high:g}] {unit} (the simulator's numeric limits, "
            f"see README 'Numeric limits'), got {out!r}"
        )
    return out


def positive(name: str, value: object) -> float:
    """A positive finite real number."""
    out = real_number(name, value)
    if out <= 0.0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return out
