"""Argument checks shared by every simulator entry point, with one set of messages.

``simulate``, ``shoot``, ``simulate_batch`` and ``simulate_batch_threads`` check their
arguments here; the environment layer may call the same functions. Every problem is a
``ValueError`` naming the argument. Arrays handed to the compiled kernels are normalised
here to native-endian, C-contiguous, writable float64: numba compiles a separate version
of a kernel for every array layout and flag it meets (a read-only positions array used to
cost a second compile of the whole event loop), so there is exactly one.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.kernels import limits, validation
from pool_env.sim.scalars import real_number
from pool_env.sim.table import Table

#: Default event cap. A 16-ball break has a few hundred events; pooltool's FastFiz
#: ancestor used 5,000. A shot that reaches the cap is reported, never hangs.
DEFAULT_MAX_EVENTS = 10_000

_NUMERIC_KINDS = "iuf"  # integer, unsigned, float: no bools, complex, strings, objects
_FLOAT64 = np.dtype(np.float64)  # native byte order: a big-endian float64 compares unequal


def check_table(table: object) -> Table:
    """``table`` itself if it is a :class:`Table`."""
    if not isinstance(table, Table):
        raise ValueError(f"table must be a pool_env.Table, got {type(table).__name__}")
    return table


def check_max_events(value: object) -> int:
    """An event cap: a (numpy) integer, not a bool, in ``[0, 2**63 - 1]``."""
    if type(value) is int and 0 <= value <= limits.MAX_EVENTS_LIMIT:  # the common case, fast
        return value
    if isinstance(value, bool | np.bool_) or not isinstance(value, int | np.integer):
        raise ValueError(f"max_events must be a non-negative integer, got {value!r}")
    if not 0 <= value <= limits.MAX_EVENTS_LIMIT:
        raise ValueError(
            f"max_events must be a non-negative integer of at most 2**63 - 1, got {value!r}"
        )
    return int(value)


def kernel_array(name: str, value: ArrayLike, what: str) -> NDArray[np.float64]:
    """``value`` as the one float64 array layout the kernels are compiled for.

    A copy only when needed (another dtype or byte order, not contiguous, read-only); an
    array that is already right comes back as it is, after a fast check (this runs for
    every argument of every shot).

    Args:
        name: The argument's name, for messages.
        value: Array-like of real numbers.
        what: What the argument should be, for messages (e.g. ``"an (N, 2) array"``).
    """
    if type(value) is np.ndarray and value.dtype == _FLOAT64 and value.flags.carray:
        return value  # C-contiguous, aligned, writable, native float64: the kernels' layout
    try:
        arr = np.asarray(value)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{name} must be {what} of numbers: {exc}") from None
    if arr.dtype.kind not in _NUMERIC_KINDS:
        raise ValueError(f"{name} must be {what} of real numbers, got dtype {arr.dtype}")
    return np.require(arr, dtype=np.float64, requirements=["C", "A", "W"])


def as_points(name: str, value: ArrayLike, n: int | None = None) -> NDArray[np.float64]:
    """``(N, 2)`` points (positions or velocities), ``N == n`` when given."""
    arr = kernel_array(name, value, "an (N, 2) array")
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (N, 2), got {arr.shape}")
    if n is not None and arr.shape[0] != n:
        raise ValueError(f"{name} has {arr.shape[0]} rows for {n} balls")
    return arr


def as_batch_points(name: str, value: ArrayLike, shape: tuple[int, ...] | None = None):
    """``(B, N, 2)`` points of a batch, of ``shape`` when given."""
    arr = kernel_array(name, value, "a (B, N, 2) array")
    if shape is None and (arr.ndim != 3 or arr.shape[2] != 2):
        raise ValueError(f"{name} must have shape (B, N, 2), got {arr.shape}")
    if shape is not None and arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    return arr


# Masses left to the kernels: every ball weighs the table's ball_mass. Writable like every
# other array the kernels get (one compiled version); it is empty, so nothing can change.
TABLE_MASSES = np.empty(0, dtype=np.float64)


def as_masses(masses: ArrayLike | None, n: int) -> NDArray[np.float64]:
    """``(N,)`` per-ball masses, or an empty array for the table's ``ball_mass``."""
    if masses is None:
        return TABLE_MASSES
    arr = kernel_array("masses", masses, "a sequence of N")
    if arr.shape != (n,):
        raise ValueError(f"masses must have shape ({n},), got {arr.shape}")
    return arr


