"""The public entry of the reference: check the input, convert it exactly, run the loop."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt
from mpmath import mp, mpf

from pool_env.testing.reference.model import DPS, INPUT_TOLERANCE, dot, sub
from pool_env.testing.reference.result import ReferenceResult
from pool_env.testing.reference.simulator import Simulator

if TYPE_CHECKING:
    # Type checking only: at run time the reference reads the table's attributes and runs
    # no code from pool_env at all.
    from pool_env.sim.table import Table


def _as_pairs(name: str, values: npt.ArrayLike, n: int | None) -> list[tuple[float, float]]:
    arr = np.asarray(values, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (N, 2), got {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ValueError(f"{name} has {arr.shape[0]} rows, expected {n}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    return [(float(x), float(y)) for x, y in arr]


def reference_simulate(
    table: Table,
    positions: npt.ArrayLike,
    velocities: npt.ArrayLike,
    masses: npt.ArrayLike | None = None,
    max_events: int = 200,
) -> ReferenceResult:
    """Simulate a shot to rest at 50 significant digits.

    Args:
        table: The table (only its attributes are read).
        positions: ``(N, 2)`` ball centres (floats or an array).
        velocities: ``(N, 2)`` initial velocities (m/s).
        masses: ``(N,)`` masses (kg); ``None`` gives every ball ``table.ball_mass``.
        max_events: Hard cap on the number of events.

    Returns:
        A :class:`ReferenceResult`. Its numbers are ``mpf`` values carrying 50 digits; do
        arithmetic on them inside ``mp.workdps(50)`` to keep that precision.

    Raises:
        ValueError: On malformed input, a ball outside the rails or overlapping another by
            more than :data:`INPUT_TOLERANCE`, or a non-positive mass.
        ReferenceSimulationError: If the event cap is exceeded or a sustained contact arises.
    """
    pos = _as_pairs("positions", positions, None)
    vel = _as_pairs("velocities", velocities, len(pos))
    if masses is None:
        mass = [float(table.ball_mass)] * len(pos)
    else:
        mass = [float(m) for m in np.asarray(masses, dtype=np.float64).reshape(-1)]
        if len(mass) != len(pos):
            raise ValueError(f"masses has {len(mass)} entries, expected {len(pos)}")
        if not all(math.isfinite(m) and m > 0 for m in mass):
            raise ValueError("masses must be positive and finite")
    with mp.workdps(DPS):
        p_mp = [(mpf(x), mpf(y)) for x, y in pos]
        v_mp = [(mpf(x), mpf(y)) for x, y in vel]
        r = mpf(table.ball_radius)
        tol = mpf(INPUT_TOLERANCE)
        # A jaw table's throats lie beyond the rail lines, within a mouth's width of the
        # middle of the mouth (a coarse check: the oracle is not a validator).
        mouths = [
            ((mpf(float(j.points[0][0])) + mpf(float(j.points[1][0]))) / 2,
             (mpf(float(j.points[0][1])) + mpf(float(j.points[1][1]))) / 2,
             mpf(float(math.dist(j.points[0], j.points[1]))))
            for j in table.jaws
        ]  # fmt: skip
        for k, (x, y) in enumerate(p_mp):
            if not (
                r - tol <= x <= mpf(table.length) - r + tol
                and r - tol <= y <= mpf(table.width) - r + tol
            ) and not any((x - mx) ** 2 + (y - my) ** 2 < w * w for mx, my, w in mouths):
                raise ValueError(f"ball {k} at ({float(x)}, {float(y)}) is outside the rails")
        for i in range(len(p_mp)):
            for j in range(i + 1, len(p_mp)):
                d = sub(p_mp[j], p_mp[i])
                if mp.sqrt(dot(d, d)) < 2 * r - tol:
                    raise ValueError(f"balls {i} and {j} overlap")
        sim = Simulator(table, p_mp, v_mp, [mpf(m) for m in mass])
        return sim.run(max_events)
