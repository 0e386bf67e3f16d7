"""pooltool 0.6.0's ``System`` to this package's table, layout and shot, and back.

:func:`from_system` reads a pooltool ``System`` (its table's size and cushion height, its
balls' positions and parameters, its cue's ``V0, phi, theta, a, b`` and specs) into a
:class:`Scene`: a :class:`~pool_env.sim.table.Table`, the positions ``(N, 2)`` with the
balls' ids, the cue ball's row and the shot's ``angle, speed, tip, elevation``, which
:meth:`Scene.shoot` plays through :func:`pool_env.shoot`. :func:`to_system` builds the
``System`` of a layout and a shot, to watch it in pooltool's 3D interface
(``pooltool.show``) or to run it there. pooltool is imported only by these two (and by
:meth:`Scene.to_system`); the mappings are plain functions that need no pooltool.

The modules, each re-exported here: :mod:`~pool_env.interop.pooltool.frame` (points and
aim between the frames), :mod:`~pool_env.interop.pooltool.cue_params` (the cue's
``V0, phi, theta, a, b``), :mod:`~pool_env.interop.pooltool.ball_params` (ball parameters
and table size), :mod:`~pool_env.interop.pooltool.loader` (pooltool itself, imported when
called), :mod:`~pool_env.interop.pooltool.scene` (:class:`Scene` and :func:`to_system`)
and :mod:`~pool_env.interop.pooltool.read_system` (:func:`from_system`, the way back).

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

from pool_env.interop.pooltool.ball_params import (
    BALL_FIELDS,
    POOLTOOL_MODELS,
    PORTED_BALL_PARAMS,
    ball_params_from_table,
    table_options_from_pooltool,
)
from pool_env.interop.pooltool.cue_params import CueParams, cue_from_pooltool, cue_to_pooltool
from pool_env.interop.pooltool.frame import (
    angle_from_phi,
    phi_from_angle,
    xy_from_pooltool,
    xy_to_pooltool,
)
from pool_env.interop.pooltool.loader import INSTALL, pooltool_available
from pool_env.interop.pooltool.read_system import from_system
from pool_env.interop.pooltool.scene import Scene, to_system
from pool_env.sim.cue import POOLTOOL_CUE_MASS

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
