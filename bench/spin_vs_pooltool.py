"""The spin level beside pooltool 0.6.0 on equal models, and the 50-digit reference.

Run (pooltool from ``bash bench/setup_pooltool.sh``)::

    python -m bench.spin_vs_pooltool              # 200 shots -> results/spin_vs_pooltool.md
    python -m bench.spin_vs_pooltool --shots 20   # smoke run (prints, writes nothing)
    python -m bench.spin_vs_pooltool --time       # speed: pool_env's spin level and pooltool

The seeded shots of :mod:`bench.spin_scenes` (a cue strike with side and vertical tip
offsets and sometimes an elevated cue, 1-3 collisions, pocketless table) run through
pooltool (frictional inelastic ball-ball with the same Alciatore fit, Han 2005 cushions,
instantaneous-point strike with squirt, equal ball and table parameters), through the
reference :mod:`pool_env.testing.spin_reference` and, once it exists, through pool_env's
``Table(model="spin")``. Reported per pair: the per-shot largest final-position difference
over the balls (median, 95th percentile, max, shots within 1e-6 m). pooltool runs twice:
as released, and with its collision spacer ``MIN_DIST`` set to 1e-12 m, which isolates
what that spacer contributes.
"""

from __future__ import annotations

import argparse
import os
import time
from pathlib import Path
from typing import Any

import numpy as np

from bench.engines.pooltool_engine import run_pooltool
from bench.spin_scenes import SpinShot, pooltool_strike, spin_shots, spin_table, worker_scene
from pool_env.testing.spin_reference import spin_reference_simulate

ROOT = Path(__file__).resolve().parents[1]
TARGET = 1e-6  # m


def pool_env_spin() -> bool:
    """Whether this tree's pool_env has the spin level (``Table(model="spin")``)."""
    from pool_env import Table

    try:
        Table(model="spin", pockets="none")  # type: ignore[call-arg]
    except TypeError:
        return False
    return True


def ours(table: Any, shot: SpinShot, record: bool = True) -> Any:
    """pool_env's spin level on one shot (its own strike)."""
    from pool_env import shoot

    return shoot(  # type: ignore[call-arg]
        table, shot.positions, shot.angle, shot.speed, 0, tip=shot.tip,
        elevation=shot.elevation, record=record,
    )  # fmt: skip


def time_ours(
    table: Any, shots: list[SpinShot], repeats: int, record: bool = False
) -> list[tuple[float, float, int]]:
    """Time pool_env's spin level on each shot, kernels warmed up first.

    Returns:
        Per shot: the median wall and thread-CPU seconds over ``repeats`` calls of
        :func:`ours` with ``record``, and the shot's event count.
    """
    for s in shots:
        ours(table, s, record=record)  # warm up (compile or load the cached kernels)
    out = []
    for s in shots:
        wall, cpu = [], []
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.thread_time()
            ours(table, s, record=record)
            wall.append(time.perf_counter() - t0)
            cpu.append(time.thread_time() - c0)
        out.append((float(np.median(wall)), float(np.median(cpu)), ours(table, s).n_events))
    return out


def time_roll(shots: list[SpinShot], repeats: int) -> list[tuple[float, float, int]]:
    """:func:`time_ours` for the roll level on the same shots (no tip, no elevation).

    ``Table(pockets="none")`` with the spin table's dimensions (the defaults): the cue
    ball leaves at the shot's speed and aim, rolling; the roll level has no spin, so the
    shot differs from the spin level's after the strike (its own events are counted).
    """
    from pool_env import Table, shoot

    table = Table(pockets="none")
    for s in shots:
        shoot(table, s.positions, s.angle, s.speed, record=False)  # warm up
    out = []
    for s in shots:
        wall, cpu = [], []
        for _ in range(repeats):
            t0, c0 = time.perf_counter(), time.thread_time()
            shoot(table, s.positions, s.angle, s.speed, record=False)
            wall.append(time.perf_counter() - t0)
            cpu.append(time.thread_time() - c0)
        n_events = shoot(table, s.positions, s.angle, s.speed).n_events
        out.append((float(np.median(wall)), float(np.median(cpu)), n_events))
    return out


