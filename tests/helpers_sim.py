"""Closed forms and small helpers shared by the simulator tests."""

from __future__ import annotations

import math

import numpy as np

from pool_env import Table


def stop_point(table: Table, p0, speed: float, angle: float) -> np.ndarray:
    """Where a free ball from ``p0`` at ``speed`` along ``angle`` rests: ``p0 + u v^2/(2a)``."""
    d = speed * speed / (2.0 * table.deceleration)
    return np.asarray(p0, dtype=float) + d * np.array([math.cos(angle), math.sin(angle)])


def speed_after(table: Table, speed: float, distance: float) -> float:
    """Speed left after rolling ``distance`` from ``speed``: ``sqrt(v^2 - 2 a s)``."""
    return math.sqrt(speed * speed - 2.0 * table.deceleration * distance)


def time_to(table: Table, speed: float, distance: float) -> float:
    """Time to roll ``distance`` from ``speed``."""
    return (speed - speed_after(table, speed, distance)) / table.deceleration


def normal_velocities(ma: float, mb: float, ua: float, ub: float, e: float) -> tuple[float, float]:
    """Momentum conservation with separation speed ``e`` times the approach speed."""
    total = ma + mb
    return (
        (ma * ua + mb * ub + mb * e * (ub - ua)) / total,
        (ma * ua + mb * ub + ma * e * (ua - ub)) / total,
    )


def unfold(x: float, lo: float, hi: float) -> float:
    """Fold an unbounded coordinate back between two mirrors (elastic rails)."""
    span = hi - lo
    k = math.floor((x - lo) / span)
    r = (x - lo) - k * span
    return lo + (r if k % 2 == 0 else span - r)
