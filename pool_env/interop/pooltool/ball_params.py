"""pooltool's ball parameters and table size as a :class:`~pool_env.sim.table.Table`'s, and back.

:data:`BALL_FIELDS` pairs each of pooltool's ``BallParams`` with the ``Table`` field holding
the same number; :func:`table_options_from_pooltool` and :func:`ball_params_from_table`
convert between them (``spin_decel = (5/2) u_sp_proportionality g``), and
:data:`POOLTOOL_MODELS` names the ``Table`` models of pooltool's default physics engine,
which a ``System`` does not carry. Plain functions: no pooltool needed.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from pool_env.sim.inputs import check_table
from pool_env.sim.presets import PRESETS
from pool_env.sim.scalars import real_number
from pool_env.sim.table import Table

#: The ``Table`` keywords of pooltool 0.6.0's default physics engine (its default resolver:
#: Stronge's cushions at ``omega_ratio`` 1.8, the frictional inelastic ball-ball impulse with
#: its friction rule), which a ``System`` does not carry: ``from_system(system,
#: table_options=POOLTOOL_MODELS)``. The models of ``Table.preset("pooltool-0.6")``.
POOLTOOL_MODELS: dict[str, Any] = {
    name: PRESETS["pooltool-0.6"][name]
    for name in ("ball_friction", "cushion_model", "cushion_omega_ratio", "ball_model")
}

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
