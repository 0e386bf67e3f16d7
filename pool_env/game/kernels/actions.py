"""Actions to shots: decode an action, aim it, add execution noise, strike the cue ball.

Each kernel works on a batch (a leading dimension over tables), so that the single env
(B = 1) and the vector env (B = N) run the very same code.

On a spin table (``params[SPIN]``) the action's last two components are the cue tip's axis
offset ``(a, b)`` (side, vertical), each ``c * tip_limit`` for ``c`` in ``[-1, 1]`` and
scaled back onto the circle of radius ``tip_limit`` when outside it (the miscue limit,
:mod:`pool_env.game.kernels.tips`); the strike is
:func:`pool_env.sim.kernels.level_strike.level_strike` (the table level's: on a spin
table velocity with squirt, and spin). Tip
noise draws after the angle and speed draws.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.game.kernels.params import (
    AIM_HIGH,
    AIM_LOW,
    AIM_MODE,
    BALL_MASS,
    CUE_END_MASS,
    CUE_TIP_RADIUS,
    NOISE,
    RADIUS,
    SIGMA_ANGLE,
    SIGMA_SPEED,
    SIGMA_TIP,
    SPEED_HIGH,
    SPEED_LOW,
    SPIN,
    TIP_COLUMN,
    TIP_LIMIT,
)
from pool_env.game.kernels.rng import standard_normal
from pool_env.game.kernels.tips import decode_tips, onto_tip_circle
from pool_env.sim.jit import kernel
from pool_env.sim.kernels.level_strike import level_strike


@kernel
def decode_actions(actions, aim_low, aim_high, speed_low, speed_high):
    """Map actions in ``[-1, 1]^2`` linearly to an aim parameter and a speed.

    Values outside ``[-1, 1]`` (infinities included) are clipped; NaN must be rejected
    before (:func:`pool_env.game.checks.check_actions`).

    Args:
        actions: ``(B, 2)``: ``[:, 0]`` the aim, ``[:, 1]`` the speed.
        aim_low: Aim parameter that -1 maps to.
        aim_high: Aim parameter that +1 maps to.
        speed_low: Speed (m/s) that -1 maps to.
        speed_high: Speed (m/s) that +1 maps to.

    Returns:
        ``(aims, speeds)``, each ``(B,)`` float64.
    """
    b = actions.shape[0]
    aims = np.empty(b)
    speeds = np.empty(b)
    for k in range(b):
        u = (min(max(float(actions[k, 0]), -1.0), 1.0) + 1.0) * 0.5
        v = (min(max(float(actions[k, 1]), -1.0), 1.0) + 1.0) * 0.5
        aims[k] = aim_low + u * (aim_high - aim_low)
        speeds[k] = speed_low + v * (speed_high - speed_low)
    return aims, speeds


@kernel
def wrap_angle(angle):
    """``angle`` as a direction in ``[-pi, pi)``: itself there (exactly), else wrapped.

    The executed shot's reported direction and the encoder's offsets. An angle inside the
    range is returned as it is: ``(angle + pi) % 2 pi - pi`` would round it.
    """
    if -math.pi <= angle < math.pi:
        return angle
    wrapped = (angle + math.pi) % (2.0 * math.pi) - math.pi
    # An angle a hair below -pi gives exactly pi after rounding: it is -pi then.
    return wrapped if wrapped < math.pi else -math.pi


@kernel
def nearest_object_ball(positions, on_table, cue):
    """The reference ball of relative and cut aim: the object ball nearest to the cue ball.

    Args:
        positions: ``(N, 2)`` ball centres of one table.
        on_table: ``(N,)`` which balls are on the table.
        cue: Index of the cue ball.

    Returns:
        ``(index, distance, angle)``: the ball (ties go to the lower number), its centre's
        distance from the cue ball's and the direction to it (radians from +x); with no
        object ball on the table ``(-1, inf, 0.0)``.
    """
    best, best_j, base = np.inf, -1, 0.0
    cx, cy = positions[cue, 0], positions[cue, 1]
    for j in range(on_table.shape[0]):
        if j != cue and on_table[j]:
            dx = positions[j, 0] - cx
            dy = positions[j, 1] - cy
            d2 = dx * dx + dy * dy
            if d2 < best:
                best, best_j, base = d2, j, math.atan2(dy, dx)
    return best_j, math.sqrt(best), base


@kernel
def _aim_angle(param, mode, ball_radius, j, dist, base):
    """The direction of one relative or cut aim, from :func:`nearest_object_ball`'s answer."""
    if mode == 1 or j < 0:
        return base + (param if mode == 1 else 0.0)
    # cut: the cue ball's path passes param * 2R from the object ball's centre
    s = param * 2.0 * ball_radius / dist
    return base + math.asin(min(max(s, -1.0), 1.0))


