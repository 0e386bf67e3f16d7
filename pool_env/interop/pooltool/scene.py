"""A table, a layout and a shot (:class:`Scene`), and the pooltool ``System`` of one.

:class:`Scene` is what :func:`~pool_env.interop.pooltool.from_system` reads from a
``System``, ready for :func:`pool_env.shoot`; :func:`to_system` builds the ``System`` of a
layout and a shot (pooltool imported only then).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.interop.pooltool.ball_params import ball_params_from_table
from pool_env.interop.pooltool.cue_params import cue_to_pooltool
from pool_env.interop.pooltool.frame import xy_to_pooltool
from pool_env.interop.pooltool.loader import load_pooltool
from pool_env.sim.cue import POOLTOOL_CUE_MASS
from pool_env.sim.inputs import as_masses, as_points, check_cue, check_table
from pool_env.sim.scalars import real_number
from pool_env.sim.simulate import check_positions, shoot
from pool_env.sim.spin_inputs import check_tip
from pool_env.sim.table import Table

if TYPE_CHECKING:
    from pool_env.sim.result import ShotResult


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
    pt = load_pooltool()
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
