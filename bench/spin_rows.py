"""The spin level's rows of the speed-against-error benchmark: pool_env and pooltool 0.6.0.

Both run the seeded struck shots of :mod:`bench.spin_scenes` (side and vertical tip offsets,
sometimes an elevated cue, 1-3 collisions, pocketless table) on equal physics, configured as
:mod:`bench.spin_vs_pooltool` configures them (:func:`~bench.spin_scenes.worker_scene`:
the same ball, cloth, throw, cushion and strike models and parameters); each is timed and
its final positions compared with the 50-digit reference
(:mod:`pool_env.testing.spin_reference`). pooltool runs as released and with its collision
spacer ``MIN_DIST`` at 1e-12 m (the spacer is the whole of its difference from the
reference: ``results/spin_vs_pooltool.md``).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from bench.engines.pooltool_engine import DEFAULT_VENV, run_pooltool
from bench.report import fmt_len, fmt_time
from bench.spin_scenes import SpinShot, spin_shots, spin_table, worker_scene
from bench.spin_vs_pooltool import TARGET, final_distance, ours, time_ours


@dataclass
class SpinRow:
    """One method over the spin shots.

    Attributes:
        method: Row label.
        engine: ``pool_env`` or ``pooltool``.
        times: Wall seconds per shot (median over repeats).
        errors: Per shot, the largest distance (m) between a ball's final centre and the
            reference's.
    """

    method: str
    engine: str
    times: list[float] = field(default_factory=list)
    errors: list[float] = field(default_factory=list)


@dataclass
class SpinSuite:
    """The spin rows of one run and what they ran on.

    Attributes:
        rows: pool_env first, then pooltool's if it ran.
        shots: Number of shots.
        pooltool: pooltool's run info (``available``, version, ``reason`` if not).
        load: The 1-minute load average before and after the timed runs.
    """

    rows: list[SpinRow]
    shots: int
    pooltool: dict[str, Any]
    load: tuple[float, float]


def run_spin_suite(
    n_shots: int, repeats: int, use_pooltool: bool = True, venv: Path = DEFAULT_VENV
) -> SpinSuite:
    """Time pool_env's spin level and pooltool on ``n_shots`` seeded shots; errors vs the reference.

    Args:
        n_shots: Shots (seeded; the reference is computed for each, about 0.1 s a shot).
        repeats: Timed calls per shot (the median is kept).
        use_pooltool: Run pooltool (in its virtualenv, see ``bench/setup_pooltool.sh``).
        venv: pooltool's virtualenv.

    Returns:
        The :class:`SpinSuite`; without pooltool its rows are pool_env's only and
        ``pooltool["reason"]`` says why.

    Raises:
        ValueError: On fewer than one shot or repeat.
    """
    if n_shots < 1 or repeats < 1:
        raise ValueError(f"n_shots and repeats must be >= 1, got {n_shots}, {repeats}")
    table = spin_table()
    shots = spin_shots(n_shots, table=table)
    load0 = os.getloadavg()[0]
    rows = []
    for record in (False, True):
        row = SpinRow(f"pool_env spin level (record={record})", "pool_env")
        row.times = [wall for wall, _, _ in time_ours(table, shots, repeats, record=record)]
        row.errors = [_error(ours(table, s, record=record).positions, s) for s in shots]
        rows.append(row)
    info: dict[str, Any] = {"available": False, "reason": "disabled with --no-pooltool"}
    if use_pooltool:
        scenes = [worker_scene(table, s) for s in shots]
        for label, min_dist in (("", None), (", MIN_DIST 1e-12", 1e-12)):
            out = run_pooltool(scenes, repeats=repeats, max_events=5000, venv=venv,
                               min_dist=min_dist)  # fmt: skip
            if not out.get("available"):
                info = out
                break
            info = out
            row = SpinRow(f"pooltool {out['pooltool']} (equal physics{label})", "pooltool")
            for r, s in zip(out["results"], shots, strict=True):
                failed = bool(r.get("error"))
                row.times.append(float(np.median(r["times"])) if not failed else np.nan)
                row.errors.append(np.nan if failed else _error(r["positions"], s))
            rows.append(row)
    return SpinSuite(rows, len(shots), info, (load0, os.getloadavg()[0]))


def _error(positions: Any, shot: SpinShot) -> float:
    return final_distance(positions, shot.ref_positions)


def _quantiles(values: list[float]) -> tuple[float, float, float]:
    v = np.asarray(values, dtype=np.float64)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return (np.nan, np.nan, np.nan)
    return float(np.median(v)), float(np.percentile(v, 95)), float(v.max())


def spin_table_lines(suite: SpinSuite) -> list[str]:
    """The markdown table of the spin rows (time relative to pool_env's ``record=False``)."""
    base = float(np.median(suite.rows[0].times))
    lines = [
        "| method | shots | time/shot median | p95 | x pool_env | final-position error median "
        "| p95 | max | within 1e-6 m |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for row in suite.rows:
        t_med, t95, _ = _quantiles(row.times)
        e_med, e95, e_max = _quantiles(row.errors)
        within = int(np.sum(np.asarray(row.errors) <= TARGET))
        lines.append(
            f"| {row.method} | {len(row.times)} | {fmt_time(t_med)} | {fmt_time(t95)} | "
            f"{t_med / base:.3g} | {fmt_len(e_med)} | {fmt_len(e95)} | {fmt_len(e_max)} | "
            f"{within} ({100.0 * within / len(row.errors):.1f}%) |"
        )
    return lines


def spin_section(suite: SpinSuite, command: str, date: str, commit: str) -> list[str]:
    """The report's spin section: how it was run, the table and what it shows."""
    pt = suite.pooltool
    lines = [
        "## Spin level: pool_env and pooltool on equal physics",
        "",
        f"Generated by `{command}` on {date} (commit {commit}); 1-minute load average "
        f"{suite.load[0]:.2f} before the timed runs, {suite.load[1]:.2f} after. "
        f"{suite.shots} seeded struck shots (`bench/spin_scenes.py`, as "
        "`results/spin_vs_pooltool.md`: 2-4 balls on a pocketless table, the cue ball struck "
        "at 0.4-3 m/s with tip offsets up to 0.5 R sideways and 0.6 R vertically, an "
        "elevated cue on 40% of them; kept when the reference counts 1-3 collisions), run "
        'by pool_env\'s `Table(model="spin")` (`shoot(..., tip=, elevation=)`) and by '
        "pooltool from the same strike with the same models and parameters "
        "(`bench/spin_scenes.worker_scene`). Errors are each shot's largest distance "
        "between a ball's final centre and the 50-digit spin reference's "
        "(`pool_env/testing/spin_reference.py`); times are wall-clock medians over shots of "
        "each shot's median call (pooltool: `pooltool.simulate` alone, in its own "
        "virtualenv).",
        "",
        *spin_table_lines(suite),
        "",
        "![spin level: time per shot against error](speed_vs_error_spin.png)",
        "",
    ]
    if pt.get("available"):
        lines.append(
            "pooltool's error as released is its collision spacer (`MIN_DIST` = 1e-6 m: it "
            "backs the balls apart before each impact without moving the clock); with the "
            "spacer at 1e-12 m the same shots agree with the reference a million times "
            "closer, so both codes implement the same physics and the time column compares "
            "equal work."
        )
    else:
        lines.append(f"pooltool did not run: {pt.get('reason', 'unknown reason')}.")
    return lines


def spin_plot(suite: SpinSuite, path: Path) -> None:
    """Time per shot against final-position error (log-log), a point per method."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.2), dpi=90)
    floor = 1e-16
    styles = {"pool_env": ("tab:blue", "o"), "pooltool": ("tab:red", "s")}
    for row in suite.rows:
        (e_med, e95, _), (t_med, _, _) = _quantiles(row.errors), _quantiles(row.times)
        if not (np.isfinite(e_med) and np.isfinite(t_med)):
            continue
        colour, marker = styles[row.engine]
        fill = "none" if "record=True" in row.method or "MIN_DIST" in row.method else colour
        x, hi = max(e_med, floor), max(e95, floor)
        ax.errorbar(
            [x],
            [t_med],
            xerr=[[0.0], [hi - x]],
            color=colour,
            marker=marker,
            markerfacecolor=fill,
            linestyle="none",
            capsize=2,
            label=row.method,
        )
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("final-position error vs 50-digit spin reference (m): median, bar to p95")
    ax.set_ylabel("wall time per shot, median (s)")
    ax.set_title(f"spin level, {suite.shots} struck shots (1-3 collisions)")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=7, loc="center right")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