@kernel
def aim_angles(params, positions, on_table, cue, mode, ball_radius):
    """Absolute shot directions (radians from +x) from decoded aim parameters.

    Args:
        params: ``(B,)`` aim parameters.
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on the table.
        cue: Index of the cue ball.
        mode: Code of the aim mode (:data:`pool_env.game.config.AIM_MODES`): 0 absolute,
            1 relative, 2 cut.
        ball_radius: ``R`` (m), for ``cut``.

    Returns:
        ``(B,)`` angles. With no object ball left the reference line is +x: ``relative``
        offsets from it, ``cut`` aims along it.
    """
    b = on_table.shape[0]
    out = np.empty(b)
    for k in range(b):
        if mode == 0:
            out[k] = params[k]
        else:
            j, dist, base = nearest_object_ball(positions[k], on_table[k], cue)
            out[k] = _aim_angle(params[k], mode, ball_radius, j, dist, base)
    return out


@kernel
def decode_shots(actions, positions, on_table, cue, mode, ball_radius, aim_range, speed_range):
    """:func:`decode_actions` then :func:`aim_angles`: the shots that actions ask for.

    Args:
        actions: ``(B, 2)`` actions.
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on the table.
        cue: Index of the cue ball.
        mode: Code of the aim mode (0 absolute, 1 relative, 2 cut).
        ball_radius: ``R`` (m).
        aim_range: ``(low, high)`` that action 0 maps to.
        speed_range: ``(low, high)`` speeds (m/s) that action 1 maps to.

    Returns:
        ``(angles, speeds)``: directions (radians from +x) and speeds (m/s), each ``(B,)``.
    """
    aims, speeds = decode_actions(
        actions, aim_range[0], aim_range[1], speed_range[0], speed_range[1]
    )
    return aim_angles(aims, positions, on_table, cue, mode, ball_radius), speeds


@kernel
def shot_arrays(params, n_shots, n_balls):
    """Shots, states to fill: spin ``(K, 4)``, ``(K, N, 5)``; roll ``(K, 2)``, ``(K, N, 2)``."""
    spin = params[SPIN] != 0.0
    shots = np.empty((n_shots, 4 if spin else 2))
    velocities = np.zeros((n_shots, n_balls, 5 if spin else 2))
    return shots, velocities


@kernel
def decoded_tips(params, actions, column):
    """The decoded tips of a spin table's actions, zeros on a roll table."""
    if params[SPIN] != 0.0:
        return decode_tips(actions, column, params[TIP_LIMIT])
    return np.zeros((actions.shape[0], 2))


