"""Solitaire's rule, compiled: one player pots every object ball, in any order and pocket.

:func:`judge` runs through :func:`pool_env.game.step.step`, right after the simulator has
said where every ball ended and which dropped; it loops over the tables that shot and per
table applies the rule, reading only the outcome and the table's state:

* A potted object ball leaves the table (keeping its capture point as its position).
* A potted cue ball (a scratch) goes back on the head spot, or, when the spot is taken
  (the ruleset finishes that case with :func:`pool_env.game.spots.free_spot`), on the
  free point nearest to it.
* Reward, as four terms (:data:`pool_env.game.games.solitaire.game.REWARD_TERMS`):
  ``pot`` per object ball potted, ``scratch`` for a scratch, ``no_contact`` when the cue
  ball hits no ball, and ``shaping`` times the change of the pocket-distance potential
  (:func:`pool_env.game.kernels.observe.potential`), each times its scale.
* The episode terminates when the table is cleared, and with ``end_on_miss`` after a shot
  that pots nothing or scratches; it is truncated after ``shot_limit`` shots.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.games.solitaire.params import (
    END_ON_MISS,
    W_NO_CONTACT,
    W_POT,
    W_SCRATCH,
    W_SHAPING,
)
from pool_env.game.kernels.observe import potential
from pool_env.game.kernels.outcome import (
    CLEARED,
    CUE,
    FIRST_BALL,
    N_FLAGS,
    N_HITS,
    POTTED_BITS,
    REWARD,
    SCRATCH,
    SPOT_TAKEN,
    TERMINATED,
    TRUNCATED,
    first_ball,
    settle,
    spot_ball,
)
from pool_env.game.kernels.params import DIAGONAL, SHOT_LIMIT, SPOT_X, SPOT_Y
from pool_env.sim.jit import kernel

#: Columns of the float results after the reward: the four scaled reward terms.
POT, SCRATCHED, NO_CONTACT, SHAPING = 1, 2, 3, 4


@kernel
def judge(params, pockets, tables, balls, positions, on_table, shots, final, pocketed, first):
    """Apply a batch of simulated shots to the tables, by the solitaire rule.

    Args:
        params: The config's numbers (:mod:`pool_env.game.kernels.params`, solitaire's
            tail: :mod:`pool_env.game.games.solitaire.params`).
        pockets: ``(P, 3)`` capture circles.
        tables: ``(K,)`` tables that shot; row ``k`` of the results is table ``tables[k]``.
        balls: ``(M,)`` ball number of each column of the results (the simulator may have
            seen only the balls on the table).
        positions: ``(B, N, 2)`` state, updated in place.
        on_table: ``(B, N)`` state, updated in place.
        shots: ``(B,)`` shots of each table's episode, counted up in place.
        final: ``(K, M, 2)`` simulated final positions.
        pocketed: ``(K, M)`` pocket of each ball, -1 for none.
        first: ``(K, 2)`` result columns of the first ball-ball impact, -1 for none.

    Returns:
        ``(values, flags, hits)``: ``(K, 5)`` floats, the reward (:data:`REWARD`) then its
        four scaled terms (:data:`POT` ..); ``(K, 5)`` booleans by the shared column names
        (:mod:`pool_env.game.kernels.outcome`: ``SPOT_TAKEN``, something covers the head
        spot, the cue ball is back on the table but not yet placed); ``(K, 2)`` integers:
        ``POTTED_BITS`` and ``FIRST_BALL``.
    """
    n_shots = pocketed.shape[0]
    n_balls = on_table.shape[1]
    # Few returned arrays: numba spends about a microsecond handing each one to Python.
    values = np.empty((n_shots, 5))
    flags = np.zeros((n_shots, N_FLAGS), dtype=np.bool_)
    balls_hit = np.zeros((n_shots, N_HITS), dtype=np.int64)
    others = np.empty((n_balls, 2))
    potted = np.zeros(n_balls, dtype=np.bool_)
    shaping = params[W_SHAPING] != 0.0
    for k in range(n_shots):
        b = tables[k]
        phi_before = 0.0
        if shaping:
            phi_before = potential(positions[b], on_table[b], pockets, params[DIAGONAL])
        n_potted, bits, scratch = settle(positions, on_table, b, balls, final, pocketed, k,
                                         potted)  # fmt: skip
        shots[b] += 1
        first_hit = first_ball(balls, first, k)
        phi_change = 0.0
        if shaping:
            phi_after = potential(positions[b], on_table[b], pockets, params[DIAGONAL])
            phi_change = phi_after - phi_before
        terminated, truncated, cleared, spot_taken = _solitaire(
            params, pockets, positions[b], on_table[b], shots[b], n_potted, scratch, others,
        )  # fmt: skip
        no_contact = first_hit < 0
        values[k, REWARD] = (
            params[W_POT] * n_potted
            + params[W_SCRATCH] * (1.0 if scratch else 0.0)
            + params[W_NO_CONTACT] * (1.0 if no_contact else 0.0)
            + params[W_SHAPING] * phi_change
        )
        # The terms as info reports them: a term that did not happen is 0.0, not -0.0.
        values[k, POT] = params[W_POT] * n_potted if n_potted else 0.0
        values[k, SCRATCHED] = params[W_SCRATCH] if scratch else 0.0
        values[k, NO_CONTACT] = params[W_NO_CONTACT] if no_contact else 0.0
        values[k, SHAPING] = params[W_SHAPING] * phi_change if shaping else 0.0
        flags[k, TERMINATED], flags[k, TRUNCATED], flags[k, CLEARED] = (
            terminated, truncated, cleared
        )  # fmt: skip
        flags[k, SCRATCH], flags[k, SPOT_TAKEN] = scratch, spot_taken
        balls_hit[k, POTTED_BITS], balls_hit[k, FIRST_BALL] = bits, first_hit
    return values, flags, balls_hit


@kernel
def _solitaire(params, pockets, positions, on_table, shots, n_potted, scratch, others):
    """The solitaire rule's ends for one table after its shot (see the module docstring).

    Args:
        params: The config's numbers.
        pockets: ``(P, 3)`` capture circles.
        positions: ``(N, 2)`` the table's balls after the shot, updated in place.
        on_table: ``(N,)`` which are on the table, updated in place.
        shots: Shots of the episode, this one included.
        n_potted: Object balls the shot potted.
        scratch: Whether the cue ball dropped.
        others: ``(N, 2)`` scratch space.

    Returns:
        ``(terminated, truncated, cleared, spot_taken)``.
    """
    spot_taken = False
    if scratch:  # back on the head spot when it is free
        spot_taken = not spot_ball(
            positions, on_table, CUE, params[SPOT_X], params[SPOT_Y], params, pockets, others
        )
    cleared = True
    for j in range(on_table.shape[0]):
        if j != CUE and on_table[j]:
            cleared = False
    missed = n_potted == 0 or scratch
    terminated = cleared or (params[END_ON_MISS] != 0.0 and missed)
    limit = params[SHOT_LIMIT]
    truncated = limit > 0.0 and shots >= limit
    return terminated, truncated, cleared, spot_taken
