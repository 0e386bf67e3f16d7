"""pooltool's cue parameters ``V0, phi, theta, a, b`` of a shot, and the shot of a cue.

:class:`CueParams` holds a stroke in pooltool's names and units; :func:`cue_to_pooltool`
maps a shot of :func:`pool_env.shoot` (``angle, speed, tip, elevation``) to one, and
:func:`cue_from_pooltool` maps one back. Plain functions: no pooltool needed (the mapping
is set out in :mod:`pool_env.interop.pooltool`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

from pool_env.interop.pooltool.frame import phi_from_angle
from pool_env.sim.cue import POOLTOOL_CUE_MASS, StrikeTable, from_pooltool
from pool_env.sim.scalars import positive, real_number
from pool_env.sim.table import Table


class CueParams(NamedTuple):
    """pooltool's cue parameters of a shot (``pooltool.Cue``'s names and units).

    Attributes:
        V0: The stick's speed at impact (m/s).
        phi: The aim (degrees counter-clockwise from pooltool's ``+x``).
        theta: The cue's elevation (degrees).
        a: The contact point's side offset (fraction of ``R``; ``+`` the ball's left).
        b: The contact point's vertical offset (fraction of ``R``; ``+`` above centre).
    """

    V0: float
    phi: float
    theta: float
    a: float
    b: float


def cue_to_pooltool(
    table: Table | StrikeTable,
    angle: float,
    speed: float,
    tip: tuple[float, float] = (0.0, 0.0),
    elevation: float = 0.0,
    *,
    cue_mass: float = POOLTOOL_CUE_MASS,
) -> CueParams:
    """The pooltool cue parameters of a shot of :func:`pool_env.shoot` (in pooltool's frame).

    The inverse of :func:`cue_from_pooltool`: ``a, b = (-tip[0], tip[1]) / (1 + r_tip /
    R)``, ``V0 = speed / cos(elevation) (1 + m / M + (5/2)(a^2 + b^2)) / 2``, ``phi =
    degrees(angle) + 90``, ``theta = degrees(elevation)``.

    Args:
        table: The table (its ``ball_radius``, ``ball_mass`` and ``cue_tip_radius``).
        angle: The aim (radians counter-clockwise from this package's ``+x``).
        speed: The cue ball's speed in the table plane after the strike (m/s), positive.
        tip: The cue axis's offset ``(side, vertical)`` (fractions of ``R``; ``+`` right
            english, ``+`` above centre), each in ``[-1, 1]``, meeting the ball.
        elevation: The cue's elevation (radians), in ``[0, pi/2)``.
        cue_mass: The cue's mass ``M`` (kg), pooltool's ``CueSpecs.M``.

    Returns:
        The :class:`CueParams` ``(V0, phi, theta, a, b)``.

    Raises:
        ValueError: A value that is not a finite real number or lies out of its range
            (a speed that is not positive, a tip outside ``[-1, 1]`` or off the ball, an
            elevation outside ``[0, pi/2)``, a non-positive mass or radius).
    """
    radius = positive("table.ball_radius", table.ball_radius)
    ball_mass = positive("table.ball_mass", table.ball_mass)
    tip_radius = real_number("table.cue_tip_radius", table.cue_tip_radius)
    if tip_radius < 0.0:
        raise ValueError(f"table.cue_tip_radius must be >= 0, got {tip_radius!r}")
    mass = positive("cue_mass", cue_mass)
    speed = positive("speed", speed)
    elevation = real_number("elevation", elevation)
    if not 0.0 <= elevation < 0.5 * math.pi:
        raise ValueError(f"elevation must lie in [0, pi/2) radians, got {elevation!r}")
    try:
        side, vertical = tip
    except (TypeError, ValueError):
        raise ValueError(f"tip must be a pair (side, vertical) of numbers, got {tip!r}") from None
    side, vertical = real_number("tip side", side), real_number("tip vertical", vertical)
    if max(abs(side), abs(vertical)) > 1.0:
        raise ValueError(f"tip offsets must lie in [-1, 1] (fractions of R), got {tip!r}")
    scale = 1.0 + tip_radius / radius  # the axis offset over the contact point's
    a, b = side / scale, vertical / scale
    if a * a + b * b > 1.0:
        raise ValueError(
            f"tip {tip!r} meets the ball off its surface (contact offset "
            f"{math.hypot(a, b):.4g} R with a tip of radius {tip_radius!r} m)"
        )
    # The same arithmetic as bench/spin_scenes.py's pooltool_strike had, operation for
    # operation, so the pooltool comparisons it feeds are unchanged to the last bit.
    along = speed / math.cos(elevation)
    v0 = along * (1.0 + ball_mass / mass + 2.5 * (a * a + b * b)) / 2.0
    return CueParams(v0, phi_from_angle(angle), math.degrees(elevation), 0.0 - a, b)


def cue_from_pooltool(
    table: Table | StrikeTable,
    V0: float,
    phi: float,
    theta: float,
    a: float,
    b: float,
    *,
    cue_mass: float = POOLTOOL_CUE_MASS,
) -> tuple[float, float, tuple[float, float], float]:
    """This package's ``(angle, speed, tip, elevation)`` for pooltool's cue in its frame.

    :func:`pool_env.sim.cue.from_pooltool` (which keeps ``phi``'s frame) with the quarter
    turn between the frames: ``angle = radians(phi - 90)``.

    Args:
        table: The table (its ``ball_radius``, ``ball_mass`` and ``cue_tip_radius``).
        V0: The stick's speed (m/s), positive.
        phi: The aim (degrees, pooltool's frame).
        theta: The cue's elevation (degrees), in ``[0, 90)``.
        a: The contact point's side offset (fraction of ``R``; ``+`` left english).
        b: The contact point's vertical offset (``a^2 + b^2 <= 1``).
        cue_mass: pooltool's ``CueSpecs.M`` (kg).

    Returns:
        ``(angle, speed, tip, elevation)`` for :func:`pool_env.shoot`.

    Raises:
        ValueError: As :func:`pool_env.sim.cue.from_pooltool` (out-of-range or non-real
            values, or a contact offset that needs a cue axis offset outside ``[-1, 1]``).
    """
    phi_ours = real_number("phi", phi) - 90.0
    return from_pooltool(V0, phi_ours, theta, a, b, table, cue_mass=cue_mass)
