"""One place for the numba options of every compiled kernel, and for where they are cached.

The simulator's kernels (:mod:`pool_env.sim.kernels`) and those of the layers above it all
compile through :func:`kernel`, :func:`inline_kernel` and :func:`parallel_kernel`, with the
same options (no fastmath, for bit-for-bit determinism) and one cache folder.

Kernels are cached on disk so a fresh process (every ``SubprocVecEnv`` worker) loads machine
code instead of compiling. numba keys a cached function on its own file only (its
content, not its time stamp, so a fresh clone loads what an earlier one compiled), not on
the files of the functions it calls: after an edit of ``resolve.py``, the cached
event loop of ``loop.py`` would still hold the old impact code (and numba freezes the
constants a kernel reads from other modules, such as ``params.py``, into its machine code).
So the cache lives in a folder named after a hash of the modules of :data:`KERNEL_MODULES`,
every module whose code or constants are compiled: any change of one of them starts a fresh
cache. The list is read from the sources (:func:`kernel_modules`), so this module names no
layer above the simulator; ``tests/sim/test_compile_cache.py`` checks it against the import
graph: every module compiling through this one, every module in a ``kernels`` package and
every module they import.

The folder is the first writable of: ``$NUMBA_CACHE_DIR/pool_env-<hash>`` (if that variable
is set), the package's ``__pycache__/numba-<hash>``, and ``~/.cache/pool_env/numba-<hash>``.
With none writable (a read-only install and home), kernels compile in memory, with a
warning. numba writes cache files through a temporary file and an atomic rename, and each
kernel compiles under a file lock of its own (:mod:`pool_env.sim.compile_lock`): processes
starting together on an empty cache compile each kernel once between them, then load it.
``python -m pool_env.precompile`` fills the cache ahead of a first shot.

A cache file can still be damaged from outside (a full disk, a copy cut short, a bad
sector): numba then raises from its loader (``EOFError``, ``UnpicklingError``) in this and
every later process. Each kernel's cache is therefore a :class:`HealingCache`: a cache that
cannot be read is deleted, the kernel compiles (one warning per process) and the fresh
cache is written back through numba's atomic rename, for every later process to load.
"""

from __future__ import annotations

import hashlib
import inspect
import os
import re
import sys
import tempfile
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any, TypeVar

import numba
from numba.core.caching import FunctionCache
from numba.extending import overload

from pool_env.sim import compile_lock, compile_notice

F = TypeVar("F", bound=Callable[..., Any])

# fastmath stays off: reassociation would break bit-for-bit determinism and the exactness
# of the stable root formulas. error_model="numpy" removes Python's zero-division checks.
_OPTIONS: dict[str, Any] = {"nogil": True, "error_model": "numpy", "fastmath": False}

_PACKAGE = Path(__file__).resolve().parents[1]


def module_file(root: Path, module: str) -> Path:
    """The source file of ``module`` (a dotted name) under the folder ``root`` holding it."""
    return root.joinpath(*module.split(".")).with_suffix(".py")


# ``from pool_env.x import a, b`` (parentheses and line breaks allowed) and ``import pool_env.x``.
_FROM_IMPORT = re.compile(rb"^\s*from\s+(pool_env[\w.]*)\s+import\s+(\([^)]*\)|[^\n]*)", re.M)
_IMPORT = re.compile(rb"^\s*import\s+(pool_env[\w.]*)", re.M)


def _imports(source: bytes) -> set[str]:
    """The ``pool_env`` names a module's source imports.

    ``from a.b import c`` gives ``a.b`` and ``a.b.c``, a module or not: the caller keeps
    those that are modules.
    """
    names = {m.decode() for m in _IMPORT.findall(source)}
    for module, imported in _FROM_IMPORT.findall(source):
        names.add(module.decode())
        for line in imported.decode().splitlines():
            for name in line.split("#")[0].strip("() ").split(","):
                if name.strip():
                    names.add(f"{module.decode()}.{name.split()[0]}")
    return names


