"""Solitaire's tail of the kernel parameters (:mod:`pool_env.game.kernels.params`).

:meth:`pool_env.game.games.solitaire.game.Solitaire.configure` fills these entries from the
task section and the rewards section; :func:`pool_env.game.games.solitaire.rules.judge`
reads them by these names.
"""

from __future__ import annotations

from pool_env.game.kernels.params import TAIL, TAIL_SIZE

(
    END_ON_MISS,  # 1.0: a shot without a pot, or with a scratch, ends the episode
    W_POT,  # reward per object ball potted
    W_SCRATCH,  # reward when the cue ball drops
    W_NO_CONTACT,  # reward when the cue ball hits no ball
    W_SHAPING,  # weight of the shaping potential's change
    END,
) = range(TAIL, TAIL + 6)

assert END - TAIL <= TAIL_SIZE, "solitaire's tail outgrew the parameter array"
