"""Porting a pooltool shot: its cue parameters ``(V0, phi, theta, a, b)`` in this API's terms.

pooltool 0.6.0 describes a stroke by the cue stick's speed ``V0`` (m/s), its aim ``phi`` and
elevation ``theta`` (degrees) and the contact point's offsets ``a`` (side; ``+1`` the ball's
leftmost point) and ``b`` (``+1`` the top) in fractions of the radius, which its physics uses
as the contact point itself. This API takes the cue ball's speed after the strike, the aim
and elevation in radians, and ``tip``: the offset of the cue's axis (right english
positive), which the strike maps to the contact point by ``1 / (1 + r_tip / R)``
(:mod:`pool_env.sim.kernels.spin.strike`). So

* ``angle = radians(phi)``, ``elevation = radians(theta)``;
* ``tip = (-a, b) (1 + r_tip / R)``: the axis offset whose contact point is pooltool's;
* ``speed = cos(theta) 2 V0 / (1 + m / M + (5/2)(a^2 + b^2))``: pooltool's ball speed
  (TP A-30 with an elastic tip, cue mass ``M``, ball mass ``m``) in the table plane, the
  vertical part dropped as pooltool's 2D strike does (a centre hit: ``1.54 V0``).

With the table's ``ball_mass``, ``ball_radius`` and ``cue_end_mass`` equal to pooltool's
(``m = 0.170097`` kg, ``R = 0.028575`` m, ``m / 30``) the strike gives pooltool's velocity,
spin and squirt; the tip radius cancels. pooltool's contact offsets beyond
``1 / (1 + r_tip / R)`` (0.73 with the default tip) have no axis offset in ``[-1, 1]`` and are
refused; they lie far past a miscue (about 0.5) anyway.

Frames. ``phi`` is an angle in the frame the positions are given in. pooltool's tables lie
along its ``y`` axis and this simulator's along ``x``: port positions with a rotation (e.g.
``(x, y) -> (y, W - x)``, a quarter turn clockwise) and subtract 90 degrees from ``phi``. A
mirror (swapping ``x`` and ``y``) would turn left english into right.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Protocol

from pool_env.sim.scalars import positive, real_number

if TYPE_CHECKING:
    from pool_env.sim.table import Table

__all__ = ["POOLTOOL_CUE_MASS", "from_pooltool"]

#: pooltool 0.6.0's default cue mass ``CueSpecs.M`` (kg).
POOLTOOL_CUE_MASS = 0.567


class StrikeTable(Protocol):
    """What :func:`from_pooltool` reads from a table."""

    ball_radius: float
    ball_mass: float
    cue_tip_radius: float


def from_pooltool(
    V0: float,
    phi: float,
    theta: float,
    a: float,
    b: float,
    table: Table | StrikeTable | None = None,
    *,
    cue_mass: float = POOLTOOL_CUE_MASS,
) -> tuple[float, float, tuple[float, float], float]:
    """This API's ``(angle, speed, tip, elevation)`` for pooltool's cue parameters.

    Args:
        V0: pooltool's cue stick speed at impact (m/s), positive.
        phi: pooltool's aim (degrees; 0 along +x, 90 along +y).
        theta: pooltool's cue elevation (degrees), in ``[0, 90)``.
        a: pooltool's side offset of the contact point, fraction of ``R`` (+ = the ball's
            left, i.e. left english).
        b: pooltool's vertical offset of the contact point (+ = above centre);
            ``a^2 + b^2 <= 1``.
        table: The table to shoot on (``Table(model="spin")`` if omitted): its
            ``ball_mass``, ``ball_radius`` and ``cue_tip_radius`` are used.
        cue_mass: The cue's mass ``M`` (kg), pooltool's ``CueSpecs.M``.

    Returns:
        ``(angle, speed, tip, elevation)``: the aim (rad), the cue ball's speed in the table
        plane (m/s), the tip offset ``(side, vertical)`` of the cue's axis in fractions of
        the radius, and the elevation (rad), for :func:`pool_env.shoot`.

    Raises:
        ValueError: A parameter that is not a finite real number or out of its range, or a
            contact offset that needs an axis offset outside ``[-1, 1]``.

    Example:
        pooltool's default stroke (``V0=2``, ``b=0.25``) aimed along +y, on pooltool's
        ball and tip:

        >>> from types import SimpleNamespace
        >>> table = SimpleNamespace(ball_radius=0.028575, ball_mass=0.170097,
        ...                         cue_tip_radius=0.0106045)
        >>> angle, speed, tip, elevation = from_pooltool(2.0, 90.0, 0.0, 0.0, 0.25, table)
        >>> round(angle, 6), round(speed, 6), round(tip[1], 6), elevation
        (1.570796, 2.746791, 0.342778, 0.0)
    """
    if table is None:
        from pool_env.sim.table import Table

        table = Table(model="spin")  # type: ignore[call-arg]
    v0 = positive("V0", V0)
    phi_deg = real_number("phi", phi)
    theta_deg = real_number("theta", theta)
    if not 0.0 <= theta_deg < 90.0:
        raise ValueError(f"theta must lie in [0, 90) degrees, got {theta!r}")
    a_c = real_number("a", a)
    b_c = real_number("b", b)
    if a_c * a_c + b_c * b_c > 1.0:
        raise ValueError(f"a and b must lie on the ball (a^2 + b^2 <= 1), got a={a!r}, b={b!r}")
    mass = positive("cue_mass", cue_mass)
    radius = positive("table.ball_radius", table.ball_radius)
    ball_mass = positive("table.ball_mass", table.ball_mass)
    tip_radius = real_number("table.cue_tip_radius", table.cue_tip_radius)
    if tip_radius < 0.0:
        raise ValueError(f"table.cue_tip_radius must be >= 0, got {tip_radius!r}")
    widen = 1.0 + tip_radius / radius
    tip = (0.0 - a_c * widen, b_c * widen)  # 0.0 - x: no -0.0 for a centre hit
    if max(abs(tip[0]), abs(tip[1])) > 1.0:
        raise ValueError(
            f"the contact offset (a={a!r}, b={b!r}) needs a cue axis offset {tip} outside "
            f"[-1, 1] with this tip (contact offsets up to {1.0 / widen:.3f} of the radius); "
            "beyond about 0.5 a real cue miscues"
        )
    elevation = math.radians(theta_deg)
    ball_speed = 2.0 * v0 / (1.0 + ball_mass / mass + 2.5 * (a_c * a_c + b_c * b_c))
    return math.radians(phi_deg), ball_speed * math.cos(elevation), tip, elevation
