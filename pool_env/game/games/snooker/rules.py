"""Snooker's rules (WPBSA), compiled: one stroke read against a table's frame state.

:func:`judge_stroke` is the one copy of the rules; the batch judge (:mod:`.judge`) calls
it per table. Rule numbers are those of the WPBSA's *Official Rules of the Games of
Snooker and English Billiards* (rules revised November 2019): "S2 R17" is Section 2
Rule 17.

What is on (S2 R11, S3 R3): a red while reds remain; after a red is potted, a colour the
striker nominates (S2 R12; the action's nomination column); with no red left, the
colours in ascending value (yellow 2 .. black 7). Potted reds stay off; a colour potted
while reds remain, and the colour potted after the last red, is re-spotted (S3 R7);
in order the colours stay off. Every legal pot scores its value (the reds potted on one
stroke each 1); the striker plays on after a stroke that scores, else the turn passes.

Fouls (S3 R10) and their penalty (S3 R11): the cue ball hits no ball, hits first a ball
not on, pots a ball not on, or is potted (then in hand in the D, S3 R5). The penalty goes
to the opponent and is 4, or the value of the ball on, of the nominated ball, of the ball
first hit (unless the touching-ball rule deems the ball on hit), or of a ball potted, the
highest. Balls potted on a foul score nothing; colours among them are re-spotted, reds
stay off.

Free ball (S2 R13, S3 R12): after a foul that leaves the incoming striker snookered
(S2 R17, :func:`.geometry.snookered`), the striker may nominate any colour not on as the
ball on (the nomination column; no nomination plays the ball on). That ball acquires the
value of the ball on: with reds on it scores 1 and a colour follows; in order it scores
the value of the colour on, which stays on; potted, it is re-spotted. The cue ball must
hit it first, and no ball but it and the ball on may be potted; potted with the ball on,
only the ball on scores (a red each). A free ball taken with reds on, if potted, is
followed by a colour, as a red is.

Touching ball (S3 R8): when the cue ball touches a ball that is on, or that can be on and
is nominated (within :data:`TOUCH` of ``2R`` at the stroke), the striker must play away
from it: a stroke whose first contact is that ball moved it, a push stroke (foul,
S2 R19); playing away, the ball on counts as hit, whatever the cue ball meets next.

End of frame (S3 R4): when only the black is left the first score or foul ends the frame;
the higher score wins. On equal scores the black is re-spotted (S3 R4(b)), the players
draw lots for who plays first (the table's generator), that player plays from in hand,
and the next score or foul ends the frame.

Left out, and why: the referee's judgements, which read the player's intent ("foul and a
miss", S3 R14, and with it three misses and replacing the balls: the simulator plays the
stroke given, so no attempt is more or less honest); the non-offender's choice to have the
offender play again (S3 R13: the incoming striker always plays); "snookered by the free
ball" as a foul (S3 R12(c)); hitting two balls simultaneously (S3 R6: the simulator's
first contact is one ball, exact ties have probability zero); jump shots, balls forced
off the table, push strokes other than into a touching ball, and other fouls of the
striker's body or cue (S3 R10: the simulator cannot make them); conceding and claiming
the frame; a foul for a stroke without a nomination (the nomination defaults: in a
colour-on stroke without one the colour touched, else the colour first hit; with neither
the ball on's value is taken as 7, the most it could have been).
"""

from __future__ import annotations

import numpy as np

from pool_env.game.games.snooker.geometry import (
    place_in_d,
    respot_colours,
    snookered,
    snookered_in_hand,
)
from pool_env.game.games.snooker.params import BAULK_X, CENTRE_Y, D_RADIUS
from pool_env.game.games.snooker.rack_state import (
    BLACK,
    BREAK,
    COLOUR_ON,
    FIRST_COLOUR,
    FOUL_IN_OFF,
    FOUL_NO_CONTACT,
    FOUL_POT_NOT_ON,
    FOUL_PUSH,
    FOUL_WRONG_BALL,
    FREE_BALL,
    IN_HAND,
    IN_ORDER,
    MIN_PENALTY,
    NO_FOUL,
    PHASE,
    RED_ON,
    RESPOTTED,
    SCORE_0,
    SHOOTER,
    VALUES,
    WINNER,
    lowest_colour,
    reds_left,
)
from pool_env.game.kernels.params import RADIUS
from pool_env.sim.jit import kernel

#: How near ``2R`` two centres count as touching (m): S3 R8's touching ball.
TOUCH = 1e-6