def stats(diffs: list[float]) -> dict[str, float]:
    """Median, 95th percentile, max and the count within the target of per-shot differences."""
    d = np.asarray(diffs, dtype=np.float64)
    return {
        "n": float(d.size),
        "median": float(np.median(d)),
        "p95": float(np.percentile(d, 95)),
        "max": float(d.max()),
        "within": float(np.sum(d <= TARGET)),
    }


def row(label: str, s: dict[str, float]) -> str:
    """One markdown table row."""
    return (
        f"| {label} | {s['n']:.0f} | {s['median']:.2e} | {s['p95']:.2e} | {s['max']:.2e} | "
        f"{s['within']:.0f} ({100 * s['within'] / s['n']:.1f}%) |"
    )


def final_distance(a: Any, b: Any) -> float:
    """The largest distance (m) between the same ball's final centres in two runs."""
    return float(np.max(np.hypot(*(np.asarray(a) - np.asarray(b)).T)))


def compare(n: int) -> tuple[list[str], dict[str, Any]]:
    """Run the comparison; returns the report lines and the raw figures."""
    table = spin_table()
    t0 = time.perf_counter()
    shots = spin_shots(n, table=table)
    t_ref = time.perf_counter() - t0
    scenes = [worker_scene(table, s) for s in shots]
    released = run_pooltool(scenes, repeats=1, max_events=5000)
    spacer = run_pooltool(scenes, repeats=1, max_events=5000, min_dist=1e-12)
    native_scenes = [worker_scene(table, s, throw="pooltool") for s in shots]
    native = run_pooltool(native_scenes, repeats=1, max_events=5000, min_dist=1e-12)
    for out in (released, spacer, native):
        if not out.get("available"):
            raise SystemExit(f"pooltool did not run: {out.get('reason')}")
    pairs: dict[str, list[float]] = {
        "pooltool vs reference": [],
        "pooltool (MIN_DIST 1e-12) vs reference": [],
        "pooltool's own throw (MIN_DIST 1e-12) vs reference (throw=pooltool)": [],
    }
    have_ours = pool_env_spin()
    if have_ours:
        pairs.update(
            {
                "pool_env vs reference": [],
                "pool_env vs pooltool": [],
                "pool_env vs pooltool (MIN_DIST 1e-12)": [],
            }
        )
    worst: list[tuple[float, str, str]] = []
    same_events = 0
    for k, shot in enumerate(shots):
        pt, pt0 = released["results"][k], spacer["results"][k]
        if pt.get("error") or pt0.get("error"):
            raise SystemExit(f"pooltool failed on {shot.name}: {pt.get('error')}")
        d = final_distance(pt["positions"], shot.ref_positions)
        pairs["pooltool vs reference"].append(d)
        pairs["pooltool (MIN_DIST 1e-12) vs reference"].append(
            final_distance(pt0["positions"], shot.ref_positions)
        )
        own = spin_reference_simulate(
            table, shot.positions, shot.velocities, shot.angular_velocities, max_events=400,
            throw="pooltool",
        )  # fmt: skip
        own_final = [[float(x), float(y)] for x, y in own.positions]
        pairs["pooltool's own throw (MIN_DIST 1e-12) vs reference (throw=pooltool)"].append(
            final_distance(native["results"][k]["positions"], own_final)
        )
        kinds = [e[1] for e in pt["events"] if "ball_ball" in e[1] or "cushion" in e[1]]
        worst.append((d, shot.name, " ".join(k.split("_")[-1] for k in kinds)))
        if have_ours:
            res = ours(table, shot)
            pairs["pool_env vs reference"].append(final_distance(res.positions, shot.ref_positions))
            pairs["pool_env vs pooltool"].append(final_distance(res.positions, pt["positions"]))
            pairs["pool_env vs pooltool (MIN_DIST 1e-12)"].append(
                final_distance(res.positions, pt0["positions"])
            )
            ev = [(e.kind, e.i, e.j) for e in res.events]
            same_events += ev == list(shot.ref_events)
    figures = {name: stats(d) for name, d in pairs.items()}
    figures["_meta"] = {
        "shots": len(shots),
        "pooltool": released["pooltool"],
        "reference_s": t_ref,
        "same_events": same_events,
        "have_ours": have_ours,
        "worst": sorted(worst, reverse=True)[:5],
        "table": {
            k: getattr(table, k)
            for k in ("e_ball", "e_cushion", "cushion_friction", "mu_slide", "mu_roll")
        },
        "pairs": pairs,
    }
    lines = [
        "| pair | shots | median | 95th pct | max | within 1e-6 m |",
        "|---|---:|---:|---:|---:|---:|",
        *(row(name, s) for name, s in figures.items() if not name.startswith("_")),
    ]
    return lines, figures


