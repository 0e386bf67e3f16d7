"""The mutation runner's engine: scratch copies, the test subsets, the workers.

Each mutant of :data:`tools.mutant_catalogue.CATALOGUE` is applied to a fresh scratch copy
of the tracked tree (never to the tree itself), and its focused test subset runs there with
``pytest -x`` and the derandomized hypothesis profile ``ci``. A failing subset *kills* the
mutant (the first failing test is kept); a passing one lets it *survive*. A mutant whose
snippet no longer occurs exactly once is *stale* (the code moved: re-anchor it) and is
reported, never skipped silently. With a budget no mutant starts once it is spent (the
running ones finish): the rest are *not run*. The unmutated tree runs the union of all
subsets first (the baseline): if it fails, no kill means anything.

Interpreted kernels: a mutant whose subset only uses the simulator (the files of
:data:`tools.mutant_catalogue.INTERPRETABLE`) runs with ``NUMBA_DISABLE_JIT=1``: the same
kernels as plain Python, so no ~25 s compile of a fresh cache per mutant (the suite's
simulator tests pass that way too: that is its baseline). ``compiled=True`` compiles every
mutant instead.

Compiled kernels: every scratch worker has its own numba cache (``NUMBA_CACHE_DIR`` inside
the scratch folder). ``pool_env``'s cache folder is named after a hash of the compiled
modules' sources, so a mutated kernel compiles into a folder of its own and can never be
loaded by another mutant, the baseline or the real tree; a mutant of plain Python reuses
the worker's baseline kernels (the scratch copy keeps the files' time stamps).
"""

from __future__ import annotations

import contextlib
import os
import queue
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from tools.mutant_catalogue import INTERPRETABLE, Mutant

ROOT = Path(__file__).resolve().parents[1]
#: Default limit on one mutant's subset (s); the baseline, the union of all subsets, gets
#: four times as long. Past it the verdict is "timeout": neither killed nor survived (on a
#: loaded machine, raise it with --timeout).
TIMEOUT = 900.0
FAILED_LINE = re.compile(r"^(FAILED|ERROR) (\S+)", re.MULTILINE)


@dataclass
class Outcome:
    """The verdict on one mutant (or on a baseline, ``mutant=None``)."""

    mutant: Mutant | None
    status: str  # "killed", "survived", "stale", "timeout", "error", "not run"
    detail: str  # the killing test, the reason for stale/error, or ""
    seconds: float
    interpreted: bool = False


@dataclass(frozen=True)
class Job:
    """A mutant to run (``None``: a baseline of ``tests``), and how."""

    mutant: Mutant | None
    tests: tuple[str, ...]
    interpreted: bool


def interpretable(mutant: Mutant) -> bool:
    """Whether every file of the mutant's subset can run with the kernels interpreted."""
    return all(t.split("::")[0] in INTERPRETABLE for t in mutant.tests)


def occurrences(mutant: Mutant, root: Path = ROOT) -> int:
    """How often the mutant's snippet occurs in its file under ``root`` (0 if no file)."""
    path = root / mutant.file
    if not path.is_file():
        return 0
    return path.read_text().count(mutant.original)


def tracked_files(root: Path) -> list[str]:
    """Files of the working tree that git tracks or would track (not ignored)."""
    out = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
        cwd=root,
        check=True,
        capture_output=True,
    ).stdout.decode()
    return [f for f in out.split("\0") if f and (root / f).is_file()]


def fresh_copy(root: Path, files: Sequence[str], dest: Path) -> None:
    """Copy ``files`` from ``root`` to an empty ``dest``, keeping their time stamps."""
    if dest.exists():
        shutil.rmtree(dest)
    for name in files:
        target = dest / name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(root / name, target)


def apply(mutant: Mutant, tree: Path) -> None:
    """Write the mutant into the copy ``tree`` (its snippet must occur exactly once)."""
    path = tree / mutant.file
    source = path.read_text()
    if source.count(mutant.original) != 1:
        raise ValueError(f"{mutant.name}: snippet occurs {source.count(mutant.original)} times")
    path.write_text(source.replace(mutant.original, mutant.mutated))


class Stop:
    """Shared between the workers: set on an interrupt; the running subsets are killed."""

    def __init__(self) -> None:
        self.event = threading.Event()
        self._lock = threading.Lock()
        self._running: set[subprocess.Popen[str]] = set()

    def add(self, proc: subprocess.Popen[str]) -> bool:
        """Track ``proc``; False (and ``proc`` killed) if the run is already stopping."""
        with self._lock:
            if self.event.is_set():
                proc.kill()
                return False
            self._running.add(proc)
            return True

    def remove(self, proc: subprocess.Popen[str]) -> None:
        """Forget ``proc`` (it has finished)."""
        with self._lock:
            self._running.discard(proc)

    def stop(self) -> None:
        """Stop handing out jobs and kill every running subset (its process group)."""
        with self._lock:
            self.event.set()
            for proc in self._running:
                _kill(proc)


def _kill(proc: subprocess.Popen[str]) -> None:
    """Kill a subset's pytest and whatever it started (it leads its own process group)."""
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGKILL)


