"""The step ``info``: its keys defined once, as one dict (one table) or Gymnasium's batch.

Gymnasium's vector environments gather the per-table ``info`` dicts into one dict: an array
over the tables per key, with a boolean mask ``"_key"`` of the tables that gave the key,
and the array type set by the value (``bool``, ``int64``, ``float64``, or ``object`` for
the tuple of potted balls). :func:`batch_info` builds that from a
:class:`pool_env.game.step.StepResult` without a loop over tables, :func:`table_info` the
single environment's dict; both read the same columns.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from pool_env.game.step import StepResult

#: ``info`` key -> (column of :class:`~pool_env.game.step.StepResult`, dtype); ``potted``
#: (the tuple of object balls the shot potted, ascending) comes first.
COLUMNS: dict[str, tuple[str, type]] = {
    "scratch": ("scratch", np.bool_),
    "first_contact": ("first_contact", np.int64),
    "n_events": ("n_events", np.int64),
    "hit_event_cap": ("hit_event_cap", np.bool_),
    "angle": ("angle", np.float64),
    "speed": ("speed", np.float64),
    "is_success": ("cleared", np.bool_),
}

#: Every key of a step's ``info``.
INFO_KEYS: tuple[str, ...] = ("potted", *COLUMNS)

#: Object balls up to which the potted tuples come from a lookup table (``2^n`` entries).
LOOKUP_MAX_BALLS = 16


def potted_lookup(n_objects: int) -> NDArray[np.object_] | None:
    """Tuple of potted balls for each bit mask (ascending), or ``None`` for many balls."""
    if n_objects > LOOKUP_MAX_BALLS:
        return None
    out = np.empty(1 << n_objects, dtype=object)
    balls = range(1, n_objects + 1)
    for mask in range(1 << n_objects):
        out[mask] = tuple(j for j in balls if mask >> (j - 1) & 1)
    return out


def potted_tuples(
    result: StepResult, rows: NDArray[np.bool_] | slice, lut: NDArray[np.object_] | None
) -> NDArray[np.object_]:
    """The ``potted`` tuples of ``rows`` of a result, as an object array."""
    if lut is not None:
        return lut[result.potted_bits[rows]]
    pocketed = result.pocketed[rows]
    out = np.empty(pocketed.shape[0], dtype=object)
    for k, row in enumerate(pocketed >= 0):
        out[k] = tuple(sorted(b for b in result.balls[row].tolist() if b != 0))
    return out


def table_info(result: StepResult, lut: NDArray[np.object_] | None) -> dict[str, Any]:
    """The ``info`` dict of a one-table result, with Python scalars."""
    info: dict[str, Any] = {"potted": potted_tuples(result, slice(None), lut)[0]}
    for key, (column, _) in COLUMNS.items():
        info[key] = getattr(result, column).tolist()[0]
    return info


def batch_info(
    result: StepResult, n_envs: int, mask: NDArray[np.bool_] | None, lut: NDArray[np.object_] | None
) -> dict[str, Any]:
    """The tables' infos in Gymnasium's vector layout.

    Args:
        result: The step's result; row ``k`` is table ``result.tables[k]``.
        n_envs: Number of tables.
        mask: ``(n_envs,)`` tables to report (``None``: every table that shot).
        lut: :func:`potted_lookup`'s table.

    Returns:
        The info dict; ``{}`` when no table is reported (as Gymnasium's, which only has
        the keys some table gave).
    """
    rows: NDArray[np.bool_] | slice = slice(None) if mask is None else mask[result.tables]
    tables = result.tables[rows]
    if tables.size == 0:
        return {}
    present = np.zeros(n_envs, dtype=np.bool_)
    present[tables] = True
    potted = np.full(n_envs, None, dtype=object)
    potted[tables] = potted_tuples(result, rows, lut)
    info: dict[str, Any] = {"potted": potted, "_potted": present}
    for key, (column, dtype) in COLUMNS.items():
        values = np.zeros(n_envs, dtype=dtype)
        values[tables] = getattr(result, column)[rows]
        info[key] = values
        info[f"_{key}"] = present.copy()
    return info
