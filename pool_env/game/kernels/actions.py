"""Actions to shots: decode an action, aim it, add execution noise, strike the cue ball.

Each kernel works on a batch (a leading dimension over tables), so that the single env
(B = 1) and the vector env (B = N) run the very same code.

On a spin table (``params[SPIN]``) the action's last two components are the cue tip's axis
offset ``(a, b)`` (side, vertical), each ``c * tip_limit`` for ``c`` in ``[-1, 1]`` and
scaled back onto the circle of radius ``tip_limit`` when outside it (the miscue limit,
:mod:`pool_env.game.kernels.tips`); the strike is
:func:`pool_env.sim.kernels.spin.strike.cue_strike` (velocity with squirt, and spin). Tip
noise draws after the angle and speed draws.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.game.kernels.layout import point_free
from pool_env.game.kernels.params import (
    AIM_HIGH,
    AIM_LOW,
    AIM_MODE,
    BALL_COLUMN,
    BALL_MASS,
    BREAK_HIGH,
    BREAK_LOW,
    CUE_END_MASS,
    CUE_TIP_RADIUS,
    GAME,
    HEAD_X,
    NOISE,
    OPTION_COLUMN,
    RADIUS,
    REACH,
    SIGMA_ANGLE,
    SIGMA_SPEED,
    SIGMA_TIP,
    SPEED_HIGH,
    SPEED_LOW,
    SPIN,
    TIP_COLUMN,
    TIP_LIMIT,
    X_HIGH,
    X_LOW,
    Y_HIGH,
    Y_LOW,
)
from pool_env.game.kernels.rng import standard_normal
from pool_env.game.kernels.tips import decode_tips, onto_tip_circle
from pool_env.game.kernels.wpa import (
    BEHIND,
    BREAKING,
    IN_HAND,
    OPTION,
    PUSH_OUT,
    SHOOTER,
    legal_targets,
)
from pool_env.sim.jit import kernel
from pool_env.sim.kernels.spin.strike import cue_strike

#: Columns of the calls :func:`executed_rule_shots` returns: the called pocket, the called
#: ball (10-ball; -1 none), a push-out declared where the rules allow one, the option used
#: to hand the table back (no shot is played).
CALL_POCKET, CALL_BALL, CALL_PUSH_OUT, CALL_HAND_BACK, N_CALLS = range(5)


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
def _shot_arrays(params, n_shots, n_balls):
    """Shots, states to fill: spin ``(K, 4)``, ``(K, N, 5)``; roll ``(K, 2)``, ``(K, N, 2)``."""
    spin = params[SPIN] != 0.0
    shots = np.empty((n_shots, 4 if spin else 2))
    velocities = np.zeros((n_shots, n_balls, 5 if spin else 2))
    return shots, velocities


@kernel
def _tips(params, actions, column):
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
    tips = _tips(params, actions, 2)
    shots, velocities = _shot_arrays(params, n_shots, n_balls)
    for k in range(n_shots):
        b = tables[k]
        _strike(params, aims[k], speeds[k], tips[k], positions[b], on_table[b], ptrs[b],
                shots[k], velocities[k])  # fmt: skip
    return shots, velocities


@kernel
def _strike(params, aim, speed, tip, positions, targets, ptrs, shot, velocity):
    """One shot: aim (at the nearest of ``targets`` unless absolute), noise, strike.

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
    shot[0], shot[1] = angle, speed
    if params[SPIN] == 0.0:
        velocity[0, 0] = speed * math.cos(angle)
        velocity[0, 1] = speed * math.sin(angle)
        return
    shot[2], shot[3] = side, vertical
    out = np.empty(5)
    cue_strike(speed, angle, side, vertical, 0.0, params[RADIUS], params[BALL_MASS],
               params[CUE_END_MASS], params[CUE_TIP_RADIUS], out)  # fmt: skip
    velocity[0, :] = out


@kernel
def _unit(value):
    """An action component clipped to ``[-1, 1]`` and mapped to ``[0, 1]``."""
    return (min(max(float(value), -1.0), 1.0) + 1.0) * 0.5