def as_batch_masses(table: Table, masses: ArrayLike | None, n_tables: int, n_balls: int):
    """``(B, N)`` masses of a batch from ``None`` or anything that broadcasts to it."""
    if masses is None:
        return np.full((n_tables, n_balls), table.ball_mass)
    arr = kernel_array("masses", masses, "an (N,) or (B, N) array")
    try:
        arr = np.broadcast_to(arr, (n_tables, n_balls))
    except ValueError:
        raise ValueError(
            f"masses must have shape ({n_balls},) or {(n_tables, n_balls)}, got {arr.shape}"
        ) from None
    return np.ascontiguousarray(arr)


def as_active(active: ArrayLike | None, n_tables: int, n_balls: int) -> NDArray[np.bool_]:
    """``(B, N)`` booleans, which balls are on each table (default all)."""
    if active is None:
        return np.ones((n_tables, n_balls), np.bool_)
    arr = np.asarray(active)
    if arr.dtype.kind not in "biu":
        raise ValueError(f"active must be booleans, got dtype {arr.dtype}")
    if arr.shape != (n_tables, n_balls):
        raise ValueError(f"active must have shape {(n_tables, n_balls)}, got {arr.shape}")
    return np.require(arr, dtype=np.bool_, requirements=["C", "A", "W"])


def check_angle(angle: object) -> float:
    """A finite real angle (radians)."""
    return real_number("angle", angle)


#: ``limits.speed_allowed`` as plain Python (with ``NUMBA_DISABLE_JIT=1`` it already is).
_SPEED_ALLOWED = getattr(limits.speed_allowed, "py_func", limits.speed_allowed)
_REACHABLE_SPEED2 = getattr(limits.reachable_speed2, "py_func", limits.reachable_speed2)


def check_speed(speed: object, table: Table) -> float:
    """A cue speed: real, non-negative, and within the limits (:func:`max_speed`)."""
    try:
        value = real_number("speed", speed)
    except ValueError:
        raise ValueError(f"speed must be a non-negative finite number, got {speed!r}") from None
    if value < 0.0:
        raise ValueError(f"speed must be a non-negative finite number, got {speed!r}")
    # The compiled test run as plain Python: the same code, without a dispatcher call.
    if not _SPEED_ALLOWED(value * value, table.deceleration):
        raise ValueError(f"speed {value!r} m/s is beyond {speed_limits(table)}")
    return value


def check_cue(cue: object, n: int) -> int:
    """A ball index in ``[0, n)``."""
    if type(cue) is int and 0 <= cue < n:  # the common case, fast
        return cue
    if isinstance(cue, bool | np.bool_) or not isinstance(cue, int | np.integer):
        raise ValueError(f"cue must be a ball index in [0, {n}), got {cue!r}")
    if not 0 <= cue < n:
        raise ValueError(f"cue must be a ball index in [0, {n}), got {cue!r}")
    return int(cue)


def max_speed(table: Table) -> float:
    """The fastest initial speed (m/s) the simulator accepts on ``table``.

    ``MAX_SPEED``, or less where the free rolling distance ``v^2 / (2 mu_roll g)`` would
    pass ``MAX_ROLL`` (see :mod:`pool_env.sim.kernels.limits`).
    """
    return min(limits.MAX_SPEED, (2.0 * table.deceleration * limits.MAX_ROLL) ** 0.5)


