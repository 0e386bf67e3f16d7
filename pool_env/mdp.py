"""The pure functions of the decision process: action -> shot, state -> observation, reward.

Each works on a batch: arrays with a leading dimension ``B`` (environments), so that the
single environment (:class:`pool_env.env.PoolEnv`, which passes ``B = 1`` views) and a
batched one share one definition. They are compiled with numba because numpy spends about
a microsecond per call on arrays this small, and a step has a budget of tens of them.
"""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.kernels._jit import kernel

AimMode = Literal["absolute", "relative", "cut"]

#: Aim modes, in the order of their codes for :func:`aim_angles`.
AIM_MODES: tuple[str, ...] = ("absolute", "relative", "cut")

#: Default range that action 0 maps to, per aim mode:
#:
#: * ``absolute``: radians from +x, a full turn.
#: * ``relative``: radians from the line to the nearest object ball, +-10 degrees. On
#:   random one-ball layouts 95% of ghost-ball pots need under 7 degrees, and the pottable
#:   layouts drop only from 83% to 81% against an unlimited cone, while a random angle pots
#:   1.5 times as often as with +-20 degrees.
#: * ``cut`` (the environment's default): where the cue ball meets the nearest object ball,
#:   as its offset from a full hit in units of a ball diameter ``2R``: 0 is a full hit, +-1
#:   a grazing one. The object ball leaves at ``asin(offset)`` from the cue ball's line,
#:   whatever the distance: every cut is in range and equally fine-grained, and at a fixed
#:   speed a random action pots 2-3 times as often as with ``relative``.
DEFAULT_AIM_RANGE: dict[str, tuple[float, float]] = {
    "absolute": (-math.pi, math.pi),
    "relative": (-math.radians(10.0), math.radians(10.0)),
    "cut": (-1.0, 1.0),
}

#: Default cue speed range (m/s): the shots real play uses, from Dr. Dave Alciatore's
#: "typical speeds" FAQ (slow 0.45-0.89, medium 0.89-1.9, fast 1.9-3.2, power 3.2-4.5 m/s;
#: research/REALISM.md). A soft touch rolls ~1 m, a power shot ~100 m if nothing stops it.
DEFAULT_SPEED_RANGE = (0.45, 4.5)


def check_action(action: ArrayLike) -> NDArray[np.floating]:
    """Return ``action`` as a ``(2,)`` float array; ``ValueError`` on a bad shape or NaN.

    Nothing else is checked: out-of-range values (infinities included) are clipped by
    :func:`decode_actions`.
    """
    a = action if isinstance(action, np.ndarray) and action.dtype.kind == "f" else None
    if a is None:
        try:
            a = np.asarray(action, dtype=np.float64)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"the action must be 2 numbers (angle, speed): {exc}") from None
    if a.shape != (2,):
        raise ValueError(f"the action must have shape (2,), got {a.shape}")
    x, y = a.tolist()
    if x != x or y != y:  # NaN has no direction to clip it to
        raise ValueError(f"the action contains NaN: {[x, y]}; nothing was changed")
    return a


