"""Error measures against the 50-digit reference, and its cached outcomes.

The reference is ``pool_env.testing.reference.reference_simulate`` (mpmath, 50 digits). Its
outcome of a scene is reduced to floats once (rounding a 50-digit number to float64 costs at most
1e-16 relative, far below every error measured here) and cached in memory and, optionally,
on disk under ``results/.cache`` keyed by the scene and the reference's source.
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from pool_env import ShotResult, Table
from tools.shots import Outcome, Scene

ROOT = Path(__file__).resolve().parents[1]
#: The 50-digit reference's package: its sources key the on-disk cache of its outcomes.
REFERENCE_SOURCE = ROOT / "pool_env" / "testing" / "reference"


def position_error(positions: NDArray[np.float64], reference: NDArray[np.float64]) -> float:
    """Largest distance (m) between a ball's final centre and the reference's."""
    return float(np.max(np.hypot(*(positions - reference).T)))


def direction_error_deg(v: NDArray[np.float64], v_ref: NDArray[np.float64]) -> float:
    """Angle (degrees) between two velocities; NaN if either is missing or zero."""
    if not (np.all(np.isfinite(v)) and np.all(np.isfinite(v_ref))):
        return math.nan
    nv, nr = float(np.hypot(*v)), float(np.hypot(*v_ref))
    if nv == 0.0 or nr == 0.0:
        return math.nan
    cross = v[0] * v_ref[1] - v[1] * v_ref[0]
    dot = v[0] * v_ref[0] + v[1] * v_ref[1]
    return math.degrees(abs(math.atan2(cross, dot)))


def outcome_agrees(pocketed: NDArray[np.int64], reference: NDArray[np.int64]) -> bool:
    """The same balls potted in the same pockets."""
    return bool(np.array_equal(np.asarray(pocketed), np.asarray(reference)))


def summary(values: list[float] | NDArray[np.float64]) -> tuple[float, float, float]:
    """``(median, p95, max)`` of the finite values (NaNs if there are none)."""
    arr = np.asarray(values, dtype=np.float64)
    arr = arr[np.isfinite(arr)]
    if arr.size == 0:
        return math.nan, math.nan, math.nan
    return float(np.median(arr)), float(np.percentile(arr, 95)), float(arr.max())


def ours_outcome(result: ShotResult, obj: int) -> Outcome:
    """Our simulator's outcome; needs ``record=True`` for the object-ball direction.

    The direction is exact: the object ball travels in a straight line from its first
    impact to its next event, so it is the chord between the positions at those times.
    """
    pairs = {
        (int(i), int(j))
        for k, i, j in zip(result.event_kinds, result.event_i, result.event_j, strict=True)
        if k == 1
    }
    return Outcome(
        result.positions.copy(),
        result.pocketed.copy(),
        _ours_obj_velocity(result, obj),
        pairs,
        result.hit_event_cap,
    )


def _ours_obj_velocity(result: ShotResult, obj: int) -> NDArray[np.float64]:
    times, kinds, ei, ej = result.event_times, result.event_kinds, result.event_i, result.event_j
    involved = (ei == obj) | ((kinds == 1) & (ej == obj))
    hits = np.flatnonzero(involved & (kinds == 1))
    if obj < 0 or hits.size == 0:
        return np.full(2, np.nan)
    t0 = times[hits[0]]
    later = np.flatnonzero(involved & (times > t0))
    t1 = times[later[0]] if later.size else result.duration
    if t1 <= t0:
        return np.full(2, np.nan)
    return (result.positions_at(t1)[obj] - result.positions_at(t0)[obj]) / (t1 - t0)


def _scene_key(scene: Scene) -> str:
    t = scene.table
    payload = json.dumps(
        {
            "table": [
                t.length,
                t.width,
                t.ball_radius,
                t.ball_mass,
                t.mu_roll,
                t.g,
                t.e_ball,
                t.e_cushion,
                t.pockets.tolist(),
            ],
            "positions": scene.positions.tolist(),
            "velocities": scene.velocities.tolist(),
            "masses": None if scene.masses is None else np.asarray(scene.masses).tolist(),
            "obj": scene.obj,
        }
    )
    return hashlib.sha256(payload.encode()).hexdigest()[:24]


def reference_fingerprint(source: Path | None = None) -> str:
    """12 hex digits of the reference package's sources (names and bytes of its modules).

    A change to any module of the reference makes a new cache file, so that no outcome of
    an older reference is read back.
    """
    digest = hashlib.sha256()
    for module in sorted((source or REFERENCE_SOURCE).glob("*.py")):
        digest.update(module.name.encode() + b"\0" + module.read_bytes() + b"\0")
    return digest.hexdigest()[:12]


class ReferenceCache:
    """Reference outcomes, computed once per scene (memory, and disk if a folder is given)."""

    def __init__(self, folder: Path | None = None, max_events: int = 5000) -> None:
        self.max_events = max_events
        self._memory: dict[str, dict] = {}
        self._file: Path | None = None
        if folder is not None:
            source = reference_fingerprint()
            folder.mkdir(parents=True, exist_ok=True)
            self._file = folder / f"reference-{source}.json"
            if self._file.exists():
                self._memory = json.loads(self._file.read_text())
        self.seconds = 0.0
        self.computed = 0

    def get(self, scene: Scene) -> Outcome:
        """The reference outcome of ``scene`` (``error`` set if the reference failed)."""
        key = _scene_key(scene)
        if key not in self._memory:
            self._memory[key] = self._compute(scene)
        d = self._memory[key]
        return Outcome(
            np.array(d["positions"]),
            np.array(d["pocketed"], dtype=np.int64),
            np.array(d["obj_velocity"], dtype=np.float64),
            {tuple(p) for p in d["pairs"]},
            False,
            d["error"],
        )

    def save(self) -> None:
        """Write the cache to disk (if it has a folder)."""
        if self._file is not None:
            self._file.write_text(json.dumps(self._memory))

    def _compute(self, scene: Scene) -> dict:
        import time

        from pool_env.testing.reference import reference_simulate

        t0 = time.perf_counter()
        n = scene.n_balls
        try:
            ref = reference_simulate(
                scene.table, scene.positions, scene.velocities, scene.masses, self.max_events
            )
        except Exception as exc:  # the reference refuses some hard cases (sustained contact)
            out = Outcome(
                np.full((n, 2), np.nan),
                np.full(n, -2),
                np.full(2, np.nan),
                error=f"{type(exc).__name__}: {exc}"[:200],
            )
        else:
            out = _reference_outcome(ref, scene.obj)
        self.seconds += time.perf_counter() - t0
        self.computed += 1
        d = asdict(out)
        d["positions"] = out.positions.tolist()
        d["pocketed"] = out.pocketed.tolist()
        d["obj_velocity"] = out.obj_velocity.tolist()
        d["pairs"] = sorted(list(p) for p in out.pairs)
        return d


def _reference_outcome(ref: object, obj: int) -> Outcome:
    positions = np.array([[float(x), float(y)] for x, y in ref.positions])
    pocketed = np.array(ref.pocketed, dtype=np.int64)
    pairs = {(int(i), int(j)) for _, kind, i, j in ref.events if kind == "ball"}
    obj_velocity = np.full(2, np.nan)
    for k, (_, kind, i, j) in enumerate(ref.events):
        if kind == "ball" and obj in (i, j):
            vx, vy = ref.velocities_after(k)[obj]
            obj_velocity = np.array([float(vx), float(vy)])
            break
    return Outcome(positions, pocketed, obj_velocity, pairs)


def nearest_pocket(table: Table, xy: list[float] | None) -> int:
    """Index of our pocket nearest to ``xy`` (pooltool's pockets differ in shape); -1 if None."""
    if xy is None or table.n_pockets == 0:
        return -1
    d = np.hypot(table.pockets[:, 0] - xy[0], table.pockets[:, 1] - xy[1])
    return int(np.argmin(d))
