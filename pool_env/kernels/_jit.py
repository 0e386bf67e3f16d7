"""One place for the numba options of every compiled kernel.

Kernels are cached on disk so a fresh process (every ``SubprocVecEnv`` worker) loads machine
code instead of compiling. numba refuses ``cache=True`` when it finds no writable cache
location (a read-only install with no writable user cache); we then compile in memory
instead of failing. numba writes cache files through a temporary file and an atomic rename,
so several processes compiling at once neither crash nor corrupt the cache.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from typing import Any, TypeVar

import numba

F = TypeVar("F", bound=Callable[..., Any])

# fastmath stays off: reassociation would break bit-for-bit determinism and the exactness
# of the stable root formulas. error_model="numpy" removes Python's zero-division checks.
_OPTIONS: dict[str, Any] = {"nogil": True, "error_model": "numpy", "fastmath": False}

_warned = False


def kernel(fn: F) -> F:
    """Compile ``fn`` with the project's options, cached on disk when possible.

    Args:
        fn: A function written in numba's nopython subset.

    Returns:
        The numba dispatcher (typed as the original function).
    """
    global _warned
    try:
        return numba.njit(cache=True, **_OPTIONS)(fn)  # type: ignore[no-any-return]
    except RuntimeError as exc:  # "cannot cache function ...: no locator available"
        if not _warned:
            warnings.warn(
                f"pool_env: no writable numba cache location ({exc}); compiling in memory. "
                "Set NUMBA_CACHE_DIR to a writable folder to keep compiled code.",
                RuntimeWarning,
                stacklevel=2,
            )
            _warned = True
        return numba.njit(cache=False, **_OPTIONS)(fn)  # type: ignore[no-any-return]


def parallel_kernel(fn: F) -> F:
    """Like :func:`kernel` but with ``parallel=True`` (for ``prange`` loops over tables)."""
    try:
        return numba.njit(cache=True, parallel=True, **_OPTIONS)(fn)  # type: ignore[no-any-return]
    except RuntimeError:
        return numba.njit(cache=False, parallel=True, **_OPTIONS)(fn)  # type: ignore[no-any-return]
