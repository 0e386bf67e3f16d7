"""Random scenes for property tests and fuzzing: legal layouts drawn from a numpy Generator."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.inputs import max_speed, reachable_speed
from pool_env.sim.table import Table


def random_layout(
    table: Table,
    n_balls: int,
    rng: np.random.Generator,
    min_gap: float = 0.0,
    max_tries: int = 10_000,
) -> NDArray[np.float64]:
    """Place ``n_balls`` uniformly at random: inside the rails, apart, out of the pockets.

    Args:
        table: The table.
        n_balls: How many balls.
        rng: Source of randomness.
        min_gap: Extra clearance between balls (m); 0 allows touching.
        max_tries: Rejection-sampling budget before giving up.

    Returns:
        ``(n_balls, 2)`` centres.

    Raises:
        ValueError: If the balls cannot be placed within ``max_tries`` draws.
    """
    r = table.ball_radius
    placed: list[NDArray[np.float64]] = []
    pockets = table.pockets
    min_d2 = (2 * r + min_gap) ** 2
    for _ in range(max_tries):
        if len(placed) == n_balls:
            break
        p = rng.uniform([r, r], [table.length - r, table.width - r])
        if pockets.shape[0] and np.any(
            ((pockets[:, :2] - p) ** 2).sum(axis=1) <= pockets[:, 2] ** 2 * (1 + 1e-9)
        ):
            continue
        if placed and np.any(((np.array(placed) - p) ** 2).sum(axis=1) < min_d2):
            continue
        placed.append(p)
    if len(placed) < n_balls:
        raise ValueError(f"could not place {n_balls} balls on the table in {max_tries} draws")
    return np.array(placed)


def lump_at_rail(
    table: Table,
    rng: np.random.Generator,
    n_pressed: int,
    gap: float,
    speed: float,
    spread: float = 0.02,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A chain of ``n_pressed`` touching balls on a random rail and a ball driven into it.

    The chain starts touching the rail and runs inward along the rail's normal; the driver
    (ball 0) waits ``gap`` behind it, up to ``R / 2`` off the chain's line, and rolls at
    ``speed`` towards the rail, up to ``spread`` radians off the normal.

    Args:
        table: The table (large enough for the chain and the gap).
        rng: Source of randomness.
        n_pressed: Balls in the chain (ball 1 touches the rail).
        gap: Distance from the driver to the chain (m).
        speed: The driver's speed (m/s).
        spread: Largest angle of the driver's path off the rail normal (radians).

    Returns:
        ``(positions, velocities)``, ``(n_pressed + 1, 2)`` each.
    """
    r = table.ball_radius
    rail = int(rng.integers(4))
    along = table.width if rail < 2 else table.length  # the rail's own direction
    t = rng.uniform(2 * r, along - 2 * r)
    depth = [2 * r * k for k in range(n_pressed)]  # distance from the rail line, inwards
    depth = [depth[-1] + 2 * r + gap if n_pressed else gap, *depth]
    offset = [rng.uniform(-0.5, 0.5) * r] + [0.0] * n_pressed
    points = []
    for u, dt in zip(depth, offset, strict=True):
        if rail == 0:
            points.append((r + u, t + dt))
        elif rail == 1:
            points.append((table.length - r - u, t + dt))
        elif rail == 2:
            points.append((t + dt, r + u))
        else:
            points.append((t + dt, table.width - r - u))
    inward = [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)][rail]
    phi = np.arctan2(-inward[1], -inward[0]) + rng.uniform(-spread, spread)
    velocities = np.zeros((n_pressed + 1, 2))
    velocities[0] = speed * np.array([np.cos(phi), np.sin(phi)])
    return np.array(points), velocities


def log_uniform_masses(
    rng: np.random.Generator, n: int, base: float, ratio: float
) -> NDArray[np.float64]:
    """``n`` masses spread log-uniformly over ``[base / sqrt(ratio), base * sqrt(ratio)]``."""
    half = 0.5 * np.log10(ratio)
    return base * 10.0 ** rng.uniform(-half, half, n)


def within_limits(
    table: Table, velocities: NDArray[np.float64], masses: NDArray[np.float64] | None = None
) -> NDArray[np.float64]:
    """``velocities`` scaled down, if need be, so that no impact can speed a ball past the limits.

    The simulator refuses a scene whose kinetic energy could drive its lightest ball past
    :func:`~pool_env.sim.inputs.max_speed` (:func:`~pool_env.sim.inputs.reachable_speed`);
    one factor for every velocity keeps the scene's directions and the ratios of its speeds.
    """
    reach = reachable_speed(velocities, masses)
    limit = 0.999 * max_speed(table)
    return velocities * (limit / reach) if reach > limit else velocities
