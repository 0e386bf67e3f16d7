"""The simulator's numeric limits: the scales within which its results are exact to rounding.

Every entry point enforces them with a ``ValueError`` naming the limit (``Table``,
``simulate``, ``shoot``, ``simulate_batch``); the compiled validation reads them from here,
so that a change of a limit changes the compile-cache tag. Why these values:

* Lengths (table length and width, ball radius) in ``[MIN_LENGTH, MAX_LENGTH]``: the
  contact and validation tolerances are 1e-9 m, at most 1e-5 of the smallest radius;
  positions are rounded to ~2e-16 of the largest coordinate, 2e-12 m at 1e4 m.
* Initial speeds up to ``MAX_SPEED``: the rounding left in a speed by an impact (~2e-16 of
  it) stays far below the rest threshold ``V_REST`` = 1e-9 m/s; and no square of a speed
  overflows.
* The free rolling distance ``v^2 / (2 mu_roll g)`` of each ball at its initial speed up to
  ``MAX_ROLL``: a position's rounding grows with the distance rolled (~2e-16 of it, from
  the anchors and the event times), 1.5e-11 m at 9e4 m, and stays below 1e-9 m there.
* The rolling deceleration ``mu_roll g`` in ``[MIN_DECELERATION, MAX_DECELERATION]``: event
  times stay within ~1e6 s, resolved far finer than the Zeno window of 1e-6 s.
* Masses in ``[MIN_MASS, MAX_MASS]``: momenta and energies never overflow or underflow.
"""

from __future__ import annotations

from pool_env.sim.kernels._jit import kernel

MIN_LENGTH = 1e-4  # m
MAX_LENGTH = 1e4  # m
MAX_SPEED = 1e3  # m/s
MAX_ROLL = 1e6  # m
MIN_DECELERATION = 1e-6  # m/s^2
MAX_DECELERATION = 1e6  # m/s^2
MIN_MASS = 1e-12  # kg
MAX_MASS = 1e12  # kg
#: The event cap is an int64 in the compiled loop.
MAX_EVENTS_LIMIT = 2**63 - 1


@kernel
def speed_allowed(speed2, deceleration):
    """Whether a ball at squared speed ``speed2`` lies within ``MAX_SPEED`` and ``MAX_ROLL``.

    The one test of the speed limits, for the compiled validation and for Python alike.
    """
    return speed2 <= MAX_SPEED * MAX_SPEED and speed2 <= 2.0 * deceleration * MAX_ROLL
