"""Execution noise by name: FastFiz's model, the computer billiards championships' standard.

The ``noise`` key takes sigmas ``(angle rad, speed m/s[, tip in R])``, or a named model:
``"fastfiz"`` (its sigmas) or ``("fastfiz", k)`` (its sigmas times ``k >= 0``; ``k = 0`` is
no noise). FastFiz (with its predecessor PoolFiz: Leckie and Greenspan, "An event-based
pool physics simulator", 2006), the engine of the computational pool tournaments of the
Computer Olympiad (2005-2008) and of the 2011 computer billiards championship, perturbs the
cue's five shot parameters with independent Gaussians (``FastFiz-0.2/FastFiz/Noise.h`` in
its sources):

========================= ============== ==============================================
FastFiz parameter         sigma          here
========================= ============== ==============================================
phi (aim)                 0.125 degrees  the angle's sigma, in radians
theta (cue elevation)     0.1 degrees    none: the env's cue is level (no elevation)
V (cue speed)             0.075 m/s      the speed's sigma
a, b (tip offsets)        0.5 mm each    each tip component's sigma, in fractions of R
========================= ============== ==============================================

The 2011 championship (BCA 8-ball) ran it at x1 ("low noise") and x5 ("high noise"), and at
a variable level between x0 and x5. The Olympiad winners, CueCard and PickPocket, searched
over sampled shots valued by simulating under the noise model (Archibald, Altman and
Shoham, "Analysis of a winning computational billiards player", IJCAI 2009). CueTip
(arXiv 2501.18291, 2025), an LLM pool coach on pooltool, copies the x1 model as its
baseline. ``docs/sources.md`` lists these sources.

How it maps onto the env's action:

* The env's action has no cue elevation (the cue is level, ``docs/environments/specification.md``),
  so theta's sigma has nothing to perturb and is dropped.
* The tip offsets are the env's in fractions of the ball radius ``R``: 0.5 mm is
  ``0.0005 / R`` (0.0175 for the default 28.575 mm ball). A roll table has no cue tip, so
  its ``"fastfiz"`` is the aim and speed sigmas alone (a numeric tuple with a non-zero tip
  sigma is refused there instead: a number given for a tip that does not exist is a mistake,
  a named model describes a cue whatever the table).
* As every sigma here, the draws are the env's: the executed speed is clipped at 0 and the
  executed tip onto the miscue circle (:mod:`pool_env.game.kernels.actions`).

The largest scale that means something, for any sigmas (numbers or a model times ``k``):

* The speed's: the executed speed is the action's plus ``sigma_speed`` times a standard
  normal draw, and the simulator refuses a strike beyond its speed limits
  (:class:`pool_env.game.checks.SpeedCeiling`). The draws are bounded: numpy's ziggurat
  sampler, which the kernels run (:func:`pool_env.game.kernels.rng.standard_normal`),
  returns at most :data:`MAX_NORMAL_DRAW` in size, so a config is refused when its top
  speed plus that many sigmas could pass the limit, and no step can then fail on it.
* The angle's: at most :data:`MAX_SIGMA_ANGLE` (pi). Beyond it the executed direction is
  uniform over the circle to within 1.4% (a wrapped Gaussian's density varies by
  ``2 exp(-sigma^2 / 2)``): the aim no longer means anything. For FastFiz's model that is
  ``k <= 1440``; its speed sigma reaches the speed limit first (``k`` of a few hundred on
  the default table: the message of a refusal gives the figure).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from pool_env.sim.table import Table

#: What the ``noise`` key takes besides ``None``: the sigmas, or a model by name (``"fastfiz"``)
#: or with a multiple (``("fastfiz", 5.0)``).
NoiseSpec = tuple[float, ...] | str | tuple[str, float]

#: FastFiz's sigma on the aim phi (degrees).
FASTFIZ_AIM_DEG = 0.125

#: FastFiz's sigma on the cue elevation theta (degrees): no elevation here, so not applied.
FASTFIZ_ELEVATION_DEG = 0.1

#: FastFiz's sigma on the cue speed V (m/s).
FASTFIZ_SPEED = 0.075

#: FastFiz's sigma on each cue tip offset a and b (m).
FASTFIZ_TIP = 0.0005

#: The multiples of the model the championships ran (x1 "low", x5 "high").
FASTFIZ_LEVELS: tuple[float, ...] = (1.0, 5.0)

#: The largest standard normal draw, in size, of numpy's ziggurat sampler (the kernels' own
#: copy, :func:`pool_env.game.kernels.rng.standard_normal`): 12.2258, rounded up. A draw
#: is either inside the ziggurat, below its base strip's edge ``r = 3.6542``, or in the
#: tail, ``r + x`` with ``x = -log(1 - u1) / r`` accepted only if ``x^2 < -2 log(1 - u2)``;
#: ``u2`` is a double below 1, at most ``1 - 2^-53``, so ``x < sqrt(2 * 53 ln 2) = 8.5717``.
MAX_NORMAL_DRAW = 12.23

#: The largest angle sigma (rad) that still means an aim error (the module docstring).
MAX_SIGMA_ANGLE = math.pi


def fastfiz_sigmas(table: Table, multiple: float = 1.0) -> tuple[float, ...]:
    """FastFiz's sigmas times ``multiple`` in the env's units, for ``table``.

    Args:
        table: The table: its ball radius sets the tip's sigma, its model whether there is one.
        multiple: The noise level (1: the championships' "low", 5: their "high"); ``>= 0``,
            checked by the caller (:func:`pool_env.game.checks.parse_noise`).

    Returns:
        ``(angle rad, speed m/s, tip in R)`` on a spin table, ``(angle, speed)`` on a roll
        table (no cue tip).

    Examples:
        >>> from pool_env import Table
        >>> [round(s, 5) for s in fastfiz_sigmas(Table(model="spin"))]
        [0.00218, 0.075, 0.0175]
        >>> [round(s, 4) for s in fastfiz_sigmas(Table(model="roll"), 5)]
        [0.0109, 0.375]
    """
    angle = math.radians(FASTFIZ_AIM_DEG) * multiple
    speed = FASTFIZ_SPEED * multiple
    if not table.has_spin:
        return (angle, speed)
    return (angle, speed, FASTFIZ_TIP / table.ball_radius * multiple)


#: The noise models the ``noise`` key takes by name: each gives its sigmas for a table and
#: a multiple.
NOISE_MODELS: dict[str, Callable[[Table, float], tuple[float, ...]]] = {
    "fastfiz": fastfiz_sigmas,
}
