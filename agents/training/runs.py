"""Run folders: ``runs/<env>/<name>_s<seed>_<steps>_<time>/``, one per training run."""

from __future__ import annotations

import os
import shlex
import sys
import time
from pathlib import Path

_IMPORTED = time.perf_counter()


def run_folder(root: str | Path, env_id: str, name: str, seed: int, n_timesteps: int) -> Path:
    """A new folder ``root/<env>/<name>_s<seed>_<steps>_<time>`` for one run.

    Args:
        root: Parent folder of run folders.
        env_id: The env id (its last part names the env folder).
        name: What trains (``"ppo"``, ``"rllib_ppo"``).
        seed: The run's seed.
        n_timesteps: Training steps.

    Returns:
        The new, empty folder.
    """
    env_name = env_id.split("/")[-1]
    stamp = time.strftime("%Y%m%d-%H%M%S")
    base = Path(root) / env_name / f"{name}_s{seed}_{steps_label(n_timesteps)}"
    path = Path(f"{base}_{stamp}")
    k = 1
    while path.exists():  # two runs in the same second
        path, k = Path(f"{base}_{stamp}-{k}"), k + 1
    path.mkdir(parents=True)
    return path


def process_seconds() -> float:
    """Wall seconds since this process started (imports included), from ``/proc``.

    The figure a user sees from typing ``python train.py``; where ``/proc`` is missing
    (not Linux), the seconds since this module was imported instead.
    """
    try:
        start_ticks = int(Path("/proc/self/stat").read_text().rsplit(")", 1)[1].split()[19])
        uptime = float(Path("/proc/uptime").read_text().split()[0])
        return uptime - start_ticks / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return time.perf_counter() - _IMPORTED


def steps_label(n: int) -> str:
    """``300000`` -> ``"300k"``, ``1000000`` -> ``"1M"``, ``500`` -> ``"500"``."""
    return f"{n // 1_000_000}M" if n % 1_000_000 == 0 else f"{n // 1000}k" if n >= 1000 else str(n)


def write_command(out: Path) -> str:
    """Write the command line of this process to ``out/command.txt``; return it."""
    command = shlex.join([sys.executable, *sys.argv])
    (out / "command.txt").write_text(command + "\n")
    return command
