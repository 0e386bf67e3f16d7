"""How fast a tiny perturbation grows in a break, per ball-ball collision.

A break is chaotic: each ball-ball impact multiplies a small error in direction by roughly
distance / R. We measure it directly: run the break, run it again with the cue ball moved
1e-12 m sideways, and compare all positions at the time of each ball-ball collision of the
first run (positions are continuous in time even where the order of events changes). The
growth factor per collision is ``10 ** slope`` of a least-squares line through
``log10(divergence)`` against the collision count, up to the first divergence over 1 mm.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env import simulate
from tools.shots import Scene

EPSILON = 1e-12  # m, sideways shift of the cue ball
SATURATION = 1e-3  # m: past this the runs are different shots


@dataclass
class Growth:
    """Divergence of two runs at each distinct ball-ball collision time of the first.

    Attributes:
        deltas: Largest position difference (m) at each collision time.
        factor: Growth per collision (geometric), NaN if it cannot be fitted.
        to_mm: Collisions until the divergence first exceeds 1 mm (None: never).
    """

    deltas: NDArray[np.float64]
    factor: float
    to_mm: int | None


def _growth(deltas: NDArray[np.float64]) -> Growth:
    over = np.flatnonzero(deltas > SATURATION)
    end = int(over[0]) if over.size else deltas.size
    k = np.arange(1, deltas.size + 1)[:end]
    d = deltas[:end]
    keep = d > 0.0
    factor = math.nan
    if np.count_nonzero(keep) >= 3:
        slope = np.polyfit(k[keep], np.log10(d[keep]), 1)[0]
        factor = float(10.0**slope)
    return Growth(deltas, factor, int(over[0]) + 1 if over.size else None)


def _collision_times(times: NDArray[np.float64], kinds: NDArray[np.int8]) -> NDArray[np.float64]:
    return np.unique(times[kinds == 1])


def _compare(
    at_a: Callable[[float], NDArray], at_b: Callable[[float], NDArray], times: NDArray[np.float64]
) -> NDArray[np.float64]:
    return np.array([float(np.max(np.hypot(*(at_a(t) - at_b(t)).T))) for t in times])


def perturbed(scene: Scene) -> NDArray[np.float64]:
    """The scene's positions with the cue ball moved ``EPSILON`` perpendicular to its shot."""
    pos = scene.positions.copy()
    v = scene.velocities[0]
    pos[0] += EPSILON * np.array([-v[1], v[0]]) / np.hypot(*v)
    return pos


def ours_growth(scene: Scene) -> Growth:
    """Perturbation growth in our simulator."""
    base = simulate(scene.table, scene.positions, scene.velocities, scene.masses)
    pert = simulate(scene.table, perturbed(scene), scene.velocities, scene.masses)
    times = _collision_times(base.event_times, base.event_kinds)
    return _growth(_compare(base.positions_at, pert.positions_at, times))


def _ref_at(ref: object) -> Callable[[float], NDArray]:
    def at(t: float) -> NDArray:
        return np.array([[float(x), float(y)] for x, y in ref.positions_at(t)])

    return at


def reference_growth(scene: Scene, max_events: int = 5000) -> tuple[Growth, Growth]:
    """Perturbation growth in the 50-digit reference, and how far float64 drifts from it.

    Returns:
        ``(reference growth, ours-vs-reference divergence)``: the first is the 1e-12 m
        perturbation in the reference; the second compares our simulator with the
        reference on the unperturbed break (float64 rounding, amplified by each collision).
    """
    from pool_env.testing.reference import reference_simulate

    ref = reference_simulate(
        scene.table, scene.positions, scene.velocities, scene.masses, max_events
    )
    ref_p = reference_simulate(
        scene.table, perturbed(scene), scene.velocities, scene.masses, max_events
    )
    times = np.unique([float(t) for t, kind, _, _ in ref.events if kind == "ball"])
    growth = _growth(_compare(_ref_at(ref), _ref_at(ref_p), times))
    ours = simulate(scene.table, scene.positions, scene.velocities, scene.masses)
    ours_times = np.unique(ours.event_times[ours.event_kinds == 1])
    t_end = ours.duration

    def ours_at(t: float) -> NDArray:
        return ours.positions_at(min(t, t_end))

    drift = _growth(_compare(ours_at, _ref_at(ref), ours_times))
    return growth, drift
