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

The rules of 9-ball, 10-ball and 8-ball (``GameConfig.game`` ``"nine"``, ``"ten"``,
``"eight"``) are :func:`judge_rules`: the same outcome plus what the rules read (the
cushions each ball touched after the first contact, the order the balls dropped, the
calls: pocket, ball, push-out, handing the table back), judged
by :func:`pool_env.game.kernels.wpa.judge_rack` (the one copy of those rules, whose
docstring lists them and every simplification) on the rack state each table keeps in
``GameState.rack``. Practice reward: ``reward_pot`` per object ball potted on a legal shot
that counts its pots (not a push-out; in 10-ball, the break or a call made; a re-spotted
ball and the 8 of 8-ball not counted), ``reward_foul`` for a foul, ``reward_win`` for
winning the rack and minus it for losing it. A step that hands the table back plays no
shot and gives 0.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.kernels import wpa
from pool_env.game.kernels.actions import CALL_BALL, CALL_HAND_BACK, CALL_POCKET, CALL_PUSH_OUT
from pool_env.game.kernels.layout import point_free
from pool_env.game.kernels.observe import potential
from pool_env.game.kernels.params import (
    DIAGONAL,
    END_ON_FOUL,
    END_ON_MISS,
    FOOT_X,
    FOOT_Y,
    GAME,
    HEAD_X,
    PLAYERS,
    REACH,
    SHOT_LIMIT,
    SPOT_X,
    SPOT_Y,
    W_FOUL,
    W_NO_CONTACT,
    W_POT,
    W_SCRATCH,
    W_SHAPING,
    W_WIN,
)
from pool_env.sim.jit import kernel

CUE = 0  # the cue ball's row in every layout

#: Columns of :func:`judge`'s boolean results (:func:`judge_rules` adds RESPOT_TAKEN).
TERMINATED, TRUNCATED, CLEARED, SCRATCH, SPOT_TAKEN, RESPOT_TAKEN = range(6)