def reachable_speed(velocities: ArrayLike, masses: ArrayLike | None = None) -> float:
    """The fastest speed (m/s) impacts could give any ball of a scene.

    ``sqrt(sum_k m_k v_k^2 / min m)``: kinetic energy never grows, so no ball ever moves
    faster. The simulator refuses a scene where this passes :func:`max_speed` (see
    :mod:`pool_env.sim.kernels.limits`); with one ball moving, or equal masses, it is the
    initial speed (of the one ball, or the root of the sum of squares).

    Args:
        velocities: ``(N, 2)`` initial velocities.
        masses: ``(N,)`` masses, or ``None`` for equal masses.
    """
    vel = as_points("velocities", velocities)
    mass = as_masses(masses, vel.shape[0])
    return float(_REACHABLE_SPEED2(vel, mass)[0]) ** 0.5


def speed_limits(table: Table) -> str:
    """The speed limits of ``table``, for error messages."""
    return (
        f"the simulator's numeric limits: speeds up to {limits.MAX_SPEED:g} m/s and a free "
        f"rolling distance v^2 / (2 mu_roll g) up to {limits.MAX_ROLL:g} m, here "
        f"{max_speed(table):.6g} m/s (see README 'Numeric limits')"
    )


def raise_invalid(
    code: int,
    i: int,
    j: int,
    table: Table,
    positions: NDArray[np.float64],
    velocities: NDArray[np.float64],
    masses: NDArray[np.float64],
) -> None:
    """Raise the ``ValueError`` for validation code ``code`` of ``validation.validate``.

    Args:
        code: The code (``validation.OK`` raises nothing).
        i: The ball the code names.
        j: The other ball (overlaps) or the pocket (``IN_POCKET``, ``IN_JAW``, ``BEHIND_LINE``).
        table: The table.
        positions: The validated positions.
        velocities: The validated velocities.
        masses: The validated masses (empty for the table's ball mass).
    """
    if code == validation.BAD_POSITION:
        raise ValueError(f"ball {i} has a non-finite position {positions[i].tolist()}")
    if code == validation.BAD_VELOCITY:
        raise ValueError(f"ball {i} has a non-finite velocity")
    if code == validation.TOO_FAST:
        speed = float(np.hypot(*velocities[i]))
        raise ValueError(f"ball {i} has speed {speed!r} m/s, beyond {speed_limits(table)}")
    if code == validation.TOO_ENERGETIC:
        reach = reachable_speed(velocities, masses if masses.shape[0] else None)
        raise ValueError(
            f"the scene's kinetic energy could speed ball {i} (the lightest) up to "
            f"{reach!r} m/s through impacts (sqrt(sum m v^2 / m_{i})), beyond "
            f"{speed_limits(table)}; slow the balls down or bring the masses closer"
        )
    if code == validation.BAD_MASS:
        raise ValueError(
            f"ball {i} has mass {float(masses[i])!r}: masses must be finite and lie in "
            f"[{limits.MIN_MASS:g}, {limits.MAX_MASS:g}] kg (the simulator's numeric limits)"
        )
    if code == validation.OFF_TABLE:
        r = table.ball_radius
        throats = " or in a pocket's throat" if table.pocket_model == "jaws" else ""
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is off the table: centres must lie in "
            f"[{r}, {table.length - r}] x [{r}, {table.width - r}]{throats}"
        )
    if code == validation.IN_JAW:
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is inside a jaw (facing or point) of pocket {j}"
        )
    if code == validation.BEHIND_LINE:
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is on or behind pocket {j}'s fall line"
        )
    if code == validation.IN_POCKET:
        raise ValueError(
            f"ball {i} at {positions[i].tolist()} is inside pocket {j}'s capture circle"
        )
    if code == validation.OVERLAP:
        d = float(np.hypot(*(positions[j] - positions[i])))
        raise ValueError(
            f"balls {i} and {j} overlap: centres {d:.12g} m apart, less than 2R = "
            f"{2 * table.ball_radius} m"
        )
