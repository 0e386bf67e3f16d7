"""The changing part of the decision process: B tables held in arrays.

Each table owns a ``numpy.random.Generator`` (layouts and execution noise draw from it), so
that table ``i`` of a batch plays exactly as a single environment seeded alike. Kernels
reach the generators through their addresses (:mod:`pool_env.game.kernels.rng`), which are
per process: they are taken again after unpickling.
"""

from __future__ import annotations

import ctypes
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray


@dataclass
class GameState:
    """B tables of one :class:`~pool_env.game.config.GameConfig`.

    Attributes:
        positions: ``(B, N, 2)`` ball centres (m), cue first; a potted ball keeps the point
            where it was captured.
        on_table: ``(B, N)`` which balls are on each table.
        shots: ``(B,)`` shots played in each table's episode.
        rack: ``(B, W)`` int64: each table's game state, ``W`` the game's
            :attr:`~pool_env.game.ruleset.Ruleset.rack_width` (the WPA games: who shoots,
            ball in hand, the break, groups, fouls, the winner; none in solitaire).
        generators: Each table's generator (``None`` until first seeded).
        seeds: The seed each generator was made from (``None``: not from an int).
        ptrs: ``(B, 3)`` addresses of each generator's state and draw functions.
    """

    positions: NDArray[np.float64]
    on_table: NDArray[np.bool_]
    shots: NDArray[np.int64]
    rack: NDArray[np.int64]
    generators: list[np.random.Generator | None]
    seeds: list[int | None]
    ptrs: NDArray[np.uintp]

    @property
    def n_tables(self) -> int:
        """B."""
        return int(self.positions.shape[0])

    def use_generator(self, table: int, rng: np.random.Generator, seed: int | None = None) -> None:
        """Let ``table`` draw from ``rng`` (held, not copied: its state advances)."""
        self.generators[table], self.seeds[table] = rng, seed
        self.ptrs[table] = generator_addresses(rng)

    def generators_of(self, tables: NDArray[np.intp]) -> list[np.random.Generator]:
        """The generators of ``tables``; a front seeds every table before its first reset.

        Raises:
            RuntimeError: For a table never given a generator.
        """
        out = [self.generators[b] for b in tables.tolist()]
        if any(rng is None for rng in out):
            raise RuntimeError("a table was never seeded: its front seeds it before a reset")
        return out  # type: ignore[return-value]

    def snapshot(self) -> Callable[[], None]:
        """A function that puts the tables back as they are now, generators included.

        For fronts that must undo a step that failed half-way (an opponent policy that
        raises after the agent's shot): arrays are copied, each generator keeps its object
        (so its addresses stay valid) and gets its bit state back.
        """
        arrays = [a.copy() for a in (self.positions, self.on_table, self.shots, self.rack)]
        ptrs, generators, seeds = self.ptrs.copy(), list(self.generators), list(self.seeds)
        bits = [None if g is None else g.bit_generator.state for g in generators]

        def restore() -> None:
            for now, then in zip((self.positions, self.on_table, self.shots, self.rack), arrays,
                                 strict=True):  # fmt: skip
                now[...] = then
            self.generators[:], self.seeds[:] = generators, seeds
            for g, state in zip(generators, bits, strict=True):
                if g is not None:
                    g.bit_generator.state = state
            self.ptrs[...] = ptrs

        return restore

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        for i, rng in enumerate(self.generators):  # addresses are per process
            if rng is not None:
                self.ptrs[i] = generator_addresses(rng)


def new_state(n_tables: int, n_balls: int, rack_width: int = 0) -> GameState:
    """``n_tables`` empty tables of ``n_balls`` balls (lay them out with a reset).

    ``rack_width`` is the game's (:attr:`~pool_env.game.ruleset.Ruleset.rack_width`;
    ``GameConfig.new_state`` passes it).
    """
    return GameState(
        positions=np.zeros((n_tables, n_balls, 2)),
        on_table=np.ones((n_tables, n_balls), dtype=np.bool_),
        shots=np.zeros(n_tables, dtype=np.int64),
        rack=np.zeros((n_tables, rack_width), dtype=np.int64),
        generators=[None] * n_tables,
        seeds=[None] * n_tables,
        ptrs=np.zeros((n_tables, 3), dtype=np.uintp),
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
