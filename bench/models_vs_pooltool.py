"""Stronge's cushions, Mathavan's ball-ball model and the pooltool preset, beside pooltool 0.6.0.

Run (pooltool from ``bash bench/setup_pooltool.sh``)::

    python -m bench.models_vs_pooltool             # 200 shots each -> results/models_vs_pooltool.md
    python -m bench.models_vs_pooltool --shots 20  # smoke run (prints, writes nothing)
    python -m bench.models_vs_pooltool --time      # cost per shot against the default level
    python -m bench.models_vs_pooltool --differences  # how far each model moves a shot

Three comparisons, pooltool in its own virtualenv (:mod:`bench.engines.pooltool_worker`) with
its collision spacer ``MIN_DIST`` shrunk to 1e-12 m (as :mod:`bench.spin_vs_pooltool`):

* ``stronge``: the seeded shots of :mod:`bench.spin_scenes` (1-3 collisions in the Han
  reference; a cue strike with english, draw and elevation; pocketless table) on
  ``Table(model="spin", pockets="none", cushion_model="stronge")`` against pooltool with
  ``StrongeCompliantLinear/Circular(omega_ratio=1.8)``, all else as the equal-model bench.
* ``mathavan``: the same shots on ``ball_model="mathavan"`` against pooltool's
  ``FrictionalMathavan`` (1000 steps, the same Alciatore friction fit).
* ``preset``: pooltool shots at its own defaults (default resolver, ball and cue
  parameters) on a pocketless table of its pocket table's size and cushion height: balls
  placed at random, a stroke ``V0, phi, theta, a, b`` drawn in pooltool's terms, then
  ported by :func:`pool_env.interop.pooltool.cue_from_pooltool` onto
  ``Table.preset("pooltool-0.6", pockets="none")``; shots kept with 1-3 collisions in
  pool_env's run.

Reported per comparison: the per-shot largest final-position difference over the balls
(median, 95th percentile, max, shots within 1e-6 m) and the worst shots' event sequences.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from pathlib import Path
from typing import Any

import numpy as np

from bench.engines.pooltool_engine import run_pooltool
from bench.spin_scenes import SpinShot, spin_shots, worker_scene
from bench.spin_vs_pooltool import final_distance, ours, row, stats, time_ours
from pool_env import Table
from pool_env.interop.pooltool import cue_from_pooltool
from pool_env.testing.scenes_random import random_layout

ROOT = Path(__file__).resolve().parents[1]
SPACER = 1e-12  # pooltool's MIN_DIST for the comparisons (m)


def model_table(name: str) -> Table:
    """The pocketless spin table of one comparison."""
    if name == "preset":
        return Table.preset("pooltool-0.6", pockets="none")
    options = {"stronge": {"cushion_model": "stronge"}, "mathavan": {"ball_model": "mathavan"}}
    return Table(model="spin", pockets="none", **options.get(name, {}))  # type: ignore[arg-type]


def model_scene(table: Table, shot: SpinShot, name: str) -> dict[str, Any]:
    """The worker's scene of a shot for one comparison."""
    # Mathavan integrates friction itself: pooltool's fit unscaled (the frictional model's
    # impulse rule does not enter); the frictional model keeps the equal-model scaling.
    scene = worker_scene(table, shot, throw="pooltool" if name == "mathavan" else "coulomb")
    scene["table"] |= {
        "cushion_model": table.cushion_model,
        "cushion_omega_ratio": table.cushion_omega_ratio,
        "ball_model": table.ball_model,
        "mathavan_steps": table.mathavan_steps,
    }
    return scene


