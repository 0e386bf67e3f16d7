"""One compile of each kernel between processes that start together on an empty cache.

numba compiles a kernel on its first call in each process and, with the cache of
:mod:`pool_env.sim.jit`, writes the machine code to disk; a later process loads it. Processes
that start *together* (the workers of ``gym.make_vec(..., vectorization_mode="async")``,
SB3's ``SubprocVecEnv``, RLlib's env runners, pytest-xdist) all find the cache empty, and on
their own each would compile every kernel: eight workers on two cores took 65 s to a first
step where one process took 33 s.

So each kernel's compile of one signature runs under an advisory file lock of its own in
the cache folder. The first process to need it takes the lock and compiles (numba writes
the cache before its ``compile`` returns); the others wait on the lock, then find the code
in the cache, where numba's own ``compile`` looks first, and load it. Different kernels, and
one kernel's signatures (a shared kernel specialised per model level), still compile in
parallel, one process each. Writing a kernel's cache index (one file for all its
signatures) takes the kernel's own index lock (``jit.HealingCache.save_overload``), so
that two signatures saved at once both stay in it.

Locks are taken in the order kernels are compiled: a caller's lock, then its callees'
(numba compiles a callee while typing its caller), and an index lock last, held for one
write. The call graph of the kernels has no cycles, so no two processes can each hold a
lock the other waits for; a process never
waits on a lock it holds itself (a kernel compiled again for a second signature while its
first compiles). The lock is taken inside numba's process-wide compiler lock, so the
threads of one process queue there first and never hold file locks against each other.

Without ``fcntl`` (Windows) there is no lock and every process compiles as before.
"""

from __future__ import annotations

import contextlib
import hashlib
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

from numba.core import sigutils
from numba.core.compiler_lock import global_compiler_lock

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows: no advisory locks, compile as before
    fcntl = None  # type: ignore[assignment]

#: The lock files this process holds now (its compiles in progress, outermost first).
_HELD: set[Path] = set()


@contextlib.contextmanager
def holding(path: Path, on_wait: Callable[[bool], None] | None = None) -> Iterator[None]:
    """Hold the exclusive advisory lock ``path`` (created if absent) for the block.

    Args:
        path: The lock file; it is never deleted (deleting one another process waits on
            would let a third process lock a fresh file beside it).
        on_wait: Called with True when the lock is busy and this process starts waiting,
            and with False when it has the lock after waiting.
    """
    if fcntl is None or path in _HELD:
        yield
        return
    with open(path, "a+b") as handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            if on_wait is not None:
                on_wait(True)
            try:
                fcntl.flock(handle, fcntl.LOCK_EX)
            finally:
                if on_wait is not None:
                    on_wait(False)
        _HELD.add(path)
        try:
            yield
        finally:
            _HELD.discard(path)
            fcntl.flock(handle, fcntl.LOCK_UN)


def signature_lock(stem: Path, args: tuple[Any, ...]) -> Path:
    """The lock file of one signature of a kernel: ``<stem>.<hash of the types>.lock``.

    One lock per signature, not per kernel: the shared kernels compile once per model level
    (the level's marker type is an argument), and the two levels compile side by side.
    """
    digest = hashlib.sha256(repr(tuple(str(a) for a in args)).encode()).hexdigest()[:16]
    return stem.with_name(f"{stem.name}.{digest}.lock")


def lock_compiles(
    dispatcher: Any, stem: Path, on_wait: Callable[[bool], None] | None = None
) -> None:
    """Make ``dispatcher`` compile each signature under a file lock of its own.

    A signature the process already holds compiled code for skips the lock (numba asks
    again each time it types a caller of the kernel).

    Args:
        dispatcher: A numba dispatcher with an on-disk cache.
        stem: The kernel's lock files' stem, in the cache folder (:func:`signature_lock`).
        on_wait: Passed to :func:`holding` (the compile notice's waiting line).
    """
    compile_unlocked = dispatcher.compile

    def compile_locked(sig: Any) -> Any:
        with global_compiler_lock:
            args, _ = sigutils.normalize_signature(sig)
            if tuple(args) in dispatcher.overloads:
                return compile_unlocked(sig)
            with holding(signature_lock(stem, tuple(args)), on_wait):
                return compile_unlocked(sig)

    dispatcher.compile = compile_locked
