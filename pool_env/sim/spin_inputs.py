"""The spin level's entry-point pieces: its argument checks, the cue strike, the run.

Used by :func:`pool_env.simulate` and :func:`pool_env.shoot` on a ``Table(model="spin")``
(and, for the roll level, only :func:`check_tip`, which refuses a tip there).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.inputs import (
    as_masses,
    as_points,
    kernel_array,
    raise_invalid,
    speed_limits,
)
from pool_env.sim.kernels import limits, validation
from pool_env.sim.kernels.spin.strike import cue_strike
from pool_env.sim.scalars import real_number
from pool_env.sim.table import Table

_NO_TIP = (0.0, 0.0)


def tip_touches_ball(table: Table, a: Any, b: Any) -> Any:
    """Whether a cue axis offset ``(a, b)`` (fractions of R) meets the ball on its surface.

    The tip is a sphere of radius ``r_tip``; at contact its centre lies ``R + r_tip`` from
    the ball's, so the contact point's offset is ``(a, b) / (1 + r_tip / R)``
    (:mod:`pool_env.sim.kernels.spin.strike`), and it lies on the ball only within its
    outline: ``a^2 + b^2 <= (1 + r_tip / R)^2``. Beyond it the strike model would give a
    spin that no cue can give. Scalars or arrays (element by element).
    """
    reach = 1.0 + table.cue_tip_radius / table.ball_radius
    return a * a + b * b <= reach * reach


def check_tip(table: Table, tip: object, elevation: object) -> tuple[float, float, float]:
    """The cue's tip offset ``(a, b)`` in [-1, 1], on the ball, and elevation in [0, pi/2).

    Raises:
        ValueError: On a malformed or out-of-range value, a tip whose contact point lies off
            the ball (:func:`tip_touches_ball`), or a non-zero one on a roll table (it has
            no spin: the message says to use ``model="spin"``).
    """
    if tip is _NO_TIP and type(elevation) is float and elevation == 0.0:
        return 0.0, 0.0, 0.0  # the default, fast
    if type(tip) is tuple and len(tip) == 2 and table.has_spin:  # floats in range, fast
        a, b = tip
        if isinstance(a, float) and isinstance(b, float) and isinstance(elevation, float):
            a, b, elev = float(a), float(b), float(elevation)  # NaN fails every test below
            in_box = -1.0 <= a <= 1.0 and -1.0 <= b <= 1.0 and 0.0 <= elev < 0.5 * math.pi
            if in_box and tip_touches_ball(table, a, b):
                return a, b, elev
    try:
        a_raw, b_raw = tip  # type: ignore[misc]
    except (TypeError, ValueError):
        raise ValueError(f"tip must be a pair (a, b) of numbers, got {tip!r}") from None
    a, b = real_number("tip a", a_raw), real_number("tip b", b_raw)
    elev = real_number("elevation", elevation)
    if not (-1.0 <= a <= 1.0 and -1.0 <= b <= 1.0):
        raise ValueError(f"tip offsets must lie in [-1, 1] (fractions of R), got {(a, b)}")
    if not tip_touches_ball(table, a, b):
        reach = 1.0 + table.cue_tip_radius / table.ball_radius
        raise ValueError(
            f"tip {(a, b)} meets the ball off its surface: a cue tip of radius "
            f"{table.cue_tip_radius!r} m touches it only within a^2 + b^2 <= {reach * reach:.4g}"
        )
    if not 0.0 <= elev < 0.5 * math.pi:
        raise ValueError(f"elevation must lie in [0, pi/2) radians, got {elev!r}")
    if not table.has_spin and (a != 0.0 or b != 0.0 or elev != 0.0):
        raise ValueError(
            "a cue tip offset or elevation puts spin on the ball: the roll level has none, "
            "use Table(model='spin')"
        )
    return a, b, elev


def strike(
    table: Table, speed: float, angle: float, a: float, b: float, elevation: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The cue ball's velocity ``(2,)`` and angular velocity ``(3,)`` after the strike."""
    out = np.empty(5)
    cue_strike(
        speed, angle, a, b, elevation, table.ball_radius, table.ball_mass, table.cue_end_mass,
        table.cue_tip_radius, out,
    )  # fmt: skip
    return out[:2], out[2:]


