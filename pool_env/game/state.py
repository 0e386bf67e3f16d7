"""The changing part of the decision process: B tables held in arrays.

Each table owns a ``numpy.random.Generator`` (layouts and execution noise draw from it), so
that table ``i`` of a batch plays exactly as a single environment seeded alike. Kernels
reach the generators through their addresses (:mod:`pool_env.game.kernels.rng`), which are
per process: they are taken again after unpickling.

A step that fails changes nothing: :meth:`GameState.hold` saves, before each step, what a
step changes before its simulation can fail, and :meth:`GameState.undo` puts it back
(:mod:`pool_env.game.kernels.undo`).
"""

from __future__ import annotations

import ctypes
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.kernels.undo import restore_shooters, save_shooters


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
        words_at: ``(B,)`` the address of each generator's state words, which
            :meth:`hold` copies (:func:`state_words_address`; 0: saved as a dict).
        saved_cue: ``(B, 2)`` :meth:`hold`'s copy of each shooting table's cue ball.
        saved_words: ``(B, 2)`` uint64 :meth:`hold`'s copy of each generator's state words.
        n_slow: Tables whose generator has no state words (saved through its dict).
    """

    positions: NDArray[np.float64]
    on_table: NDArray[np.bool_]
    shots: NDArray[np.int64]
    rack: NDArray[np.int64]
    generators: list[np.random.Generator | None]
    seeds: list[int | None]
    ptrs: NDArray[np.uintp]
    words_at: NDArray[np.uintp]
    saved_cue: NDArray[np.float64]
    saved_words: NDArray[np.uint64]
    n_slow: int = 0

    @property
    def n_tables(self) -> int:
        """B."""
        return int(self.positions.shape[0])

    def use_generator(self, table: int, rng: np.random.Generator, seed: int | None = None) -> None:
        """Let ``table`` draw from ``rng`` (held, not copied: its state advances)."""
        if self.generators[table] is not None and self.words_at[table] == 0:
            self.n_slow -= 1
        self.generators[table], self.seeds[table] = rng, seed
        self.ptrs[table] = generator_addresses(rng)
        self.words_at[table] = state_words_address(rng)
        self.n_slow += int(self.words_at[table] == 0)

    def hold(self, tables: NDArray[np.intp]) -> dict[int, Any] | None:
        """Save what a step of ``tables`` changes before its simulation can fail.

        The cue balls (a ball in hand is placed) and the generators' states (the noise is
        drawn): one compiled copy into :attr:`saved_cue` and :attr:`saved_words`. A
        generator without state words is saved as its ``state`` dict, returned.

        Returns:
            ``{table: state dict}`` of those generators, or ``None`` (every one has words).
        """
        save_shooters(self.positions, self.words_at, tables, self.saved_cue, self.saved_words)
        if not self.n_slow:
            return None
        return {b: g.bit_generator.state for b in tables.tolist()
                if self.words_at[b] == 0 and (g := self.generators[b]) is not None}  # fmt: skip

    def undo(self, tables: NDArray[np.intp], held: dict[int, Any] | None) -> None:
        """Put back what :meth:`hold` saved of ``tables`` (``held``: what it returned)."""
        restore_shooters(self.positions, self.words_at, tables, self.saved_cue, self.saved_words)
        for b, bits in (held or {}).items():
            self.generators[b].bit_generator.state = bits  # type: ignore[union-attr]

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
        words_at, n_slow = self.words_at.copy(), self.n_slow
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
            self.words_at[...], self.n_slow = words_at, n_slow

        return restore

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)
        for i, rng in enumerate(self.generators):  # addresses are per process
            if rng is not None:
                self.ptrs[i] = generator_addresses(rng)
                self.words_at[i] = state_words_address(rng)
        self.n_slow = sum(g is not None and w == 0 for g, w in
                          zip(self.generators, self.words_at.tolist(), strict=True))  # fmt: skip


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
        words_at=np.zeros(n_tables, dtype=np.uintp),
        saved_cue=np.zeros((n_tables, 2)),
        saved_words=np.zeros((n_tables, 2), dtype=np.uint64),
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


#: The bit generators whose whole changing state is two 64-bit words (their 128-bit LCG
#: state) at the start of the block their C state points to.
_LCG_BIT_GENERATORS = (np.random.PCG64, np.random.PCG64DXSM)


def state_words_address(rng: np.random.Generator) -> int:
    """The address of the state words of ``rng``'s bit generator, or 0 if it has none.

    ``PCG64`` and ``PCG64DXSM``: the 128-bit state that their draws advance, the first 16
    bytes of the block their C state's first field points to
    (:mod:`pool_env.game.kernels.undo`). The layout is checked against the generator's own
    ``state`` (a build that lays it out otherwise gets 0: its states are saved as dicts).
    """
    bitgen = rng.bit_generator
    if type(bitgen) not in _LCG_BIT_GENERATORS:
        return 0
    block = ctypes.c_void_p.from_address(bitgen.ctypes.state_address).value or 0
    if not block:
        return 0
    low, high = (ctypes.c_uint64 * 2).from_address(block)
    if low | high << 64 != bitgen.state["state"]["state"]:
        return 0
    return int(block)
