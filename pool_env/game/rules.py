"""The rules: what a shot's outcome means. The one place for every rule of the game.

Both fronts (:class:`pool_env.PoolEnv`, :class:`pool_env.PoolVectorEnv`) run
:func:`judge` through :func:`pool_env.game.step.step`, right after the simulator has said
where every ball ended and which dropped. ``judge`` is compiled and loops over the tables
that shot; per table it applies the rule below, reading only the outcome and the table's
state.

The rule of the registered ids is *solitaire*: one player pots every object ball in any
order and any pocket.

* A potted object ball leaves the table (keeping its capture point as its position).
* A potted cue ball (a scratch) goes back on the head spot, or, when the spot is taken
  (the caller finishes that case with :func:`pool_env.game.scenes.free_spot`), on the
  free point nearest to it.
* Reward: ``reward_pot`` per object ball potted, ``reward_scratch`` for a scratch,
  ``reward_no_contact`` when the cue ball hits no ball, and ``reward_shaping`` times the
  change of the pocket-distance potential (:func:`pool_env.game.kernels.observe.potential`).
* The episode terminates when the table is cleared, and with ``end_on_miss`` after a shot
  that pots nothing or scratches; it is truncated after ``shot_limit`` shots.

Where game rules go (fouls, ball in hand, turns, two players): here. A new rule is a
function beside :func:`_solitaire` reading the same outcome (``potted``, ``scratch``,
``first_ball``; the shot's events if it needs them) and the state it keeps in
:class:`pool_env.game.state.GameState` (whose turn, ball in hand), selected by a
:class:`pool_env.game.config.GameConfig` field; :func:`pool_env.game.step.step` and the
fronts do not change.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.kernels.layout import point_free
from pool_env.game.kernels.observe import potential
from pool_env.game.kernels.params import (
    DIAGONAL,
    END_ON_MISS,
    REACH,
    SHOT_LIMIT,
    SPOT_X,
    SPOT_Y,
    W_NO_CONTACT,
    W_POT,
    W_SCRATCH,
    W_SHAPING,
)
from pool_env.sim.kernels._jit import kernel

CUE = 0  # the cue ball's row in every layout

#: Columns of :func:`judge`'s boolean results.
TERMINATED, TRUNCATED, CLEARED, SCRATCH, SPOT_TAKEN = range(5)

#: Columns of :func:`judge`'s integer results.
POTTED_BITS, FIRST_BALL = range(2)


@kernel
def judge(params, pockets, tables, balls, positions, on_table, shots, final, pocketed, first):
    """Apply a batch of simulated shots to the tables, by the rules.

    Args:
        params: The config's numbers (:mod:`pool_env.game.kernels.params`).
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
        ``(rewards, flags, balls_hit)``: ``(K,)`` rewards; ``(K, 5)`` booleans, by the
        column names :data:`TERMINATED`, :data:`TRUNCATED`, :data:`CLEARED`,
        :data:`SCRATCH` (the cue ball dropped) and :data:`SPOT_TAKEN` (something covers
        the head spot: the cue ball is back on the table but not yet placed); ``(K, 2)``
        integers: :data:`POTTED_BITS` (bit ``j - 1`` for each object ball ``j`` potted, up
        to 63) and :data:`FIRST_BALL` (the first ball the cue ball hit, -1 for none).
    """
    n_shots, n_cols = pocketed.shape
    n_balls = on_table.shape[1]
    # Few returned arrays: numba spends about a microsecond handing each one to Python.
    rewards = np.empty(n_shots)
    flags = np.zeros((n_shots, 5), dtype=np.bool_)
    balls_hit = np.zeros((n_shots, 2), dtype=np.int64)
    others = np.empty((n_balls, 2))
    shaping = params[W_SHAPING] != 0.0
    for k in range(n_shots):
        b = tables[k]
        phi_before = 0.0
        if shaping:
            phi_before = potential(positions[b], on_table[b], pockets, params[DIAGONAL])
        n_potted, bits, scratch = 0, np.int64(0), False
        for c in range(n_cols):  # what happened: balls move, potted ones leave
            j = balls[c]
            positions[b, j, 0] = final[k, c, 0]
            positions[b, j, 1] = final[k, c, 1]
            if pocketed[k, c] >= 0:
                on_table[b, j] = False
                if j == CUE:
                    scratch = True
                else:
                    n_potted += 1
                    if j <= 63:
                        bits |= np.int64(1) << (j - 1)
        shots[b] += 1
        first_ball = -1
        if first[k, 0] >= 0:
            i, j = balls[first[k, 0]], balls[first[k, 1]]
            first_ball = j if i == CUE else i
        phi_change = 0.0
        if shaping:
            phi_after = potential(positions[b], on_table[b], pockets, params[DIAGONAL])
            phi_change = phi_after - phi_before
        reward, terminated, truncated, cleared, spot_taken = _solitaire(
            params, pockets, positions[b], on_table[b], shots[b], n_potted, scratch,
            first_ball, phi_change, others,
        )  # fmt: skip
        rewards[k] = reward
        flags[k, TERMINATED], flags[k, TRUNCATED], flags[k, CLEARED] = (
            terminated, truncated, cleared
        )  # fmt: skip
        flags[k, SCRATCH], flags[k, SPOT_TAKEN] = scratch, spot_taken
        balls_hit[k, POTTED_BITS], balls_hit[k, FIRST_BALL] = bits, first_ball
    return rewards, flags, balls_hit


@kernel
def _solitaire(params, pockets, positions, on_table, shots, n_potted, scratch, first_ball,
               phi_change, others):  # fmt: skip
    """The solitaire rule for one table after its shot (see the module docstring).

    Args:
        params: The config's numbers.
        pockets: ``(P, 3)`` capture circles.
        positions: ``(N, 2)`` the table's balls after the shot, updated in place.
        on_table: ``(N,)`` which are on the table, updated in place.
        shots: Shots of the episode, this one included.
        n_potted: Object balls the shot potted.
        scratch: Whether the cue ball dropped.
        first_ball: First ball the cue ball hit, -1 for none.
        phi_change: Change of the shaping potential.
        others: ``(N, 2)`` scratch space.

    Returns:
        ``(reward, terminated, truncated, cleared, spot_taken)``.
    """
    reward = (
        params[W_POT] * n_potted
        + params[W_SCRATCH] * (1.0 if scratch else 0.0)
        + params[W_NO_CONTACT] * (1.0 if first_ball < 0 else 0.0)
        + params[W_SHAPING] * phi_change
    )
    spot_taken = False
    if scratch:  # back on the head spot when it is free
        on_table[CUE] = True
        count = 0
        for j in range(on_table.shape[0]):
            if j != CUE and on_table[j]:
                others[count] = positions[j]
                count += 1
        sx, sy, reach = params[SPOT_X], params[SPOT_Y], params[REACH]
        if point_free(sx, sy, params, pockets, others, count, reach * reach):
            positions[CUE, 0], positions[CUE, 1] = sx, sy
        else:
            spot_taken = True
    cleared = True
    for j in range(on_table.shape[0]):
        if j != CUE and on_table[j]:
            cleared = False
    missed = n_potted == 0 or scratch
    terminated = cleared or (params[END_ON_MISS] != 0.0 and missed)
    limit = params[SHOT_LIMIT]
    truncated = limit > 0.0 and shots >= limit
    return reward, terminated, truncated, cleared, spot_taken
