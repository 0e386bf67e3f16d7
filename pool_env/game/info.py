"""The step ``info``: its keys defined once, as one dict (one table) or Gymnasium's batch.

Gymnasium's vector environments gather the per-table ``info`` dicts into one dict: an array
over the tables per key, with a boolean mask ``"_key"`` of the tables that gave the key,
and the array type set by the value (``bool``, ``int64``, ``float64``, or ``object`` for
the tuple of potted balls). :func:`batch_info` builds that from a
:class:`pool_env.game.step.StepResult` without a loop over tables, :func:`table_info` the
single environment's dict; both read the same columns. The keys a game adds are its
ruleset's (:meth:`~pool_env.game.ruleset.Ruleset.info_columns`, and for one table
:meth:`~pool_env.game.ruleset.Ruleset.info_row`), and every step reports each of the
game's reward terms, scaled, as ``reward_<term>`` (as Gymnasium's MuJoCo envs report
theirs): they sum to the step's reward.
"""

from __future__ import annotations

from functools import cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels.outcome import (
    CLEARED,
    FIRST_BALL,
    POTTED_BITS,
    REWARD,
    SCRATCH,
    TERMINATED,
    TRUNCATED,
)

if TYPE_CHECKING:
    from pool_env.game.ruleset import Ruleset
    from pool_env.game.step import StepResult

#: ``info`` key -> (array of :class:`~pool_env.game.step.StepResult`, its column or
#: ``None``, dtype). ``potted`` (the tuple of object balls the shot potted, ascending) comes
#: first, from the potted bits.
COLUMNS: dict[str, tuple[str, int | None, type]] = {
    "scratch": ("flags", SCRATCH, np.bool_),
    "first_contact": ("hits", FIRST_BALL, np.int64),
    "n_events": ("n_events", None, np.int64),
    "hit_event_cap": ("hit_event_cap", None, np.bool_),
    "angle": ("shots", 0, np.float64),
    "speed": ("shots", 1, np.float64),
    "is_success": ("flags", CLEARED, np.bool_),
}

#: Every key of a step's ``info``.
INFO_KEYS: tuple[str, ...] = ("potted", *COLUMNS)

#: The key a spin table's step adds: the executed cue tip ``(a, b)`` (side, vertical;
#: fractions of R, after noise and the miscue limit), a tuple as ``potted`` is.
TIP_KEY = "tip"

#: The prefix of the reward terms' keys: ``reward_pot``, ``reward_scratch``, ...
REWARD_KEY_PREFIX = "reward_"


@cache
def reward_keys(ruleset: Ruleset) -> tuple[str, ...]:
    """The ``info`` keys of a game's reward terms, in their order."""
    return tuple(f"{REWARD_KEY_PREFIX}{term}" for term in ruleset.reward_terms)


def info_keys(ruleset: Ruleset, spin: bool) -> tuple[str, ...]:
    """Every key of a step's ``info`` under ``ruleset`` (``spin``: a spin table's tip too)."""
    return (*INFO_KEYS, *((TIP_KEY,) if spin else ()), *reward_keys(ruleset),
            *ruleset.info_keys)  # fmt: skip


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
        return lut[result.hits[rows, POTTED_BITS]]
    pocketed = result.pocketed[rows]
    out = np.empty(pocketed.shape[0], dtype=object)
    for k, row in enumerate(pocketed >= 0):
        out[k] = tuple(sorted(b for b in result.balls[row].tolist() if b != 0))
    return out


def table_info(result: StepResult, lut: NDArray[np.object_] | None) -> dict[str, Any]:
    """The ``info`` dict of a one-table result, with Python scalars (:func:`table_step`'s)."""
    return table_step(result, lut)[3]


def table_step(
    result: StepResult, lut: NDArray[np.object_] | None
) -> tuple[float, bool, bool, dict[str, Any]]:
    """``(reward, terminated, truncated, info)`` of a one-table result, as Python values.

    Each result array's row is converted once; per-shot counts come from the
    :class:`~pool_env.ShotResult` itself (this runs on every :class:`pool_env.PoolEnv` step).
    """
    shot = result.shot
    rows = {"flags": result.flags[0].tolist(), "hits": result.hits[0].tolist(),
            "shots": result.shots[0].tolist()}  # fmt: skip
    info: dict[str, Any] = {"potted": potted_tuples(result, slice(None), lut)[0]}
    for key, (name, column, _) in COLUMNS.items():
        if column is None:
            info[key] = getattr(shot, name) if shot is not None else getattr(result, name).item()
        else:
            info[key] = rows[name][column]
    shot_row = rows["shots"]
    if len(shot_row) > 2:
        info[TIP_KEY] = (shot_row[2], shot_row[3])
    ruleset = result.ruleset
    values = result.values[0].tolist()
    info.update(zip(reward_keys(ruleset), values[1:], strict=True))
    if ruleset.info_keys:
        info.update(ruleset.info_row(rows["hits"]))
    flags = rows["flags"]
    return values[REWARD], flags[TERMINATED], flags[TRUNCATED], info


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
    if (
        tables.size == n_envs
        and tables[-1] == n_envs - 1
        and tables[0] == 0
        and (n_envs < 3 or bool((tables[1:] > tables[:-1]).all()))
    ):  # every table, in order
        rows, spread = slice(None) if mask is None or mask.all() else rows, _copied
    else:
        spread = _spreader(tables, n_envs)
    present = np.zeros(n_envs, dtype=np.bool_)
    present[tables] = True
    info: dict[str, Any] = {"potted": spread(potted_tuples(result, rows, lut)), "_potted": present}
    for key, (name, column, dtype) in COLUMNS.items():
        source = getattr(result, name)
        info[key] = spread((source if column is None else source[:, column])[rows], dtype)
        info[f"_{key}"] = present.copy()
    if result.shots.shape[1] > 2:
        # fromiter keeps each tuple whole (an array or a list of tuples would be unpacked)
        rows_tips = result.shots[rows, 2:].tolist()
        tips = np.fromiter(map(tuple, rows_tips), dtype=object, count=len(rows_tips))
        info[TIP_KEY], info[f"_{TIP_KEY}"] = spread(tips), present.copy()
    ruleset = result.ruleset
    terms = result.values[rows, 1:]
    for k, key in enumerate(reward_keys(ruleset)):
        info[key], info[f"_{key}"] = spread(terms[:, k], np.float64), present.copy()
    if ruleset.info_keys:  # as table_step: a game's keys are the ones it declares
        for key, column in ruleset.info_columns(result.hits[rows]).items():
            info[key], info[f"_{key}"] = spread(column), present.copy()
    return info


def _copied(values: NDArray[Any], dtype: Any = None) -> NDArray[Any]:
    """Every table's values, in table order: a fresh array (of ``dtype``, if given)."""
    return np.array(values, dtype=dtype if dtype is not None else values.dtype)


def _spreader(tables: NDArray[np.intp], n_envs: int) -> Any:
    """Values of ``tables`` spread over ``n_envs`` (0, False or None elsewhere), fresh."""

    def spread(values: NDArray[Any], dtype: Any = None) -> NDArray[Any]:
        kind = dtype if dtype is not None else values.dtype
        fill = np.dtype(kind).kind == "O"
        out = np.full(n_envs, None, dtype=object) if fill else np.zeros(n_envs, kind)
        out[tables] = values
        return out

    return spread
