"""One place for the numba options of every compiled kernel, and for where they are cached.

Kernels are cached on disk so a fresh process (every ``SubprocVecEnv`` worker) loads machine
code instead of compiling. numba keys a cached function on its own file's time stamp only,
not on the files of the functions it calls: after an edit of ``resolve.py``, the cached
event loop of ``loop.py`` would still hold the old impact code. So the cache lives in a
folder named after a hash of every module that holds compiled code: any change of one of
them starts a fresh cache.

The folder is the first writable of: ``$NUMBA_CACHE_DIR/pool_env-<hash>`` (if that variable
is set), the package's ``__pycache__/numba-<hash>``, and ``~/.cache/pool_env/numba-<hash>``.
With none writable (a read-only install and home), kernels compile in memory, with a
warning. numba writes cache files through a temporary file and an atomic rename, so several
processes compiling at once neither crash nor corrupt the cache.

A cache file can still be damaged from outside (a full disk, a copy cut short, a bad
sector): numba then raises from its loader (``EOFError``, ``UnpicklingError``) in this and
every later process. Each kernel's cache is therefore a :class:`HealingCache`: a cache that
cannot be read is deleted, the kernel compiles (one warning per process) and the fresh
cache is written back through numba's atomic rename, for every later process to load.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

import numba
from numba.core.caching import FunctionCache

F = TypeVar("F", bound=Callable[..., Any])

# fastmath stays off: reassociation would break bit-for-bit determinism and the exactness
# of the stable root formulas. error_model="numpy" removes Python's zero-division checks.
_OPTIONS: dict[str, Any] = {"nogil": True, "error_model": "numpy", "fastmath": False}

_PACKAGE = Path(__file__).resolve().parents[2]


def _source_hash() -> str:
    """A short hash of the modules with compiled code (names and contents).

    That is every module in ``kernels/`` and every other one that compiles with this one.
    """
    digest = hashlib.sha256()
    for path in sorted(_PACKAGE.rglob("*.py")):
        source = path.read_bytes()
        if path.parent.name == "kernels" or b"kernels._jit import" in source:
            digest.update(path.relative_to(_PACKAGE).as_posix().encode())
            digest.update(source)
    return digest.hexdigest()[:16]


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError:
        return False
    return True


def _cache_folder() -> Path | None:
    """The first writable cache folder for this version of the sources, or None."""
    tag = _source_hash()
    candidates = []
    if os.environ.get("NUMBA_CACHE_DIR"):
        candidates.append(Path(os.environ["NUMBA_CACHE_DIR"]) / f"pool_env-{tag}")
    candidates.append(_PACKAGE / "__pycache__" / f"numba-{tag}")
    candidates.append(Path.home() / ".cache" / "pool_env" / f"numba-{tag}")
    for folder in candidates:
        if _writable(folder):
            return folder
    return None


CACHE_FOLDER = _cache_folder()
_warned = False
_healed = False


class HealingCache(FunctionCache):
    """numba's on-disk cache of one kernel, deleting itself when it cannot be read."""

    def load_overload(self, sig: Any, target_context: Any) -> Any:
        """The cached compile result for ``sig``, or None (compile) if absent or unreadable."""
        try:
            return super().load_overload(sig, target_context)
        except Exception as exc:  # any unreadable cache: compiling instead is always right
            self._discard(exc)
            return None

    def save_overload(self, sig: Any, data: Any) -> None:
        """Write the compile result, replacing an index damaged since it was read."""
        try:
            super().save_overload(sig, data)
        except Exception as exc:  # the index cannot be read back: start it afresh
            self._discard(exc)
            super().save_overload(sig, data)

    def _discard(self, exc: Exception) -> None:
        """Delete this kernel's index and data files, warning once per process."""
        global _healed
        folder = Path(self._cache_path)
        base = self._impl.filename_base
        for path in folder.glob("*"):
            name = path.name
            if name == f"{base}.nbi" or (name.startswith(f"{base}.") and name.endswith(".nbc")):
                path.unlink(missing_ok=True)
        if not _healed:
            warnings.warn(
                f"pool_env: unreadable compile cache for {self._py_func.__qualname__} in {folder} "
                f"({type(exc).__name__}: {exc}); discarded it and compiling afresh",
                RuntimeWarning,
                stacklevel=2,
            )
            _healed = True


def _compile(fn: F, options: dict[str, Any]) -> F:
    global _warned
    if CACHE_FOLDER is not None:
        # numba picks a function's cache location when it is decorated, from
        # numba.config.CACHE_DIR first: point it at our folder for that moment only.
        saved = numba.config.CACHE_DIR
        numba.config.CACHE_DIR = str(CACHE_FOLDER)
        try:
            dispatcher = numba.njit(cache=True, **options)(fn)
            dispatcher._cache = HealingCache(fn)
            return dispatcher  # type: ignore[no-any-return]
        except RuntimeError:  # numba found the folder unwritable after all
            pass
        finally:
            numba.config.CACHE_DIR = saved
    if not _warned:
        warnings.warn(
            "pool_env: no writable numba cache location; compiling in memory. Set "
            "NUMBA_CACHE_DIR to a writable folder to keep compiled code.",
            RuntimeWarning,
            stacklevel=3,
        )
        _warned = True
    return numba.njit(cache=False, **options)(fn)  # type: ignore[no-any-return]


def kernel(fn: F) -> F:
    """Compile ``fn`` with the project's options, cached on disk when possible.

    Args:
        fn: A function written in numba's nopython subset.

    Returns:
        The numba dispatcher (typed as the original function).
    """
    return _compile(fn, _OPTIONS)


def inline_kernel(fn: F) -> F:
    """Like :func:`kernel`, but inlined into its callers by numba (``inline="always"``).

    For pieces of a hot loop split out to be read on their own: an ordinary call there costs
    measurably per event (array arguments are passed field by field and reference-counted).
    """
    return _compile(fn, {**_OPTIONS, "inline": "always"})


def parallel_kernel(fn: F) -> F:
    """Like :func:`kernel` but with ``parallel=True`` (for ``prange`` loops over tables)."""
    return _compile(fn, {**_OPTIONS, "parallel": True})
