"""The WPA games' tail of the kernel parameters (:mod:`pool_env.game.kernels.params`).

:meth:`pool_env.game.games.wpa.game.WpaGame.configure` fills these entries from the rules
section and the rewards section; the WPA kernels read them by these names.
"""

from __future__ import annotations

from pool_env.game.kernels.params import TAIL, TAIL_SIZE

(
    VARIANT,  # the game: NINE, EIGHT or TEN (pool_env.game.games.wpa.rules)
    END_ON_FOUL,  # 1.0: a foul or a shot that pots nothing legally ends the episode
    BREAK_LOW,  # speed (m/s) of action[1] = -1 on a break
    BREAK_HIGH,  # ... and of +1
    HEAD_X,  # x of the head string (L / 4): ball in hand behind it after an 8-ball break scratch
    FOOT_X,  # the foot spot, where the 9 (or the 8 on a break) is re-spotted
    FOOT_Y,
    BALL_COLUMN,  # the action column calling a ball (10-ball), -1 for none
    OPTION_COLUMN,  # the column declaring a push-out or handing back, -1 for none
    W_POT,  # reward per object ball potted on a legal shot that counts its pots
    W_FOUL,  # reward for a foul
    W_WIN,  # reward for winning the rack (its negative for losing it)
    END,
) = range(TAIL, TAIL + 13)

assert END - TAIL <= TAIL_SIZE, "the WPA tail outgrew the parameter array"
