"""The ``info`` of :class:`pool_env.vector.PoolVectorEnv`, in Gymnasium's vector layout.

Gymnasium's vector environments gather the per-table ``info`` dicts into one dict: an array
over the tables per key, with a boolean mask ``"_key"`` of the tables that gave the key,
and the array type set by the value (``bool``, ``int64``, ``float64``, or ``object`` for
anything else, such as ``PoolEnv``'s tuple of potted balls). This module builds the same
arrays from the batched step results, with no loop over tables.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

#: Object balls up to which the potted tuples come from a lookup table (``2^n`` entries).
LOOKUP_MAX_BALLS = 16


class StepInfo(NamedTuple):
    """Results of one batch of shots; row ``k`` is table ``tables[k]``."""

    tables: NDArray[np.intp]
    rewards: NDArray[np.float64]
    ends: tuple[NDArray[np.bool_], NDArray[np.bool_]]  # terminated, truncated
    potted_bits: NDArray[np.int64]  # bit j - 1 set: object ball j potted
    pocketed: NDArray[np.int64] | None  # (K, N) when the lookup table is not used
    scratch: NDArray[np.bool_]
    first_contact: NDArray[np.int64]
    n_events: NDArray[np.int64]
    hit_event_cap: NDArray[np.bool_]
    angle: NDArray[np.float64]
    speed: NDArray[np.float64]
    is_success: NDArray[np.bool_]


def potted_lookup(n_objects: int) -> NDArray[np.object_] | None:
    """Tuple of potted balls for each bit mask (ascending, as ``PoolEnv``), or ``None``."""
    if n_objects > LOOKUP_MAX_BALLS:
        return None
    out = np.empty(1 << n_objects, dtype=object)
    balls = range(1, n_objects + 1)
    for mask in range(1 << n_objects):
        out[mask] = tuple(j for j in balls if mask >> (j - 1) & 1)
    return out


def _potted(shot: StepInfo, rows: NDArray[np.bool_] | slice, lut: Any) -> NDArray[np.object_]:
    if lut is not None:
        return lut[shot.potted_bits[rows]]
    pocketed = shot.pocketed[rows]  # type: ignore[index]
    out = np.empty(pocketed.shape[0], dtype=object)
    for k, row in enumerate(pocketed[:, 1:] >= 0):
        out[k] = tuple((np.flatnonzero(row) + 1).tolist())
    return out


def step_infos(
    shot: StepInfo, n_envs: int, mask: NDArray[np.bool_] | None, lut: NDArray[np.object_] | None
) -> dict[str, Any]:
    """``PoolEnv``'s step info of the tables that shot (and are in ``mask``), batched.

    Args:
        shot: The batch's results.
        n_envs: Number of tables.
        mask: ``(n_envs,)`` tables to report (``None``: every table that shot).
        lut: :func:`potted_lookup`'s table.

    Returns:
        The info dict; ``{}`` when no table is reported (as Gymnasium's, which only has
        the keys some table gave).
    """
    rows: NDArray[np.bool_] | slice = slice(None) if mask is None else mask[shot.tables]
    tables = shot.tables[rows]
    if tables.size == 0:
        return {}
    present = np.zeros(n_envs, dtype=np.bool_)
    present[tables] = True
    potted = np.full(n_envs, None, dtype=object)
    potted[tables] = _potted(shot, rows, lut)
    info: dict[str, Any] = {"potted": potted, "_potted": present}
    columns = (
        ("scratch", shot.scratch, np.bool_),
        ("first_contact", shot.first_contact, np.int64),
        ("n_events", shot.n_events, np.int64),
        ("hit_event_cap", shot.hit_event_cap, np.bool_),
        ("angle", shot.angle, np.float64),
        ("speed", shot.speed, np.float64),
        ("is_success", shot.is_success, np.bool_),
    )
    for key, values, dtype in columns:
        column = np.zeros(n_envs, dtype=dtype)
        column[tables] = values[rows]
        info[key] = column
        info[f"_{key}"] = present.copy()
    return info
