"""Snooker's observation, compiled: the balls, the balls on, then the frame's state.

After the shared ball entries (:func:`pool_env.game.kernels.observe.encode_observations`):
for each object ball whether the viewer may play it as the ball on (or nominate it), then
:data:`RULE_FEATURES`, from the viewer's seat.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.games.snooker.rack_state import (
    BLACK,
    BREAK,
    COLOUR_ON,
    FIRST_COLOUR,
    FREE_BALL,
    IN_HAND,
    IN_ORDER,
    PHASE,
    RED_ON,
    RESPOTTED,
    SCORE_0,
    SHOOTER,
    VALUES,
    legal_targets,
)
from pool_env.game.games.snooker.rules import touching_balls
from pool_env.game.kernels.observe import encode_observations
from pool_env.sim.jit import kernel

#: Rule features after the balls' and the balls-on flags, in this order: the phase
#: (one-hot: a red on, a colour on, the colours in order), the cue ball in hand, a free
#: ball may be nominated, the re-spotted black is played, the cue ball touches a ball,
#: the viewer shoots next, the viewer's and the opponent's score / 147 (at most 1), the
#: viewer's lead / 147 (within [-1, 1]), the break / 147, the points left on the table
#: / 147.
RULE_FEATURES: tuple[str, ...] = (
    "red_on", "colour_on", "in_order", "ball_in_hand", "free_ball", "respotted_black",
    "touching", "to_shoot", "score", "opponent_score", "lead", "break", "remaining",
)  # fmt: skip
N_RULE_FEATURES = 13

#: The maximum break, the scale of the points features.
MAX_BREAK = 147.0


@kernel
def points_left(phase, on_table):
    """The most points the balls on the table can still score (a red and black each)."""
    reds, colours = 0, 0
    for j in range(1, FIRST_COLOUR):
        reds += 1 if on_table[j] else 0
    for j in range(FIRST_COLOUR, BLACK + 1):
        colours += VALUES[j] if on_table[j] else 0
    total = 8 * reds + colours
    if phase == COLOUR_ON:
        total += 7
    return total


@kernel
def encode_snooker_observations(positions, on_table, rack, viewers, length, width, radius):
    """``(B, 3 N + N - 1 + F)`` float32: the balls, the balls on, :data:`RULE_FEATURES`."""
    b, n = on_table.shape
    base = 3 * n + n - 1
    out = np.zeros((b, base + N_RULE_FEATURES), dtype=np.float32)
    out[:, : 3 * n] = encode_observations(positions, on_table, length, width)
    targets = np.empty(n, dtype=np.bool_)
    touching = np.empty(n, dtype=np.bool_)
    for k in range(b):
        row = rack[k]
        legal_targets(row, on_table[k], targets)
        for j in range(1, n):
            out[k, 3 * n + j - 1] = 1.0 if targets[j] else 0.0
        viewer = viewers[k]
        phase = row[PHASE]
        f = out[k, base:]
        f[0] = 1.0 if phase == RED_ON else 0.0
        f[1] = 1.0 if phase == COLOUR_ON else 0.0
        f[2] = 1.0 if phase == IN_ORDER else 0.0
        f[3] = 1.0 if row[IN_HAND] != 0 else 0.0
        f[4] = 1.0 if row[FREE_BALL] != 0 else 0.0
        f[5] = 1.0 if row[RESPOTTED] != 0 else 0.0
        touching_balls(positions[k], on_table[k], radius, touching)
        f[6] = 1.0 if touching.any() else 0.0
        f[7] = 1.0 if row[SHOOTER] == viewer else 0.0
        mine, theirs = row[SCORE_0 + viewer], row[SCORE_0 + 1 - viewer]
        f[8] = min(mine / MAX_BREAK, 1.0)
        f[9] = min(theirs / MAX_BREAK, 1.0)
        f[10] = min(max((mine - theirs) / MAX_BREAK, -1.0), 1.0)
        f[11] = min(row[BREAK] / MAX_BREAK, 1.0)
        f[12] = min(points_left(phase, on_table[k]) / MAX_BREAK, 1.0)
    return out
