"""The config's numbers as one float64 array: the shared head, then the game's own tail.

Kernels take this one array instead of a dozen scalars and tuples: numba checks the type of
every argument on each call (about 0.3 us each), and a step makes several calls.
:func:`pool_env.game.config.make_config` fills the head (what every game reads: the table,
the aim, the noise, the placement box); the game's ruleset fills its tail from
:data:`TAIL` on (:meth:`pool_env.game.ruleset.Ruleset.configure`: its rule options and its
reward scales), with indices named in its own package. Kernels read it by these names only.
"""

from __future__ import annotations

import numpy as np

(
    RADIUS,  # ball radius R (m)
    AIM_MODE,  # code of the aim mode: 0 absolute, 1 relative, 2 cut
    AIM_LOW,  # aim parameter of action[0] = -1
    AIM_HIGH,  # ... and of +1
    SPEED_LOW,  # speed (m/s) of action[1] = -1
    SPEED_HIGH,  # ... and of +1
    NOISE,  # 1.0 with execution noise, else 0.0
    SIGMA_ANGLE,  # its sigma for the direction (rad)
    SIGMA_SPEED,  # ... and for the speed (m/s)
    SHOT_LIMIT,  # shots after which an episode is truncated (0: never)
    SPOT_X,  # where a scratched cue ball goes back (the head spot)
    SPOT_Y,
    X_LOW,  # centres allowed on the table: inside the rails
    X_HIGH,
    Y_LOW,
    Y_HIGH,
    REACH,  # 2R + clearance: the distance kept between placed centres
    CLEARANCE,  # extra margin from capture circles and between placed balls (m)
    DIAGONAL,  # the table's diagonal (m), the shaping potential's scale
    TRIES,  # failed random draws in a row that end an attempt at a layout
    RESTARTS,  # attempts at a random layout before the scene's fallback layout
    PLAYERS,  # 1: one agent shoots every shot (practice), 2: the turn passes
    SPIN,  # 1.0 on a spin table (Table(model="spin")): the action ends with the cue tip
    TIP_LIMIT,  # the tip's largest axis offset (fraction of R): the miscue circle's radius
    SIGMA_TIP,  # execution noise sigma of each tip component (fraction of R)
    BALL_MASS,  # the cue ball's mass (kg), for the strike
    CUE_END_MASS,  # the cue's effective end mass (kg), for squirt
    CUE_TIP_RADIUS,  # the cue tip's radius (m), for the contact offset
    TIP_COLUMN,  # the first of a spin table's two tip columns (the game's action width)
    TAIL,  # the first entry of the game's own tail
) = range(30)

#: Entries a game's tail may hold (the array has ``TAIL + TAIL_SIZE`` entries).
TAIL_SIZE = 16

#: Entries of the whole array.
N_PARAMS = TAIL + TAIL_SIZE


def game_tail(values: dict[int, float]) -> np.ndarray:
    """A game's tail (``(TAIL_SIZE,)`` float64) from its entries by their full index."""
    tail = np.zeros(TAIL_SIZE)
    for index, value in values.items():
        tail[index - TAIL] = value
    return tail
