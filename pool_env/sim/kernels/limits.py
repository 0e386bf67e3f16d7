"""The simulator's numeric limits: the scales within which its results are exact to rounding.

Every entry point enforces them with a ``ValueError`` naming the limit (``Table``,
``simulate``, ``shoot``, ``simulate_batch``); the compiled validation reads them from here,
so that a change of a limit changes the compile-cache tag. Why these values:

* Lengths (table length and width, ball radius) in ``[MIN_LENGTH, MAX_LENGTH]``: the
  contact and validation tolerances are 1e-9 m, at most 1e-5 of the smallest radius;
  positions are rounded to ~2e-16 of the largest coordinate, 2e-12 m at 1e4 m.
* Speeds up to ``MAX_SPEED``: the rounding left in a speed by an impact (~2e-16 of
  it) stays far below the rest threshold ``V_REST`` = 1e-9 m/s; and no square of a speed
  overflows.
* The free rolling distance ``v^2 / (2 mu_roll g)`` of a ball at speed ``v`` up to
  ``MAX_ROLL``: a position's rounding grows with the distance rolled (~2e-16 of it, from
  the anchors and the event times), 1.5e-11 m at 9e4 m, and stays below 1e-9 m there.
* Both bounds hold for every speed a ball can reach during the shot, not only the initial
  ones (:func:`reachable_speed2`). Impacts can speed a light ball far beyond every initial
  speed (one rattling between a heavy ball and a rail gains twice the heavy ball's speed
  at each bounce); kinetic energy never grows (restitutions are at most 1, rolling
  resistance and sticking lumps only take energy away), so ``m_i v_i^2`` stays below the
  initial ``sum_k m_k v_k^2``. A scene whose energy could drive its lightest ball past the
  limits is refused: unbounded, such a ball reached 14 km/s on a km-scale elastic table
  and its position's rounding (speed x ulp(t)) put it 1.2e-9 m past a rail.
* On the spin level the energy counts the spin too: ``T = sum_k m_k (v_k^2 + (2/5) R^2
  |w_k|^2) / 2`` (a solid ball, ``I = (2/5) m R^2``). Spin turns into speed: the cloth's
  friction on a sliding ball (draw, follow, a stun ball's backspin), the throw of a
  ball-ball impact, a cushion's friction on english. None of them adds energy: the cloth's
  friction works at ``-mu m g |u| <= 0`` (the slip ``u`` is the contact point's velocity),
  impacts have restitutions at most 1 and friction capped at the no-slip result, the
  pressed-cushion rule conserves angular momentum about the cloth contact and only takes
  energy away. So ``m_i v_i^2 <= 2 T`` bounds every translational speed of the shot
  (:func:`reachable_speed2_spin`). Translation alone is not enough: a still ball with
  backspin of surface speed ``s`` rolls away at ``(2/7) s``, beyond any initial speed (0),
  and a spinning ball can pass its spin to a light one. The bound is the energy one; the
  cloth alone gets a single ball only to ``(5 |v| + 2 s) / 7`` (angular momentum about
  the contact point), but impacts can do better, so no tighter bound holds for every shot.
* The rolling deceleration ``mu_roll g`` in ``[MIN_DECELERATION, MAX_DECELERATION]``: event
  times stay within ~1e6 s, resolved far finer than the Zeno window of 1e-6 s.
* Masses in ``[MIN_MASS, MAX_MASS]``: momenta and energies never overflow or underflow.
"""

from __future__ import annotations

from pool_env.sim.jit import kernel

MIN_LENGTH = 1e-4  # m
MAX_LENGTH = 1e4  # m
MAX_SPEED = 1e3  # m/s
MAX_ROLL = 1e6  # m
MIN_DECELERATION = 1e-6  # m/s^2
MAX_DECELERATION = 1e6  # m/s^2
MIN_MASS = 1e-12  # kg
MAX_MASS = 1e12  # kg
#: ``I / (m R^2)`` of a solid ball: a ball's rotational energy is ``(2/5) m R^2 |w|^2 / 2``.
SOLID_INERTIA = 0.4
#: The event cap is an int64 in the compiled loop.
MAX_EVENTS_LIMIT = 2**63 - 1


@kernel
def speed_allowed(speed2, deceleration):
    """Whether a ball at squared speed ``speed2`` lies within ``MAX_SPEED`` and ``MAX_ROLL``.

    The one test of the speed limits, for the compiled validation and for Python alike.
    """
    return speed2 <= MAX_SPEED * MAX_SPEED and speed2 <= 2.0 * deceleration * MAX_ROLL


@kernel
def reachable_speed2(velocities, masses):
    """The squared speed impacts could give the lightest ball, and that ball.

    Kinetic energy never grows during a shot, so ball ``i`` stays below
    ``sqrt(sum_k m_k v_k^2 / m_i)``; the lightest ball's bound is the largest. Each term is
    ``(m_k / m_min) v_k^2``, so that with one ball moving, or equal masses, the bound is
    exactly the initial squared speed (a single shot is judged as before, to the bit).

    Args:
        velocities: ``(N, 2)`` initial velocities (finite).
        masses: ``(N,)`` masses (within the limits), or empty: every ball weighs the same.

    Returns:
        ``(speed2, i)``: the bound on any ball's squared speed and the lightest ball ``i``.
    """
    n = velocities.shape[0]
    weighed = masses.shape[0] > 0
    lightest = 0
    if weighed:
        for i in range(1, n):
            if masses[i] < masses[lightest]:
                lightest = i
    total = 0.0
    for k in range(n):
        v2 = velocities[k, 0] * velocities[k, 0] + velocities[k, 1] * velocities[k, 1]
        total += (masses[k] / masses[lightest]) * v2 if weighed else v2
    return total, lightest


@kernel
def reachable_speed2_spin(velocities, angular, masses, radius):
    """:func:`reachable_speed2` counting the spin's energy too (the spin level).

    ``sum_k (m_k / m_min) (v_k^2 + (2/5) R^2 |w_k|^2)``: twice the kinetic energy over the
    lightest mass, which no translational speed of the shot can pass (the module
    docstring). Without spin it is :func:`reachable_speed2`'s bound, to the bit.

    Args:
        velocities: ``(N, 2)`` initial velocities (finite).
        angular: ``(N, 3)`` initial angular velocities (finite).
        masses: ``(N,)`` masses (within the limits), or empty: every ball weighs the same.
        radius: The ball radius ``R``.

    Returns:
        ``(speed2, i)``: the bound on any ball's squared speed and the lightest ball ``i``.
    """
    total, lightest = reachable_speed2(velocities, masses)
    weighed = masses.shape[0] > 0
    arm2 = SOLID_INERTIA * radius * radius
    for k in range(angular.shape[0]):
        w2 = angular[k, 0] * angular[k, 0] + angular[k, 1] * angular[k, 1]
        w2 += angular[k, 2] * angular[k, 2]
        total += (masses[k] / masses[lightest]) * arm2 * w2 if weighed else arm2 * w2
    return total, lightest
