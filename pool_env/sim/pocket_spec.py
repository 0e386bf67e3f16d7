"""The ``pockets`` argument of :class:`~pool_env.sim.table.Table`: what each spec builds.

A name (``"jaws"``, ``"circles"``, ``"none"``), a :class:`~pool_env.sim.pockets.JawSpec` or
explicit capture circles become the table's pocket model, its capture circles (the
regulation ones, :func:`standard_pockets`, or the given ones) and its jaws
(:mod:`pool_env.sim.pockets`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.kernels import limits
from pool_env.sim.pockets import CORNER_MOUTH, SIDE_MOUTH, JawSpec, PocketJaws, regulation_jaws


def standard_pockets(
    length: float,
    width: float,
    ball_radius: float,
    corner_mouth: float = CORNER_MOUTH,
    side_mouth: float = SIDE_MOUTH,
) -> NDArray[np.float64]:
    """Capture circles of a regulation 6-pocket table (the cheap pocket model).

    The rails run the full length, so a pocket is a capture circle that catches a ball whose
    centre reaches the rail line (``R`` from the cushion nose) inside the pocket mouth:

    * Corner pockets: the cushion noses are cut at 45 degrees, so a mouth of width ``w``
      ends ``w / sqrt(2)`` from the corner along each rail. The circle is centred on the
      corner of the nose rectangle with radius ``sqrt(R^2 + (w / sqrt(2))^2)``: a ball
      rolling along a rail (centre at ``R`` from the nose) is captured exactly when it
      reaches the mouth.
    * Side pockets: centred at the middle of each long rail, ``R`` behind the nose line
      (where a dropping ball sits), with radius ``sqrt((2R)^2 + (w / 2)^2)`` so that again a
      ball along the rail is captured exactly inside the mouth of width ``w``.

    Args:
        length: Table length ``L`` (m).
        width: Table width ``W`` (m).
        ball_radius: Ball radius ``R`` (m).
        corner_mouth: Corner mouth width (m), the WPA one by default.
        side_mouth: Side mouth width (m), the WPA one by default.

    Returns:
        A ``(6, 3)`` array of ``(x, y, radius)``, ordered: bottom-left, bottom-middle,
        bottom-right, top-left, top-middle, top-right.
    """
    r = ball_radius
    corner_r = math.hypot(r, corner_mouth / math.sqrt(2.0))
    side_r = math.hypot(2.0 * r, side_mouth / 2.0)
    return np.array(
        [
            (0.0, 0.0, corner_r),
            (length / 2.0, -r, side_r),
            (length, 0.0, corner_r),
            (0.0, width, corner_r),
            (length / 2.0, width + r, side_r),
            (length, width, corner_r),
        ],
        dtype=np.float64,
    )


def parse_pockets(
    spec: object, length: float, width: float, ball_radius: float
) -> tuple[str, NDArray[np.float64], tuple[PocketJaws, ...]]:
    """The pocket model, capture circles and jaws of a ``Table(pockets=spec)``.

    Args:
        spec: ``"jaws"`` (or ``"standard"``), ``"circles"``, ``"none"``, a
            :class:`~pool_env.sim.pockets.JawSpec`, or ``(K, 3)`` circles
            ``(x, y, radius)`` (empty: no pockets).
        length: The table's (validated) length (m).
        width: Its width (m).
        ball_radius: Its ball radius (m).

    Returns:
        ``(model, circles, jaws)``: ``"jaws"``, ``"circles"`` or ``"none"``; the
        ``(K, 3)`` capture circles (on a jaw table those of its own mouths: the summary
        of where its pockets are that the games' spots and aim points read); the jaws
        of each pocket (empty unless ``"jaws"``).

    Raises:
        ValueError: On an unknown name, a malformed array, or a non-finite, too large
            or non-positive value.
    """
    if isinstance(spec, JawSpec):
        mouths = (spec.corner_mouth, spec.side_mouth)
        circles = standard_pockets(length, width, ball_radius, *mouths)
        return "jaws", circles, regulation_jaws(length, width, ball_radius, spec)
    circles = standard_pockets(length, width, ball_radius)
    if isinstance(spec, str):
        if spec in ("jaws", "standard"):
            jaws = regulation_jaws(length, width, ball_radius, JawSpec())
            return "jaws", circles, jaws
        if spec == "circles":
            return "circles", circles, ()
        if spec == "none":
            return "none", np.zeros((0, 3), dtype=np.float64), ()
        raise ValueError(
            f"unknown pocket specification {spec!r}: use 'jaws', 'circles', 'none', a "
            "JawSpec or a sequence of (x, y, radius)"
        )
    try:
        arr = np.array(spec, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"pockets must be a sequence of (x, y, radius): {exc}") from None
    if arr.size == 0:
        return "none", np.zeros((0, 3), dtype=np.float64), ()
    if arr.ndim != 2 or arr.shape[1] != 3:
        raise ValueError(f"pockets must have shape (K, 3) of (x, y, radius), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError("pocket coordinates and radii must be finite")
    if np.abs(arr).max() > limits.MAX_LENGTH:
        raise ValueError(
            f"pocket coordinates and radii must lie within {limits.MAX_LENGTH:g} m (the "
            "simulator's numeric limits, see README 'Numeric limits')"
        )
    if np.any(arr[:, 2] <= 0.0):
        raise ValueError("every pocket radius must be positive")
    return "circles", np.ascontiguousarray(arr), ()
