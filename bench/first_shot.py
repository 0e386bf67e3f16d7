"""A newcomer's first shot: the README's quick start in a fresh clone, from an empty cache.

Clones this repository's committed ``HEAD`` into a temporary folder (no compiled kernels,
no ``__pycache__``), then runs the README's first Python block (the quick start:
``gym.make`` + ``reset`` + ``step`` + ``render``) in a fresh interpreter of this venv with the
clone first on ``sys.path``, three ways: after the README's install, whose last part,
``python -m pool_env.precompile``, compiles every kernel from an empty cache (its seconds
are the install's added time); from an empty cache with no precompile (what a user who
skips it waits); and again with the cache that run wrote. Each run reports, from inside
the child, the seconds spent importing, making, resetting and stepping, and, from outside,
the seconds from spawn to the first line on standard error (the compile notice,
:mod:`pool_env.sim.compile_notice`) and to the end.

    python -m bench.first_shot --runs 3

Writes ``results/first_shot.md``. CPU-heavy (each cold run compiles for tens of seconds,
each precompile for about a minute): run it alone on the machine.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "results" / "first_shot.md"

# Timestamps around each phase of the quick start, printed by the child.
PROLOGUE = "import time as _t\n_t0 = _t.perf_counter()\n"
PHASES = {  # a line of the quick start that starts a phase -> the phase's name
    "import gymnasium": "import",
    "env = gym.make": "make",
    "obs, info = env.reset": "reset",
    "obs, reward, terminated": "step",
    "frame = env.render": "render",
}


def quick_start() -> str:
    """The README's first Python block, with a timestamp printed after each phase."""
    text = (ROOT / "README.md").read_text()
    block = re.search(r"```python\n(.*?)```", text, re.S)
    if block is None:
        raise RuntimeError("README.md has no python block")
    lines, current = [PROLOGUE], None
    for line in block.group(1).splitlines():
        phase = next((name for start, name in PHASES.items() if line.startswith(start)), None)
        if phase is not None and current is not None and phase != current:
            lines.append(f"print('phase', {current!r}, _t.perf_counter() - _t0)")
        current = phase or current
        lines.append(line)
    lines.append(f"print('phase', {current!r}, _t.perf_counter() - _t0)")
    return "\n".join(lines) + "\n"


def run_once(clone: Path, code: str, cache: Path) -> dict[str, float]:
    """Run ``code`` in a fresh interpreter; the phases' end times and the spawn-to-X times."""
    env = dict(os.environ, PYTHONPATH=str(clone), NUMBA_CACHE_DIR=str(cache))
    start = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, "-c", code],
        cwd=clone,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stderr is not None
    first_err = proc.stderr.readline()
    first_err_at = time.perf_counter() - start if first_err else float("nan")
    out, err = proc.communicate(timeout=900)
    total = time.perf_counter() - start
    if proc.returncode != 0:
        raise RuntimeError(f"quick start failed:\n{first_err}{err}")
    figures = {"wall": total, "first stderr line": first_err_at}
    previous = 0.0
    for line in out.splitlines():
        if line.startswith("phase "):
            _, name, seconds = line.split()
            figures[name.strip("'")] = float(seconds) - previous
            previous = float(seconds)
    figures["notice"] = 1.0 if "compiling" in first_err else 0.0
    return figures


def precompile(clone: Path, cache: Path) -> float:
    """Seconds ``python -m pool_env.precompile`` takes in ``clone`` into ``cache``."""
    env = dict(os.environ, PYTHONPATH=str(clone), NUMBA_CACHE_DIR=str(cache))
    start = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "pool_env.precompile", "--quiet"],
        cwd=clone,
        env=env,
        check=True,
        capture_output=True,
        timeout=1800,
    )
    return time.perf_counter() - start


def head_commit() -> str:
    """This repository's ``HEAD``, short."""
    return subprocess.run(
        ["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True
    ).stdout.strip()


def publish(lines: list[str], out: Path) -> None:
    """Print the report's ``lines`` and write them to ``out``."""
    report = "\n".join(lines) + "\n"
    print(report)
    out.write_text(report)


def main(argv: list[str] | None = None) -> int:
    """Clone, run cold and warm ``--runs`` times each, print and write the table."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=3, help="cold and warm runs of each kind")
    args = parser.parse_args(argv)
    code = quick_start()
    head = head_commit()
    after_install = "after the install (`python -m pool_env.precompile`)"
    rows: dict[str, list[dict[str, float]]] = {
        after_install: [],
        "empty cache, no precompile": [],
        "warm cache": [],
    }
    added: list[float] = []
    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as scratch:
        for run in range(args.runs):
            clone = Path(scratch) / f"clone{run}"
            subprocess.run(["git", "clone", "-q", str(ROOT), str(clone)], check=True)
            installed = Path(scratch) / f"installed{run}"
            added.append(precompile(clone, installed))
            rows[after_install].append(run_once(clone, code, installed))
            cache = Path(scratch) / f"cache{run}"
            rows["empty cache, no precompile"].append(run_once(clone, code, cache))
            rows["warm cache"].append(run_once(clone, code, cache))
    load_after = os.getloadavg()[0]
    names = ["import", "make", "reset", "step", "render", "wall", "first stderr line"]
    lines = [
        "# A newcomer's first shot: the README's quick start, from an empty compile cache",
        "",
        f"Command: `python -m bench.first_shot --runs {args.runs}` at `{head}`, "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load {load_before:.1f} "
        f"before and {load_after:.1f} after. Each run is a fresh clone of the commit (no "
        "compiled kernels, no `__pycache__`) and a fresh interpreter of the same venv; the "
        "warm run follows its cold run with the cache that run wrote. Medians of the runs, "
        "in seconds: each phase of the quick start as the child timed it, then from spawn "
        "to the end and to the first line on standard error (the compile notice).",
        "",
        f"The install's added time, `python -m pool_env.precompile` from an empty cache "
        f"(every kernel of every id, {os.cpu_count()} processes): "
        f"{statistics.median(added):.1f} s (median; runs: "
        + ", ".join(f"{a:.1f}" for a in added)
        + ").",
        "",
        "| cache | " + " | ".join(names) + " | notice printed |",
        "|---" * (len(names) + 2) + "|",
    ]
    for kind, runs in rows.items():
        cells = [f"{statistics.median(r.get(n, float('nan')) for r in runs):.2f}" for n in names]
        said = sum(int(r["notice"]) for r in runs)
        lines.append(f"| {kind} | " + " | ".join(cells) + f" | {said} of {len(runs)} |")
    publish(lines, OUT)
    return 0


if __name__ == "__main__":
    sys.exit(main())