@kernel
def decode_actions(actions, aim_low, aim_high, speed_low, speed_high):
    """Map actions in ``[-1, 1]^2`` linearly to an aim parameter and a speed.

    Values outside ``[-1, 1]`` (infinities included) are clipped; NaN must be rejected
    before (:func:`check_action`).

    Args:
        actions: ``(B, 2)``: ``[:, 0]`` the aim, ``[:, 1]`` the speed.
        aim_low: Aim parameter that -1 maps to (see :data:`DEFAULT_AIM_RANGE`).
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
def aim_angles(params, positions, on_table, cue, mode, ball_radius):
    """Absolute shot directions (radians from +x) from decoded aim parameters.

    Args:
        params: ``(B,)`` aim parameters (see :data:`DEFAULT_AIM_RANGE`).
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on the table.
        cue: Index of the cue ball.
        mode: Index of the aim mode in :data:`AIM_MODES`.
        ball_radius: ``R`` (m), for ``cut``.

    Returns:
        ``(B,)`` angles. With no object ball left the reference line is +x: ``relative``
        offsets from it, ``cut`` aims along it.
    """
    b, n = on_table.shape
    out = np.empty(b)
    for k in range(b):
        if mode == 0:
            out[k] = params[k]
            continue
        best, base = np.inf, 0.0
        cx, cy = positions[k, cue, 0], positions[k, cue, 1]
        for j in range(n):  # the nearest object ball; ties go to the lower number
            if j != cue and on_table[k, j]:
                dx = positions[k, j, 0] - cx
                dy = positions[k, j, 1] - cy
                d2 = dx * dx + dy * dy
                if d2 < best:
                    best, base = d2, math.atan2(dy, dx)
        if mode == 1 or best == np.inf:
            out[k] = base + (params[k] if mode == 1 else 0.0)
        else:  # the cue ball's path passes params * 2R from the object ball's centre
            s = params[k] * 2.0 * ball_radius / math.sqrt(best)
            out[k] = base + math.asin(min(max(s, -1.0), 1.0))
    return out


@kernel
def decode_shots(actions, positions, on_table, cue, mode, ball_radius, aim_range, speed_range):
    """:func:`decode_actions` then :func:`aim_angles`, in one call: actions to shots.

    Args:
        actions: ``(B, 2)`` actions.
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on the table.
        cue: Index of the cue ball.
        mode: Index of the aim mode in :data:`AIM_MODES`.
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
def encode_observations(positions, on_table, length, width):
    """Observation: per ball ``(x, y, on_table)``, ``x`` and ``y`` scaled to ``[-1, 1]``.

    A potted ball reads ``(0, 0, 0)``.

    Args:
        positions: ``(B, N, 2)`` centres (m).
        on_table: ``(B, N)`` which balls are on the table.
        length: Table length (m).
        width: Table width (m).

    Returns:
        ``(B, 3 N)`` float32.
    """
    b, n = on_table.shape
    out = np.zeros((b, 3 * n), dtype=np.float32)
    for k in range(b):
        for j in range(n):
            if on_table[k, j]:
                # Clamp: a ball on a rail may sit 1e-9 m outside it after rounding.
                x = (2.0 * positions[k, j, 0] - length) / length  # exact 0 on the centre line
                out[k, 3 * j] = min(max(x, -1.0), 1.0)
                y = (2.0 * positions[k, j, 1] - width) / width
                out[k, 3 * j + 1] = min(max(y, -1.0), 1.0)
                out[k, 3 * j + 2] = 1.0
    return out


@kernel
def pocket_potentials(positions, on_table, pockets, scale):
    """Shaping potential: minus the summed distance of object balls to their nearest pocket.

    Ball 0 (the cue) is left out and potted balls count 0, so a cleared table has potential
    0; a table without pockets has potential 0 everywhere.

    Args:
        positions: ``(B, N, 2)`` centres.
        on_table: ``(B, N)`` which balls are on the table.
        pockets: ``(K, 3)`` capture circles.
        scale: Length to divide by (the table diagonal in the environment).

    Returns:
        ``(B,)`` potentials (<= 0).
    """
    b, n = on_table.shape
    out = np.zeros(b)
    if pockets.shape[0] == 0:
        return out
    for k in range(b):
        total = 0.0
        for j in range(1, n):
            if on_table[k, j]:
                best = np.inf
                for p in range(pockets.shape[0]):
                    d = math.hypot(
                        positions[k, j, 0] - pockets[p, 0], positions[k, j, 1] - pockets[p, 1]
                    )
                    best = min(best, d)
                total += best
        out[k] = -total / scale
    return out


def shot_rewards(
    n_potted: ArrayLike,
    scratch: ArrayLike,
    no_contact: ArrayLike,
    potential_change: ArrayLike,
    weights: tuple[float, float, float, float],
) -> ArrayLike:
    """Reward of a shot: ``weights . (n_potted, scratch, no_contact, potential_change)``.

    Plain arithmetic, so it takes Python scalars (one shot) and arrays (a batch) alike.

    Args:
        n_potted: Object balls potted by the shot.
        scratch: Whether the cue ball was potted.
        no_contact: Whether the cue ball touched no other ball.
        potential_change: ``phi(after) - phi(before)`` of :func:`pocket_potentials`.
        weights: ``(reward_pot, reward_scratch, reward_no_contact, reward_shaping)``.

    Returns:
        The reward(s).
    """
    w_pot, w_scratch, w_miss, w_shape = weights
    return w_pot * n_potted + w_scratch * scratch + w_miss * no_contact + w_shape * potential_change
