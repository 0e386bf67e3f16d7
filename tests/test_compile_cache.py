"""Compiled code on disk: shared by concurrent processes, optional on read-only installs.

Each test starts fresh Python processes, because caching is about process start-up.
"""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

import pool_env

PACKAGE = Path(pool_env.__file__).parent

SHOT = """
import hashlib, warnings
warnings.simplefilter("always")
from pool_env import Table, shoot
from pool_env.sim.kernels import loop
from pool_env.sim.layouts import break_scene
t = Table()
r = shoot(t, break_scene(t, "nine"), 0.0, 8.0)
print(hashlib.sha256(r.positions.tobytes()).hexdigest(), r.n_events)
print("cache_hits", sum(loop.run_shot.stats.cache_hits.values()))
"""


def _run(env: dict[str, str], **kwargs) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-c", SHOT],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        **kwargs,
    )


def test_concurrent_cold_starts_share_one_cache(tmp_path: Path) -> None:
    """Three workers compiling into one empty cache at once all succeed and agree."""
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"))
    procs = [_run(env) for _ in range(3)]
    outputs = [p.communicate(timeout=600) for p in procs]
    for proc, (_, err) in zip(procs, outputs, strict=True):
        assert proc.returncode == 0, err
    digests = {out.splitlines()[0] for out, _ in outputs}
    assert len(digests) == 1
    # A fourth process loads the kernels from the cache the others wrote.
    out, err = _run(env).communicate(timeout=600)
    assert out.splitlines()[0] in digests, err
    assert int(out.splitlines()[1].split()[1]) > 0  # loaded from disk, not compiled


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
