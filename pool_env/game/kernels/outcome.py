"""What every game's judge shares: the result columns, and the outcome applied to a table.

A game's compiled judge (its package's ``judge`` kernel) reads the simulator's outcome
through these helpers, which know no rule: the balls move to where they stopped and the
potted ones leave (:func:`settle`), the cue ball's first ball (:func:`first_ball`), a ball
put back on a spot when it is free (:func:`spot_ball`). Its results are three arrays whose
first columns every game has (named here, read by :mod:`pool_env.game.info` and the
fronts); a game appends its own columns after them.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.kernels.layout import point_free
from pool_env.game.kernels.params import REACH, SPOT_X, SPOT_Y
from pool_env.sim.jit import kernel

CUE = 0  # the cue ball's row in every layout

#: Columns of a judge's boolean results every game has; a game's own follow from N_FLAGS.
TERMINATED, TRUNCATED, CLEARED, SCRATCH, SPOT_TAKEN, N_FLAGS = range(6)

#: Columns of a judge's integer results every game has: the potted object balls' bits (ball
#: ``j`` sets bit ``j - 1``, up to 63) and the first ball the cue ball hit (-1: none).
POTTED_BITS, FIRST_BALL, N_HITS = range(3)

#: Column of a judge's float results holding the reward; the game's reward terms (each
#: scaled, in the order of its ``reward_terms``) follow, and the reward is their sum.
REWARD = 0


@kernel
def settle(positions, on_table, b, balls, final, pocketed, k, potted):
    """What happened on table ``b`` (result row ``k``): balls move, potted ones leave.

    Returns:
        ``(n_potted, bits, scratch)``: object balls potted, their bits (ball ``j`` sets bit
        ``j - 1``, up to 63) and whether the cue ball dropped; ``potted[j]`` is set for
        each object ball ``j`` potted (cleared first).
    """
    n_potted, bits, scratch = 0, np.int64(0), False
    potted[:] = False
    for c in range(balls.shape[0]):
        j = balls[c]
        positions[b, j, 0] = final[k, c, 0]
        positions[b, j, 1] = final[k, c, 1]
        if pocketed[k, c] >= 0:
            on_table[b, j] = False
            if j == CUE:
                scratch = True
            else:
                potted[j] = True
                n_potted += 1
                if j <= 63:
                    bits |= np.int64(1) << (j - 1)
    return n_potted, bits, scratch


@kernel
def first_ball(balls, first, k):
    """The first ball the cue ball hit in result row ``k`` (-1 for none)."""
    if first[k, 0] < 0:
        return -1
    i, j = balls[first[k, 0]], balls[first[k, 1]]
    return j if i == CUE else i


@kernel
def spot_ball(positions, on_table, ball, x, y, params, pockets, others):
    """Put ``ball`` back on ``(x, y)`` if free; False when something covers the point.

    The ball is on the table either way; when the point is covered the caller finishes
    the placement (:meth:`pool_env.game.ruleset.Ruleset.judge`: the free point nearest).
    """
    on_table[ball] = True
    count = 0
    for j in range(on_table.shape[0]):
        if j != ball and on_table[j]:
            others[count] = positions[j]
            count += 1
    reach = params[REACH]
    if point_free(x, y, params, pockets, others, count, reach * reach):
        positions[ball, 0], positions[ball, 1] = x, y
        return True
    return False


@kernel
def settle_rows(params, pockets, tables, balls, positions, on_table, shots, final, pocketed,
                first):  # fmt: skip
    """What every judge does first, for all rows: the outcomes applied, the shots counted.

    :func:`settle` on each table, its shot counted, and a scratched cue ball put back on
    the head spot when it is free.

    Returns:
        ``(potted, scratch, first_hit, bits, spot_taken)``: ``(K, N)`` the object balls each
        shot potted, ``(K,)`` the cue ball dropped, the first ball it hit (-1: none), the
        potted bits, and the head spot was covered (the cue ball is on the table but not
        yet placed: the caller finishes it).
    """
    n_shots, n_balls = pocketed.shape[0], on_table.shape[1]
    potted = np.zeros((n_shots, n_balls), dtype=np.bool_)
    scratch = np.zeros(n_shots, dtype=np.bool_)
    spot_taken = np.zeros(n_shots, dtype=np.bool_)
    first_hit = np.empty(n_shots, dtype=np.int64)
    bits = np.zeros(n_shots, dtype=np.int64)
    others = np.empty((n_balls, 2))
    for k in range(n_shots):
        b = tables[k]
        _, bits[k], scratch[k] = settle(positions, on_table, b, balls, final, pocketed, k,
                                        potted[k])  # fmt: skip
        shots[b] += 1
        first_hit[k] = first_ball(balls, first, k)
        if scratch[k]:
            spot_taken[k] = not spot_ball(positions[b], on_table[b], CUE, params[SPOT_X],
                                          params[SPOT_Y], params, pockets, others)  # fmt: skip
    return potted, scratch, first_hit, bits, spot_taken
