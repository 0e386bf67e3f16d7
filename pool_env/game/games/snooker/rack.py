"""Snooker's frame state as a dict and back: ``options["rules"]`` and ``PoolEnv.rack``."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import is_integer, parse_bool
from pool_env.game.games.snooker import rack_state as sk

#: The keys of a frame state dict, and what each holds.
KEYS = ("shooter", "score_0", "score_1", "phase", "ball_in_hand", "free_ball", "break",
        "respotted_black", "winner")  # fmt: skip


def state_dict(row: NDArray[np.int64]) -> dict[str, Any]:
    """A frame-state row as a dict (``winner`` None while the frame goes on)."""
    return {
        "shooter": int(row[sk.SHOOTER]),
        "score_0": int(row[sk.SCORE_0]),
        "score_1": int(row[sk.SCORE_1]),
        "phase": sk.PHASE_NAMES[int(row[sk.PHASE])],
        "ball_in_hand": bool(row[sk.IN_HAND]),
        "free_ball": bool(row[sk.FREE_BALL]),
        "break": int(row[sk.BREAK]),
        "respotted_black": bool(row[sk.RESPOTTED]),
        "winner": None if row[sk.WINNER] < 0 else int(row[sk.WINNER]),
    }


def default_row(reds: bool, in_hand: bool) -> NDArray[np.int64]:
    """Player 0 to play, no score, a red on (the colours in order without reds)."""
    row = np.zeros(sk.N_RACK, dtype=np.int64)
    row[sk.PHASE] = sk.RED_ON if reds else sk.IN_ORDER
    row[sk.IN_HAND] = int(in_hand)
    row[sk.WINNER] = -1
    return row


#: A raw row's columns other than the phase: each one's key and its least and most value
#: (``None``: no most).
ROW_RANGES = (
    ("shooter", sk.SHOOTER, 0, 1), ("score_0", sk.SCORE_0, 0, None),
    ("score_1", sk.SCORE_1, 0, None), ("ball_in_hand", sk.IN_HAND, 0, 1),
    ("free_ball", sk.FREE_BALL, 0, 1), ("break", sk.BREAK, 0, None),
    ("respotted_black", sk.RESPOTTED, 0, 1), ("winner", sk.WINNER, -1, 1),
)  # fmt: skip


def _count(name: str, value: Any, high: int | None = None) -> int:
    if not is_integer(value) or value < 0 or (high is not None and value > high):
        valid = ">= 0" if high is None else f"in 0..{high}"
        raise ValueError(f"options['rules'][{name!r}] must be an integer {valid}, got {value!r}")
    return int(value)


def _check_row(row: NDArray[np.int64]) -> None:
    """Refuse a raw row's value out of its column's range, naming the column's key."""
    for key, column, low, high in ROW_RANGES:
        value = int(row[column])
        if value < low or (high is not None and value > high):
            valid = f">= {low}" if high is None else f"in {low}..{high}"
            raise ValueError(
                f"options['rules'] row column {column} ({key!r}) must be {valid}, got {value}"
            )


def row_of(given: Any, reds: bool, in_hand: bool) -> NDArray[np.int64]:
    """The row of ``given``: ``None`` (the default), a dict of :data:`KEYS`, or a row.

    Raises:
        ValueError: On an unknown key, a bad value, or a phase the balls cannot have (a
            red on without a red on the table, the colours in order with one), naming it.
    """
    if given is None:
        return default_row(reds, in_hand)
    if isinstance(given, Mapping):
        unknown = sorted(set(given) - set(KEYS))
        if unknown:
            raise ValueError(f"options['rules'] keys {unknown} unknown: use {list(KEYS)}")
        row = default_row(reds, in_hand)
        if "shooter" in given:
            row[sk.SHOOTER] = _count("shooter", given["shooter"], 1)
        for key, column in (("score_0", sk.SCORE_0), ("score_1", sk.SCORE_1), ("break", sk.BREAK)):
            if key in given:
                row[column] = _count(key, given[key])
        if "phase" in given:
            if given["phase"] not in sk.PHASE_NAMES:
                raise ValueError(
                    f"options['rules']['phase'] must be one of {list(sk.PHASE_NAMES)}, "
                    f"got {given['phase']!r}"
                )
            row[sk.PHASE] = sk.PHASE_NAMES.index(given["phase"])
        for key, column in (("ball_in_hand", sk.IN_HAND), ("free_ball", sk.FREE_BALL),
                            ("respotted_black", sk.RESPOTTED)):  # fmt: skip
            if key in given:
                row[column] = int(parse_bool(f"options['rules'][{key!r}]", given[key]))
        if given.get("winner") is not None:
            row[sk.WINNER] = _count("winner", given["winner"], 1)
    else:
        try:
            row = np.array(given, dtype=np.int64).reshape(sk.N_RACK)
        except (TypeError, ValueError):
            raise ValueError(
                f"options['rules'] must be a dict of {list(KEYS)} or {sk.N_RACK} integers, "
                f"got {given!r}"
            ) from None
        _check_row(row)
    phase = int(row[sk.PHASE])
    if phase not in (sk.RED_ON, sk.COLOUR_ON, sk.IN_ORDER):
        raise ValueError(f"options['rules'] phase must be 0, 1 or 2, got {phase}")
    if phase == sk.RED_ON and not reds:
        raise ValueError("options['rules']['phase'] 'red' needs a red on the table")
    if phase == sk.IN_ORDER and reds:
        raise ValueError("options['rules']['phase'] 'in_order' needs no red on the table")
    return row