@kernel
def place_in_hand(params, pockets, actions, tables, positions, on_table, rack):
    """Put the cue ball of each table in hand where ``actions[:, 2:4]`` ask.

    The two components map linearly onto the allowed centres: inside the cushions by a
    ball radius (``[R, L - R] x [R, W - R]``), and only behind the head string
    (``x <= L / 4``) when the rack state says so (after a scratch on an 8-ball break, and
    on every break). The cue ball is moved to that point, free or not.

    Args:
        params: The config's numbers.
        pockets: ``(P, 3)`` capture circles.
        actions: ``(K, 5)`` actions.
        tables: ``(K,)`` the tables that shoot.
        positions: ``(B, N, 2)`` ball centres, the cue balls in hand moved in place.
        on_table: ``(B, N)`` which balls are on each table.
        rack: ``(B, N_RACK)`` rack states.

    Returns:
        ``(K,)`` booleans: the requested point is not free (on or next to a ball, in a
        pocket): the caller moves the cue ball to the free point nearest to it
        (:func:`pool_env.game.scenes.free_spot`).
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    unplaced = np.zeros(n_shots, dtype=np.bool_)
    others = np.empty((n_balls, 2))
    reach = params[REACH]
    for k in range(n_shots):
        b = tables[k]
        if rack[b, IN_HAND] == 0:
            continue
        x_high = params[HEAD_X] if rack[b, BEHIND] != 0 else params[X_HIGH]
        x = params[X_LOW] + _unit(actions[k, 2]) * (x_high - params[X_LOW])
        y = params[Y_LOW] + _unit(actions[k, 3]) * (params[Y_HIGH] - params[Y_LOW])
        count = 0
        for j in range(1, n_balls):
            if on_table[b, j]:
                others[count] = positions[b, j]
                count += 1
        positions[b, 0, 0], positions[b, 0, 1] = x, y
        free = point_free(x, y, params, pockets, others, count, reach * reach)
        unplaced[k] = not (free and x <= x_high)
    return unplaced


@kernel
def executed_rule_shots(params, pockets, actions, tables, positions, on_table, ptrs, rack):
    """The shots of the rules' actions, the cue ball placed: the calls, aim, strike.

    The action is ``(aim, speed, cue x, cue y, pocket)``, then the game's own columns
    (``params[BALL_COLUMN]``: the called ball of 10-ball; ``params[OPTION_COLUMN]``: 9-ball
    and 10-ball's option), then on a spin table the tip (from ``params[TIP_COLUMN]``).

    ``actions[:, 4]`` calls pocket ``min(floor(P (a + 1) / 2), P - 1)`` (``P = 6``: six
    equal bins over ``[-1, 1]``, in ``table.pockets`` order; read by the rules when the
    shooter is on the 8, and on every 10-ball shot after the break); the ball column calls
    ball ``1 + min(floor(n (a + 1) / 2), n - 1)`` of the ``n`` object balls the same way.
    The option column, ``> 0``, declares a push-out on the shot right after a legal break
    (``rack[PUSH_OUT]``), and when the shooter has the option (``rack[OPTION]``) hands the
    table back instead of shooting: that row plays no shot (zero speed, no noise drawn).
    The speed maps onto the break range on a break. Relative and cut aim refer to the
    nearest ball the shooter may hit first (:func:`pool_env.game.kernels.wpa.legal_targets`),
    not to the nearest ball.

    Args:
        params: The config's numbers.
        pockets: ``(P, 3)`` capture circles.
        actions: ``(K, A)`` actions.
        tables: ``(K,)`` the tables that shoot.
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on each table.
        ptrs: ``(B, 3)`` generator addresses (noise as :func:`executed_shots`).
        rack: ``(B, N_RACK)`` rack states.

    Returns:
        ``(shots, velocities, calls)``: as :func:`executed_shots`, and ``(K, N_CALLS)``
        int64 calls (columns :data:`CALL_POCKET` ...).
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    game = int(params[GAME])
    aims, speeds = decode_actions(
        actions, params[AIM_LOW], params[AIM_HIGH], params[SPEED_LOW], params[SPEED_HIGH]
    )
    tips = _tips(params, actions, int(params[TIP_COLUMN]))
    shots, velocities = _shot_arrays(params, n_shots, n_balls)
    calls = np.full((n_shots, N_CALLS), -1, dtype=np.int64)
    targets = np.empty(n_balls, dtype=np.bool_)
    n_pockets, n_objects = pockets.shape[0], n_balls - 1
    ball_column, option_column = int(params[BALL_COLUMN]), int(params[OPTION_COLUMN])
    for k in range(n_shots):
        b = tables[k]
        row = rack[b]
        calls[k, CALL_POCKET] = min(int(_unit(actions[k, 4]) * n_pockets), n_pockets - 1)
        if ball_column >= 0:
            calls[k, CALL_BALL] = 1 + min(int(_unit(actions[k, ball_column]) * n_objects),
                                          n_objects - 1)  # fmt: skip
        declared = option_column >= 0 and actions[k, option_column] > 0.0
        calls[k, CALL_PUSH_OUT] = 1 if declared and row[PUSH_OUT] != 0 else 0
        calls[k, CALL_HAND_BACK] = 1 if declared and row[OPTION] != 0 else 0
        if calls[k, CALL_HAND_BACK] != 0:  # the table goes back: nothing is struck
            shots[k, :] = 0.0
            continue
        speed = speeds[k]
        if row[BREAKING] != 0:
            speed = params[BREAK_LOW] + _unit(actions[k, 1]) * (
                params[BREAK_HIGH] - params[BREAK_LOW]
            )
        legal_targets(game, row, on_table[b], row[SHOOTER], targets)
        _strike(params, aims[k], speed, tips[k], positions[b], targets, ptrs[b], shots[k],
                velocities[k])  # fmt: skip
    return shots, velocities, calls
