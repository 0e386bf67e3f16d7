"""The notice printed while a first compile takes long: once, only when it takes long."""

from __future__ import annotations

import io
import subprocess
import sys
from pathlib import Path
from typing import Any

import numba
from numba.core import event

from pool_env.sim.compile_notice import CompileNotice

ROOT = Path(__file__).resolve().parents[2]


def _fresh_kernel(module: str) -> Any:  # a numba dispatcher
    def probe(x: float) -> float:
        total = 0.0
        for i in range(10):
            total += x * i
        return total

    probe.__module__ = module
    return numba.njit(cache=False)(probe)


def _compile_with(notice: CompileNotice, module: str) -> None:
    with event.install_listener("numba:compile", notice):
        _fresh_kernel(module)(1.5)


def test_a_long_compile_of_ours_prints_one_line_once() -> None:
    stream = io.StringIO()
    notice = CompileNotice(Path("/cache"), delay=0.0, stream=stream)
    _compile_with(notice, "pool_env.sim.kernels.probe")
    _compile_with(notice, "pool_env.sim.kernels.probe")
    lines = stream.getvalue().splitlines()
    assert notice.said
    assert len(lines) == 1
    assert "once" in lines[0] and "/cache" in lines[0]


def test_a_short_compile_prints_nothing() -> None:
    stream = io.StringIO()
    notice = CompileNotice(None, delay=60.0, stream=stream)
    _compile_with(notice, "pool_env.sim.kernels.probe")
    assert stream.getvalue() == "" and not notice.said


def test_other_packages_compiles_print_nothing() -> None:
    stream = io.StringIO()
    notice = CompileNotice(None, delay=0.0, stream=stream)
    _compile_with(notice, "somebody_else.kernels")
    assert stream.getvalue() == "" and not notice.said


def test_loading_from_the_cache_prints_nothing() -> None:
    code = (
        "import gymnasium as gym, pool_env;"
        "env = gym.make('pool_env/OneBallRoll-v1'); env.reset(seed=0);"
        "env.step(env.action_space.sample())"
    )
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)  # fill the cache
    again = subprocess.run(
        [sys.executable, "-c", code], check=True, cwd=ROOT, capture_output=True, text=True
    )
    assert "compiling" not in again.stderr