def preset_shots(table: Table, n: int, seed: int = 23) -> list[tuple[SpinShot, dict[str, float]]]:
    """``n`` pooltool strokes at its defaults with 1-3 collisions in pool_env, and each stroke."""
    rng = np.random.default_rng(seed)
    out: list[tuple[SpinShot, dict[str, float]]] = []
    while len(out) < n:
        k = len(out)
        pos = random_layout(table, int(rng.integers(2, 5)), rng, min_gap=2e-3)
        aim = pos[int(rng.integers(1, len(pos)))] - pos[0]
        angle = math.atan2(aim[1], aim[0]) + float(rng.normal(0.0, 0.15))
        stroke = {
            "V0": float(rng.uniform(0.5, 3.5)),
            "phi": math.degrees(angle) + 90.0,  # pooltool's frame (interop's phi_from_angle)
            "theta": 0.0 if rng.random() < 0.6 else float(rng.uniform(1.0, 15.0)),
            "a": float(rng.uniform(-0.4, 0.4)),
            "b": float(rng.uniform(-0.5, 0.5)),
        }
        try:
            angle, speed, tip, elev = cue_from_pooltool(table, **stroke)
        except ValueError:  # a stroke the mapping refuses (a tip off the ball)
            continue
        shot = SpinShot(f"preset{k}", pos, angle, speed, tip, elev,
                        np.zeros((len(pos), 2)), np.zeros((len(pos), 3)))  # fmt: skip
        res = ours(table, shot)
        impacts = sum(e.kind in ("ball", "cushion") for e in res.events)
        if 1 <= impacts <= 3:
            out.append((shot, stroke))
    return out


def preset_scene(table: Table, shot: SpinShot, stroke: dict[str, float]) -> dict[str, Any]:
    """The worker's scene: pooltool at its defaults, pocketless, the stroke as drawn."""
    n = len(shot.positions)
    keys = ("length", "width", "cushion_height", "ball_radius", "ball_mass")
    spec = {k: getattr(table, k) for k in keys}
    spec |= {"model": "spin", "defaults": "pocketless", "pockets": False, "g": table.g}
    return {
        "table": spec,
        "positions": shot.positions.tolist(),
        "velocities": [[0.0, 0.0]] * n,
        "angular_velocities": [[0.0, 0.0, 0.0]] * n,
        "strike": stroke,
        "obj": 1,
        "masses": None,
    }


def shots_and_scenes(name: str, n: int) -> tuple[Table, list[SpinShot], list[dict[str, Any]]]:
    """The table, shots and worker scenes of one comparison."""
    table = model_table(name)
    if name == "preset":
        pairs = preset_shots(table, n)
        return table, [s for s, _ in pairs], [preset_scene(table, s, k) for s, k in pairs]
    shots = spin_shots(n, table=Table(model="spin", pockets="none"))
    return table, shots, [model_scene(table, s, name) for s in shots]


def compare(name: str, n: int) -> tuple[str, list[tuple[float, str, str, str]]]:
    """One comparison: its table row and its five worst shots (distance, name, events)."""
    table, shots, scenes = shots_and_scenes(name, n)
    out = run_pooltool(scenes, repeats=1, max_events=5000, min_dist=SPACER)
    if not out.get("available"):
        raise SystemExit(f"pooltool did not run: {out.get('reason')}")
    diffs, worst = [], []
    for shot, pt in zip(shots, out["results"], strict=True):
        if pt.get("error"):
            diffs.append(math.inf)
            worst.append((math.inf, shot.name, pt["error"], ""))
            continue
        res = ours(table, shot)
        d = final_distance(res.positions, pt["positions"])
        diffs.append(d)
        mine = " ".join(f"{e.kind}{e.i}{e.j if e.j >= 0 else ''}" for e in res.events
                        if e.kind in ("ball", "cushion"))  # fmt: skip
        theirs = " ".join(
            ("ball" + "".join(map(str, ids))) if "ball_ball" in kind else f"cushion{ids[0]}"
            for _, kind, ids in pt["events"] if "ball_ball" in kind or "cushion" in kind
        )  # fmt: skip
        worst.append((d, shot.name, mine, theirs))
    return row(name, stats(diffs)), sorted(worst, reverse=True)[:5]