#: Columns of :func:`judge`'s integer results (:func:`judge_rules` adds the rest): the
#: foul code, the ball on before the shot, the winner (-1: undecided), why the rack was
#: lost, the re-spotted ball (-1: none), whether the shooter's turn goes on, and how the
#: step was played (:data:`pool_env.game.kernels.wpa.SHOT`, ``PUSHED_OUT``, ``HANDED_BACK``).
POTTED_BITS, FIRST_BALL, FOUL, BALL_ON, WINNER, LOSS, RESPOT, KEEPS, PLAY = range(9)


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
    n_shots = pocketed.shape[0]
    n_balls = on_table.shape[1]
    # Few returned arrays: numba spends about a microsecond handing each one to Python.
    rewards = np.empty(n_shots)
    flags = np.zeros((n_shots, 5), dtype=np.bool_)
    balls_hit = np.zeros((n_shots, 2), dtype=np.int64)
    others = np.empty((n_balls, 2))
    potted = np.zeros(n_balls, dtype=np.bool_)
    shaping = params[W_SHAPING] != 0.0
    for k in range(n_shots):
        b = tables[k]
        phi_before = 0.0
        if shaping:
            phi_before = potential(positions[b], on_table[b], pockets, params[DIAGONAL])
        n_potted, bits, scratch = _settle(positions, on_table, b, balls, final, pocketed, k,
                                          potted)  # fmt: skip
        shots[b] += 1
        first_ball = _first_ball(balls, first, k)
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
def _settle(positions, on_table, b, balls, final, pocketed, k, potted):
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
def _first_ball(balls, first, k):
    """The first ball the cue ball hit in result row ``k`` (-1 for none)."""
    if first[k, 0] < 0:
        return -1
    i, j = balls[first[k, 0]], balls[first[k, 1]]
    return j if i == CUE else i


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
        spot_taken = not _spot(
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
    return reward, terminated, truncated, cleared, spot_taken


@kernel
def _spot(positions, on_table, ball, x, y, params, pockets, others):
    """Put ``ball`` back on ``(x, y)`` if free; False when something covers the point."""
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
def judge_rules(params, pockets, tables, balls, positions, on_table, shots, rack, final,
                pocketed, first, cushions, order, calls, crossed):  # fmt: skip
    """Apply a batch of simulated shots to the tables by the 9-ball, 10-ball or 8-ball rules.

    Args:
        params: The config's numbers; ``params[GAME]`` selects the game.
        pockets: ``(P, 3)`` capture circles.
        tables: ``(K,)`` tables that shot.
        balls: ``(M,)`` ball number of each column of the results.
        positions: ``(B, N, 2)`` state, updated in place.
        on_table: ``(B, N)`` state, updated in place.
        shots: ``(B,)`` shots of each episode, counted up in place.
        rack: ``(B, N_RACK)`` rack states (:mod:`pool_env.game.kernels.wpa`), updated.
        final: ``(K, M, 2)`` simulated final positions.
        pocketed: ``(K, M)`` pocket of each ball, -1 for none.
        first: ``(K, 2)`` result columns of the first ball-ball impact, -1 for none.
        cushions: ``(K, M)`` each ball's cushion impacts after the first contact.
        order: ``(K, M)`` the order the balls dropped (0 first), -1 if they did not.
        calls: ``(K, N_CALLS)`` the calls (``executed_rule_shots``): the pocket (the 8's,
            10-ball's), the ball (10-ball), a push-out, handing the table back.
        crossed: ``(K,)`` the cue ball's centre passed the head string before its first
            contact (read only when the cue ball was in hand behind the head string and
            its first ball lies behind it: :func:`pool_env.game.contact.read_first`).

    Returns:
        ``(rewards, flags, hits)``: ``(K,)``; ``(K, 6)`` booleans (:data:`TERMINATED` ..
        :data:`RESPOT_TAKEN`: the foot spot is covered, the re-spotted ball is on the table
        but not yet placed); ``(K, 9)`` integers (:data:`POTTED_BITS` .. :data:`PLAY`).
        ``CLEARED`` is set when the shooter won the rack with the shot.
    """
    n_shots, n_cols = pocketed.shape
    n_balls = on_table.shape[1]
    game, players = int(params[GAME]), int(params[PLAYERS])
    rewards = np.empty(n_shots)
    flags = np.zeros((n_shots, 6), dtype=np.bool_)
    hits = np.zeros((n_shots, 9), dtype=np.int64)
    others = np.empty((n_balls, 2))
    before = np.empty(n_balls, dtype=np.bool_)
    potted = np.zeros(n_balls, dtype=np.bool_)
    limit = params[SHOT_LIMIT]
    for k in range(n_shots):
        b = tables[k]
        shooter = rack[b, wpa.SHOOTER]
        if calls[k, CALL_HAND_BACK] != 0 and wpa.hand_back(players, rack[b]):
            shots[b] += 1  # a decision of its own, counted as a step; nothing moved
            rewards[k] = 0.0
            flags[k, TERMINATED] = params[END_ON_FOUL] != 0.0
            flags[k, TRUNCATED] = limit > 0.0 and shots[b] >= limit
            hits[k, FIRST_BALL], hits[k, WINNER], hits[k, RESPOT] = -1, -1, -1
            hits[k, BALL_ON] = wpa.ball_on(game, rack[b], on_table[b], shooter)
            hits[k, PLAY] = wpa.HANDED_BACK
            continue
        before[:] = on_table[b]
        first_ball = _first_ball(balls, first, k)
        first_x = positions[b, first_ball, 0] if first_ball >= 0 else 0.0  # still at rest
        kitchen = wpa.kitchen_foul(rack[b], first_ball, first_x, params[HEAD_X], crossed[k])
        _, bits, scratch = _settle(positions, on_table, b, balls, final, pocketed, k, potted)
        rail, to_rail = False, 0
        first_dropped, first_order, eight_pocket = -1, n_cols + 1, -1
        called_ball = calls[k, CALL_BALL] if game == wpa.TEN else -1
        call_made = False
        for c in range(n_cols):  # what the rules read besides: rails, the order of drops
            j = balls[c]
            if cushions[k, c] > 0:
                rail = True
                if j != CUE:
                    to_rail += 1
            if j != CUE and potted[j]:
                if j == called_ball and pocketed[k, c] == calls[k, CALL_POCKET]:
                    call_made = True
                if j == 8 and game == wpa.EIGHT:
                    eight_pocket = pocketed[k, c]
                elif order[k, c] < first_order:
                    first_order, first_dropped = order[k, c], j
        shots[b] += 1
        pushed = calls[k, CALL_PUSH_OUT] != 0 and rack[b, wpa.PUSH_OUT] != 0
        foul, on, respot, loss, keeps, counts = wpa.judge_rack(
            game, players, rack[b], before, first_ball, scratch, potted, first_dropped,
            eight_pocket, calls[k, CALL_POCKET], rail, to_rail, kitchen, pushed, called_ball,
            call_made,
        )  # fmt: skip
        winner = rack[b, wpa.WINNER]
        legal_pots = 0  # the 8 of 8-ball is no pot: it wins or loses the rack
        if counts:
            for j in range(1, n_balls):
                if potted[j] and j != respot and not (j == 8 and game == wpa.EIGHT):
                    legal_pots += 1
        reward = params[W_POT] * legal_pots
        if foul != wpa.NO_FOUL:
            reward += params[W_FOUL]
        if winner >= 0:
            reward += params[W_WIN] if winner == shooter else -params[W_WIN]
        rewards[k] = reward
        if respot >= 0:  # on the foot spot when it is free
            flags[k, RESPOT_TAKEN] = not _spot(
                positions[b], on_table[b], respot, params[FOOT_X], params[FOOT_Y], params,
                pockets, others,
            )  # fmt: skip
        if scratch:  # on the head spot while in hand (the next shot places it)
            flags[k, SPOT_TAKEN] = not _spot(
                positions[b], on_table[b], CUE, params[SPOT_X], params[SPOT_Y], params,
                pockets, others,
            )  # fmt: skip
        turn_over = foul != wpa.NO_FOUL or not keeps
        flags[k, TERMINATED] = winner >= 0 or (params[END_ON_FOUL] != 0.0 and turn_over)
        flags[k, TRUNCATED] = limit > 0.0 and shots[b] >= limit
        flags[k, CLEARED] = winner >= 0 and winner == shooter
        flags[k, SCRATCH] = scratch
        hits[k, POTTED_BITS], hits[k, FIRST_BALL], hits[k, FOUL] = bits, first_ball, foul
        hits[k, BALL_ON], hits[k, WINNER], hits[k, LOSS] = on, winner, loss
        hits[k, RESPOT], hits[k, KEEPS] = respot, 1 if keeps else 0
        hits[k, PLAY] = wpa.PUSHED_OUT if pushed else wpa.SHOT
    return rewards, flags, hits
