"""The game's formulas and array names that a player reuses to plan the env's own shots.

A planner must predict exactly what the decision process does with an action, so it uses
the game's own code, not a copy. These are that code (compiled kernels, or a call of one
with a config's numbers), named here so that nothing outside :mod:`pool_env` imports
:mod:`pool_env.game.kernels` (the import contract "agents, bench and tools use public
names only" in ``pyproject.toml``):

* :func:`decode_on_layout`: what the env executes for a batch of actions on one layout,
  ``(angles, speeds)`` before execution noise (:func:`pool_env.decode_shots` with the
  config's numbers);
* :func:`decode_tips`: the cue tip ``(side, vertical)`` the env executes for actions;
* :func:`to_unit`: a value of a range as its action component in ``[-1, 1]``;
* :func:`cue_speed`: the cue speed at which an object ball drops at a given speed
  (:func:`pool_env.game.geometry.cue_speeds` for one shot).

A game's own names (the WPA rack state's columns, its results' columns) are its package's
public names (:mod:`pool_env.game.games.wpa`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.game.config import GameConfig
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.actions import decode_shots
from pool_env.game.kernels.encode import to_unit
from pool_env.game.kernels.geometry import cue_speed
from pool_env.game.kernels.tips import decode_tips

__all__ = [
    "cue_speed",
    "decode_on_layout",
    "decode_tips",
    "to_unit",
]


def decode_on_layout(
    config: GameConfig,
    actions: NDArray[np.floating],
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """What the env executes for ``(B, A)`` actions on one layout: ``(angles, speeds)``.

    The environment's own decoding (:func:`pool_env.decode_shots`) with ``config``'s aim
    mode, ball radius and ranges, before execution noise.

    Args:
        config: The env's config.
        actions: ``(B, A)`` actions (their aim and speed components are read).
        positions: ``(N, 2)`` ball centres, cue first.
        on_table: ``(N,)`` the balls the aim may refer to.

    Returns:
        ``(angles, speeds)``, each ``(B,)``.
    """
    acts = np.ascontiguousarray(actions, dtype=np.float32)
    b = acts.shape[0]
    pos = np.ascontiguousarray(np.broadcast_to(positions, (b, *positions.shape)))
    on = np.ascontiguousarray(np.broadcast_to(on_table, (b, *on_table.shape)))
    return decode_shots(
        acts,
        pos,
        on,
        0,
        int(config.params[kp.AIM_MODE]),
        float(config.params[kp.RADIUS]),
        config.aim_range,  # tuples, as the env passes them: no new compiled signature
        config.speed_range,
    )
