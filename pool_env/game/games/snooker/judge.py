"""Snooker's step kernels, compiled: the strokes struck, then the outcomes judged.

:func:`snooker_shots` places each cue ball in hand in the D and decodes the nomination,
then strikes; :func:`judge_snooker` reads each outcome (the balls that dropped, the first
ball hit, the balls the cue ball touched at the stroke) and hands it to
:func:`pool_env.game.games.snooker.rules.judge_stroke`, the one copy of the rules.

The action is ``(aim, speed, cue x, cue y, nomination)``, then a spin table's tip:

- ``cue x`` and ``cue y`` place a cue ball in hand in the D (:func:`.geometry.d_point`:
  ``cue x`` from the baulk line (-1) to the D's rear (+1), ``cue y`` across the D's chord
  there); a covered point goes to the nearest free one of the D; read only in hand;
- ``nomination``: seven equal bins over ``[-1, 1]``: the first nominates nothing, the
  others yellow .. black (balls 16 .. 21). Read after a red (the colour on) and for a
  free ball (a colour other than the ball on; nothing plays the ball on).

Reward terms (:data:`pool_env.game.games.snooker.section.REWARD_TERMS`): ``pot`` per
point the striker scores, ``foul`` per penalty point the striker's foul gives the
opponent, ``win`` for winning the frame (minus it for losing it), each times its scale.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.games.snooker.geometry import d_point, place_in_d
from pool_env.game.games.snooker.params import END_ON_FOUL, W_PENALTY, W_POINTS, W_WIN
from pool_env.game.games.snooker.rack_state import (
    FIRST_COLOUR,
    IN_HAND,
    SCORE_0,
    SCORE_1,
    SHOOTER,
    WINNER,
    legal_targets,
)
from pool_env.game.games.snooker.rules import (
    R_BALL_ON,
    R_BREAK,
    R_FOUL,
    R_FREE,
    R_NOMINATED,
    R_PENALTY,
    R_PLACED,
    R_POINTS,
    R_TIE,
    R_TURN_OVER,
    judge_stroke,
    touching_balls,
)
from pool_env.game.kernels.actions import decode_actions, decoded_tips, shot_arrays, strike, unit
from pool_env.game.kernels.outcome import (
    CLEARED,
    FIRST_BALL,
    N_FLAGS,
    N_HITS,
    POTTED_BITS,
    REWARD,
    SCRATCH,
    TERMINATED,
    TRUNCATED,
    first_ball,
    settle,
)
from pool_env.game.kernels.params import (
    AIM_HIGH,
    AIM_LOW,
    RADIUS,
    SHOT_LIMIT,
    SPEED_HIGH,
    SPEED_LOW,
    TIP_COLUMN,
)
from pool_env.game.kernels.rng import next_double
from pool_env.sim.jit import kernel

#: Bins of the nomination column: none, then the six colours.
N_NOMINATIONS = 7

#: Snooker's boolean result column after the shared ones: a ball could not be placed by
#: the rules (no room on a colour's lines, or in the D): the caller places it.
UNPLACED = N_FLAGS

#: Snooker's integer result columns after the shared ones.
(
    FOUL, PENALTY, POINTS, BALL_ON, NOMINATED, FREE, TURN_OVER, BREAK_AFTER, WINNER_AFTER,
    SCORE_A, SCORE_B, N_SNOOKER_HITS,
) = range(N_HITS, N_HITS + 12)  # fmt: skip

#: Columns of the float results after the reward: the three scaled reward terms.
POINTS_TERM, PENALTY_TERM, WIN_TERM = 1, 2, 3


@kernel
def nomination_of(value):
    """The colour a nomination component names (16 .. 21), or 0 for none."""
    bin_ = min(int(unit(value) * N_NOMINATIONS), N_NOMINATIONS - 1)
    return 0 if bin_ == 0 else FIRST_COLOUR - 1 + bin_


@kernel
def snooker_shots(params, pockets, actions, tables, positions, on_table, ptrs, rack):
    """Each cue ball in hand placed in the D, the nominations read, the strokes struck.

    Returns:
        ``(shots, velocities, nominations, unplaced)``: as
        :func:`pool_env.game.kernels.actions.executed_shots`, the ``(K,)`` nominated
        colours (0: none), and the ``(K,)`` rows whose D had no free point (the caller
        refuses the step).
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    aims, speeds = decode_actions(
        actions, params[AIM_LOW], params[AIM_HIGH], params[SPEED_LOW], params[SPEED_HIGH]
    )
    tips = decoded_tips(params, actions, int(params[TIP_COLUMN]))
    shots, velocities = shot_arrays(params, n_shots, n_balls)
    nominations = np.zeros(n_shots, dtype=np.int64)
    unplaced = np.zeros(n_shots, dtype=np.bool_)
    targets = np.empty(n_balls, dtype=np.bool_)
    others = np.empty((n_balls, 2))
    for k in range(n_shots):
        b = tables[k]
        if rack[b, IN_HAND] != 0:
            x, y = d_point(params, unit(actions[k, 2]), 2.0 * unit(actions[k, 3]) - 1.0)
            if not place_in_d(params, pockets, positions[b], on_table[b], x, y, others):
                unplaced[k] = True
                shots[k, :] = 0.0
                continue
        nominations[k] = nomination_of(actions[k, 4])
        legal_targets(rack[b], on_table[b], targets)
        strike(params, aims[k], speeds[k], tips[k], positions[b], targets, ptrs[b], shots[k],
               velocities[k])  # fmt: skip
    return shots, velocities, nominations, unplaced