#: The results of :func:`judge_stroke`, in order (an int64 row).
(
    R_FOUL, R_PENALTY, R_POINTS, R_BALL_ON, R_NOMINATED, R_FREE, R_TURN_OVER, R_FRAME_OVER,
    R_TIE, R_PLACED, R_BREAK, N_RESULTS,
) = range(12)  # fmt: skip


@kernel
def touching_balls(positions, on_table, radius, out):
    """The object balls the cue ball touches (within :data:`TOUCH` of ``2R``) into ``out``."""
    out[:] = False
    limit = 2.0 * radius + TOUCH
    for j in range(1, on_table.shape[0]):
        if on_table[j]:
            dx = positions[j, 0] - positions[0, 0]
            dy = positions[j, 1] - positions[0, 1]
            out[j] = dx * dx + dy * dy <= limit * limit
    return out


@kernel
def judge_stroke(params, pockets, row, positions, on_table, potted, first, nominated,
                 touching, others):  # fmt: skip
    """Apply one stroke to a table by the rules (the module's text lists them).

    Args:
        params: The config's numbers (the markings, :mod:`.params`).
        pockets: ``(P, 3)`` capture circles.
        row: ``(N_RACK,)`` the table's frame state, moved on in place.
        positions: ``(N, 2)`` where the balls stopped; re-spotted colours and a cue ball
            in hand are placed in it.
        on_table: ``(N,)`` the balls on the table before the stroke; on return, after it
            (the potted ones off, the re-spotted ones back, the cue ball back in the D).
        potted: ``(N,)`` the balls the stroke potted, the cue ball's column included.
        first: The first ball the cue ball hit, -1 for none.
        nominated: The nominated colour (16 .. 21), or 0 for none.
        touching: ``(N,)`` the balls the cue ball touched before the stroke.
        others: ``(N, 2)`` scratch space.

    Returns:
        ``(N_RESULTS,)`` int64: the foul code, the penalty, the points scored, the ball on
        (1 for a red, a colour's number, 0 for an unnamed colour), the nominated ball
        that counted (-1: none), a free ball was played, the turn passes, the frame is
        over, it ended level (the re-spotted black follows), every ball was placed, the
        striker's break after the stroke (0 when the turn passes; a tie's reset leaves
        the row's break 0 for the next player, this keeps the striker's).
    """
    n = on_table.shape[0]
    out = np.zeros(N_RESULTS, dtype=np.int64)
    phase, free = row[PHASE], row[FREE_BALL] != 0
    shooter = row[SHOOTER]
    legal = np.zeros(n, dtype=np.bool_)
    is_colour = FIRST_COLOUR <= nominated <= BLACK and on_table[nominated]
    free_ball, colour, low = -1, -1, lowest_colour(on_table)
    on_value = 1
    if phase == RED_ON:
        if free and is_colour:
            free_ball = nominated
            legal[nominated] = True
        else:
            for j in range(1, FIRST_COLOUR):
                legal[j] = on_table[j]
        out[R_BALL_ON] = 1
    elif phase == COLOUR_ON:
        colour = nominated if is_colour else -1
        if colour < 0:  # no nomination: the colour touched, else the colour first hit
            for j in range(FIRST_COLOUR, BLACK + 1):
                if touching[j] and on_table[j]:
                    colour = j
                    break
        if colour < 0 and first >= FIRST_COLOUR and on_table[first]:
            colour = first
        if colour >= 0:
            legal[colour] = True
            on_value = VALUES[colour]
        else:
            on_value = VALUES[BLACK]
        out[R_BALL_ON] = max(colour, 0)
    else:
        on_value = VALUES[low]
        out[R_BALL_ON] = low
        if free and is_colour and nominated != low:
            free_ball = nominated
            legal[nominated] = True
        else:
            legal[low] = True
    out[R_NOMINATED] = free_ball if free_ball >= 0 else colour
    out[R_FREE] = 1 if free_ball >= 0 else 0
    touch_on = False
    for j in range(1, n):
        if touching[j] and legal[j]:
            touch_on = True
    push = first >= 0 and touching[first]
    deemed = touch_on and not push  # played away from a touching ball on: it counts as hit
    first_ok = (first >= 0 and legal[first]) or deemed
    pots_ok = True
    top_potted = 0
    for j in range(1, n):
        if not potted[j]:
            continue
        top_potted = max(top_potted, VALUES[j])
        if phase == RED_ON:
            allowed = j < FIRST_COLOUR or j == free_ball
        elif phase == COLOUR_ON:
            allowed = j == colour
        else:
            allowed = j == low or (free_ball >= 0 and j == free_ball)
        if not allowed:
            pots_ok = False
    foul = NO_FOUL
    if push:
        foul = FOUL_PUSH
    elif first < 0 and not deemed:
        foul = FOUL_NO_CONTACT
    elif not first_ok:
        foul = FOUL_WRONG_BALL
    elif potted[0]:
        foul = FOUL_IN_OFF
    elif not pots_ok:
        foul = FOUL_POT_NOT_ON
    points = 0
    to_spot = np.zeros(n, dtype=np.bool_)
    if foul != NO_FOUL:
        penalty = max(MIN_PENALTY, on_value, top_potted)
        if free_ball >= 0:
            penalty = max(penalty, VALUES[free_ball])
        if first >= 0 and (legal[first] or not deemed):
            penalty = max(penalty, VALUES[first])
        out[R_PENALTY] = penalty
        for j in range(FIRST_COLOUR, BLACK + 1):
            to_spot[j] = potted[j]
    elif phase == RED_ON:
        for j in range(1, n):
            if potted[j]:
                points += 1  # each red, and a free ball taken as a red
        if free_ball >= 0:
            to_spot[free_ball] = potted[free_ball]
    elif phase == COLOUR_ON:
        if potted[colour]:
            points = VALUES[colour]
            to_spot[colour] = True
    else:
        if potted[low] or (free_ball >= 0 and potted[free_ball]):
            points = VALUES[low]
        if free_ball >= 0:
            to_spot[free_ball] = potted[free_ball]
    out[R_FOUL], out[R_POINTS] = foul, points
    only_black = phase != COLOUR_ON and low == BLACK and not reds_left(on_table)
    for j in range(n):  # the balls potted leave the table (a cue ball potted: in hand)
        if potted[j]:
            on_table[j] = False
    if foul != NO_FOUL:
        row[SCORE_0 + 1 - shooter] += out[R_PENALTY]
    else:
        row[SCORE_0 + shooter] += points
    turn_over = foul != NO_FOUL or points == 0
    frame_over = only_black and (foul != NO_FOUL or points > 0)
    out[R_TURN_OVER] = 1 if turn_over else 0
    out[R_FRAME_OVER] = 1 if frame_over else 0
    out[R_BREAK] = 0 if turn_over else row[BREAK] + points
    row[FREE_BALL] = 0
    row[IN_HAND] = 1 if potted[0] else 0
    placed = True
    if frame_over:  # the balls stay as they lie, but a tie's re-spotted black
        row[BREAK] = out[R_BREAK]
        mine, theirs = row[SCORE_0 + shooter], row[SCORE_0 + 1 - shooter]
        if mine != theirs:
            row[WINNER] = shooter if mine > theirs else 1 - shooter
        else:  # S3 R4(b): the black re-spotted, played from in hand; lots drawn (caller)
            out[R_TIE] = 1
            to_spot[:] = False
            to_spot[BLACK] = True
            on_table[0] = False  # in hand, off the table: it covers no spot of the black's
            placed = respot_colours(params, pockets, positions, on_table, to_spot, others)
            row[SHOOTER], row[BREAK] = 1 - shooter, 0
            row[PHASE], row[IN_HAND], row[RESPOTTED] = IN_ORDER, 1, 1
    else:
        placed = respot_colours(params, pockets, positions, on_table, to_spot, others)
    if row[IN_HAND] != 0:  # S3 R5: in hand, in the D (the next stroke places it)
        placed = place_in_d(params, pockets, positions, on_table,
                            params[BAULK_X] - params[D_RADIUS] / 2.0, params[CENTRE_Y],
                            others) and placed  # fmt: skip
    out[R_PLACED] = 1 if placed else 0
    if frame_over:
        return out
    reds = reds_left(on_table)
    if not turn_over:
        row[BREAK] = out[R_BREAK]
        if phase == RED_ON:
            row[PHASE] = COLOUR_ON
        elif phase == COLOUR_ON:
            row[PHASE] = RED_ON if reds else IN_ORDER
        return out
    row[SHOOTER], row[BREAK] = 1 - shooter, 0
    row[PHASE] = RED_ON if reds else IN_ORDER
    if foul != NO_FOUL:  # S3 R12: a free ball when the incoming striker is snookered
        balls_on = np.zeros(n, dtype=np.bool_)
        if reds:
            for j in range(1, FIRST_COLOUR):
                balls_on[j] = on_table[j]
        else:
            low_after = lowest_colour(on_table)
            if low_after >= 0:
                balls_on[low_after] = True
        if row[IN_HAND] != 0:
            hidden = snookered_in_hand(params, pockets, positions, on_table, balls_on, others)
        else:
            hidden = snookered(positions[0, 0], positions[0, 1], positions, on_table,
                               balls_on, params[RADIUS])  # fmt: skip
        row[FREE_BALL] = 1 if hidden else 0
    return out
