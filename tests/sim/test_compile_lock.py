"""The file locks that let processes starting together compile each kernel once.

The whole effect (three cold processes, each kernel signature compiled in one of them) is
tested in ``test_compile_cache.py``; here the lock's own behaviour, fast.
"""

from __future__ import annotations

import io
import os
import subprocess
import sys
import time
from pathlib import Path

import numba
import pytest

from pool_env.sim import compile_lock
from pool_env.sim.compile_notice import CompileNotice

pytestmark = pytest.mark.skipif(compile_lock.fcntl is None, reason="no fcntl (Windows)")

HOLDER = """
import sys, time
from pathlib import Path
from pool_env.sim.compile_lock import holding
with holding(Path(sys.argv[1])):
    print("held", flush=True)
    time.sleep(float(sys.argv[2]))
"""


def _hold_elsewhere(path: Path, seconds: float) -> subprocess.Popen:
    proc = subprocess.Popen(
        [sys.executable, "-c", HOLDER, str(path), str(seconds)],
        stdout=subprocess.PIPE,
        text=True,
    )
    assert proc.stdout is not None and proc.stdout.readline() == "held\n"
    return proc


def test_a_busy_lock_waits_for_the_other_process_and_says_so(tmp_path: Path) -> None:
    path = tmp_path / "kernel.lock"
    proc = _hold_elsewhere(path, 1.0)
    calls: list[tuple[bool, float]] = []
    start = time.perf_counter()
    with compile_lock.holding(path, lambda started: calls.append((started, time.perf_counter()))):
        waited = time.perf_counter() - start
    proc.communicate(timeout=30)
    assert waited > 0.5, "the lock did not wait for the process holding it"
    assert [started for started, _ in calls] == [True, False]
    assert calls[1][1] - calls[0][1] > 0.5


def test_a_free_lock_is_taken_without_waiting_and_released(tmp_path: Path) -> None:
    path = tmp_path / "kernel.lock"
    calls: list[bool] = []
    with compile_lock.holding(path, calls.append):
        assert path in compile_lock._HELD
    assert calls == [] and path not in compile_lock._HELD
    proc = _hold_elsewhere(path, 0.0)  # another process gets it at once: it was released
    proc.communicate(timeout=30)


def test_a_process_never_waits_on_a_lock_it_holds(tmp_path: Path) -> None:
    """A kernel compiled for a second signature inside its first compile (same lock)."""
    path = tmp_path / "kernel.lock"
    with compile_lock.holding(path), compile_lock.holding(path):
        pass
    assert path not in compile_lock._HELD


def test_signatures_of_one_kernel_have_locks_of_their_own(tmp_path: Path) -> None:
    stem = tmp_path / "loop.run-12.py311"
    a = compile_lock.signature_lock(stem, (numba.float64, numba.int64))
    b = compile_lock.signature_lock(stem, (numba.float64, numba.float64))
    assert a != b and a.parent == tmp_path and a.name.startswith(stem.name)
    assert a == compile_lock.signature_lock(stem, (numba.float64, numba.int64))


def test_a_locked_kernel_compiles_under_its_signature_lock(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    stem = tmp_path / "probe"

    def probe(x: float) -> float:
        return x + 1.0

    dispatcher = numba.njit(cache=False)(probe)
    compile_lock.lock_compiles(dispatcher, stem)
    seen: list[Path] = []
    original = compile_lock.holding

    def spy(path: Path, on_wait=None):  # type: ignore[no-untyped-def]
        seen.append(path)
        return original(path, on_wait)

    monkeypatch.setattr(compile_lock, "holding", spy)
    assert dispatcher(1.0) == 2.0
    assert dispatcher(2.0) == 3.0  # compiled already: no lock taken again
    assert dispatcher(1) == 2.0  # a second signature: a lock of its own
    assert seen == [
        compile_lock.signature_lock(stem, (numba.float64,)),
        compile_lock.signature_lock(stem, (numba.int64,)),
    ]


def test_the_waiting_line_is_printed_once_after_the_delay() -> None:
    stream = io.StringIO()
    notice = CompileNotice(Path("/cache"), delay=0.05, stream=stream)
    notice.waiting(True)
    time.sleep(0.3)
    notice.waiting(False)
    notice.waiting(True)
    time.sleep(0.3)
    notice.waiting(False)
    lines = stream.getvalue().splitlines()
    assert len(lines) == 1 and "another process" in lines[0] and "once" in lines[0]


def test_a_short_wait_prints_nothing() -> None:
    stream = io.StringIO()
    notice = CompileNotice(None, delay=60.0, stream=stream)
    notice.waiting(True)
    notice.waiting(False)
    assert stream.getvalue() == "" and not notice.said_waiting


def test_a_silenced_notice_prints_neither_line() -> None:
    stream = io.StringIO()
    notice = CompileNotice(None, delay=0.0, stream=stream)
    notice.silence()
    notice.waiting(True)
    time.sleep(0.1)
    notice.waiting(False)
    assert stream.getvalue() == ""


def test_with_numba_jit_disabled_kernels_run_as_python() -> None:
    """``NUMBA_DISABLE_JIT=1`` (bench.prediction_count's counting mode): no lock, no error."""
    code = (
        "from pool_env import Table, simulate\n"
        "r = simulate(Table(model='roll'), [[1.0, 0.635], [1.5, 0.635]], [[1.0, 0.0], [0, 0]])\n"
        "print(r.n_events)\n"
    )
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    proc = subprocess.run(
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    assert int(proc.stdout.split()[-1]) > 0
