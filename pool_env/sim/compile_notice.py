"""A line on standard error while a first compile takes long: what the wait is, and that it's once.

numba compiles a kernel on its first call and caches the machine code on disk
(:mod:`pool_env.sim.jit`). From an empty cache the first shot of a table compiles the event
loop, which takes tens of seconds on a small machine; with no word said, a newcomer's first
``env.step`` looks hung. :class:`CompileNotice` listens to numba's compile events: when a
compile of one of this package's kernels has run for :data:`DELAY_SECONDS`, it prints one
line saying so, once per process. A compile that ends sooner, and every load from the cache
(numba fires no compile event for it), prints nothing.
"""

from __future__ import annotations

import sys
import threading
from pathlib import Path
from typing import Any, TextIO

from numba.core import event

#: Seconds a compile runs (or a wait for another process's compile lasts) before a line.
DELAY_SECONDS = 2.0

#: The command that fills the cache ahead of a first shot (:mod:`pool_env.precompile`).
PRECOMPILE = "python -m pool_env.precompile"


class CompileNotice(event.Listener):
    """Print one line when a compile of this package's kernels outlasts ``delay`` seconds.

    Args:
        cache_folder: Where the compiled code is cached (named in the line), or None.
        delay: Seconds a compile runs before the line is printed.
        prefix: Module prefix of the kernels watched.
        stream: Where to print (default: ``sys.stderr`` at the time of printing).
    """

    def __init__(
        self,
        cache_folder: Path | None,
        delay: float = DELAY_SECONDS,
        prefix: str = "pool_env.",
        stream: TextIO | None = None,
    ) -> None:
        self._cache_folder = cache_folder
        self._delay = delay
        self._prefix = prefix
        self._stream = stream
        self._depth = 0  # nested compiles: a kernel compiles the kernels it calls
        self._timer: threading.Timer | None = None
        self._wait_timer: threading.Timer | None = None
        self.said = False
        self.said_waiting = False

    def on_start(self, ev: event.Event) -> None:
        """A compile starts: at the outermost one of ours, start the clock."""
        self._depth += 1
        if self._depth == 1 and not self.said and self._is_ours(ev):
            self._timer = threading.Timer(self._delay, self._say)
            self._timer.daemon = True  # never keeps a finished program alive
            self._timer.start()

    def on_end(self, ev: event.Event) -> None:
        """A compile ends: at the outermost one, stop the clock."""
        self._depth -= 1
        if self._depth == 0 and self._timer is not None:
            self._timer.cancel()
            self._timer = None

    def silence(self) -> None:
        """Print nothing more in this process (one that says what it compiles itself)."""
        self.said = self.said_waiting = True

    def waiting(self, started: bool) -> None:
        """Another process compiles a kernel this one needs: a line if the wait is long.

        Called by :mod:`pool_env.sim.compile_lock` when this process starts waiting on a
        kernel's lock (``started`` True) and when it has the lock (False). Printed once per
        process, and not after the compile line (which already says what the wait is).
        """
        if started and not (self.said or self.said_waiting):
            self._wait_timer = threading.Timer(self._delay, self._say_waiting)
            self._wait_timer.daemon = True
            self._wait_timer.start()
        elif not started and self._wait_timer is not None:
            self._wait_timer.cancel()
            self._wait_timer = None

    def _is_ours(self, ev: event.Event) -> bool:
        data: dict[str, Any] = ev.data or {}
        dispatcher = data.get("dispatcher")
        module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
        return module.startswith(self._prefix)

    def _print(self, line: str) -> None:
        stream = self._stream if self._stream is not None else sys.stderr
        print(line, file=stream, flush=True)

    def _say(self) -> None:
        self.said = True
        where = f" in {self._cache_folder}" if self._cache_folder is not None else " in memory"
        self._print(
            "pool_env: compiling the simulator's kernels for this machine, once (tens of "
            f"seconds); the machine code is cached{where}, so later runs load it in about a "
            f"second. `{PRECOMPILE}` compiles them all ahead of time."
        )

    def _say_waiting(self) -> None:
        self.said_waiting = True
        self._print(
            "pool_env: waiting for another process to finish compiling the simulator's "
            "kernels, once; this process then loads them from the cache"
        )


def install(cache_folder: Path | None) -> CompileNotice:
    """Register a :class:`CompileNotice` for numba's compile events; return it."""
    notice = CompileNotice(cache_folder)
    event.register("numba:compile", notice)
    return notice
