"""Frozen copies of the values a config is given, so that it never shares the caller's.

A config section keeps what it was given (a layout, a range, a dict of table arguments);
were it the caller's own object, changing that object afterwards would change every
environment made from the config later, and a config handed back to a caller would let
it change the next environment. :func:`freeze` copies what can change into what cannot:
arrays into read-only copies, mappings into :class:`FrozenMap`, lists into tuples.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import fields
from typing import Any

import numpy as np

__all__ = ["FrozenMap", "freeze", "freeze_fields"]


class FrozenMap(Mapping[str, Any]):
    """A read-only mapping: a copy of what it was made from, equal to a dict of the same items.

    Unlike ``types.MappingProxyType`` it can be pickled and deep-copied (Gymnasium copies
    its ``make()`` keywords, ``AsyncVectorEnv`` pickles them), and it hashes when its
    values do.

    Examples:
        >>> scales = FrozenMap({"pot": 2.0})
        >>> scales == {"pot": 2.0}, scales["pot"]
        (True, 2.0)
        >>> scales["pot"] = 3.0
        Traceback (most recent call last):
        ...
        TypeError: 'FrozenMap' object does not support item assignment
    """

    __slots__ = ("_items",)

    def __init__(self, items: Mapping[str, Any] | None = None) -> None:
        self._items: dict[str, Any] = dict(items or {})

    def __getitem__(self, key: str) -> Any:
        return self._items[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __repr__(self) -> str:
        return repr(self._items)  # as the dict it was given: messages name values as written

    def __hash__(self) -> int:
        return hash(frozenset(self._items.items()))

    def __reduce__(self) -> tuple[type[FrozenMap], tuple[dict[str, Any]]]:
        return FrozenMap, (self._items,)


def freeze(value: Any) -> Any:
    """``value`` with nothing left that its giver could change.

    An array becomes a read-only copy, a mapping a :class:`FrozenMap` of frozen values, a
    list or tuple a tuple of frozen items; anything else (numbers, strings, a frozen
    ``Table``, a callable scene) is kept as it is.

    Examples:
        >>> import numpy as np
        >>> given = np.zeros(2)
        >>> kept = freeze(given)
        >>> given[0] = 1.0
        >>> kept.tolist(), kept.flags.writeable
        ([0.0, 0.0], False)
        >>> freeze([[0.5, 0.5], [1.0, 0.5]])
        ((0.5, 0.5), (1.0, 0.5))
    """
    if isinstance(value, np.ndarray):
        copy = np.array(value, copy=True)
        copy.setflags(write=False)
        return copy
    if isinstance(value, Mapping):
        return FrozenMap({key: freeze(item) for key, item in value.items()})
    if isinstance(value, list) or type(value) is tuple:  # a named tuple keeps its type
        return tuple(freeze(item) for item in value)
    return value


def freeze_fields(section: Any) -> None:
    """Freeze every field of a frozen dataclass in place (its ``__post_init__`` calls this)."""
    for f in fields(section):
        value = getattr(section, f.name)
        frozen = freeze(value)
        if frozen is not value:
            object.__setattr__(section, f.name, frozen)  # a frozen dataclass: set once, here
