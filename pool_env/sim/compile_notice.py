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

#: Seconds a compile runs before the notice is printed.
DELAY_SECONDS = 2.0


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
        self.said = False

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

    def _is_ours(self, ev: event.Event) -> bool:
        data: dict[str, Any] = ev.data or {}
        dispatcher = data.get("dispatcher")
        module = getattr(getattr(dispatcher, "py_func", None), "__module__", "") or ""
        return module.startswith(self._prefix)

    def _say(self) -> None:
        self.said = True
        where = f" in {self._cache_folder}" if self._cache_folder is not None else " in memory"
        stream = self._stream if self._stream is not None else sys.stderr
        print(
            "pool_env: compiling the simulator's kernels for this machine, once (20-40 s on 2 "
            f"cores); the machine code is cached{where}, so later runs load it in about a second",
            file=stream,
            flush=True,
        )


def install(cache_folder: Path | None) -> CompileNotice:
    """Register a :class:`CompileNotice` for numba's compile events; return it."""
    notice = CompileNotice(cache_folder)
    event.register("numba:compile", notice)
    return notice
