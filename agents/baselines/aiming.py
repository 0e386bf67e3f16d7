"""From a desired shot (absolute direction, speed) to the environment's action, and back.

Both ways are the decision process's own codec: :func:`shot_to_action` is
:func:`pool_env.game.codec.encode_shots` (what :func:`pool_env.encode_action` writes, for one
shot or many), :func:`decode` is :func:`pool_env.decode_shots`. A direction outside what the
aim mode can express (outside the relative cone, or turned away from the nearest ball in
``cut`` mode) is *not representable* and gives ``None``. Speeds are clipped to the range: a
planner that wants more than the maximum gets the maximum, and its simulation says whether
that is enough.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from agents.baselines.base import EnvSpec
from pool_env.game.codec import encode_shots
from pool_env.game.formulas import decode_on_layout


def shot_to_action(
    angle: float,
    speed: float,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    spec: EnvSpec,
    tip: tuple[float, float] = (0.0, 0.0),
) -> NDArray[np.float32] | None:
    """The float32 action for a shot, or ``None`` when the aim mode cannot express its direction.

    Args:
        angle: Shot direction (radians from +x).
        speed: Cue speed (m/s); clipped to the speed range.
        positions: ``(N, 2)`` ball centres, cue first.
        on_table: ``(N,)`` the balls the aim may refer to (on the table; rules: legal).
        spec: The environment (its config's codec).
        tip: The cue tip's offset ``(side, vertical)`` in fractions of R, within the tip
            limit (a spin env; centre ball by default).

    Returns:
        A float32 action in ``[-1, 1]``: ``(aim, speed)``, and ``(side, vertical)`` on a
        spin env; or ``None``.
    """
    tips = [[tip]] if spec.spin else None
    actions, playable = encode_shots(
        spec.config, positions[None], on_table[None], [[angle]], [[speed]], tips
    )
    if not playable[0, 0]:
        return None
    return actions[0, 0].astype(np.float32)


def decode(
    actions: NDArray[np.floating],
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    spec: EnvSpec,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """What the environment executes for ``(B, 2)`` actions on one layout: ``(angles, speeds)``.

    The environment's own decoding (:func:`pool_env.game.formulas.decode_on_layout`), so
    that a planner simulates exactly the shot its action will play (before execution noise).
    """
    return decode_on_layout(spec.config, actions, positions, on_table)