def run_tests(
    tree: Path,
    cache: Path,
    tests: Sequence[str],
    timeout: float,
    interpreted: bool,
    stop: Stop | None = None,
) -> tuple[str, str]:
    """Run ``tests`` in ``tree``; return ``(verdict, first failure)``.

    The verdict is ``"passed"``, ``"failed"``, ``"timeout"``, ``"error"`` or
    ``"stopped"`` (the run was interrupted).
    """
    env = {
        **os.environ,
        "PYTHONPATH": str(tree),
        "NUMBA_CACHE_DIR": str(cache),
        "HYPOTHESIS_PROFILE": "ci",
        "PYTHONDONTWRITEBYTECODE": "1",
    }
    if interpreted:
        env["NUMBA_DISABLE_JIT"] = "1"
    else:
        env.pop("NUMBA_DISABLE_JIT", None)
    command = [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider", "-rfE"]
    proc = subprocess.Popen(
        [*command, *tests],
        cwd=tree,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        start_new_session=True,  # its own process group, so a kill takes its children too
    )
    stop = stop or Stop()
    if not stop.add(proc):
        proc.communicate()
        return "stopped", "run interrupted"
    try:
        output, _ = proc.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        _kill(proc)
        proc.communicate()
        return "timeout", f"no verdict after {timeout:.0f} s"
    finally:
        stop.remove(proc)
    if stop.event.is_set():
        return "stopped", "run interrupted"
    first = FAILED_LINE.search(output)
    where = first.group(2) if first else ""
    if proc.returncode == 0:
        return "passed", ""
    if proc.returncode in (1, 2):  # tests failed, or collection/import failed
        return "failed", where or "collection error: " + output.strip().splitlines()[-1]
    return "error", f"pytest exit code {proc.returncode}: " + output.strip()[-300:]


def _worker(
    jobs: queue.Queue[Job],
    results: list[Outcome],
    lock: threading.Lock,
    scratch: Path,
    snapshot: Path,
    files: list[str],
    timeout: float,
    stop: Stop,
    deadline: float,
) -> None:
    tree, cache = scratch / "tree", scratch / "numba"
    while not stop.event.is_set() and time.monotonic() < deadline:
        try:
            job = jobs.get_nowait()
        except queue.Empty:
            return
        start = time.perf_counter()
        fresh_copy(snapshot, files, tree)
        mutant = job.mutant
        if mutant is not None:
            apply(mutant, tree)
        limit = timeout if mutant is not None else 4 * timeout
        verdict, where = run_tests(tree, cache, job.tests, limit, job.interpreted, stop)
        if verdict == "stopped":
            return
        # A baseline must pass ("survived"); a mutant should fail ("killed").
        status = {"passed": "survived", "failed": "killed"}.get(verdict, verdict)
        if mutant is None and status == "killed":
            status = "failed"
        outcome = Outcome(mutant, status, where, time.perf_counter() - start, job.interpreted)
        with lock:
            results.append(outcome)
            label = "baseline" if mutant is None else mutant.name
            label += " (interpreted)" if job.interpreted else ""
            print(f"{label:28s} {outcome.status:9s} {outcome.seconds:6.1f} s  {where}", flush=True)


def run(
    mutants: Sequence[Mutant],
    workers: int,
    timeout: float = TIMEOUT,
    compiled: bool = False,
    budget: float | None = None,
) -> tuple[list[Outcome], list[Outcome]]:
    """Run the baselines and every mutant; return ``(baselines, outcomes in catalogue order)``.

    Mutants whose subsets are all :data:`INTERPRETABLE` run with the kernels interpreted
    unless ``compiled``; each mode has its own baseline (the union of its subsets). With a
    ``budget`` (s), no job starts after it; the mutants left are ``"not run"``.
    """
    results: list[Outcome] = []
    runnable = []
    for m in mutants:
        count = occurrences(m)
        if count == 1:
            runnable.append(m)
        else:
            where = "file missing" if not (ROOT / m.file).is_file() else f"{count} occurrences"
            results.append(Outcome(m, "stale", f"snippet not found once ({where})", 0.0))
    mode = {m.name: not compiled and interpretable(m) for m in runnable}
    jobs: queue.Queue[Job] = queue.Queue()
    for interpreted in (False, True):  # the baselines first
        union = tuple(
            dict.fromkeys(t for m in runnable if mode[m.name] == interpreted for t in m.tests)
        )
        if union:
            jobs.put(Job(None, union, interpreted))
    for m in runnable:
        jobs.put(Job(m, m.tests, mode[m.name]))
    files = tracked_files(ROOT)
    lock = threading.Lock()
    stop = Stop()
    deadline = time.monotonic() + (budget if budget is not None else float("inf"))
    root = Path(tempfile.mkdtemp(prefix="pool_env-mutants-"))
    threads: list[threading.Thread] = []
    try:
        # One snapshot of the tree at the start: edits made while the run goes on do not
        # leak into later mutants.
        snapshot = root / "snapshot"
        fresh_copy(ROOT, files, snapshot)
        threads = [
            threading.Thread(
                target=_worker,
                args=(
                    jobs,
                    results,
                    lock,
                    root / f"w{k}",
                    snapshot,
                    files,
                    timeout,
                    stop,
                    deadline,
                ),
            )
            for k in range(workers)
        ]
        for t in threads:
            t.start()
        for t in threads:
            while t.is_alive():  # join in slices, so that Ctrl-C reaches this thread
                t.join(0.5)
    finally:
        # Interrupted (Ctrl-C, SIGTERM) or done: kill the running subsets, wait for the
        # workers, then remove every scratch copy and cache.
        stop.stop()
        for t in threads:
            t.join()
        shutil.rmtree(root, ignore_errors=True)
    baselines = [r for r in results if r.mutant is None]
    order = {m.name: k for k, m in enumerate(mutants)}
    mutated = [r for r in results if r.mutant is not None]
    done = {r.mutant.name for r in mutated}  # type: ignore[union-attr]
    left = f"not started: the budget of {(budget or 0.0) / 60:.0f} min was spent"
    mutated += [Outcome(m, "not run", left, 0.0) for m in mutants if m.name not in done]
    outcomes = sorted(mutated, key=lambda r: order[r.mutant.name])  # type: ignore[union-attr]
    return baselines, outcomes