def as_angular(table: Table, value: ArrayLike | None, n: int) -> NDArray[np.float64]:
    """``(N, 3)`` angular velocities as a kernel array (zeros for ``None``).

    Their values (finite, a surface speed ``R |w|`` within ``limits.MAX_SPEED``) are checked
    by the compiled validation of :func:`pool_env.simulate`, in one call with the rest.
    """
    if value is None:
        return np.zeros((n, 3))
    arr = kernel_array("angular_velocities", value, "an (N, 3) array")
    if arr.shape != (n, 3):
        raise ValueError(f"angular_velocities must have shape ({n}, 3), got {arr.shape}")
    return arr


def raise_bad_spin(code: int, i: int, table: Table, ang: NDArray[np.float64]) -> None:
    """Raise the ``ValueError`` for a spin validation code of ``spin.level.validate_spins``."""
    if code == validation.BAD_SPIN:
        raise ValueError(f"angular_velocities must be finite: ball {i} has {ang[i].tolist()}")
    surface = table.ball_radius * float(np.sqrt(ang[i] @ ang[i]))
    raise ValueError(
        f"ball {i} spins with surface speed R |w| = {surface!r} m/s, beyond the "
        f"simulator's numeric limit of {limits.MAX_SPEED:g} m/s"
    )


_REACHABLE_SPIN = getattr(limits.reachable_speed2_spin, "py_func", limits.reachable_speed2_spin)


def reachable_spin_speed(
    table: Table,
    velocities: ArrayLike,
    angular_velocities: ArrayLike,
    masses: ArrayLike | None = None,
) -> float:
    """The fastest speed (m/s) impacts and cloth friction could give any ball of a spin scene.

    ``sqrt(sum_k m_k (v_k^2 + (2/5) R^2 |w_k|^2) / min m)``: twice the kinetic energy,
    spin included, over the lightest mass (:mod:`pool_env.sim.kernels.limits` says why no
    ball ever moves faster). The simulator refuses a spin scene where this passes the
    speed limits.

    Args:
        table: The (spin) table: its ball radius.
        velocities: ``(N, 2)`` initial velocities.
        angular_velocities: ``(N, 3)`` initial angular velocities (rad/s).
        masses: ``(N,)`` masses, or ``None`` for equal masses.
    """
    vel = as_points("velocities", velocities)
    ang = as_angular(table, angular_velocities, vel.shape[0])
    mass = as_masses(masses, vel.shape[0])
    return float(_REACHABLE_SPIN(vel, ang, mass, table.ball_radius)[0]) ** 0.5


def raise_spin_invalid(
    code: int,
    i: int,
    j: int,
    table: Table,
    pos: NDArray[np.float64],
    vel: NDArray[np.float64],
    ang: NDArray[np.float64],
    mass: NDArray[np.float64],
) -> None:
    """Raise the ``ValueError`` for a code of ``spin.level.validate_spin_scene``.

    As :func:`~pool_env.sim.inputs.raise_invalid`, with the spin's codes and the energy
    limit counting the spin.
    """
    if code in (validation.BAD_SPIN, validation.SPIN_TOO_FAST):
        raise_bad_spin(code, i, table, ang)
    if code == validation.TOO_ENERGETIC:
        reach = reachable_spin_speed(table, vel, ang, mass if mass.shape[0] else None)
        raise ValueError(
            f"the scene's kinetic energy could speed ball {i} (the lightest) up to "
            f"{reach!r} m/s through impacts and cloth friction "
            f"(sqrt(sum m (v^2 + (2/5) R^2 |w|^2) / m_{i}): spin counts), beyond "
            f"{speed_limits(table)}; slow the balls or their spin down or bring the masses "
            "closer"
        )
    raise_invalid(code, i, j, table, pos, vel, mass)
