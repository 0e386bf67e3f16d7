"""What the agent sees of the balls (every game's observation starts so), and the potential."""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel


@kernel
def encode_observations(positions, on_table, length, width):
    """Observation: per ball ``(x, y, on_table)``, ``x`` and ``y`` scaled to ``[-1, 1]``.

    A potted ball reads ``(0, 0, 0)``.

    Args:
        positions: ``(B, N, 2)`` centres (m).
        on_table: ``(B, N)`` which balls are on the table.
        length: Table length (m).
        width: Table width (m).

    Returns:
        ``(B, 3 N)`` float32.
    """
    b, n = on_table.shape
    out = np.zeros((b, 3 * n), dtype=np.float32)
    for k in range(b):
        for j in range(n):
            if on_table[k, j]:
                # Clamp: a ball on a rail may sit 1e-9 m outside it after rounding.
                x = (2.0 * positions[k, j, 0] - length) / length  # exact 0 on the centre line
                out[k, 3 * j] = min(max(x, -1.0), 1.0)
                y = (2.0 * positions[k, j, 1] - width) / width
                out[k, 3 * j + 1] = min(max(y, -1.0), 1.0)
                out[k, 3 * j + 2] = 1.0
    return out


@kernel
def potential(positions, on_table, pockets, scale):
    """Shaping potential: minus the summed distance of object balls to their nearest pocket.

    Ball 0 (the cue) is left out and potted balls count 0, so a cleared table has potential
    0; a table without pockets has potential 0 everywhere.

    Args:
        positions: ``(N, 2)`` centres of one table.
        on_table: ``(N,)`` which balls are on the table.
        pockets: ``(P, 3)`` capture circles.
        scale: Length to divide by (the table diagonal in the environment).

    Returns:
        The potential (<= 0).
    """
    if pockets.shape[0] == 0:
        return 0.0
    total = 0.0
    for j in range(1, on_table.shape[0]):
        if on_table[j]:
            best = np.inf
            for p in range(pockets.shape[0]):
                # sqrt of a sum is correctly rounded everywhere; libm's hypot is not (it
                # differs from CPython's in the last bits), and rewards must be reproducible.
                dx = positions[j, 0] - pockets[p, 0]
                dy = positions[j, 1] - pockets[p, 1]
                best = min(best, math.sqrt(dx * dx + dy * dy))
            total += best
    return -total / scale


@kernel
def pocket_potentials(positions, on_table, pockets, scale):
    """:func:`potential` of each of ``B`` tables: ``(B, N, 2)``, ``(B, N)`` in, ``(B,)`` out."""
    out = np.zeros(on_table.shape[0])
    for k in range(on_table.shape[0]):
        out[k] = potential(positions[k], on_table[k], pockets, scale)
    return out