@kernel
def judge_snooker(params, pockets, tables, balls, positions, on_table, shots, rack, final,
                  pocketed, first, nominations, ptrs):  # fmt: skip
    """Apply a batch of simulated strokes to the tables by the rules.

    Returns:
        ``(values, flags, hits)``: ``(K, 4)`` floats, the reward then its three scaled
        terms; ``(K, N_FLAGS + 1)`` booleans (the shared columns, then :data:`UNPLACED`);
        ``(K, N_SNOOKER_HITS)`` integers (``POTTED_BITS``, ``FIRST_BALL``, then
        :data:`FOUL` .. :data:`SCORE_B`). ``CLEARED`` is set when the striker won the
        frame with the stroke. ``TERMINATED``: the frame is decided, or with
        ``end_on_foul`` (one visit) the turn passes.
    """
    n_shots = pocketed.shape[0]
    n_balls = on_table.shape[1]
    values = np.zeros((n_shots, 4))
    flags = np.zeros((n_shots, N_FLAGS + 1), dtype=np.bool_)
    hits = np.zeros((n_shots, N_SNOOKER_HITS), dtype=np.int64)
    others = np.empty((n_balls, 2))
    before = np.empty(n_balls, dtype=np.bool_)
    potted = np.zeros(n_balls, dtype=np.bool_)
    touching = np.zeros(n_balls, dtype=np.bool_)
    limit = params[SHOT_LIMIT]
    for k in range(n_shots):
        b = tables[k]
        row = rack[b]
        shooter = row[SHOOTER]
        touching_balls(positions[b], on_table[b], params[RADIUS], touching)
        before[:] = on_table[b]
        first_hit = first_ball(balls, first, k)
        _, bits, scratch = settle(positions, on_table, b, balls, final, pocketed, k, potted)
        on_table[b, :] = before  # the rules take the balls off (and put colours back)
        potted[0] = scratch
        shots[b] += 1
        res = judge_stroke(params, pockets, row, positions[b], on_table[b], potted, first_hit,
                           nominations[k], touching, others)  # fmt: skip
        if res[R_TIE] != 0:  # S3 R4(b)(ii): lots drawn for who plays the re-spotted black
            row[SHOOTER] = 0 if next_double(ptrs[b]) < 0.5 else 1
        winner = row[WINNER]
        values[k, POINTS_TERM] = params[W_POINTS] * res[R_POINTS] if res[R_POINTS] else 0.0
        values[k, PENALTY_TERM] = params[W_PENALTY] * res[R_PENALTY] if res[R_PENALTY] else 0.0
        if winner >= 0:
            values[k, WIN_TERM] = params[W_WIN] if winner == shooter else -params[W_WIN]
        values[k, REWARD] = values[k, POINTS_TERM] + values[k, PENALTY_TERM] + values[k, WIN_TERM]
        turn_over = res[R_TURN_OVER] != 0
        flags[k, TERMINATED] = winner >= 0 or (params[END_ON_FOUL] != 0.0 and turn_over)
        flags[k, TRUNCATED] = limit > 0.0 and shots[b] >= limit
        flags[k, CLEARED] = winner >= 0 and winner == shooter
        flags[k, SCRATCH] = scratch
        flags[k, UNPLACED] = res[R_PLACED] == 0
        hits[k, POTTED_BITS], hits[k, FIRST_BALL] = bits, first_hit
        hits[k, FOUL], hits[k, PENALTY], hits[k, POINTS] = (
            res[R_FOUL],
            res[R_PENALTY],
            res[R_POINTS],
        )
        hits[k, BALL_ON], hits[k, NOMINATED] = res[R_BALL_ON], res[R_NOMINATED]
        hits[k, FREE], hits[k, TURN_OVER] = res[R_FREE], res[R_TURN_OVER]
        hits[k, BREAK_AFTER], hits[k, WINNER_AFTER] = res[R_BREAK], winner
        hits[k, SCORE_A], hits[k, SCORE_B] = row[SCORE_0], row[SCORE_1]
    return values, flags, hits
