"""The quarter turn between pooltool's frame and this package's: points and aim.

This package's frame is pooltool's turned a quarter turn clockwise: ``ours (x, y) =
pooltool (py - y0, W - (px - x0))``, ``pooltool (px, py) = (W - y, x)``, and an aim
``angle`` (radians from our ``+x``) is pooltool's ``phi = degrees(angle) + 90`` (degrees
from its ``+x``). Plain functions: no pooltool needed (the frame is set out in
:mod:`pool_env.interop.pooltool`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.scalars import positive, real_number


def _points(name: str, points: ArrayLike) -> NDArray[np.float64]:
    arr = np.array(points, dtype=np.float64)  # a copy: the caller's array is never touched
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (N, 2), got {arr.shape}")
    if not np.isfinite(arr).all():
        raise ValueError(f"{name} must be finite")
    return arr


def xy_to_pooltool(positions: ArrayLike, width: float) -> NDArray[np.float64]:
    """Points of this package's frame in pooltool's: ``(x, y) -> (W - y, x)``.

    Args:
        positions: ``(N, 2)`` points of this package's frame (m).
        width: The table's width ``W`` (m).

    Returns:
        ``(N, 2)`` the same points in pooltool's frame (a new array).

    Raises:
        ValueError: A malformed or non-finite array, or a width that is not positive.
    """
    pos = _points("positions", positions)
    w = positive("width", width)
    return np.column_stack((w - pos[:, 1], pos[:, 0]))


def xy_from_pooltool(
    points: ArrayLike, width: float, origin: tuple[float, float] = (0.0, 0.0)
) -> NDArray[np.float64]:
    """Points of pooltool's frame in this package's: ``(px, py) -> (py - y0, W - (px - x0))``.

    Args:
        points: ``(N, 2)`` points of pooltool's frame (m).
        width: The table's width ``W`` (m).
        origin: pooltool's corner ``(x0, y0)`` of the playing surface (the low ends of its
            cushion segments ``"3"`` and ``"18"``; ``(0, 0)`` on the tables it builds).

    Returns:
        ``(N, 2)`` the same points in this package's frame (a new array).

    Raises:
        ValueError: A malformed or non-finite array or origin, or a width that is not
            positive.
    """
    pts = _points("points", points)
    w = positive("width", width)
    x0, y0 = (real_number("origin x", origin[0]), real_number("origin y", origin[1]))
    return np.column_stack((pts[:, 1] - y0, w - (pts[:, 0] - x0)))


def phi_from_angle(angle: float) -> float:
    """The pooltool ``phi`` (degrees) of this package's aim ``angle`` (radians): ``+ 90``.

    Raises:
        ValueError: A non-finite or non-real angle.
    """
    return math.degrees(real_number("angle", angle)) + 90.0


def angle_from_phi(phi: float) -> float:
    """This package's aim (radians) of pooltool's ``phi`` (degrees): ``radians(phi - 90)``.

    Raises:
        ValueError: A non-finite or non-real ``phi``.
    """
    return math.radians(real_number("phi", phi) - 90.0)