def _breaks(table: Any, n: int, seed: int) -> list[SpinShot]:
    """``n`` seeded 9-ball breaks on ``table``: a centre-ball hit at 6-9 m/s on the apex."""
    from bench.spin_scenes import strike_state
    from pool_env.sim.layouts import break_scene

    rng = np.random.default_rng(seed)
    base = break_scene(table, "nine")
    out = []
    for k in range(n):
        aim = base[1] - base[0]
        angle = float(np.arctan2(aim[1], aim[0]) + rng.normal(0.0, np.radians(0.5)))
        speed = float(rng.uniform(6.0, 9.0))
        vel, ang = np.zeros((len(base), 2)), np.zeros((len(base), 3))
        vel[0], ang[0] = strike_state(table, angle, speed, (0.0, 0.0), 0.0)
        out.append(SpinShot(f"break{k}", base.copy(), angle, speed, (0.0, 0.0), 0.0, vel, ang))
    return out


def full_table_shots(table: Any, n: int, seed: int = 13) -> list[SpinShot]:
    """``n`` seeded two-ball shots at 2 m/s on the full table: a centre-ball hit at ball 1.

    Random layouts of the table (pockets and jaws included), the aim at the object ball
    jittered by N(0, 0.05 rad).
    """
    from bench.spin_scenes import strike_state
    from pool_env.testing.scenes_random import random_layout

    rng = np.random.default_rng(seed)
    out = []
    for k in range(n):
        pos = random_layout(table, 2, rng, min_gap=0.05)
        d = pos[1] - pos[0]
        angle = float(np.arctan2(d[1], d[0]) + rng.normal(0.0, 0.05))
        vel, ang = np.zeros((2, 2)), np.zeros((2, 3))
        vel[0], ang[0] = strike_state(table, angle, 2.0, (0.0, 0.0), 0.0)
        out.append(SpinShot(f"full{k}", pos, angle, 2.0, (0.0, 0.0), 0.0, vel, ang))
    return out


def _time_set(
    table: Any, shots: list[SpinShot], scenes: list[dict[str, Any]], repeats: int, n: int
) -> list[str]:
    """Time both simulators on one shot set; the report's rows (two-ball, then breaks)."""
    mine = time_ours(table, shots, 2 * repeats + 1)
    out = run_pooltool(scenes, repeats=repeats, max_events=20000, timeout=300.0)
    if not out.get("available"):
        raise SystemExit(f"pooltool did not run: {out.get('reason')}")
    pt = [(float(np.median(r["times"])), float(np.median(r["cpu_times"])), r["n_events"])
          for r in out["results"]]  # fmt: skip
    rows = []
    for name, part in (("two-ball shots", slice(0, n)), ("9-ball breaks", slice(n, None))):
        p = np.array(pt[part], dtype=float)
        pw, pc = np.median(p[:, 0]), np.median(p[:, 1])
        pe = np.median(p[:, 0] / np.maximum(p[:, 2], 1))
        o = np.array(mine[part], dtype=float)
        ow, oc = np.median(o[:, 0]), np.median(o[:, 1])
        oe = np.median(o[:, 0] / np.maximum(o[:, 2], 1))
        rows.append(
            f"| {name} | {len(p)} | {np.median(p[:, 2]):.0f} | {pw * 1e3:.2f} ms | "
            f"{pc * 1e3:.2f} ms | {pe * 1e6:.1f} us | {np.median(o[:, 2]):.0f} | "
            f"{ow * 1e6:.1f} us | {oc * 1e6:.1f} us | {oe * 1e6:.2f} us | {pw / ow:.0f}x | "
            f"{pc / oc:.0f}x |"
        )
    return rows


