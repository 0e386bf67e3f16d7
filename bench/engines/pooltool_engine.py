"""Drive pooltool in its own virtualenv through :mod:`bench.engines.pooltool_worker`.

pooltool 0.6.0 pins numba/llvmlite versions that would downgrade this project's, so it lives
in ``.bench-venvs/pooltool`` (made by ``bench/setup_pooltool.sh``) and runs as a subprocess
that reads scenes as JSON and prints results as JSON. pooltool writes its config under
``$HOME/.config`` on import, so the subprocess gets a scratch ``HOME``.
"""

from __future__ import annotations

import json
import os
import subprocess
import tempfile
from pathlib import Path
from typing import Any

from pool_env import Table

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_VENV = ROOT / ".bench-venvs" / "pooltool"
WORKER = Path(__file__).with_name("pooltool_worker.py")


def table_spec(table: Table) -> dict[str, Any]:
    """The worker's description of ``table`` (pooltool uses its own pocket geometry)."""
    return {
        "length": table.length,
        "width": table.width,
        "ball_radius": table.ball_radius,
        "ball_mass": table.ball_mass,
        "mu_roll": table.mu_roll,
        "g": table.g,
        "e_ball": table.e_ball,
        "e_cushion": table.e_cushion,
        "pockets": table.n_pockets > 0,
    }


def pooltool_python(venv: Path = DEFAULT_VENV) -> Path | None:
    """The pooltool virtualenv's interpreter, or None if it is not installed."""
    python = venv / "bin" / "python"
    return python if python.exists() else None


def run_pooltool(
    scenes: list[dict[str, Any]],
    repeats: int = 3,
    max_events: int = 5000,
    timeout: float = 60.0,
    total_timeout: float = 1800.0,
    venv: Path = DEFAULT_VENV,
    min_dist: float | None = None,
) -> dict[str, Any]:
    """Run ``scenes`` through pooltool in a subprocess.

    Args:
        scenes: Worker scene dicts (``table``, ``positions``, ``velocities``, ``obj``).
        repeats: Timed runs per scene.
        max_events: pooltool's event cap (0: none).
        timeout: Seconds per simulation before the worker reports a hang.
        total_timeout: Seconds for the whole subprocess.
        venv: The pooltool virtualenv.
        min_dist: Replaces pooltool's collision spacer ``constants.MIN_DIST`` (1e-6 m).

    Returns:
        The worker's JSON output with ``available: True``, or ``{"available": False,
        "reason": ...}`` if pooltool is missing or the worker failed.
    """
    job = {
        "repeats": repeats,
        "max_events": max_events,
        "timeout": timeout,
        "scenes": scenes,
        "min_dist": min_dist,
    }
    return run_worker(WORKER, job, total_timeout, venv)


def run_worker(
    worker: Path, job: dict[str, Any], total_timeout: float = 1800.0, venv: Path = DEFAULT_VENV
) -> dict[str, Any]:
    """Run a worker script in pooltool's virtualenv: ``job`` as JSON on stdin, JSON back.

    Args:
        worker: The script (it imports pooltool, nothing of this project).
        job: Its input document.
        total_timeout: Seconds for the whole subprocess.
        venv: The pooltool virtualenv.

    Returns:
        The worker's JSON output with ``available: True``, or ``{"available": False,
        "reason": ...}`` if pooltool is missing or the worker failed.
    """
    python = pooltool_python(venv)
    if python is None:
        return {
            "available": False,
            "reason": f"no pooltool virtualenv at {venv} (run bash bench/setup_pooltool.sh)",
        }
    with tempfile.TemporaryDirectory(prefix="pooltool-home-") as home:
        env = {**os.environ, "HOME": home, "PYTHONNOUSERSITE": "1"}
        env.pop("PYTHONPATH", None)
        try:
            proc = subprocess.run(
                [str(python), str(worker)],
                input=json.dumps(job),
                capture_output=True,
                text=True,
                env=env,
                timeout=total_timeout,
                check=False,
            )
        except subprocess.TimeoutExpired:
            return {"available": False, "reason": f"worker timed out after {total_timeout} s"}
    if proc.returncode != 0:
        tail = proc.stderr.strip().splitlines()[-3:]
        return {"available": False, "reason": f"worker exit {proc.returncode}: {' | '.join(tail)}"}
    try:
        out = json.loads(proc.stdout)
    except json.JSONDecodeError as exc:
        return {"available": False, "reason": f"unreadable worker output: {exc}"}
    out["available"] = True
    return out
