"""pooltool 0.6.0's ``System`` to this package's table, layout and shot, and back.

:func:`from_system` reads a pooltool ``System`` (its table's size and cushion height, its
balls' positions and parameters, its cue's ``V0, phi, theta, a, b`` and specs) into a
:class:`Scene`: a :class:`~pool_env.sim.table.Table`, the positions ``(N, 2)`` with the
balls' ids, the cue ball's row and the shot's ``angle, speed, tip, elevation``, which
:meth:`Scene.shoot` plays through :func:`pool_env.shoot`. :func:`to_system` builds the
``System`` of a layout and a shot, to watch it in pooltool's 3D interface
(``pooltool.show``) or to run it there. pooltool is imported only by these two (and by
:meth:`Scene.to_system`); the mappings below are plain functions that need no pooltool.

The mapping, as :mod:`bench.engines.pooltool_worker` and ``bench/spin_scenes.py`` use it
for the equal-model comparisons (final positions within 1e-11 m of pooltool's,
``results/spin_vs_pooltool.md``; pooltool-native shots ported by :func:`from_system`, in
``tests/sim/test_interop_pooltool.py``, within 1e-9 m):

Frame. Both origins are a corner of the playing surface at the cushion noses, but
pooltool's ``x`` runs across the width and its ``y`` along the length, this package's
``x`` along the length and ``y`` across. This package's frame is pooltool's turned a
quarter turn clockwise (a rotation, not a mirror: counter-clockwise stays
counter-clockwise and left english stays left)::

    ours (x, y)  =  pooltool (py - y0, W - (px - x0))        (xy_from_pooltool)
    pooltool (px, py)  =  (W - y, x)                          (xy_to_pooltool)

with ``W`` the width and ``(x0, y0)`` pooltool's corner (``(0, 0)`` on every table
pooltool builds). Our ``(0, 0)`` is pooltool's ``(W, 0)``; pooltool's head rail
(``py = 0``, where it breaks from) is our ``x = 0``. A vector ``(vx, vy)`` of ours is
pooltool's ``(-vy, vx)``, so a direction at ``angle`` (radians counter-clockwise from our
``+x``) is pooltool's ``phi`` (degrees counter-clockwise from its ``+x``)::

    phi = degrees(angle) + 90        angle = radians(phi - 90)

Cue. pooltool's ``a`` (side, ``+1`` the ball's leftmost point) and ``b`` (``+1`` the
top) are the contact point's offsets in fractions of ``R``; this package's ``tip`` is the
offset of the cue's axis, ``+`` right english and ``+`` above centre, which meets the ball
at ``tip / (1 + r_tip / R)`` (``r_tip``: ``Table.cue_tip_radius``, pooltool's
``CueSpecs.tip_radius``). pooltool's ``V0`` is the stick's speed, this package's
``speed`` the cue ball's speed in the table plane after the strike (TP A-30 with an
elastic tip, cue mass ``M``, ball mass ``m``; pooltool drops the vertical part)::

    tip = (-a, b) (1 + r_tip / R)          elevation = radians(theta)
    speed = cos(theta) 2 V0 / (1 + m / M + (5/2)(a^2 + b^2))

(:func:`pool_env.sim.cue.from_pooltool`, of which :func:`cue_from_pooltool` is the
framed form, and :func:`cue_to_pooltool` the inverse).

Parameters. One :class:`~pool_env.sim.table.Table` holds what pooltool keeps per ball, so
the balls of a ``System`` share them (pooltool 0.6.0 itself holds every ball to one mass
and radius)::

    Table            pooltool
    length, width    table.l, table.w (cushion segments "9" - "18", "12" - "3")
    cushion_height   the cushion segments' height (TableSpecs.cushion_height)
    ball_radius      BallParams.R
    ball_mass        BallParams.m
    mu_roll          BallParams.u_r
    mu_slide         BallParams.u_s
    spin_decel       (5/2) BallParams.u_sp_proportionality g   (u_sp = proportionality R)
    e_ball, e_cushion, cushion_friction, g   BallParams.e_b, e_c, f_c, g
    cue_tip_radius, cue_end_mass             CueSpecs.tip_radius, end_mass
    (Scene.cue_mass)                         CueSpecs.M

Not carried by a ``System``, so not ported: pooltool's physics engine (its default
resolver uses Stronge's compliant cushions, ``Table(cushion_model="stronge")``, and the
frictional inelastic ball-ball model with Alciatore's friction fit,
``Table(ball_friction="pooltool")``: pass ``table_options=POOLTOOL_MODELS`` to play its
default engine), its
``BallParams.u_b`` (read only by its ``AverageBallBallFriction``, not a default), and its
pocket geometry: a pooltool table with pockets becomes this package's regulation jaw table
(``pockets="jaws"``), one without a carom table (``"none"``), and :func:`to_system` builds
pooltool's own ``PocketTableSpecs`` pockets or a ``BilliardTableSpecs`` table.

Example:
    A cue ball in the kitchen, struck up the table with right english and a touch of draw:

    >>> from pool_env import Table
    >>> from pool_env.interop.pooltool import cue_to_pooltool, xy_to_pooltool
    >>> table = Table(model="spin")
    >>> xy_to_pooltool([[0.635, 0.3]], table.width).tolist()  # pooltool's (W - y, x)
    [[0.97, 0.635]]
    >>> cue = cue_to_pooltool(table, angle=0.0, speed=2.0, tip=(0.2, -0.3))
    >>> cue.phi, round(cue.a, 6), round(cue.b, 6)  # phi = 90: up pooltool's table
    (90.0, -0.145884, -0.218826)
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from types import ModuleType
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.extras import require
from pool_env.sim.cue import POOLTOOL_CUE_MASS, StrikeTable, from_pooltool
from pool_env.sim.inputs import as_masses, as_points, check_cue, check_table
from pool_env.sim.presets import PRESETS
from pool_env.sim.scalars import positive, real_number
from pool_env.sim.simulate import check_positions, shoot
from pool_env.sim.spin_inputs import check_tip
from pool_env.sim.table import Table

if TYPE_CHECKING:
    from pool_env.sim.result import ShotResult

__all__ = [
    "BALL_FIELDS",
    "INSTALL",
    "POOLTOOL_CUE_MASS",
    "POOLTOOL_MODELS",
    "PORTED_BALL_PARAMS",
    "CueParams",
    "Scene",
    "angle_from_phi",
    "ball_params_from_table",
    "cue_from_pooltool",
    "cue_to_pooltool",
    "from_system",
    "phi_from_angle",
    "pooltool_available",
    "table_options_from_pooltool",
    "to_system",
    "xy_from_pooltool",
    "xy_to_pooltool",
]

#: The ``Table`` keywords of pooltool 0.6.0's default physics engine (its default resolver:
#: Stronge's cushions at ``omega_ratio`` 1.8, the frictional inelastic ball-ball impulse with
#: its friction rule), which a ``System`` does not carry: ``from_system(system,
#: table_options=POOLTOOL_MODELS)``. The models of ``Table.preset("pooltool-0.6")``.
POOLTOOL_MODELS: dict[str, Any] = {
    name: PRESETS["pooltool-0.6"][name]
    for name in ("ball_friction", "cushion_model", "cushion_omega_ratio", "ball_model")
}

#: How to install pooltool 0.6.0 beside this package. Not an extra: on Linux
#: pooltool-billiards 0.6.0 pins an unpublished panda3d build, so a plain pip install falls
#: back to pooltool 0.3.3; the script installs 0.6.0 with panda3d 1.10 (and numba <= 0.62,
#: which this package runs on too).
INSTALL = (
    "install pooltool-billiards 0.6.0 beside pool_env; on Linux, from this repository, "
    "bash bench/setup_pooltool.sh VENV (pooltool 0.6.0 with panda3d 1.10), then "
    "VENV/bin/python -m pip install -e ."
)

#: pooltool's ``BallParams`` name -> the :class:`Table` field holding the same number.
#: ``u_sp_proportionality`` is converted (:func:`table_options_from_pooltool`).
BALL_FIELDS: dict[str, str] = {
    "R": "ball_radius",
    "m": "ball_mass",
    "u_s": "mu_slide",
    "u_r": "mu_roll",
    "e_b": "e_ball",
    "e_c": "e_cushion",
    "f_c": "cushion_friction",
    "g": "g",
}
#: pooltool's ``BallParams`` read by :func:`from_system` (each shared by every ball, but
#: ``m``).
PORTED_BALL_PARAMS = (*BALL_FIELDS, "u_sp_proportionality")
#: pooltool's motion state of a pocketed ball (``pooltool.constants.pocketed``).
_POCKETED = 4
#: pooltool's motion state of a ball at rest (``pooltool.constants.stationary``).
_STATIONARY = 0


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


# --- pure mappings: no pooltool needed --------------------------------------------------------


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


def table_options_from_pooltool(
    ball: Mapping[str, float],
    length: float,
    width: float,
    cushion_height: float,
    tip_radius: float,
    end_mass: float,
) -> dict[str, float]:
    """:class:`Table` keywords for pooltool's ball parameters, table size and cue specs.

    Args:
        ball: pooltool ``BallParams`` values by name: every name of
            :data:`PORTED_BALL_PARAMS` (``R, m, u_s, u_r, e_b, e_c, f_c, g,
            u_sp_proportionality``); others are ignored.
        length: pooltool's ``table.l`` (m).
        width: pooltool's ``table.w`` (m).
        cushion_height: The cushions' height (m).
        tip_radius: pooltool's ``CueSpecs.tip_radius`` (m).
        end_mass: pooltool's ``CueSpecs.end_mass`` (kg).

    Returns:
        The keywords (``spin_decel = (5/2) u_sp_proportionality g``).

    Raises:
        ValueError: A missing name or a value that is not a finite real number.
    """
    missing = [name for name in PORTED_BALL_PARAMS if name not in ball]
    if missing:
        raise ValueError(f"ball parameters lack {missing} (pooltool's BallParams names)")
    options = {field: real_number(name, ball[name]) for name, field in BALL_FIELDS.items()}
    # pooltool's spin friction u_sp = proportionality R decelerates the vertical-axis spin
    # at (5/2) u_sp g / R (a uniform ball, torque u_sp m g): R cancels.
    proportionality = real_number("u_sp_proportionality", ball["u_sp_proportionality"])
    options["spin_decel"] = 2.5 * proportionality * options["g"]
    options["length"] = real_number("length", length)
    options["width"] = real_number("width", width)
    options["cushion_height"] = real_number("cushion_height", cushion_height)
    options["cue_tip_radius"] = real_number("tip_radius", tip_radius)
    options["cue_end_mass"] = real_number("end_mass", end_mass)
    return options


def ball_params_from_table(table: Table) -> dict[str, float]:
    """The pooltool ``BallParams`` keywords of a :class:`Table` (the inverse of the above).

    Args:
        table: The table.

    Returns:
        ``R, m, u_s, u_r, e_b, e_c, f_c, g`` and ``u_sp_proportionality = spin_decel /
        ((5/2) g)``.

    Raises:
        ValueError: Not a :class:`Table`, or a parameter pooltool refuses (it needs every
            friction positive: ``cushion_friction = 0`` has no pooltool equivalent).
    """
    table = check_table(table)
    params = {name: float(getattr(table, field)) for name, field in BALL_FIELDS.items()}
    params["u_sp_proportionality"] = table.spin_decel * 2.0 / (5.0 * table.g)
    if params["f_c"] <= 0.0:
        raise ValueError(
            "pooltool needs a positive cushion friction (BallParams.f_c), got "
            f"cushion_friction={table.cushion_friction!r}"
        )
    return params


# --- pooltool's objects --------------------------------------------------------------------------


def _pooltool() -> ModuleType:
    """pooltool, or a ModuleNotFoundError saying how to install it."""
    return require("pooltool", None, "pool_env.interop.pooltool", install=INSTALL)


def pooltool_available() -> bool:
    """Whether pooltool can be imported here (:func:`from_system` and :func:`to_system`).

    Only looks for the package: it does not import it (pooltool writes its settings under
    ``~/.config`` on its first import).
    """
    from importlib.util import find_spec

    return find_spec("pooltool") is not None


@dataclass(frozen=True, eq=False)
class Scene:
    """A table, a layout and a shot, as :func:`from_system` reads them from a ``System``.

    Attributes:
        table: The table (pooltool's size and ball, cushion and cue parameters).
        positions: ``(N, 2)`` the balls on the table, in this package's frame (read-only).
        ids: pooltool's ball id of each row.
        cue: The row of the cue ball (``System.cue.cue_ball_id``).
        angle: The aim (radians counter-clockwise from ``+x``).
        speed: The cue ball's speed in the table plane after the strike (m/s).
        tip: The cue axis's offset ``(side, vertical)``, fractions of ``R``.
        elevation: The cue's elevation (radians).
        masses: ``(N,)`` per-ball masses for :func:`pool_env.shoot`, or ``None`` (every
            ball has ``table.ball_mass``; always so from a ``System``, and needed by
            :meth:`to_system`: pooltool gives every ball one mass).
        cue_mass: The cue's mass (kg), pooltool's ``CueSpecs.M``.
    """

    table: Table
    positions: NDArray[np.float64]
    ids: tuple[str, ...]
    cue: int
    angle: float
    speed: float
    tip: tuple[float, float] = (0.0, 0.0)
    elevation: float = 0.0
    masses: NDArray[np.float64] | None = None
    cue_mass: float = POOLTOOL_CUE_MASS

    def __post_init__(self) -> None:
        table = check_table(self.table)
        positions = check_positions(table, self.positions)
        positions.setflags(write=False)
        object.__setattr__(self, "positions", positions)
        n = positions.shape[0]
        ids = _check_ids(self.ids, n)
        object.__setattr__(self, "ids", ids)
        object.__setattr__(self, "cue", check_cue(self.cue, n))
        if self.masses is not None:
            masses = np.array(as_masses(self.masses, n))
            if not (masses > 0.0).all():  # as simulate refuses them, but before pooltool sees them
                raise ValueError(f"masses must be positive, got {masses.tolist()}")
            masses.setflags(write=False)
            object.__setattr__(self, "masses", masses)
        a, b, elevation = check_tip(table, self.tip, self.elevation)
        object.__setattr__(self, "tip", (a, b))
        object.__setattr__(self, "elevation", elevation)
        for name in ("angle", "speed", "cue_mass"):
            object.__setattr__(self, name, real_number(name, getattr(self, name)))
        # the whole shot through the one mapping, for its checks (a positive speed and mass)
        cue_to_pooltool(table, self.angle, self.speed, self.tip, elevation, cue_mass=self.cue_mass)

    def shoot_kwargs(self) -> dict[str, Any]:
        """The keywords of :func:`pool_env.shoot` for this shot (``table`` included)."""
        return {
            "table": self.table,
            "positions": self.positions,
            "angle": self.angle,
            "speed": self.speed,
            "cue": self.cue,
            "masses": self.masses,
            "tip": self.tip,
            "elevation": self.elevation,
        }

    def shoot(self, **kwargs: Any) -> ShotResult:
        """Play the shot with :func:`pool_env.shoot` (``kwargs``: ``max_events``, ``record``)."""
        return shoot(**self.shoot_kwargs(), **kwargs)

    def to_system(self) -> Any:
        """The ``pooltool.System`` of this scene (:func:`to_system`).

        Raises:
            ValueError: Per-ball masses other than ``table.ball_mass`` (pooltool 0.6.0's
                ``System`` holds every ball to one mass), or as :func:`to_system`.
        """
        if self.masses is not None and (self.masses != self.table.ball_mass).any():
            raise ValueError(
                "pooltool 0.6.0 gives every ball one mass: a scene with masses "
                f"{self.masses.tolist()} has no System (table.ball_mass is "
                f"{self.table.ball_mass!r})"
            )
        return to_system(
            self.table,
            self.positions,
            self.angle,
            self.speed,
            cue=self.cue,
            tip=self.tip,
            elevation=self.elevation,
            ids=self.ids,
            cue_mass=self.cue_mass,
        )


def _check_ids(ids: object, n: int) -> tuple[str, ...]:
    if isinstance(ids, str) or not isinstance(ids, Sequence):
        raise ValueError(f"ids must be a sequence of {n} strings, got {ids!r}")
    out = tuple(ids)
    if len(out) != n or not all(isinstance(i, str) and i for i in out):
        raise ValueError(f"ids must be {n} non-empty strings (one per ball), got {ids!r}")
    if len(set(out)) != n:
        raise ValueError(f"ids must be distinct, got {ids!r}")
    return out


def _default_ids(n: int, cue: int) -> tuple[str, ...]:
    """As pooltool names balls: ``"cue"`` for the cue ball, ``"1", "2", ...`` for the others."""
    others = iter(range(1, n))
    return tuple("cue" if k == cue else str(next(others)) for k in range(n))


def to_system(
    table: Table,
    positions: ArrayLike,
    angle: float,
    speed: float,
    *,
    cue: int = 0,
    tip: tuple[float, float] = (0.0, 0.0),
    elevation: float = 0.0,
    ids: Sequence[str] | None = None,
    cue_mass: float = POOLTOOL_CUE_MASS,
) -> Any:
    """A ``pooltool.System`` of a layout and a shot (the arguments of :func:`pool_env.shoot`).

    The balls stand at rest at the positions (turned into pooltool's frame) with the table's
    parameters, the cue holds the shot's ``V0, phi, theta, a, b`` (:func:`cue_to_pooltool`)
    and its specs the table's tip radius and end mass and ``cue_mass``. ``pooltool.simulate``
    then strikes and plays it; ``pooltool.show`` shows it.

    Args:
        table: The table. With pockets, pooltool's own ``PocketTableSpecs`` pockets (not
            this package's jaws); without, a ``BilliardTableSpecs`` table.
        positions: ``(N, 2)`` ball centres (this package's frame), a layout
            :func:`pool_env.check_layout` accepts.
        angle: The aim (radians).
        speed: The cue ball's speed after the strike (m/s), positive.
        cue: The cue ball's row.
        tip: The cue axis's offset ``(side, vertical)``, as :func:`pool_env.shoot` takes it.
        elevation: The cue's elevation (radians).
        ids: pooltool's ball ids, one per row; ``None``: ``"cue"`` for the cue ball and
            ``"1", "2", ...`` for the others in row order.
        cue_mass: The cue's mass (kg), pooltool's ``CueSpecs.M``.

    Returns:
        The ``pooltool.System``.

    Raises:
        ModuleNotFoundError: pooltool is not installed (the message says how to install it).
        ValueError: A layout or shot :func:`pool_env.shoot` would refuse, bad ids, or a
            table parameter pooltool has no equivalent for (:func:`ball_params_from_table`).
    """
    pos = as_points("positions", positions)
    cue = check_cue(cue, pos.shape[0])
    scene = Scene(
        table,
        pos,
        _default_ids(pos.shape[0], cue) if ids is None else _check_ids(ids, pos.shape[0]),
        cue,
        angle,
        speed,
        tip,
        elevation,
        None,
        cue_mass,
    )
    params = ball_params_from_table(scene.table)
    pt = _pooltool()
    table = scene.table
    if table.pocket_model == "none":
        specs: Any = pt.objects.BilliardTableSpecs(
            l=table.length, w=table.width, cushion_height=table.cushion_height
        )
    else:
        specs = pt.objects.PocketTableSpecs(
            l=table.length, w=table.width, cushion_height=table.cushion_height
        )
    xy = xy_to_pooltool(scene.positions, table.width)
    balls = {
        bid: pt.Ball.create(bid, xy=(float(xy[k, 0]), float(xy[k, 1])), **params)
        for k, bid in enumerate(scene.ids)
    }
    shot = cue_to_pooltool(table, scene.angle, scene.speed, scene.tip, scene.elevation,
                           cue_mass=scene.cue_mass)  # fmt: skip
    cue_specs = pt.objects.CueSpecs(
        M=scene.cue_mass, tip_radius=table.cue_tip_radius, end_mass=table.cue_end_mass
    )
    stick = pt.Cue(cue_ball_id=scene.ids[scene.cue], specs=cue_specs, **shot._asdict())
    return pt.System(cue=stick, table=pt.Table.from_table_specs(specs), balls=balls)


def _corners(table: Any) -> tuple[float, float, float, float, float]:
    """The pooltool table's ``(x0, y0, length, width, cushion height)``, from its cushions."""
    linear = table.cushion_segments.linear
    needed = ("3", "9", "12", "18")
    if not all(k in linear for k in needed):
        raise ValueError(
            "the pooltool table lacks the linear cushion segments 3, 9, 12 and 18 that "
            "bound the playing surface on pooltool's own layouts (pocket, billiard and "
            f"snooker tables); it has {sorted(linear)}"
        )
    x0, y0 = float(linear["3"].p1[0]), float(linear["18"].p1[1])
    width = float(linear["12"].p1[0]) - x0
    length = float(linear["9"].p1[1]) - y0
    heights = {float(linear[k].p1[2]) for k in needed}
    if len(heights) != 1:
        raise ValueError(f"the pooltool table's cushions differ in height: {sorted(heights)}")
    return x0, y0, length, width, heights.pop()


def _shared_params(balls: Sequence[Any]) -> dict[str, float]:
    """The ball parameters every ball shares."""
    first = balls[0].params
    shared = {name: float(getattr(first, name)) for name in PORTED_BALL_PARAMS}
    for ball in balls[1:]:
        for name in PORTED_BALL_PARAMS:
            value = float(getattr(ball.params, name))
            if value != shared[name]:
                raise ValueError(
                    f"ball {ball.id!r} has {name}={value!r} and ball {balls[0].id!r} "
                    f"{shared[name]!r}: a Table holds one value for every ball"
                )
    return shared


def from_system(
    system: Any,
    *,
    model: str = "spin",
    pockets: Any = None,
    table_options: Mapping[str, Any] | None = None,
) -> Scene:
    """The table, layout and shot of a ``pooltool.System`` at rest (before its shot).

    Args:
        system: The ``pooltool.System``: its balls at rest (pocketed balls are left out),
            its cue's ball on the table.
        model: The :class:`Table` model, ``"spin"`` (the level that plays a cue's english,
            draw and elevation) or ``"roll"`` (a centre hit, flat cue only).
        pockets: The :class:`Table` pockets; ``None``: ``"jaws"`` if pooltool's table has
            pockets, else ``"none"``.
        table_options: More :class:`Table` keywords, over the ported ones (e.g.
            ``{"ball_friction": "pooltool"}`` for pooltool's ball-ball friction impulse).

    Returns:
        The :class:`Scene`; ``scene.shoot()`` plays the shot.

    Raises:
        ModuleNotFoundError: pooltool is not installed (the message says how to install it).
        ValueError: Not a ``pooltool.System``; a ball in motion; no ball or the cue ball
            pocketed or missing; balls whose shared parameters differ; a cue stroke out of
            range (:func:`cue_from_pooltool`); or a table or layout this package refuses
            (off the table, overlapping, in a pocket).
    """
    pt = _pooltool()
    if not isinstance(system, pt.System):
        raise ValueError(f"system must be a pooltool.System, got {type(system).__name__}")
    x0, y0, length, width, height = _corners(system.table)
    on_table = [b for b in system.balls.values() if int(b.state.s) != _POCKETED]
    if not on_table:
        raise ValueError("the System has no ball on the table")
    for ball in on_table:
        moving = np.asarray(ball.state.rvw)[1:]
        if int(ball.state.s) != _STATIONARY or np.any(moving != 0.0):
            raise ValueError(
                f"ball {ball.id!r} is in motion (state {int(ball.state.s)}): port a System "
                "at rest, before its shot or after pooltool.simulate"
            )
    ids = tuple(str(b.id) for b in on_table)
    cue_id = system.cue.cue_ball_id
    if cue_id not in ids:
        raise ValueError(f"the cue ball {cue_id!r} is not on the table (balls: {ids})")
    cue = ids.index(cue_id)
    params = _shared_params(on_table)
    specs = system.cue.specs
    options: dict[str, Any] = table_options_from_pooltool(
        params, length, width, height, specs.tip_radius, specs.end_mass
    )
    options["model"] = model
    options["pockets"] = pockets
    if pockets is None:
        options["pockets"] = "jaws" if system.table.has_pockets else "none"
    options.update(table_options or {})
    table = Table(**options)
    xy = np.array([np.asarray(b.state.rvw[0][:2], dtype=np.float64) for b in on_table])
    stroke = system.cue
    angle, speed, tip, elevation = cue_from_pooltool(
        table, stroke.V0, stroke.phi, stroke.theta, stroke.a, stroke.b, cue_mass=specs.M
    )
    return Scene(
        table,
        xy_from_pooltool(xy, width, (x0, y0)),
        ids,
        cue,
        angle,
        speed,
        tip,
        elevation,
        None,
        float(specs.M),
    )
