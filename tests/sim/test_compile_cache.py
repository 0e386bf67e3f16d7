"""Compiled code on disk: shared by concurrent processes, optional on read-only installs.

Each test starts fresh Python processes, because caching is about process start-up.
"""

from __future__ import annotations

import json
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import grimp
import pytest

import pool_env
from pool_env.sim import jit

PACKAGE = Path(pool_env.__file__).parent

SHOT = """
import hashlib, warnings
warnings.simplefilter("always")
from pool_env import Table, shoot
from pool_env.sim.kernels.roll.level import ENTRIES
from pool_env.sim.layouts import break_scene
t = Table()
r = shoot(t, break_scene(t, "nine"), 0.0, 8.0)
print(hashlib.sha256(r.positions.tobytes()).hexdigest(), r.n_events)
print("cache_hits", sum(ENTRIES.packed_strike.stats.cache_hits.values()))
"""


def _run(env: dict[str, str], code: str = SHOT, **kwargs) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", code],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        **kwargs,
    )


# Each kernel signature this process compiled (a cache miss) or loaded (a hit), by name.
COMPILED = """
import gc, json
from numba.core.registry import CPUDispatcher
stats = {"compiled": [], "loaded": []}
for kernel in gc.get_objects():
    if isinstance(kernel, CPUDispatcher) and kernel.py_func.__module__.startswith("pool_env"):
        name = kernel.py_func.__module__ + "." + kernel.py_func.__qualname__
        counters = {"compiled": kernel.stats.cache_misses, "loaded": kernel.stats.cache_hits}
        for key, counter in counters.items():
            stats[key] += [f"{name}{sig}" for sig, n in counter.items() if n]
print(json.dumps(stats))
"""


def _writable_copy(root: Path) -> Path:
    shutil.copytree(PACKAGE, root / "pool_env", ignore=shutil.ignore_patterns("__pycache__"))
    return root


def test_concurrent_cold_starts_compile_each_kernel_once(tmp_path: Path) -> None:
    """Three processes starting at once on an empty cache compile each kernel once.

    Each kernel signature compiles in exactly one of them (under its file lock,
    :mod:`pool_env.sim.compile_lock`); the others wait and load it. All agree on the shot.
    Then every source file gets a new modification time (a fresh clone, a checkout back
    and forth): a fourth process still loads everything (numba 0.68 stamps a cache index
    with a hash of its source file's content, and the folder is named after one).
    """
    root = _writable_copy(tmp_path / "src")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(root))
    code = SHOT + COMPILED
    procs = [_run(env, code=code, cwd=root) for _ in range(3)]
    outputs = [p.communicate(timeout=900) for p in procs]
    for proc, (_, err) in zip(procs, outputs, strict=True):
        assert proc.returncode == 0, err
    assert len({out.splitlines()[0] for out, _ in outputs}) == 1
    compiled = [json.loads(out.splitlines()[-1])["compiled"] for out, _ in outputs]
    every = [name for names in compiled for name in names]
    twice = {name for name in every if every.count(name) > 1}
    assert every and not twice, f"compiled in more than one process: {sorted(twice)[:5]}"
    later = time.time() + 3600
    for path in root.rglob("*.py"):
        os.utime(path, (later, later))
    out, err = _run(env, code=code, cwd=root).communicate(timeout=900)
    stats = json.loads(out.splitlines()[-1])
    assert out.splitlines()[0] == outputs[0][0].splitlines()[0], err
    # A warm process loads the entry points it calls (their callees are linked into them).
    assert stats["compiled"] == [] and stats["loaded"], stats


def _readonly_copy() -> Path:
    root = Path(tempfile.mkdtemp(prefix="pool_env_ro_"))
    shutil.copytree(PACKAGE, root / "pool_env", ignore=shutil.ignore_patterns("__pycache__"))
    for path in [root, *root.rglob("*")]:
        mode = stat.S_IREAD | stat.S_IRGRP | stat.S_IROTH
        if path.is_dir():
            mode |= stat.S_IEXEC | stat.S_IXGRP | stat.S_IXOTH
        path.chmod(mode)
    return root


