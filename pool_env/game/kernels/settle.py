"""What a batch of shots did to the tables: balls that left, the first contact, shot counts.

The physical bookkeeping only; what it means (rewards, re-spotting, the end of an episode)
is the rules' (:mod:`pool_env.game.rules`).
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.kernels._jit import kernel


@kernel
def settle(tables, balls, positions, on_table, n_left, shots, final, pocketed, first, cue):
    """Write the simulated outcomes into the tables' state.

    Potted balls leave the table and keep their capture point as their position.

    Args:
        tables: ``(K,)`` tables that shot; row ``k`` of the results is table ``tables[k]``.
        balls: ``(M,)`` ball number of each column of the results (the simulator may have
            seen only the balls on the table).
        positions: ``(B, N, 2)`` state, updated in place.
        on_table: ``(B, N)`` state, updated in place.
        n_left: ``(B,)`` object balls on each table, updated in place.
        shots: ``(B,)`` shots of each table's episode, counted up in place.
        final: ``(K, M, 2)`` simulated final positions.
        pocketed: ``(K, M)`` pocket per ball, -1 for none.
        first: ``(K, 2)`` result columns of the first ball-ball impact, -1 for none.
        cue: Ball number of the cue ball.

    Returns:
        ``(n_potted, potted_bits, potted, scratch, first_ball)``: per shot the object balls
        potted, a bit mask of them (bit ``j - 1`` for ball ``j`` up to 63), ``(K, N)``
        booleans of them, whether the cue ball dropped, and the first ball the cue ball hit
        (the other ball of the first impact; -1 for none).
    """
    n_shots, n_cols = pocketed.shape
    n_potted = np.zeros(n_shots, dtype=np.int64)
    bits = np.zeros(n_shots, dtype=np.int64)
    potted = np.zeros((n_shots, on_table.shape[1]), dtype=np.bool_)
    scratch = np.zeros(n_shots, dtype=np.bool_)
    first_ball = np.full(n_shots, -1, dtype=np.int64)
    for k in range(n_shots):
        b = tables[k]
        for c in range(n_cols):
            j = balls[c]
            positions[b, j, 0] = final[k, c, 0]
            positions[b, j, 1] = final[k, c, 1]
            if pocketed[k, c] >= 0:
                on_table[b, j] = False
                if j == cue:
                    scratch[k] = True
                else:
                    potted[k, j] = True
                    n_potted[k] += 1
                    if 1 <= j <= 63:
                        bits[k] |= np.int64(1) << (j - 1)
        n_left[b] -= n_potted[k]
        shots[b] += 1
        if first[k, 0] >= 0:
            i, j = balls[first[k, 0]], balls[first[k, 1]]
            first_ball[k] = j if i == cue else i
    return n_potted, bits, potted, scratch, first_ball