def kernel_modules(root: Path) -> tuple[str, ...]:
    """Every module whose code or constants end up in compiled code, read from the sources.

    A module counts when it lies in a ``kernels`` package, when it compiles through this
    one (imports ``pool_env.sim.jit``), or when a module that counts imports it; packages'
    ``__init__`` files hold docstrings only and do not. The layers above the simulator are
    found, not named: a kernels package added to any layer joins the key by itself. A
    plain scan of the sources (a few ms at import), no parsing.

    Args:
        root: The folder holding the top-level package (``pool_env``'s parent).

    Returns:
        The dotted names, sorted.
    """
    sources: dict[str, bytes] = {}
    for folder, subfolders, files in os.walk(root / "pool_env"):
        subfolders[:] = [d for d in subfolders if d != "__pycache__"]  # numba's caches
        base = Path(folder).relative_to(root).parts
        for name in files:
            if name.endswith(".py") and name != "__init__.py":
                sources[".".join((*base, name[:-3]))] = (Path(folder) / name).read_bytes()
    imports = {module: _imports(text) & set(sources) for module, text in sources.items()}
    found = {
        module
        for module, imported in imports.items()
        if "kernels" in module.split(".") or __name__ in imported
    } | {__name__}
    pending = list(found)
    while pending:  # what they import, and so on
        for module in imports[pending.pop()] - found:
            found.add(module)
            pending.append(module)
    return tuple(sorted(found))


#: Every module whose code or constants end up in compiled code, the simulator's and the
#: layers' above it, this one included (its options): :func:`kernel_modules` of the sources.
#: ``tests/sim/test_compile_cache.py`` checks it against the import graph.
KERNEL_MODULES: tuple[str, ...] = kernel_modules(_PACKAGE.parent)


def source_hash(root: Path, modules: tuple[str, ...] = KERNEL_MODULES) -> str:
    """A short hash of the names and sources of ``modules``, read under ``root``.

    Args:
        root: The folder holding the top-level package (``pool_env``'s parent).
        modules: Dotted names of the modules to hash.

    Returns:
        16 hex digits.

    Raises:
        RuntimeError: A listed module has no source file (it moved: update the list).
    """
    digest = hashlib.sha256()
    for module in sorted(modules):
        path = module_file(root, module)
        if not path.is_file():
            raise RuntimeError(f"pool_env: compiled module {module} has no file {path}")
        digest.update(module.encode())
        digest.update(path.read_bytes())
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
    tag = source_hash(_PACKAGE.parent)
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
# A first compile takes tens of seconds: say so once, instead of looking hung.
COMPILE_NOTICE = compile_notice.install(CACHE_FOLDER)
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
        """Write the compile result, replacing an index damaged since it was read.

        Under the kernel's index lock: numba reads the index, adds the entry and writes it
        back, and another process saving another signature meanwhile would drop one entry.
        """
        index_lock = self.lock_stem.with_name(f"{self.lock_stem.name}.index.lock")
        with compile_lock.holding(index_lock):
            try:
                super().save_overload(sig, data)
            except Exception as exc:  # the index cannot be read back: start it afresh
                self._discard(exc)
                super().save_overload(sig, data)

    @property
    def lock_stem(self) -> Path:
        """The stem of this kernel's lock files, beside its cache files."""
        return Path(self._cache_path) / self._impl.filename_base

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
            if not numba.config.DISABLE_JIT:  # else numba hands back the plain function
                compile_lock.lock_compiles(
                    dispatcher, dispatcher._cache.lock_stem, COMPILE_NOTICE.waiting
                )
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


def level_method(
    stub: Callable[..., Any], level_class: type, inline: bool = True
) -> Callable[[F], F]:
    """Register the decorated function as model level ``level_class``'s ``stub``.

    The shared kernels call a model level's parts through the stubs of
    :mod:`pool_env.sim.kernels.level`, passing the level's marker (an instance of
    ``level_class``, a named tuple) first; numba picks the implementation from the
    marker's type when it compiles the caller. A compiled caller is therefore one
    specialised function per level, cached on disk like any kernel (the marker's type is
    part of its signature). The implementation takes the stub's parameters, the marker
    included.

    Args:
        stub: The interface function (its signature is the implementation's).
        level_class: The marker type of the level that implements it.
        inline: Inline the implementation into its callers at numba's IR level (as
            :func:`inline_kernel` does): a call with array arguments costs per event. Off
            for implementations that write through a named tuple of arrays (the segment
            log): numba's IR inliner loses those stores (the rows came back unwritten).

    Returns:
        A decorator that registers and returns the implementation.
    """

    def register(impl: F) -> F:
        def typer(*args: Any) -> F | None:
            return impl if getattr(args[0], "instance_class", None) is level_class else None

        typer.__signature__ = inspect.signature(impl)  # type: ignore[attr-defined]
        options = {"inline": "always"} if inline else {}
        overload(stub, jit_options=_OPTIONS, **options)(typer)
        # For the interface's calls from plain Python (numba's JIT disabled).
        sys.modules[stub.__module__].IMPLEMENTATIONS[(stub.__name__, level_class)] = impl
        return impl

    return register
