"""Snooker's frame state: one int64 row per table, its columns, phases and ball values.

The rules (:mod:`.rules`) read a stroke's outcome against this row and move it on; the
observation and the shot's decoding ask it which balls are on (:func:`legal_targets`).
Balls: 0 the cue ball, 1-15 the reds, 16 yellow, 17 green, 18 brown, 19 blue, 20 pink,
21 black.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.jit import kernel

#: Columns of a frame-state row: the striker (0 or 1), each player's score, the phase
#: (what is on), the cue ball in hand in the D, a free ball may be nominated, the points
#: of the striker's current break (visit), the re-spotted black is being played, the
#: winner (-1 while the frame goes on).
SHOOTER, SCORE_0, SCORE_1, PHASE, IN_HAND, FREE_BALL, BREAK, RESPOTTED, WINNER, N_RACK = range(10)

#: Phases (Section 3 Rule 3): a red is on; a colour is on (after a red, or a free ball
#: taken as a red, was potted: the striker nominates one); the colours in order (no red
#: left: the lowest-valued colour on the table is on).
RED_ON, COLOUR_ON, IN_ORDER = 0, 1, 2
PHASE_NAMES = ("red", "colour", "in_order")

#: Each ball's value (Section 2 Rule 4 / Section 3 Rule 1): the cue ball 0, a red 1,
#: yellow 2 .. black 7.
VALUES = np.array([0] + [1] * 15 + [2, 3, 4, 5, 6, 7], dtype=np.int64)
FIRST_COLOUR, BLACK = 16, 21

#: The least penalty of a foul (Section 3 Rule 11).
MIN_PENALTY = 4

#: Foul codes (the judge's ``FOUL`` column) and their ``info["foul"]`` names: the cue
#: ball potted (in-off); no ball hit; a ball not on hit first; a ball not on potted; the
#: cue ball moved a touching ball (a push stroke, Section 3 Rule 8).
NO_FOUL, FOUL_IN_OFF, FOUL_NO_CONTACT, FOUL_WRONG_BALL, FOUL_POT_NOT_ON, FOUL_PUSH = range(6)
FOUL_NAMES: tuple[str | None, ...] = (
    None, "in_off", "no_contact", "wrong_ball_first", "ball_not_on_potted", "push",
)  # fmt: skip


@kernel
def reds_left(on_table):
    """Whether any red is on the table."""
    found = False
    for j in range(1, FIRST_COLOUR):
        found = found or on_table[j]
    return found


@kernel
def lowest_colour(on_table):
    """The lowest-valued colour on the table (the ball on in order), -1 for none."""
    for j in range(FIRST_COLOUR, BLACK + 1):
        if on_table[j]:
            return j
    return -1


@kernel
def legal_targets(row, on_table, targets):
    """Which balls may be on for the striker of ``row``: written into ``targets``.

    Reds while a red is on (and, with a free ball, any colour: it may be nominated);
    every colour on the table when a colour is on; the lowest colour in order (and, with
    a free ball, any other colour). The cue ball never.
    """
    targets[:] = False
    phase = row[PHASE]
    free = row[FREE_BALL] != 0
    if phase == RED_ON:
        for j in range(1, FIRST_COLOUR):
            targets[j] = on_table[j]
        if free:
            for j in range(FIRST_COLOUR, BLACK + 1):
                targets[j] = on_table[j]
    elif phase == COLOUR_ON:
        for j in range(FIRST_COLOUR, BLACK + 1):
            targets[j] = on_table[j]
    else:
        low = lowest_colour(on_table)
        for j in range(FIRST_COLOUR, BLACK + 1):
            targets[j] = on_table[j] and (free or j == low)
