"""The WPA games' judge, compiled: a batch of simulated shots read by the rules.

:func:`judge_rules` reads what the rules need of each outcome (the balls that dropped and
in which order, the cushions each ball touched after the first contact, the calls: pocket,
ball, push-out, handing the table back) and hands it to
:func:`pool_env.game.games.wpa.rules.judge_rack` (the one copy of the rules, whose
docstring lists them and every simplification) on the rack state each table keeps in
``GameState.rack``. Run-out mode (``end_on_foul``) ends the episode at a foul or a legal
shot that does not keep the table, but for one agent's legal push-out: it shoots on.
Practice reward, as three terms
(:data:`pool_env.game.games.wpa.game.REWARD_TERMS`): ``pot`` per object ball potted on a
legal shot that counts its pots (not a push-out; in 10-ball, the break or a call made; a
re-spotted ball and the 8 of 8-ball not counted), ``foul`` for a foul, ``win`` for winning
the rack and minus it for losing it, each times its scale. A step that hands the table
back plays no shot and gives 0.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.games.wpa import rack_state as wpa
from pool_env.game.games.wpa.params import (
    END_ON_FOUL,
    FOOT_X,
    FOOT_Y,
    HEAD_X,
    OPTION_COLUMN,
    VARIANT,
    W_FOUL,
    W_POT,
    W_WIN,
)
from pool_env.game.games.wpa.rules import hand_back, judge_rack, kitchen_foul
from pool_env.game.games.wpa.shots import CALL_BALL, CALL_HAND_BACK, CALL_POCKET, CALL_PUSH_OUT
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
from pool_env.game.kernels.params import PLAYERS, SHOT_LIMIT, SPOT_X, SPOT_Y
from pool_env.sim.jit import kernel

#: The WPA games' boolean result column after the shared ones: the foot spot is covered,
#: the re-spotted ball is on the table but not yet placed.
RESPOT_TAKEN = N_FLAGS

#: The WPA games' integer result columns after the shared ones: the foul code, the ball on
#: before the shot, the winner (-1: undecided), why the rack was lost, the re-spotted ball
#: (-1: none), whether the shooter's turn goes on, and how the step was played
#: (:data:`pool_env.game.games.wpa.rack_state.SHOT`, ``PUSHED_OUT``, ``HANDED_BACK``).
FOUL, BALL_ON, WINNER, LOSS, RESPOT, KEEPS, PLAY, N_WPA_HITS = range(N_HITS, N_HITS + 8)

#: Columns of the float results after the reward: the three scaled reward terms.
POT, FOUL_TERM, WIN = 1, 2, 3


@kernel
def judge_rules(params, pockets, tables, balls, positions, on_table, shots, rack, final,
                pocketed, first, cushions, order, calls, crossed):  # fmt: skip
    """Apply a batch of simulated shots to the tables by the 9-ball, 10-ball or 8-ball rules.

    Args:
        params: The config's numbers; ``params[VARIANT]`` selects the game.
        pockets: ``(P, 3)`` capture circles.
        tables: ``(K,)`` tables that shot.
        balls: ``(M,)`` ball number of each column of the results.
        positions: ``(B, N, 2)`` state, updated in place.
        on_table: ``(B, N)`` state, updated in place.
        shots: ``(B,)`` shots of each episode, counted up in place.
        rack: ``(B, N_RACK)`` rack states (:mod:`pool_env.game.games.wpa.rack_state`), updated.
        final: ``(K, M, 2)`` simulated final positions.
        pocketed: ``(K, M)`` pocket of each ball, -1 for none.
        first: ``(K, 2)`` result columns of the first ball-ball impact, -1 for none.
        cushions: ``(K, M)`` each ball's cushion impacts after the first contact.
        order: ``(K, M)`` the order the balls dropped (0 first), -1 if they did not.
        calls: ``(K, N_CALLS)`` the calls (``executed_rule_shots``): the pocket (the 8's,
            10-ball's), the ball (10-ball), a push-out, handing the table back.
        crossed: ``(K,)`` the cue ball's centre passed the head string before its first
            contact (read only when the cue ball was in hand behind the head string and
            its first ball lies behind it: :func:`.first_contact.read_first`).

    Returns:
        ``(values, flags, hits)``: ``(K, 4)`` floats, the reward then its three scaled
        terms (:data:`POT`, :data:`FOUL_TERM`, :data:`WIN`); ``(K, 6)`` booleans (the
        shared columns, then :data:`RESPOT_TAKEN`); ``(K, 9)`` integers (``POTTED_BITS``,
        ``FIRST_BALL``, then :data:`FOUL` .. :data:`PLAY`).
        ``CLEARED`` is set when the shooter won the rack with the shot.
    """
    n_shots, n_cols = pocketed.shape
    n_balls = on_table.shape[1]
    game, players = int(params[VARIANT]), int(params[PLAYERS])
    offers_push_out = params[OPTION_COLUMN] >= 0.0  # False: push_out=False (NineBallGame-v1)
    values = np.zeros((n_shots, 4))
    flags = np.zeros((n_shots, N_FLAGS + 1), dtype=np.bool_)
    hits = np.zeros((n_shots, N_WPA_HITS), dtype=np.int64)
    others = np.empty((n_balls, 2))
    before = np.empty(n_balls, dtype=np.bool_)
    potted = np.zeros(n_balls, dtype=np.bool_)
    limit = params[SHOT_LIMIT]
    for k in range(n_shots):
        b = tables[k]
        shooter = rack[b, wpa.SHOOTER]
        if calls[k, CALL_HAND_BACK] != 0 and hand_back(players, rack[b]):
            shots[b] += 1  # a decision of its own, counted as a step; nothing moved
            flags[k, TERMINATED] = params[END_ON_FOUL] != 0.0
            flags[k, TRUNCATED] = limit > 0.0 and shots[b] >= limit
            hits[k, FIRST_BALL], hits[k, WINNER], hits[k, RESPOT] = -1, -1, -1
            hits[k, BALL_ON] = wpa.ball_on(game, rack[b], on_table[b], shooter)
            hits[k, PLAY] = wpa.HANDED_BACK
            continue
        before[:] = on_table[b]
        first_hit = first_ball(balls, first, k)
        first_x = positions[b, first_hit, 0] if first_hit >= 0 else 0.0  # still at rest
        kitchen = kitchen_foul(rack[b], first_hit, first_x, params[HEAD_X], crossed[k])
        _, bits, scratch = settle(positions, on_table, b, balls, final, pocketed, k, potted)
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
        foul, on, respot, loss, keeps, counts = judge_rack(
            game, players, rack[b], before, first_hit, scratch, potted, first_dropped,
            eight_pocket, calls[k, CALL_POCKET], rail, to_rail, kitchen, pushed, called_ball,
            call_made, offers_push_out,
        )  # fmt: skip
        winner = rack[b, wpa.WINNER]
        legal_pots = 0  # the 8 of 8-ball is no pot: it wins or loses the rack
        if counts:
            for j in range(1, n_balls):
                if potted[j] and j != respot and not (j == 8 and game == wpa.EIGHT):
                    legal_pots += 1
        reward = params[W_POT] * legal_pots
        values[k, POT] = reward if legal_pots else 0.0  # 0.0, not -0.0, for no pot
        if foul != wpa.NO_FOUL:
            values[k, FOUL_TERM] = params[W_FOUL]
            reward += params[W_FOUL]
        if winner >= 0:
            values[k, WIN] = params[W_WIN] if winner == shooter else -params[W_WIN]
            reward += values[k, WIN]
        values[k, REWARD] = reward
        if respot >= 0:  # on the foot spot when it is free
            flags[k, RESPOT_TAKEN] = not spot_ball(
                positions[b], on_table[b], respot, params[FOOT_X], params[FOOT_Y], params,
                pockets, others,
            )  # fmt: skip
        if scratch:  # on the head spot while in hand (the next shot places it)
            flags[k, SPOT_TAKEN] = not spot_ball(
                positions[b], on_table[b], CUE, params[SPOT_X], params[SPOT_Y], params,
                pockets, others,
            )  # fmt: skip
        turn_over = foul != wpa.NO_FOUL or not keeps
        # One player shoots on after its legal push-out (the option needs an opponent), so
        # the run-out goes on though the turn, as two players count it, is over.
        run_ends = turn_over and not (pushed and foul == wpa.NO_FOUL and players == 1)
        flags[k, TERMINATED] = winner >= 0 or (params[END_ON_FOUL] != 0.0 and run_ends)
        flags[k, TRUNCATED] = limit > 0.0 and shots[b] >= limit
        flags[k, CLEARED] = winner >= 0 and winner == shooter
        flags[k, SCRATCH] = scratch
        hits[k, POTTED_BITS], hits[k, FIRST_BALL], hits[k, FOUL] = bits, first_hit, foul
        hits[k, BALL_ON], hits[k, WINNER], hits[k, LOSS] = on, winner, loss
        hits[k, RESPOT], hits[k, KEEPS] = respot, 1 if keeps else 0
        hits[k, PLAY] = wpa.PUSHED_OUT if pushed else wpa.SHOT
    return values, flags, hits
