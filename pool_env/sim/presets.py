"""Named table presets: ``Table.preset(name)``, every parameter from one source.

``"pooltool-0.6"`` is pooltool 0.6.0 as it ships, each value as its source code has it (read
from the released package; the file and name of each):

==========================  ============================================  ==============
``Table`` keyword           pooltool 0.6.0                                value
==========================  ============================================  ==============
``length``, ``width``       ``PocketTableSpecs.l``, ``.w = l / 2``        1.9812, 0.9906
``cushion_height``          ``PocketTableSpecs.cushion_height``           0.64 x 2 x 0.028575
``ball_radius``             ``BallParams.R``                              0.028575
``ball_mass``               ``BallParams.m``                              0.170097
``mu_slide``, ``mu_roll``   ``BallParams.u_s``, ``.u_r``                  0.2, 0.01
``spin_decel``              ``(5/2) u_sp_proportionality g``,             10.9 rad/s^2
                            ``u_sp_proportionality = 10 x 2 / 5 / 9``
``e_ball``, ``e_cushion``   ``BallParams.e_b``, ``.e_c``                  0.95, 0.85
``cushion_friction``        ``BallParams.f_c``                            0.2
``g``                       ``BallParams.g``                              9.81
``cue_tip_radius``          ``CueSpecs.tip_radius``                       0.0106045
``cue_end_mass``            ``CueSpecs.end_mass = 0.170097 / 30``         0.00566990
``ball_friction``           ``FrictionalInelastic`` with                  ``"pooltool"``
                            ``AlciatoreBallBallFriction(0.009951,
                            0.108, 1.088)`` (default resolver)
``cushion_model``           ``StrongeCompliantLinear/Circular``           ``"stronge"``
``cushion_omega_ratio``     their ``omega_ratio`` in the default          1.8
                            resolver (the classes' own default: 1.7)
``e_jaw``                   (pooltool's jaws are cushions: ``e_c``)       ``None``
``model``                   (pooltool has spin)                           ``"spin"``
==========================  ============================================  ==============

Not a ``Table`` parameter: pooltool's cue mass ``CueSpecs.M = 0.567`` kg is
:data:`pool_env.sim.cue.POOLTOOL_CUE_MASS` (the mapping of its ``V0``); ``BallParams.u_b``
is read only by pooltool's ``AverageBallBallFriction``, not its default. Not pooltool's:
the pockets. pooltool's ``PocketTableSpecs`` cuts its own pocket shapes (jaw circles
of 0.02095 m, corner mouths 0.118 m); the preset keeps this package's WPA jaw pockets
(``pockets="jaws"``), sized for any table. ``Table.preset("pooltool-0.6", pockets="none")``
is the pocketless table on which shots agree with pooltool's (``bench/models_vs_pooltool.py``).

``"snooker"`` is the 12-ft snooker table (WPBSA Rules, Section 1, "The Standard Table"),
on the spin level by default; ``model="roll"`` over it is allowed, as it sets no spin-only
value. Each value and its source:

==========================  ============================================  ==============
``Table`` keyword           source                                        value
==========================  ============================================  ==============
``length``, ``width``       WPBSA 1(a): 11 ft 8.5 in x 5 ft 10 in          3.569, 1.778
``ball_radius``             WPBSA 2: balls of 52.5 mm (+/- 0.05 mm)       0.02625
``ball_mass``               pooltool 0.6.0 ``SNOOKER_GENERIC.m``          0.140
``pockets``                 :data:`SNOOKER_POCKETS` (below)               ``JawSpec``
==========================  ============================================  ==============

WPBSA 1(c)(ii) has the pocket openings "conform to the templates authorised by the
WPBSA"; the templates are not published, so the pocket shape is pooltool 0.6.0's
``SnookerTableSpecs``: corner and centre mouths 0.083 m and 0.087 m, facings parallel to
the pocket's axis (its pocket angle 0: a cut of 135 degrees at corners, 90 at the centre),
rounded jaws of 4 in (corner) and 2.5 in (centre) radius, fall lines 0.036 m and
0.95 in behind the mouth. The rest (cloth, restitution) is the package's defaults.

``"carom"`` is the match carom table of three-cushion (UMB "Rules of the game of
billiards", article 1: playing area 2.84 x 1.42 m, balls of 61-61.5 mm and 205-220 g,
cushion nose 37 mm high), pocketless, on the spin level (three-cushion is played there).
The ball mass and the cloth and cushion friction are pooltool 0.6.0's ``BILLIARD_GENERIC``
(``m = 0.210``, ``f_c = 0.15``); the rest is the package's defaults.
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Any

from pool_env.sim.pockets import JawSpec

#: pooltool 0.6.0's ball radius and mass (``BallParams.R``, ``.m``), used twice below.
_R, _M = 0.028575, 0.170097

_INCH = 0.0254

#: The snooker pockets: pooltool 0.6.0's ``SnookerTableSpecs`` (see the module's text).
SNOOKER_POCKETS = JawSpec(
    corner_mouth=0.083,
    side_mouth=0.087,
    corner_cut=135.0,
    side_cut=90.0,
    corner_shelf=0.036,
    side_shelf=0.95 * _INCH,
    corner_tip_radius=4.0 * _INCH,
    side_tip_radius=2.5 * _INCH,
)

#: The presets: name -> ``Table`` keywords.
PRESETS: MappingProxyType[str, MappingProxyType[str, Any]] = MappingProxyType(
    {
        "pooltool-0.6": MappingProxyType(
            {
                "length": 1.9812,
                "width": 1.9812 / 2,
                "ball_radius": _R,
                "ball_mass": _M,
                "mu_roll": 0.01,
                "g": 9.81,
                "e_ball": 0.95,
                "e_cushion": 0.85,
                "model": "spin",
                "mu_slide": 0.2,
                # pooltool's u_sp = proportionality R slows the vertical spin at
                # (5/2) u_sp g / R; its expression of the proportionality, evaluated as it does
                "spin_decel": 2.5 * (10 * 2 / 5 / 9) * 9.81,
                "ball_friction": "pooltool",
                "cushion_friction": 0.2,
                "cushion_height": 0.64 * 2 * _R,
                "cue_tip_radius": 0.0106045,
                "cue_end_mass": _M / 30,
                "cushion_model": "stronge",
                "cushion_omega_ratio": 1.8,
                "ball_model": "frictional",
            }
        ),
        "snooker": MappingProxyType(
            {
                "length": 3.569,
                "width": 1.778,
                "ball_radius": 0.0525 / 2,
                "ball_mass": 0.140,
                "pockets": SNOOKER_POCKETS,
                "model": "spin",
            }
        ),
        "carom": MappingProxyType(
            {
                "length": 2.84,
                "width": 1.42,
                "ball_radius": 0.0615 / 2,
                "ball_mass": 0.210,
                "pockets": "none",
                "model": "spin",
                "cushion_height": 0.037,
                "cushion_friction": 0.15,
            }
        ),
    }
)