def time_mode(n: int, repeats: int) -> list[str]:
    """Median per-shot time of each model against the default spin level, same shots.

    Stronge and Mathavan on the shots of :mod:`bench.spin_scenes`; the preset on its own
    shots (pooltool's 7-ft table), against ``Table(model="spin", pockets="none")`` of the
    preset's size (the default models: Han, the frictional impulse with Coulomb's rule).
    """
    load = os.getloadavg()[0]
    stamp = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    lines = [
        f"load {load:.2f}; {stamp}; {n} shots per set, median of {repeats} calls each",
        "| table | shots | default level, median | this table, median | ratio: median of "
        "per-shot | ratio of totals | shots with the model's impact | their median ratio |",
        "|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    kind = {"stronge": "cushion", "mathavan": "ball", "preset": "cushion"}
    for name in ("stronge", "mathavan", "preset"):
        table, shots, _ = shots_and_scenes(name, n)
        base = Table(model="spin", pockets="none", length=table.length, width=table.width)
        t_base = np.array([w for w, _, _ in time_ours(base, shots, repeats)])
        t = np.array([w for w, _, _ in time_ours(table, shots, repeats)])
        hit = np.array([any(e.kind == kind[name] for e in ours(table, s).events) for s in shots])
        ratio = t / t_base
        lines.append(
            f"| {name} | {'preset' if name == 'preset' else 'spin_scenes'} | "
            f"{np.median(t_base) * 1e6:.1f} us | {np.median(t) * 1e6:.1f} us | "
            f"{np.median(ratio):.2f} | {t.sum() / t_base.sum():.2f} | {hit.sum()} "
            f"({kind[name]}) | {np.median(ratio[hit]):.2f} |"
        )
    lines.append(f"load after: {os.getloadavg()[0]:.2f}")
    return lines


def model_differences(n: int) -> list[str]:
    """How far each new model moves the final positions from the default's (no pooltool)."""
    base = Table(model="spin", pockets="none")
    shots = spin_shots(n, table=base)
    finals = [ours(base, s).positions for s in shots]
    lines = ["| against the default | median | 95th pct | max |", "|---|---:|---:|---:|"]
    for name in ("stronge", "mathavan"):
        table = model_table(name)
        pairs = zip(shots, finals, strict=True)
        d = np.array([final_distance(ours(table, s).positions, f) for s, f in pairs])
        lines.append(
            f"| {name} | {np.median(d):.3g} m | {np.percentile(d, 95):.3g} m | {d.max():.3g} m |"
        )
    return lines


def main() -> None:
    """Entry point."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shots", type=int, default=200)
    ap.add_argument("--only", choices=("stronge", "mathavan", "preset"), default=None)
    ap.add_argument("--time", action="store_true")
    ap.add_argument("--differences", action="store_true")
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "models_vs_pooltool.md")
    args = ap.parse_args()
    if args.time:
        print("\n".join(time_mode(args.shots, args.repeats)))
        return
    if args.differences:
        print("\n".join(model_differences(args.shots)))
        return
    lines = ["| comparison | shots | median | 95th pct | max | within 1e-6 m |",
             "|---|---:|---:|---:|---:|---:|"]  # fmt: skip
    notes = []
    for name in (args.only,) if args.only else ("stronge", "mathavan", "preset"):
        t0 = time.perf_counter()
        line, worst = compare(name, args.shots)
        lines.append(line)
        notes.append(f"\nWorst {name} shots ({time.perf_counter() - t0:.0f} s):")
        notes += [f"- {s}: {d:.2e} m; pool_env: {a}; pooltool: {b}" for d, s, a, b in worst]
    print("\n".join(lines + notes))
    if args.shots >= 200 and args.only is None:
        header = (f"# Models beside pooltool 0.6.0\n\n`python -m bench.models_vs_pooltool` "
                  f"({time.strftime('%Y-%m-%d', time.gmtime())}); see the script's docstring "
                  "for the set-up.\n\n")  # fmt: skip
        args.out.write_text(header + "\n".join(lines + notes) + "\n")
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
