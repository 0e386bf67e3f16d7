"""Draws from numpy ``Generator`` objects inside compiled code, one stream per table.

A batched environment keeps one ``numpy.random.Generator`` per table, so that each table
draws exactly what a single environment seeded alike would. Passing the generators
themselves into a kernel costs a Python-level call per table; instead a kernel receives,
per table, the address of the bit generator's state and of its C ``next_double`` /
``next_uint64`` functions (numpy's documented ``bit_generator.ctypes`` interface, which is
also how numba implements ``Generator`` support) and calls them directly. The generators'
states advance in place, exactly as if numpy had drawn the numbers.

Callers must keep the generators alive while a kernel runs, and must not run two kernels
on the same generator at once (numpy's own lock is bypassed).
"""

from __future__ import annotations

import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

# The ziggurat tables of numpy's standard normal sampler, as numba ships them for its own
# np.random.Generator support (a private module, but stable since numba 0.56).
from numba.np.random._constants import (
    fi_double,
    ki_double,
    wi_double,
    ziggurat_nor_inv_r,
    ziggurat_nor_r,
)

from pool_env.sim.jit import kernel

#: Columns of the per-table address rows built by :func:`pool_env.envs.vector` callers.
STATE, NEXT_DOUBLE, NEXT_UINT64 = 0, 1, 2


def _call_bitgen(return_type: types.Type):
    """An intrinsic ``(fn_address, state_address) -> return_type`` calling a C function."""

    @intrinsic
    def call(typingctx, fn, state):
        sig = return_type(types.uintp, types.uintp)

        def codegen(context, builder, signature, args):
            fn_addr, state_addr = args
            ll_ret = context.get_value_type(return_type)
            ll_ptr = context.get_value_type(types.voidptr)
            fnty = ir.FunctionType(ll_ret, (ll_ptr,))
            fn_ptr = builder.inttoptr(fn_addr, fnty.as_pointer())
            return builder.call(fn_ptr, (builder.inttoptr(state_addr, ll_ptr),))

        return sig, codegen

    return call


_next_double = _call_bitgen(types.float64)
_next_uint64 = _call_bitgen(types.uint64)


@kernel
def next_double(ptrs):
    """One ``Generator.random()`` draw: a double in ``[0, 1)`` from the row ``ptrs``."""
    return _next_double(ptrs[NEXT_DOUBLE], ptrs[STATE])


@kernel
def standard_normal(ptrs):
    """One ``Generator.standard_normal()`` draw, numpy's ziggurat step by step."""
    while True:
        r = _next_uint64(ptrs[NEXT_UINT64], ptrs[STATE])
        idx = r & 0xFF
        r >>= 8
        sign = r & 0x1
        rabs = (r >> 1) & 0x000FFFFFFFFFFFFF
        x = rabs * wi_double[idx]
        if sign & 0x1:
            x = -x
        if rabs < ki_double[idx]:
            return x  # 99.3% of draws end here
        if idx == 0:  # the tail, beyond ziggurat_nor_r
            while True:
                xx = -ziggurat_nor_inv_r * np.log1p(-next_double(ptrs))
                yy = -np.log1p(-next_double(ptrs))
                if yy + yy > xx * xx:
                    if (rabs >> 8) & 0x1:
                        return -(ziggurat_nor_r + xx)
                    return ziggurat_nor_r + xx
        else:
            u = next_double(ptrs)
            if (fi_double[idx - 1] - fi_double[idx]) * u + fi_double[idx] < np.exp(-0.5 * x * x):
                return x
