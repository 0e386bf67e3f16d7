"""The spin level's model choices as ``Table`` names, and their validation.

``Table.cushion_model`` picks the ball-cushion impact (``"han"``: Han 2005,
:mod:`~pool_env.sim.kernels.spin.cushion`; ``"stronge"``: Stronge's compliant model,
:mod:`~pool_env.sim.kernels.spin.stronge`), ``Table.ball_model`` the ball-ball impact
(``"frictional"``: :mod:`~pool_env.sim.kernels.spin.collide`; ``"mathavan"``:
:mod:`~pool_env.sim.kernels.spin.mathavan`). The codes reach the kernels through
``Table.spin_params``.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from pool_env.sim.kernels.spin.collide import ALCIATORE_A, ALCIATORE_B
from pool_env.sim.kernels.spin.params import (
    FRICTIONAL_BALLS,
    HAN_CUSHION,
    MATHAVAN_BALLS,
    STRONGE_CUSHION,
)
from pool_env.sim.scalars import real_number

#: The cushion models and ball-ball models, by ``Table`` name -> kernel code.
CUSHION_MODELS = {"han": HAN_CUSHION, "stronge": STRONGE_CUSHION}
BALL_MODELS = {"frictional": FRICTIONAL_BALLS, "mathavan": MATHAVAN_BALLS}
#: Mathavan's step count ``N``: at most this many (an impact costs about ``N`` steps).
MAX_MATHAVAN_STEPS = 1_000_000


def check_models(table: Any) -> dict[str, Any]:
    """Validate a table's model choices and their parameters.

    Returns:
        The validated ``cushion_omega_ratio`` and ``mathavan_steps`` by name.

    Args:
        table: The ``Table`` being built (its restitutions already validated).

    Raises:
        ValueError: An unknown model name; ``cushion_omega_ratio`` outside ``(1, 2)``; with
            Stronge's model, ``e_cushion`` or ``e_jaw`` below ``1 / cushion_omega_ratio``
            (the model's range, :mod:`~pool_env.sim.kernels.spin.stronge`); or
            ``mathavan_steps`` not an integer in ``[1, MAX_MATHAVAN_STEPS]``; with
            Mathavan's model, ``mu_slide`` times the largest ball-ball friction above 1 (the
            table's friction could then stall the impact,
            :mod:`~pool_env.sim.kernels.spin.mathavan`).
    """
    for name, models in (("cushion_model", CUSHION_MODELS), ("ball_model", BALL_MODELS)):
        value = getattr(table, name)
        if not isinstance(value, str) or value not in models:
            raise ValueError(f"{name} must be one of {sorted(models)}, got {value!r}")
    ratio = real_number("cushion_omega_ratio", table.cushion_omega_ratio)
    if not 1.0 < ratio < 2.0:
        raise ValueError(f"cushion_omega_ratio must lie in (1, 2), got {ratio!r}")
    if table.cushion_model == "stronge":
        for name in ("e_cushion", "e_jaw"):
            if getattr(table, name) < 1.0 / ratio:
                raise ValueError(
                    f"Stronge's cushion model needs {name} >= 1 / cushion_omega_ratio = "
                    f"{1.0 / ratio!r} (its closed forms hold from there up), got "
                    f"{getattr(table, name)!r}"
                )
    steps = table.mathavan_steps
    if isinstance(steps, bool) or not isinstance(steps, int | np.integer):
        raise ValueError(f"mathavan_steps must be an integer, got {steps!r}")
    if not 1 <= steps <= MAX_MATHAVAN_STEPS:
        raise ValueError(f"mathavan_steps must lie in [1, {MAX_MATHAVAN_STEPS}], got {steps!r}")
    if table.ball_model == "mathavan":
        friction = table.ball_friction
        mu_b = ALCIATORE_A + ALCIATORE_B if isinstance(friction, str) else float(friction)
        if table.mu_slide * mu_b > 1.0:
            raise ValueError(
                "Mathavan's ball-ball model needs mu_slide * ball_friction <= 1 (the largest "
                f"ball-ball friction, {mu_b!r} for ball_friction={friction!r}), got "
                f"mu_slide={table.mu_slide!r}: the product is {table.mu_slide * mu_b!r}"
            )
    return {"cushion_omega_ratio": ratio, "mathavan_steps": int(steps)}
