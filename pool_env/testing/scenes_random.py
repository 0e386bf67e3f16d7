"""Random scenes for property tests and fuzzing: legal layouts drawn from a numpy Generator."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

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
