"""From a desired shot (absolute direction, speed) to the environment's action, and back.

The environment decodes an action with :func:`pool_env.decode_shots`: action[0] maps
linearly onto ``aim_range`` and is read as an absolute angle, an angle relative to the line
to the nearest object ball, or a cut offset on that ball (in ball diameters); action[1] maps
linearly onto ``speed_range``. :func:`shot_to_action` inverts that; a direction outside what
the aim mode can express (outside the relative cone, or missing the nearest ball in ``cut``
mode) is *not representable* and gives ``None``. Speeds are clipped to the range: a planner
that wants more than the maximum gets the maximum, and its simulation says whether that is
enough.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import EnvSpec
from pool_env import AIM_MODES, decode_shots, nearest_object_ball

# Slack when testing a parameter against its range: the float32 round trip moves it ~1e-7.
_RANGE_TOL = 1e-9


def wrap_angle(angle: float) -> float:
    """``angle`` wrapped into ``(-pi, pi]``."""
    a = math.remainder(angle, 2.0 * math.pi)
    return math.pi if a == -math.pi else a


def aim_parameter(
    angle: float,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    spec: EnvSpec,
) -> float | None:
    """The aim parameter (before scaling to [-1, 1]) that shoots along ``angle``, or ``None``."""
    lo, hi = spec.aim_range
    if spec.aim == "absolute":
        # The range may be any interval: try the representatives of the angle near it.
        for k in (0.0, -1.0, 1.0, -2.0, 2.0):
            p = wrap_angle(angle) + 2.0 * math.pi * k
            if lo - _RANGE_TOL <= p <= hi + _RANGE_TOL:
                return p
        return None
    j, dist, base = nearest_object_ball(
        np.ascontiguousarray(positions, dtype=np.float64), np.asarray(on_table, np.bool_), 0
    )
    delta = wrap_angle(angle - base)
    if spec.aim == "relative":
        param = delta
    elif j < 0:  # nothing left to cut: the env aims along +x
        param = 0.0 if abs(delta) < 1e-12 else math.nan
    elif abs(delta) > math.pi / 2.0:
        return None  # pointing away from the nearest ball: no offset gives this direction
    else:
        param = math.sin(delta) * dist / (2.0 * spec.table.ball_radius)
    if not (lo - _RANGE_TOL <= param <= hi + _RANGE_TOL):
        return None
    return param


def shot_to_action(
    angle: float,
    speed: float,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    spec: EnvSpec,
) -> NDArray[np.float32] | None:
    """The float32 action for a shot, or ``None`` when the aim mode cannot express its direction.

    Args:
        angle: Shot direction (radians from +x).
        speed: Cue speed (m/s); clipped to ``spec.speed_range``.
        positions: ``(N, 2)`` ball centres, cue first.
        on_table: ``(N,)`` balls on the table.
        spec: The environment's aim mode and ranges.

    Returns:
        A ``(2,)`` float32 action in ``[-1, 1]``, or ``None``.
    """
    param = aim_parameter(angle, positions, on_table, spec)
    if param is None:
        return None
    lo, hi = spec.aim_range
    slo, shi = spec.speed_range
    a0 = 2.0 * (param - lo) / (hi - lo) - 1.0
    a1 = 2.0 * (speed - slo) / (shi - slo) - 1.0 if shi > slo else 0.0
    return np.clip(np.array([a0, a1], dtype=np.float32), -1.0, 1.0)


def decode(
    actions: NDArray[np.floating],
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    spec: EnvSpec,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """What the environment executes for ``(B, 2)`` actions on one layout: ``(angles, speeds)``.

    The environment's own decoding (:func:`pool_env.decode_shots`), so that a planner
    simulates exactly the shot its action will play (before execution noise).
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
        AIM_MODES.index(spec.aim),
        spec.table.ball_radius,
        spec.aim_range,  # tuples, as the env passes them: no new compiled signature
        spec.speed_range,
    )