@kernel
def executed_shots(params, actions, tables, positions, on_table, ptrs):
    """The shots that are played: decoded, with execution noise, as initial velocities.

    Args:
        params: The config's numbers (:mod:`pool_env.game.kernels.params`).
        actions: ``(K, 2)`` actions of the tables that shoot (``(K, 4)`` on a spin table).
        tables: ``(K,)`` those tables.
        positions: ``(B, N, 2)`` ball centres of every table (ball 0 is the cue ball).
        on_table: ``(B, N)`` which balls are on each table.
        ptrs: ``(B, 3)`` generator addresses (:mod:`pool_env.game.kernels.rng`). With
            noise, each table draws from its own generator, angle first, then speed, then
            (spin, a tip sigma) the tip's side and vertical; the noisy speed is clipped at
            0 and the noisy tip onto the miscue circle.

    Returns:
        ``(shots, velocities)``: ``(K, 2)`` executed ``(angle, speed)`` (radians from +x,
        m/s; on a spin table ``(K, 4)``: and the tip ``(a, b)``) and ``(K, N, 2)`` initial
        velocities, only the cue ball moving; on a spin table ``(K, N, 5)``: velocity and
        angular velocity ``(vx, vy, wx, wy, wz)``.
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    aims, speeds = decode_actions(
        actions, params[AIM_LOW], params[AIM_HIGH], params[SPEED_LOW], params[SPEED_HIGH]
    )
    tips = decoded_tips(params, actions, int(params[TIP_COLUMN]))  # after the game's columns
    shots, velocities = shot_arrays(params, n_shots, n_balls)
    for k in range(n_shots):
        b = tables[k]
        strike(params, aims[k], speeds[k], tips[k], positions[b], on_table[b], ptrs[b],
                shots[k], velocities[k])  # fmt: skip
    return shots, velocities


@kernel
def strike(params, aim, speed, tip, positions, targets, ptrs, shot, velocity):
    """One shot: aim (at the nearest of ``targets`` unless absolute), noise, strike.

    The executed direction is reported in ``[-pi, pi)`` (:func:`wrap_angle`).

    Args:
        params: The config's numbers.
        aim: Decoded aim parameter.
        speed: Decoded speed (m/s).
        tip: ``(2,)`` decoded tip offset (zeros on a roll table).
        positions: ``(N, 2)`` the table's balls.
        targets: ``(N,)`` the balls relative and cut aim may refer to (the nearest one).
        ptrs: The table's generator addresses.
        shot: ``(2,)`` written: the executed ``(angle, speed)``; ``(4,)`` on a spin
            table: and the executed tip ``(a, b)``.
        velocity: ``(N, 2)`` written: the cue ball's initial velocity (others stay 0);
            ``(N, 5)`` on a spin table: and its angular velocity.
    """
    angle = aim  # absolute aim: the parameter is the angle
    mode = int(params[AIM_MODE])
    if mode != 0:
        j, dist, base = nearest_object_ball(positions, targets, 0)
        angle = _aim_angle(aim, mode, params[RADIUS], j, dist, base)
    side, vertical = tip[0], tip[1]
    if params[NOISE] != 0.0:
        angle = angle + params[SIGMA_ANGLE] * standard_normal(ptrs)
        s = speed + params[SIGMA_SPEED] * standard_normal(ptrs)
        speed = s if s > 0.0 else 0.0  # clipped at 0 (and -0.0 becomes 0.0)
        if params[SIGMA_TIP] != 0.0:  # after angle and speed: roll tables' streams unchanged
            side = side + params[SIGMA_TIP] * standard_normal(ptrs)
            vertical = vertical + params[SIGMA_TIP] * standard_normal(ptrs)
            side, vertical = onto_tip_circle(side, vertical, params[TIP_LIMIT])
    # The direction is reported (info["angle"], last_strike, decode_action) in [-pi, pi);
    # the strike keeps the angle as aimed (the same direction), so play is unchanged.
    shot[0], shot[1] = wrap_angle(angle), speed
    spin = params[SPIN] != 0.0
    if spin:
        shot[2], shot[3] = side, vertical
    level_strike(spin, speed, angle, side, vertical, params[RADIUS], params[BALL_MASS],
                 params[CUE_END_MASS], params[CUE_TIP_RADIUS], velocity[0])  # fmt: skip


@kernel
def unit(value):
    """An action component clipped to ``[-1, 1]`` and mapped to ``[0, 1]``."""
    return (min(max(float(value), -1.0), 1.0) + 1.0) * 0.5
