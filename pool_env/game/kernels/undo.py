"""What a step changes before its simulation can fail, saved and put back in compiled code.

A step (:func:`pool_env.game.step.step`) places each cue ball in hand and draws each
table's execution noise before the simulator runs, and the simulator may still refuse the
shot (a ``ValueError``). A refused step must change nothing, so the step saves, before it
starts, the two things that have changed by then: each shooting table's cue ball and its
generator's state; on a failure it puts them back. Saving runs on every step, so it must
cost nothing measurable: one compiled call over the shooting tables, copying two floats and
two 64-bit words a table into buffers the state keeps (a generator's ``state`` dict would
cost a microsecond a table, a third of a 64-table vector step).

The two words: numpy's ``PCG64`` and ``PCG64DXSM`` (Gymnasium's ``np_random`` is a
``PCG64``) keep their 128-bit LCG state in the first 16 bytes of the block their C state
points to, and the draws the kernels make (``next_double``, ``next_uint64``,
:mod:`pool_env.game.kernels.rng`) change nothing else of the generator (not its buffered
32-bit half). :func:`pool_env.game.state.state_words_address` finds that block (and checks
it against the generator's own ``state`` once); a generator of another kind is saved
through its ``state`` dict instead (slow, for those only).
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from pool_env.game.kernels.outcome import CUE
from pool_env.sim.jit import kernel


@intrinsic
def _load_word(typingctx, address, index):
    """The 64-bit word ``index`` of the memory at ``address`` (an integer)."""
    sig = types.uint64(address, index)

    def codegen(context, builder, signature, args):
        base = builder.inttoptr(args[0], ir.IntType(64).as_pointer())
        return builder.load(builder.gep(base, [args[1]]))

    return sig, codegen


@intrinsic
def _store_word(typingctx, address, index, value):
    """Write the 64-bit ``value`` as word ``index`` of the memory at ``address``."""
    sig = types.void(address, index, value)

    def codegen(context, builder, signature, args):
        base = builder.inttoptr(args[0], ir.IntType(64).as_pointer())
        builder.store(args[2], builder.gep(base, [args[1]]))
        return context.get_dummy_value()

    return sig, codegen


@kernel
def save_shooters(positions, words_at, tables, cue, words):
    """Copy each shooting table's cue ball and generator state into the buffers.

    Args:
        positions: ``(B, N, 2)`` ball centres.
        words_at: ``(B,)`` the address of each table's generator state words (0: none).
        tables: ``(K,)`` the tables that shoot.
        cue: ``(B, 2)`` written: row ``b`` the cue ball of table ``b``.
        words: ``(B, 2)`` uint64 written: row ``b`` the state words of table ``b``.
    """
    for k in range(tables.shape[0]):
        b = tables[k]
        cue[b, 0], cue[b, 1] = positions[b, CUE, 0], positions[b, CUE, 1]
        address = words_at[b]
        if address != 0:
            words[b, 0] = _load_word(address, 0)
            words[b, 1] = _load_word(address, 1)


@kernel
def restore_shooters(positions, words_at, tables, cue, words):
    """Put back what :func:`save_shooters` saved of ``tables`` (the arguments alike)."""
    for k in range(tables.shape[0]):
        b = tables[k]
        positions[b, CUE, 0], positions[b, CUE, 1] = cue[b, 0], cue[b, 1]
        address = words_at[b]
        if address != 0:
            _store_word(address, 0, words[b, 0])
            _store_word(address, 1, words[b, 1])
