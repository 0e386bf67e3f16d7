"""The way back: a pooltool ``System`` at rest read into a table, a layout and a shot.

:func:`from_system` returns a :class:`~pool_env.interop.pooltool.scene.Scene`: the table's
size and cushion height from its cushion segments, the balls' positions and shared
parameters, and the cue's stroke and specs (pooltool imported only then).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from pool_env.interop.pooltool.ball_params import PORTED_BALL_PARAMS, table_options_from_pooltool
from pool_env.interop.pooltool.cue_params import cue_from_pooltool
from pool_env.interop.pooltool.frame import xy_from_pooltool
from pool_env.interop.pooltool.loader import load_pooltool
from pool_env.interop.pooltool.scene import Scene
from pool_env.sim.table import SPIN_ONLY, Table

#: pooltool's motion state of a pocketed ball (``pooltool.constants.pocketed``).
_POCKETED = 4
#: pooltool's motion state of a ball at rest (``pooltool.constants.stationary``).
_STATIONARY = 0
#: How far (relative to ``R``) a ball's centre may sit from the cloth plane ``z = R`` and
#: still be read as on it: rounding only (pooltool places and keeps a resting ball at
#: ``z = R`` exactly). A ball higher or lower is airborne or sunk: this simulator has no
#: height, so it is refused rather than flattened.
HEIGHT_RTOL = 1e-9


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
            draw and elevation) or ``"roll"`` (a centre hit, flat cue only; pooltool's spin
            parameters, such as its sliding friction and cue tip, are then not ported, as
            the roll table reads none of them).
        pockets: The :class:`Table` pockets; ``None``: ``"jaws"`` if pooltool's table has
            pockets, else ``"none"``.
        table_options: More :class:`Table` keywords, over the ported ones (e.g.
            ``{"ball_friction": "pooltool"}`` for pooltool's ball-ball friction impulse).

    Returns:
        The :class:`Scene`; ``scene.shoot()`` plays the shot.

    Raises:
        ModuleNotFoundError: pooltool is not installed (the message says how to install it).
        ValueError: Not a ``pooltool.System``; a ball in motion (a vertical velocity
            included) or off the cloth plane (its centre's height ``z`` not ``R`` to within
            :data:`HEIGHT_RTOL` of ``R``: airborne or sunk); no ball or the cue ball
            pocketed or missing; balls whose shared parameters differ; a cue stroke out of
            range (:func:`cue_from_pooltool`); or a table or layout this package refuses
            (off the table, overlapping, in a pocket).
    """
    pt = load_pooltool()
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
        z, radius = float(np.asarray(ball.state.rvw)[0][2]), float(ball.params.R)
        if not abs(z - radius) <= HEIGHT_RTOL * radius:
            raise ValueError(
                f"ball {ball.id!r} is at height z={z!r} m, off the cloth (its centre belongs "
                f"at z = R = {radius!r} m): this simulator keeps every ball on the cloth and "
                "cannot port an airborne or sunk ball"
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
    if model == "roll":  # the roll level reads no spin parameter: port none
        options = {k: v for k, v in options.items() if k not in SPIN_ONLY}
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
