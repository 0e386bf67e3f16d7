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
on the spin level by default. ``model="roll"`` over it is allowed (:data:`ROLL_ALLOWED`):
the roll table then takes the preset without its spin-only values (the last three rows),
which the roll level does not read. Each value and its source:

==========================  ============================================  ==============
``Table`` keyword           source                                        value
==========================  ============================================  ==============
``length``, ``width``       WPBSA 1(a): 11 ft 8.5 in x 5 ft 10in          3.569, 1.778
                            ("3569mm x 1778mm", +/- 13 mm); pooltool's
                            ``SnookerTableSpecs`` has 3.5445 x 1.7465,
                            inside that tolerance but not the figure
``ball_radius``             WPBSA 2: balls of 52.5 mm (+0.05 mm);         0.02625
                            pooltool's 0.02619375 is 2 1/16 in
``ball_mass``               pooltool 0.6.0 ``SNOOKER_GENERIC.m`` (the     0.140
                            WPBSA sets no mass, only 3 g within a set)
``mu_roll``                 pooltool's ``SNOOKER_GENERIC.u_r``, inside    0.01
                            Alciatore's 0.005-0.015 (no snooker-cloth
                            measurement found: kept)
``e_ball``, ``e_cushion``   the package's defaults (``docs/sources.md``   0.95, 0.65
                            "Physical properties"); Mathavan's 0.98 for
                            the cushion belongs to his model (friction
                            at the cloth during the impact), pooltool's
                            0.85 is unresearched: kept
``pockets``                 :data:`SNOOKER_POCKETS` (below)               ``JawSpec``
``mu_slide`` (spin)         Mathavan et al. 2010, measured on a snooker   0.212
                            table (``docs/sources.md``, "Real
                            tables"); pooltool's ``SNOOKER_GENERIC.u_s``
                            0.5 is, by its own comment, unresearched
``cushion_friction`` (spin) Mathavan et al. 2010 (same): 0.14; pooltool   0.14
                            ``SNOOKER_GENERIC.f_c`` 0.5 (unresearched)
``cushion_height`` (spin)   Mathavan et al. 2010 (same): the snooker      0.03675
                            cushion's contact at ``7 R / 5``; pooltool's
                            0.028 is below ``R`` here, which no cushion
                            model takes (the ball would ride over it)
==========================  ============================================  ==============

WPBSA 1(c)(ii) has the pocket openings "conform to the templates authorised by the
WPBSA"; the templates are not published, so the pocket shape is pooltool 0.6.0's
``SnookerTableSpecs``, the same shape (``tests/sim/test_presets.py`` builds both):
corner and centre mouths 0.083 m and 0.087 m between the points (where each rail's nose
line meets its facing's); pocket angle 0 (facings parallel to the pocket's axis: a cut of
135 degrees to the rail at corners, 90 at the centre); rounded jaws of 4 in (corner) and
2.5 in (centre) radius, each a circle tangent to the rail's nose and to the facing (its
centre ``r / tan(cut / 2)`` along the rail from the point, ``r`` behind the nose, as
pooltool's ``create_pocket_table_cushion_segments`` puts it). pooltool's pocket
*depths* (0.036 m and 0.95 in) are not the same quantity here: pooltool pots a ball
whose centre enters a circle (of radius 4 in and 1.68 in) centred that far behind the
corner and the rail, which on the pocket's axis reaches 24 mm (corner) and 19 mm (centre)
in front of the mouth; this package pots at a fall line behind the mouth, which must lie
in the throat. The preset takes pooltool's two depths as the fall lines' distances
behind the mouth (no published snooker shelf figure found).

``"carom"`` is the match carom table of three-cushion (UMB "Rules of the game of
billiards", article 1, the source pooltool's ``BilliardTableSpecs`` cites), pocketless,
on the spin level only (three-cushion is played there; ``model="roll"`` is refused, as
its cushion values are spin-only):

==========================  ============================================  ==============
``Table`` keyword           source                                        value
==========================  ============================================  ==============
``length``, ``width``       UMB art. 1: playing area 2.84 x 1.42 m        2.84, 1.42
``ball_radius``             UMB: balls of 61-61.5 mm; pooltool            0.03075
                            ``BILLIARD_GENERIC.R`` = 0.0615 / 2
``ball_mass``               UMB: 205-220 g; pooltool                      0.210
                            ``BILLIARD_GENERIC.m``
``cushion_height`` (spin)   UMB: cushion nose 37 mm (+/- 1 mm) above      0.037
                            the cloth; pooltool ``BilliardTableSpecs``
``cushion_friction`` (spin) pooltool ``BILLIARD_GENERIC.f_c``             0.15
``mu_roll``, ``mu_slide``   the package's defaults (pooltool's            0.01, 0.2
                            ``BILLIARD_GENERIC`` has the same); the
                            heated cloth plays faster, but no measured
                            coefficient was found: kept
``e_ball``, ``e_cushion``   the package's defaults (pooltool's            0.95, 0.65
                            ``BILLIARD_GENERIC.e_c`` 0.85 is
                            unresearched; no measured carom cushion
                            restitution found: kept)
==========================  ============================================  ==============
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

#: The presets a roll table may be made from (``model="roll"``): each loses its spin-only
#: values there (:data:`pool_env.sim.table.SPIN_ONLY`), which the roll level does not read.
ROLL_ALLOWED = frozenset({"snooker"})

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
                "mu_roll": 0.01,
                "pockets": SNOOKER_POCKETS,
                "model": "spin",
                "mu_slide": 0.212,
                "cushion_friction": 0.14,
                "cushion_height": 7.0 / 5.0 * 0.0525 / 2,
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
