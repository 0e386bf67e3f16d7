"""The cue tip of a spin table's action: its two components as the cue's axis offset.

Each component ``c`` in ``[-1, 1]`` maps to ``c * tip_limit`` (fractions of R); an offset
outside the circle of radius ``tip_limit`` (the miscue limit) is scaled back onto it. One
copy of the rule for the step's decoder, :func:`pool_env.encode_action` and the baselines.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel


@kernel
def onto_tip_circle(a, b, limit):
    """The tip the spin env executes: ``(a, b)`` scaled back onto the miscue circle.

    The one copy of the rule, used by the decoder, :func:`pool_env.encode_action` and the
    baselines (``pool_env.onto_tip_circle``).

    Args:
        a: Side offset of the cue's axis, fraction of R.
        b: Vertical offset, fraction of R.
        limit: The tip limit (radius of the circle, fraction of R).

    Returns:
        ``(a, b)`` unchanged inside the circle, else the same direction at distance ``limit``.
    """
    h = math.sqrt(a * a + b * b)  # not hypot: libm's and Python's may differ in the last bit
    if h > limit:
        scale = limit / h
        return a * scale, b * scale
    return a, b


@kernel
def decode_tips(actions, column, limit):
    """The cue tip's axis offsets of actions: ``actions[:, column:column + 2]``.

    Each component is clipped to ``[-1, 1]`` and mapped linearly onto ``[-limit, limit]``
    (fractions of R); an offset outside the circle of radius ``limit`` is scaled back
    onto it (:func:`onto_tip_circle`).

    Args:
        actions: ``(B, W)`` actions.
        column: The side component's column (the vertical one follows it).
        limit: The tip limit (``params[TIP_LIMIT]``).

    Returns:
        ``(B, 2)`` float64 ``(a, b)``: side (+ right english) and vertical (+ follow).
    """
    b = actions.shape[0]
    tips = np.empty((b, 2))
    for k in range(b):
        a_raw = min(max(float(actions[k, column]), -1.0), 1.0) * limit
        b_raw = min(max(float(actions[k, column + 1]), -1.0), 1.0) * limit
        tips[k, 0], tips[k, 1] = onto_tip_circle(a_raw, b_raw, limit)
    return tips
