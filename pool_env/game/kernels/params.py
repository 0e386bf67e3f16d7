"""The config's numbers as one float64 array, and the names of its entries.

Kernels take this one array instead of a dozen scalars and tuples: numba checks the type of
every argument on each call (about 0.3 us each), and a step makes several calls.
:func:`pool_env.game.config.make_config` fills it; kernels read it by these indices only.
"""

from __future__ import annotations

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
    W_POT,  # reward per object ball potted
    W_SCRATCH,  # reward when the cue ball drops
    W_NO_CONTACT,  # reward when the cue ball hits no ball
    W_SHAPING,  # weight of the shaping potential's change
    END_ON_MISS,  # 1.0: a shot without a pot, or with a scratch, ends the episode
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
    GAME,  # the rule: 0 solitaire, 1 9-ball, 2 8-ball, 3 10-ball (pool_env.game.kernels.wpa)
    PLAYERS,  # 1: one agent shoots every shot (practice), 2: the turn passes
    END_ON_FOUL,  # 1.0: a foul or a shot that pots nothing legally ends the episode
    BREAK_LOW,  # speed (m/s) of action[1] = -1 on a break
    BREAK_HIGH,  # ... and of +1
    W_FOUL,  # reward for a foul (rules)
    W_WIN,  # reward for winning the rack (its negative for losing it)
    HEAD_X,  # x of the head string (L / 4): ball in hand behind it after an 8-ball break scratch
    FOOT_X,  # the foot spot, where the 9 (or the 8 on a break) is re-spotted
    FOOT_Y,
    SPIN,  # 1.0 on a spin table (Table(model="spin")): the action ends with the cue tip
    TIP_LIMIT,  # the tip's largest axis offset (fraction of R): the miscue circle's radius
    SIGMA_TIP,  # execution noise sigma of each tip component (fraction of R)
    BALL_MASS,  # the cue ball's mass (kg), for the strike
    CUE_END_MASS,  # the cue's effective end mass (kg), for squirt
    CUE_TIP_RADIUS,  # the cue tip's radius (m), for the contact offset
    BALL_COLUMN,  # rules: the action column calling a ball (10-ball), -1 for none
    OPTION_COLUMN,  # rules: the column declaring a push-out or handing back, -1 for none
    TIP_COLUMN,  # the first of a spin table's two tip columns
    N_PARAMS,
) = range(46)
