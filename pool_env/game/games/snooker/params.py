"""Snooker's tail of the kernel parameters (:mod:`pool_env.game.kernels.params`).

:meth:`pool_env.game.games.snooker.game.Snooker.configure` fills these entries from the
rules section, the table's markings (:mod:`.markings`) and the rewards section.
"""

from __future__ import annotations

from pool_env.game.kernels.params import TAIL, TAIL_SIZE

(
    END_ON_FOUL,  # 1.0: the episode is one visit (a foul or a stroke that scores nothing ends it)
    BAULK_X,  # the baulk line (x)
    D_RADIUS,  # the D's radius
    CENTRE_Y,  # the long centre line (y): the brown, blue, pink and black spots
    BLUE_X,  # the blue, pink and black spots (x); yellow, green and brown are on the baulk line
    PINK_X,
    BLACK_X,
    W_POINTS,  # reward per point the striker scores
    W_PENALTY,  # reward per penalty point the striker's foul gives away
    W_WIN,  # reward for winning the frame (its negative for losing it)
    END,
) = range(TAIL, TAIL + 11)

assert END - TAIL <= TAIL_SIZE, "snooker's tail outgrew the parameter array"
