"""Run each engine over a list of scenes: wall time per scene and the outcomes."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from bench.engines.fixed_step import simulate_fixed_step
from bench.engines.pooltool_engine import run_pooltool, table_spec
from bench.errors import ours_outcome
from pool_env import simulate
from tools.shots import Outcome, Scene


@dataclass
class Run:
    """One method over one suite.

    Attributes:
        method: Row label.
        engine: ``ours``, ``fixed-step``, ``pymunk`` or ``pooltool``.
        dt: Step (s) of a time-stepped engine, else None.
        index: Indices into the suite of the scenes it ran (a subset for slow engines).
        times: Wall seconds per scene (median over repeats), aligned with ``index``.
        outcomes: Outcomes aligned with ``index``.
        note: Caveat printed next to the row.
    """

    method: str
    engine: str
    dt: float | None
    index: list[int] = field(default_factory=list)
    times: list[float] = field(default_factory=list)
    outcomes: list[Outcome] = field(default_factory=list)
    note: str = ""


def _timed(fn: Any, repeats: int) -> tuple[float, Any]:
    times = []
    out = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def run_ours(scenes: list[Scene], repeats: int, record: bool) -> Run:
    """Our simulator; ``record=False`` is the training-loop call (final state only)."""
    label = f"this simulator (record={record})"
    run = Run(label, "ours", None)
    for k, s in enumerate(scenes):
        t, _ = _timed(
            lambda s=s: simulate(s.table, s.positions, s.velocities, s.masses, record=record),
            repeats,
        )
        res = simulate(s.table, s.positions, s.velocities, s.masses)
        run.index.append(k)
        run.times.append(t)
        run.outcomes.append(ours_outcome(res, s.obj))
    return run


def fixed_outcome(raw: tuple) -> Outcome:
    """An :class:`Outcome` from :func:`run_fixed_step`'s tuple."""
    pos, pocketed, _, capped, obj_vel, hits, _, _ = raw
    ii, jj = np.nonzero(np.triu(hits))
    return Outcome(
        pos,
        pocketed,
        obj_vel,
        {(int(i), int(j)) for i, j in zip(ii, jj, strict=True)},
        bool(capped),
    )


def run_fixed(scenes: list[Scene], dt: float, repeats: int, index: list[int] | None = None) -> Run:
    """The fixed-step integrator at step ``dt``."""
    run = Run(f"fixed-step dt={dt:g}", "fixed-step", dt)
    for k in range(len(scenes)) if index is None else index:
        s = scenes[k]
        m = s.mass_array()
        t, raw = _timed(
            lambda s=s, m=m: simulate_fixed_step(
                s.table.params, s.table.pockets, s.positions, s.velocities, m, dt, s.obj
            ),
            repeats,
        )
        run.index.append(k)
        run.times.append(t)
        run.outcomes.append(fixed_outcome(raw))
    return run


def pymunk_outcome(res: Any) -> Outcome:
    """An :class:`Outcome` from a :class:`~bench.engines.pymunk_engine.PymunkResult`."""
    return Outcome(res.positions, res.pocketed, res.obj_velocity, set(res.hits), res.capped)


def run_pymunk(scenes: list[Scene], dt: float, index: list[int] | None = None) -> Run:
    """Run pymunk at step ``dt`` (one run per scene: it is slow)."""
    from bench.engines.pymunk_engine import simulate_pymunk

    label = f"pymunk dt={dt:g}" if dt != 1 / 60 else "pymunk dt=1/60"
    run = Run(label, "pymunk", dt)
    for k in range(len(scenes)) if index is None else index:
        s = scenes[k]
        t, res = _timed(
            lambda s=s: simulate_pymunk(s.table, s.positions, s.velocities, s.masses, dt, s.obj), 1
        )
        run.index.append(k)
        run.times.append(t)
        run.outcomes.append(pymunk_outcome(res))
    return run


def worker_scene(s: Scene) -> dict[str, Any]:
    """The pooltool worker's description of a scene."""
    return {
        "table": table_spec(s.table),
        "positions": s.positions.tolist(),
        "velocities": s.velocities.tolist(),
        "obj": s.obj,
        "masses": None if s.masses is None else np.asarray(s.masses).tolist(),
    }


def pooltool_outcome(s: Scene, r: dict[str, Any]) -> Outcome:
    """An :class:`Outcome` from one worker result (pockets matched to ours by position)."""
    from bench.errors import nearest_pocket

    n = s.n_balls
    if r.get("error"):
        return Outcome(
            np.full((n, 2), np.nan), np.full(n, -2), np.full(2, np.nan), error=r["error"]
        )
    pocketed = np.array([nearest_pocket(s.table, xy) for xy in r["pocket_xy"]], dtype=np.int64)
    obj_vel = np.array(r["obj_vel"] if r["obj_vel"] is not None else [np.nan, np.nan])
    return Outcome(
        np.array(r["positions"]),
        pocketed,
        obj_vel,
        {(int(i), int(j)) for i, j in r["hits"]},
        bool(r["capped"]),
    )


def run_pooltool_suite(
    scenes: list[Scene], repeats: int, max_events: int = 5000, timeout: float = 60.0
) -> tuple[Run | None, dict[str, Any]]:
    """Run pooltool on ``scenes`` in its own virtualenv; ``(None, info)`` if it cannot run."""
    info = run_pooltool([worker_scene(s) for s in scenes], repeats, max_events, timeout)
    if not info.get("available"):
        return None, info
    run = Run(
        "pooltool 0.6.0",
        "pooltool",
        None,
        note="adds sliding, spin and throw (default physics): its differences from the "
        "reference are model differences, not integration error",
    )
    for k, (s, r) in enumerate(zip(scenes, info["results"], strict=True)):
        run.index.append(k)
        run.times.append(float(np.median(r["times"])) if r["times"] else float("nan"))
        run.outcomes.append(pooltool_outcome(s, r))
    info = {k: v for k, v in info.items() if k != "results"}
    return run, info
