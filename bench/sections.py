"""Report sections for the breaks (outcome statistics, perturbation growth) and hard cases."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np

from bench.engines.fixed_step import simulate_fixed_step
from bench.errors import ReferenceCache, ours_outcome, position_error
from bench.report import Metrics, fmt_len, fmt_time
from bench.runners import Run, fixed_outcome, pooltool_outcome, pymunk_outcome, worker_scene
from pool_env import simulate
from pool_env.sim.layouts import break_scene
from tools.chaos import Growth, ours_growth, reference_growth
from tools.hard_cases import HardCase, check, hard_cases
from tools.shots import Outcome, Scene


def breaks_table(rows: list[Metrics], runs: list[Run], refs: list[Outcome]) -> list[str]:
    """Markdown lines: time per break and outcome statistics (no accuracy claim)."""
    out = [
        "| method | breaks | time/break median | p95 | x ours | balls potted per break (mean) "
        "| breaks potting a ball | same pots as reference | final-position difference "
        "vs reference, median |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    ref_pots = [int(np.count_nonzero(r.pocketed >= 0)) for r in refs if r.error is None]
    out.append(
        f"| 50-digit reference | {len(ref_pots)} | | | | {np.mean(ref_pots):.2f} | "
        f"{100 * np.mean([p > 0 for p in ref_pots]):.0f}% | | |"
    )
    for m, run in zip(rows, runs, strict=True):
        ok = [o for o in run.outcomes if o.error is None]
        pots = [int(np.count_nonzero(o.pocketed >= 0)) for o in ok]
        fails = len(run.outcomes) - len(ok) + sum(o.capped for o in ok)
        out.append(
            f"| {m.method}{'*' if m.note else ''} | {m.n}{f' ({fails} failed)' if fails else ''}"
            f" | {fmt_time(m.t_med)} | {fmt_time(m.t_p95)} | {m.ratio:.3g} | "
            f"{np.mean(pots) if pots else math.nan:.2f} | "
            f"{100 * np.mean([p > 0 for p in pots]) if pots else math.nan:.0f}% | "
            f"{100 * m.agree:.0f}% | {fmt_len(m.pos[0])} |"
        )
    return out


def spaced(scene: Scene, gap: float = 1e-4) -> Scene:
    """The same break with the rack balls ``gap`` apart (every impact at its own instant)."""
    rack = "nine" if scene.n_balls == 10 else "eight"
    pos = break_scene(scene.table, rack, gap)
    pos[0] = scene.positions[0]
    return dataclasses.replace(scene, name=scene.name + "-spaced", positions=pos)


def chaos_rows(breaks: list[Scene]) -> list[str]:
    """Markdown lines: growth of a 1e-12 m perturbation per collision, touching and spaced."""
    out = [
        "| rack | breaks | growth per collision, ours (median) | reference (median) | "
        "collisions until 1 mm, ours (median) | reference (median) | float64 vs 50 digits: "
        "collisions until 1 mm apart (median) |",
        "|---|---:|---:|---:|---:|---:|---:|",
    ]
    for label, scenes in (
        ("touching (gap 0)", breaks),
        ("spaced (gap 0.1 mm)", [spaced(s) for s in breaks]),
    ):
        ours = [ours_growth(s) for s in scenes]
        refs = [reference_growth(s) for s in scenes]
        out.append(
            f"| {label} | {len(scenes)} | {_factor(ours)} | {_factor([r[0] for r in refs])} | "
            f"{_to_mm(ours)} | {_to_mm([r[0] for r in refs])} | {_to_mm([r[1] for r in refs])} |"
        )
    return out


def _factor(gs: list[Growth]) -> str:
    f = [g.factor for g in gs if math.isfinite(g.factor)]
    return f"{np.median(f):.3g}" if f else "n/a"


def _to_mm(gs: list[Growth]) -> str:
    never = sum(g.to_mm is None for g in gs)
    vals = [g.to_mm if g.to_mm is not None else math.inf for g in gs]
    med = np.median(vals)
    txt = "never" if not math.isfinite(med) else f"{med:g}"
    return f"{txt} ({never} of {len(gs)} never)" if never else txt


HARD_CONFIGS: list[tuple[str, str, float | None]] = [
    ("this simulator", "ours", None),
    ("fixed-step 1e-3", "fixed-step", 1e-3),
    ("fixed-step 1e-5", "fixed-step", 1e-5),
    ("pymunk 1/60", "pymunk", 1 / 60),
    ("pymunk 1e-4", "pymunk", 1e-4),
    ("pooltool", "pooltool", None),
]


def _run_hard(case: HardCase, engine: str, dt: float | None) -> tuple[Outcome, float]:
    s = case.scene
    try:
        if engine == "ours":
            res = simulate(s.table, s.positions, s.velocities, s.masses, max_events=100_000)
            return ours_outcome(res, s.obj), 0.0
        if engine == "fixed-step":
            raw = simulate_fixed_step(
                s.table.params,
                s.table.pockets,
                s.positions,
                s.velocities,
                s.mass_array(),
                dt,
                s.obj,
                max_time=400.0,
            )
            return fixed_outcome(raw), raw[6]
        from bench.engines.pymunk_engine import simulate_pymunk

        res = simulate_pymunk(
            s.table,
            s.positions,
            s.velocities,
            s.masses,
            dt,
            s.obj,
            max_time=400.0,
            diagnostics=True,
        )
        return pymunk_outcome(res), res.max_overlap
    except Exception as exc:  # a crash is a result
        n = s.n_balls
        return Outcome(
            np.full((n, 2), np.nan),
            np.full(n, -2),
            np.full(2, np.nan),
            error=f"{type(exc).__name__}: {exc}",
        ), math.nan


def hard_section(cache: ReferenceCache, pooltool: Any, use_pymunk: bool) -> list[str]:
    """Markdown lines: which engine survives which hard case, and final-position errors.

    Args:
        cache: Reference outcomes.
        pooltool: ``run_pooltool``-like callable taking worker scenes, or None to skip.
        use_pymunk: Whether pymunk is available.
    """
    cases = hard_cases()
    configs = [c for c in HARD_CONFIGS if use_pymunk or c[1] != "pymunk"]
    pt_results: list[dict] | None = None
    pt_reason = ""
    if pooltool is not None:
        info = pooltool([worker_scene(c.scene) for c in cases])
        if info.get("available"):
            pt_results = info["results"]
        else:
            pt_reason = info.get("reason", "")
    if pt_results is None:
        configs = [c for c in configs if c[1] != "pooltool"]
    head = "| case | " + " | ".join(c[0] for c in configs) + " |"
    rule = "|---|" + "---|" * len(configs)
    survive, errors = [head, rule], [head, rule]
    for ci, case in enumerate(cases):
        ref = cache.get(case.scene)
        mark = ""
        if ref.error is not None:  # e.g. sustained contact: compare with ours instead
            res = simulate(
                case.scene.table,
                case.scene.positions,
                case.scene.velocities,
                case.scene.masses,
                max_events=100_000,
            )
            ref, mark = ours_outcome(res, case.scene.obj), "*"
        cells, errs = [], []
        for _, engine, dt in configs:
            if engine == "pooltool":
                out = pooltool_outcome(case.scene, pt_results[ci])
            else:
                out, _ = _run_hard(case, engine, dt)
            tags = check(case, out, jaws=engine == "pooltool")
            cells.append(", ".join(tags) if tags else "ok")
            err = position_error(out.positions, ref.positions) if out.error is None else math.nan
            errs.append(fmt_len(err) + ("" if engine != "pooltool" else " (spin)"))
        survive.append(f"| {case.scene.name} | " + " | ".join(cells) + " |")
        errors.append(f"| {case.scene.name}{mark} | " + " | ".join(errs) + " |")
    lines = [
        "#### Survival (failure tags; `ok` = none)",
        "",
        *survive,
        "",
        "#### Final-position error against the reference (`*`: the reference refuses the "
        "case, compared with this simulator)",
        "",
        *errors,
    ]
    if pt_reason:
        lines += ["", f"pooltool not run: {pt_reason}"]
    return lines