def time_mode(shots_n: int, breaks_n: int, repeats: int) -> None:
    """Time pool_env's spin level and pooltool per shot in one run, on both shot sets.

    Set 1, equal models: the short shots of :mod:`bench.spin_scenes` (1-3 collisions) and
    nine-ball breaks on a pocketless table, pooltool configured to the spin level's models.
    Set 2, each at its defaults: 2 m/s two-ball shots and breaks on a full table with
    pockets, ``Table(model="spin")`` (jaws) against pooltool's default pocket table,
    physics engine and balls. Prints the tables; the roll level on set 1's scenes after.
    """
    from pool_env import Table

    if not pool_env_spin():
        raise SystemExit("pool_env has no spin level in this tree")
    header = (
        "| suite | scenes | pooltool events | pooltool wall | pooltool CPU | pooltool per event "
        "| pool_env events | pool_env wall | pool_env CPU | pool_env per event | ratio wall "
        "| ratio CPU |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    )
    load = os.getloadavg()[0]
    table = spin_table()
    shots = [s for s in spin_shots(4 * shots_n, table=table) if len(s.positions) == 2]
    equal = [*shots[:shots_n], *_breaks(table, breaks_n, 9)]
    rows_equal = _time_set(table, equal, [worker_scene(table, s) for s in equal], repeats, shots_n)
    full = Table(model="spin")
    at_defaults = [*full_table_shots(full, shots_n), *_breaks(full, breaks_n, 10)]
    scenes = []
    for s in at_defaults:
        scene = worker_scene(full, s)
        scene["table"] |= {"defaults": True, "pockets": True}
        scenes.append(scene)
    rows_defaults = _time_set(full, at_defaults, scenes, repeats, shots_n)
    roll = time_roll(equal, 2 * repeats + 1)
    print(f"load {load:.1f} -> {os.getloadavg()[0]:.1f}; "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")  # fmt: skip
    print("\nSet 1: equal models, short shots and breaks on a pocketless table")
    print(header)
    print("\n".join(rows_equal))
    print("\nSet 2: each at its defaults, 2 m/s shots and breaks on a full table with pockets")
    print(header)
    print("\n".join(rows_defaults))
    print("\nThe roll level on set 1's scenes (same positions, aim and speed; no spin):")
    print("| suite | roll wall | roll CPU | roll events | roll per event |")
    print("|---|---:|---:|---:|---:|")
    n = shots_n
    for name, part in (("two-ball shots", slice(0, n)), ("9-ball breaks", slice(n, None))):
        r = np.array(roll[part], dtype=float)
        roll_event = np.median(r[:, 0] / np.maximum(r[:, 2], 1)) * 1e6
        print(f"| {name} | {np.median(r[:, 0]) * 1e6:.1f} us | {np.median(r[:, 1]) * 1e6:.1f} us "
              f"| {np.median(r[:, 2]):.1f} | {roll_event:.2f} us |")  # fmt: skip


def main() -> None:
    """Entry point."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--shots", type=int, default=200)
    ap.add_argument("--time", action="store_true", help="time pool_env's spin level and pooltool")
    ap.add_argument("--breaks", type=int, default=4)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", type=Path, default=ROOT / "results" / "spin_vs_pooltool.md")
    args = ap.parse_args()
    if args.time:
        time_mode(min(args.shots, 40), args.breaks, args.repeats)
        return
    t0 = time.perf_counter()
    lines, fig = compare(args.shots)
    meta = fig["_meta"]
    print("\n".join(lines))
    print(f"pool_env spin level: {meta['have_ours']}; same event sequences as the reference: "
          f"{meta['same_events']}; {time.perf_counter() - t0:.0f} s")  # fmt: skip
    for d, name, kinds in meta["worst"]:
        print(f"  {name}: {d:.2e} m ({kinds})")
    if args.shots >= 200:
        from bench.spin_vs_pooltool_report import render

        args.out.write_text(render(lines, fig, pooltool_strike.__doc__ or ""))
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