# Root writes through any permission bits, so as root the child process is told that every
# cache location is unwritable at the point numba checks it (where a read-only filesystem
# raises): numba's locators then find no place, exactly as on a read-only install.
UNWRITABLE = """
import numba.core.caching as caching
def refuse(self):
    raise PermissionError(13, "Permission denied", self.get_cache_path())
caching._CacheLocator.ensure_cache_path = refuse
"""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX permissions")
def test_read_only_install_falls_back_to_memory() -> None:
    """No writable cache anywhere: a warning, in-memory compilation, the same results."""
    root = _readonly_copy()
    try:
        env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
        env |= {"PYTHONPATH": str(root), "HOME": "/nonexistent"}
        code = (UNWRITABLE if os.geteuid() == 0 else "") + SHOT
        proc = subprocess.Popen(
            [sys.executable, "-c", code],
            env=env,
            cwd="/",
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        out, err = proc.communicate(timeout=600)
        assert proc.returncode == 0, err
        assert "no writable numba cache location" in err
        assert not list(root.rglob("*.nbi"))  # nothing was written into the install
        reference = _run(dict(os.environ)).communicate(timeout=600)[0]
        assert out.splitlines()[0] == reference.splitlines()[0]
    finally:
        for path in [root, *root.rglob("*")]:
            path.chmod(0o755)
        shutil.rmtree(root)


HEAL = """
import hashlib, warnings
warnings.simplefilter("always")
from pool_env import Table, shoot
from pool_env.sim.kernels import timeline, validation
from pool_env.sim.kernels.roll.level import ENTRIES
from pool_env.sim.layouts import break_scene
from pool_env.sim.simulate import check_positions
t = Table()
r = shoot(t, break_scene(t, "nine"), 0.0, 8.0)
check_positions(t, break_scene(t, "nine"))  # validation.validate from Python (shoot: packed_strike)
print(hashlib.sha256(r.positions.tobytes() + r.positions_at(0.1).tobytes()).hexdigest())
for k in (ENTRIES.packed_strike, validation.validate, timeline.positions_at):
    print(k.__name__, sum(k.stats.cache_hits.values()), sum(k.stats.cache_misses.values()))
"""


def _warm_cache_copy(root: Path) -> Path:
    """A copy of this process's compile cache, as ``$NUMBA_CACHE_DIR`` would hold it."""
    if jit.CACHE_FOLDER is None:
        pytest.skip("no on-disk compile cache in this process")
    tag = jit.CACHE_FOLDER.name.rsplit("-", 1)[-1]
    out = subprocess.run([sys.executable, "-c", HEAL], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr  # the package's cache now holds every kernel used
    shutil.copytree(jit.CACHE_FOLDER, root / f"pool_env-{tag}")
    return root / f"pool_env-{tag}"


def _heal_run(env: dict[str, str]) -> tuple[str, dict[str, tuple[int, int]], str]:
    proc = subprocess.run(
        [sys.executable, "-c", HEAL], env=env, capture_output=True, text=True, timeout=900
    )
    assert proc.returncode == 0, proc.stderr
    digest, *rows = proc.stdout.split("\n")[:4]
    stats = {name: (int(hits), int(misses)) for name, hits, misses in (r.split() for r in rows)}
    return digest, stats, proc.stderr


def test_a_corrupted_cache_heals(tmp_path: Path) -> None:
    """An empty index, a truncated index and a garbage data file heal.

    The next process warns once, recompiles those kernels and writes them back; the one
    after loads them from disk.
    """
    folder = _warm_cache_copy(tmp_path)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    reference, stats, err = _heal_run(env)
    assert all(hits > 0 and misses == 0 for hits, misses in stats.values()), (stats, err)

    def only(pattern: str) -> Path:
        (path,) = folder.rglob(pattern)
        return path

    only("entries.entries.locals.RollLevel.packed_strike-*.nbi").write_bytes(
        b""
    )  # a process killed mid-write
    index = only("validation.validate-*.nbi")
    index.write_bytes(index.read_bytes()[: index.stat().st_size // 2])  # a full disk
    only("timeline.positions_at-*.nbc").write_bytes(b"\x80\x05garbage" * 64)
    digest, stats, err = _heal_run(env)
    assert digest == reference
    assert err.count("unreadable compile cache") == 1, err
    assert all(misses == 1 for _, misses in stats.values()), stats  # each compiled once
    # The next process loads every kernel from the cache the healing one wrote back.
    digest, stats, err = _heal_run(env)
    assert digest == reference
    assert "unreadable compile cache" not in err
    assert all(hits > 0 and misses == 0 for hits, misses in stats.values()), (stats, err)
    assert not list(folder.rglob("*.tmp.*"))  # written through numba's atomic rename


LEVELS = """
import sys
from pool_env import Table, simulate
from pool_env.sim.levels import level_of
for model in sys.argv[1:]:
    table = Table(model=model)
    r = simulate(table, [[1.0, 0.635], [1.5, 0.635]], [[1.0, 0.0], [0.0, 0.0]])
    entry = level_of(table).kernels.packed_shot
    (compiled,) = entry.overloads.values()
    hits = sum(entry.stats.cache_hits.values())
    print(model, r.n_events, hits, id(compiled.environment), repr(r.positions.tolist()))
"""


def _levels_run(env: dict[str, str], *models: str) -> list[list[str]]:
    proc = subprocess.run(
        [sys.executable, "-c", LEVELS, *models],
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stderr
    return [line.split(" ", 4) for line in proc.stdout.splitlines()]


def test_both_levels_load_from_caches_written_by_separate_processes(tmp_path: Path) -> None:
    """Each level's entry points compiled by a process of its own, then both loaded by one.

    numba names a compiled function's environment (the constants its machine code reads,
    such as the dtypes of the arrays it returns) after the function's qualified name, its
    argument types and a per-process counter, and a process loading two cached functions
    of one such name gives both the environment loaded first. The levels' entries are one
    closure per level: with one qualified name for both, the roll process and the spin
    process each named ``packed_shot``'s environment alike, and a process loading both ran
    the spin level's code on the roll level's constants (``SystemError ... 'descr' is
    NULL`` where their constants differed).
    """
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    alone = [_levels_run(env, "roll")[0], _levels_run(env, "spin")[0]]
    together = _levels_run(env, "roll", "spin")
    assert [row[0] for row in together] == ["roll", "spin"]
    for row, single in zip(together, alone, strict=True):
        assert row[1] == single[1] and row[4] == single[4]  # the same events and final state
        assert row[2] == "1"  # loaded from the cache the single-level process wrote
    assert together[0][3] != together[1][3], "the levels' loaded code shares one environment"


# The cache key: the folder's name hashes the sources of jit.KERNEL_MODULES, found in the
# sources (jit.kernel_modules: kernels packages, modules compiling through jit, what they
# import), so that an edit of any module with compiled code (or of constants compiled into it)
# starts a fresh cache; a module missing from the key would let a stale kernel load. The
# import graph (grimp) is the independent reading checked here.


def test_every_compiled_module_is_in_the_cache_key() -> None:
    """The list holds every module that compiles, every kernels module, and all they import."""
    graph = grimp.build_graph("pool_env", cache_dir=None)
    listed = set(jit.KERNEL_MODULES)
    compiling = set()
    for decorators in ("pool_env.sim.jit",):
        if decorators in graph.modules:
            compiling |= graph.find_modules_that_directly_import(decorators)
    kernels = {
        m
        for package in ("pool_env.sim.kernels", "pool_env.game.kernels")
        for m in graph.find_descendants(package)
    }
    assert compiling, "no module compiles through pool_env.sim.jit?"
    # Packages' __init__ files hold docstrings only (each model level is a package).
    package_init = {"pool_env", "pool_env.sim", "pool_env.sim.kernels", "pool_env.game.kernels"}
    package_init |= {"pool_env.sim.kernels.roll", "pool_env.sim.kernels.spin"}
    assert not (compiling | kernels) - listed - package_init
    imported = {i for m in listed for i in graph.find_modules_directly_imported_by(m)}
    inside = {m for m in imported if m.startswith("pool_env.")} - package_init
    assert not inside - listed, "a compiled module reads a module the key does not hash"
    for module in listed:
        assert jit.module_file(PACKAGE.parent, module).is_file(), module


def test_the_key_changes_with_every_listed_module_and_no_other(tmp_path: Path) -> None:
    """Editing any one listed file gives a new key; editing a file not listed does not."""
    shutil.copytree(PACKAGE, tmp_path / "pool_env", ignore=shutil.ignore_patterns("__pycache__"))
    key = jit.source_hash(tmp_path)
    assert key == jit.source_hash(PACKAGE.parent)  # the key reads the sources only
    assert jit.CACHE_FOLDER is None or jit.CACHE_FOLDER.name.endswith(key)
    keys = {key}
    for module in jit.KERNEL_MODULES:
        path = jit.module_file(tmp_path, module)
        source = path.read_bytes()
        path.write_bytes(source + b"\n")  # any edit, a blank line too, is a new key
        keys.add(jit.source_hash(tmp_path))
        path.write_bytes(source)
    assert len(keys) == len(jit.KERNEL_MODULES) + 1
    assert jit.source_hash(tmp_path) == key
    (tmp_path / "pool_env" / "envs" / "env.py").write_text("# not compiled\n")
    assert jit.source_hash(tmp_path) == key
    jit.module_file(tmp_path, jit.KERNEL_MODULES[-1]).unlink()
    with pytest.raises(RuntimeError, match="has no file"):
        jit.source_hash(tmp_path)
