"""The action encoding, compiled: the aim and speed components that play a shot.

The inverse of the decoder's kernels (:mod:`pool_env.game.kernels.actions`), one copy for
:func:`pool_env.encode_action` (one shot, raising on what the action cannot play) and for
:func:`encode_shots` (many candidate shots at once, marking what it cannot play), which the
agents' planners and features call.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.game.kernels.actions import nearest_object_ball, wrap_angle
from pool_env.sim.jit import kernel

#: :func:`aim_parameter` status: the parameter lies in the aim range.
AIM_OK = 0
#: The parameter lies outside the aim range.
AIM_OUT_OF_RANGE = 1
#: Cut aim: the direction turns more than 90 degrees from the reference ball.
AIM_AWAY = 2
#: Cut aim with no reference ball: every action aims along +x, the direction does not.
AIM_NO_REFERENCE = 3


@kernel
def to_unit(value, low, high):
    """``value`` of ``[low, high]`` as an action component (-1 at ``low``; 0 if they are equal)."""
    if high == low:
        return 0.0
    return 2.0 * (value - low) / (high - low) - 1.0


@kernel
def aim_parameter(mode, low, high, radius, angle, ref, dist, base, tol):
    """The aim parameter (before scaling onto ``[-1, 1]``) that plays direction ``angle``.

    Args:
        mode: Aim mode (0 absolute, 1 relative, 2 cut; ``pool_env.AIM_MODES``).
        low: The aim range's low end; ``high`` its high end.
        radius: Ball radius (m): the cut is an offset in ball diameters.
        angle: The direction (radians from +x).
        ref: The reference ball (-1: none), at ``dist`` (m) and bearing ``base`` (rad) from
            the cue ball (:func:`~pool_env.game.kernels.actions.nearest_object_ball`).
        tol: Slack on the range's ends (a float32 round trip moves a parameter ~1e-7).

    Returns:
        ``(param, status)``: the status one of ``AIM_OK`` .. ``AIM_NO_REFERENCE``. Out of
        range, ``param`` is the angle's turn just above ``low`` (absolute) or the offset
        itself; turned away (cut), the offset is held at 90 degrees.
    """
    if mode == 0:  # absolute: the turn of the angle that lies in the range, if one does
        param = low + (angle - low) % (2.0 * math.pi)
        if param > high + tol and param - 2.0 * math.pi >= low - tol:
            param -= 2.0 * math.pi  # just below low: within the slack
        return param, AIM_OK if param <= high + tol else AIM_OUT_OF_RANGE
    offset = wrap_angle(angle - base)
    status = AIM_OK
    if mode == 1:
        param = offset
    elif ref < 0:
        return 0.0, AIM_OK if abs(offset) < 1e-12 else AIM_NO_REFERENCE
    else:
        if abs(offset) > 0.5 * math.pi:
            status = AIM_AWAY
            offset = max(-0.5 * math.pi, min(0.5 * math.pi, offset))
        param = math.sin(offset) * dist / (2.0 * radius)
    if status == AIM_OK and not (low - tol <= param <= high + tol):
        status = AIM_OUT_OF_RANGE
    return param, status


@kernel
def tip_components(side, vertical, limit):
    """The action components of a tip inside the miscue circle: each offset over ``limit``.

    The inverse of :func:`~pool_env.game.kernels.tips.decode_tips` there (clipped to
    ``[-1, 1]``; a tip beyond the circle is the caller's to refuse or move onto it).
    """
    return min(max(side / limit, -1.0), 1.0), min(max(vertical / limit, -1.0), 1.0)


@kernel
def encode_shots(
    mode, aim_low, aim_high, speed_low, speed_high, radius, limit, positions, refer, angles,
    speeds, tips,
):  # fmt: skip
    """The ``(aim, speed[, side, vertical])`` action components of ``M`` shots on ``B`` layouts.

    Args:
        mode: Aim mode (0 absolute, 1 relative, 2 cut).
        aim_low: The aim range; ``aim_high`` its other end.
        speed_low: The speed range (m/s); ``speed_high`` its other end.
        radius: Ball radius (m).
        limit: The tip limit (fraction of R) on a spin table; 0 on a roll table (no tip).
        positions: ``(B, N, 2)`` ball centres, cue first.
        refer: ``(B, N)`` the balls the aim may refer to (on the table; under rules, legal
            first contacts).
        angles: ``(B, M)`` shot directions (radians from +x).
        speeds: ``(B, M)`` cue speeds (m/s), clipped to the speed range.
        tips: ``(B, M, 2)`` tips inside the miscue circle (read on a spin table only).

    Returns:
        ``(actions, playable)``: ``(B, M, 2)`` components (``(B, M, 4)`` with the tip on a
        spin table) clipped to ``[-1, 1]``, and ``(B, M)`` whether the aim mode can play
        each direction (1e-9 of slack).
    """
    nb, nm = angles.shape
    actions = np.zeros((nb, nm, 4 if limit > 0.0 else 2))
    playable = np.zeros((nb, nm), dtype=np.bool_)
    for i in range(nb):
        ref, dist, base = nearest_object_ball(positions[i], refer[i], 0)
        for m in range(nm):
            param, status = aim_parameter(
                mode, aim_low, aim_high, radius, angles[i, m], ref, dist, base, 1e-9
            )
            playable[i, m] = status == AIM_OK
            speed = min(max(speeds[i, m], speed_low), speed_high)
            actions[i, m, 0] = min(max(to_unit(param, aim_low, aim_high), -1.0), 1.0)
            actions[i, m, 1] = min(max(to_unit(speed, speed_low, speed_high), -1.0), 1.0)
            if limit > 0.0:
                actions[i, m, 2], actions[i, m, 3] = tip_components(
                    tips[i, m, 0], tips[i, m, 1], limit
                )
    return actions, playable


@kernel
def reference_balls(positions, refer):
    """The aim's reference ball of each of ``B`` layouts (-1: none), cue ball 0.

    :func:`~pool_env.game.kernels.actions.nearest_object_ball` of each ``(N, 2)`` layout
    among its ``refer`` balls: the ball relative and cut aim refer to.
    """
    out = np.empty(positions.shape[0], dtype=np.int64)
    for i in range(positions.shape[0]):
        out[i] = nearest_object_ball(positions[i], refer[i], 0)[0]
    return out
