"""Independent 50-digit reference simulator for the pool table model (a test oracle).

This package re-implements the physics of ``docs/physics.md`` from scratch in ``mpmath`` at
50 significant digits. It deliberately shares no code with the simulator kernels in
``pool_env/sim/kernels``: it only reads the attributes of a ``pool_env.sim.table.Table`` (and
imports that class for type checking only), so a bug in a float64 kernel cannot hide in both
implementations at once.

Model (SI units):

* A ball centre lives in ``[R, L-R] x [R, W-R]``. A moving ball decelerates at
  ``a = mu_roll * g`` against its velocity along a straight segment,
  ``p(t) = p0 + u (v0 t - a t^2 / 2)``, until ``t_stop = v0 / a``; it never reverses.
* Ball-ball impact when ``|pb - pa| = 2R`` while approaching; tangential components are kept
  and the normal components follow momentum conservation with restitution ``e_ball``.
* Cushions: the rails are the centre lines ``x = R`` (0), ``x = L-R`` (1), ``y = R`` (2),
  ``y = W-R`` (3); only a ball moving into a rail bounces, ``v_n -> -e_cushion v_n``.
* Pockets: capture circles; a ball is potted where its centre enters the circle.
* Jaw tables (``table.jaws`` not empty): the rails are the finite segments
  ``table.rails``; each pocket has two straight facings (``"jaw"`` events, ``j = 2 k +
  side``) and two round points (``"point"``), and a fall line. A ball touches a segment
  (rail or facing) when its centre is ``R`` from the segment's line on the table side with
  the foot of the perpendicular inside the segment, and a point when its centre is
  ``R + tip_radius`` from the tip centre; both reflect the normal component (the
  segment's normal, or the line from the tip centre) with ``e_cushion`` (rails) or
  ``e_jaw``. A ball is potted (``"pocket"``) when its centre reaches the fall line (the
  segment across the throat between the two facings). Every
  piece is checked for every ball (no culling): these are read from the table's
  documented geometry (points, rail ends, tip centres, facings, fall lines) and offset by
  ``R`` here, at 50 digits.

Departures from the classic formulas as printed (``docs/physics.md``, "Three mistakes in
the classic formulas"):

* The seed's restitution term has the wrong sign (``- m_b e (v_ib - v_ia)``); with that sign
  and ``e = 1``, equal masses pass through each other. The impact law (:mod:`.simulator`) uses
  ``+ m_b e (u_b - u_a)`` so that the separation speed is ``e`` times the approach speed.
* The seed rotates back with ``sin(phi + 90)`` and ``cos(phi + 90)`` swapped. We never rotate
  at all: the impulse is applied along the unit line of centres ``n``, which is the same
  physics without the trigonometry.
* The seed's ``theta = atan(vy / vx)`` loses the quadrant; we carry unit vectors instead.

Numerics (why this is an oracle and not another kernel):

* Every input float is converted exactly (``mpf(float)`` is exact) and all arithmetic runs
  at 50 digits inside ``mp.workdps(50)``, so rounding is ~1e-50 relative, 35 orders below
  float64.
* Ball-cushion and ball-pocket events are solved in closed form in the arc length ``s`` of
  the straight path; ``t`` follows from ``t = 2 s / (v + sqrt(v^2 - 2 a s))``, which has no
  cancellation.
* A pair with one ball resting is a quadratic in the arc length of the moving ball, solved
  in the cancellation-free form ``s = c / (-b + sqrt(b^2 - c))``.
* A pair with both balls moving is a quartic in time. Its real roots are *isolated* rather
  than computed as complex roots: the critical points of a polynomial are the sign changes
  of its derivative, found recursively (quartic -> cubic -> quadratic -> linear), so the
  window splits into pieces on which the gap is monotone; the first piece on which the gap
  decreases to zero holds the event, which is then refined by bracketed, safeguarded Newton
  iteration. No step divides by a leading coefficient, so the degree drops (equal
  directions, equal velocities) need no special case.
* Each pair is predicted only up to the earlier stop of its two balls. Stops are events;
  after every event everything is re-predicted, so the second phase of a pair (one ball at
  rest) is handled by the one-ball-resting quadratic after the stop event.
* Contact rule: a touching or overlapping state that is approaching (a rail, a ball or a
  pocket circle) is an event *now*; a separating one is no event. A touch with zero
  approach speed (exact tangency, reaching a rail exactly as the ball stops) is not an
  impact.
* Events are ordered by ``(time, kind, i, j)`` with ``pocket < ball < cushion < stop``.
  Exact ties of the ideal model show up at 50 digits as times ~1e-48 s apart, so candidates
  within :data:`TIE_TOLERANCE` (1e-30 s) of the earliest are treated as simultaneous and
  ordered by ``(kind, i, j)``; such choices are listed in ``ReferenceResult.near_ties`` so
  a test can see them rather than have them happen silently.

Choices where the model leaves room (a kernel may differ here; compare with care):

* A ball brought exactly to rest by an event (a head-on exchange with ``e = 1``, a square
  hit on a rail with ``e_cushion = 0``) has no separate ``"stop"`` event.
* The corner capture circles reach the rail corners, so a ball may *start* inside one. It
  is potted at once if it moves towards the pocket centre (the contact rule), never if it
  rests there or moves outwards until it re-enters.
* Zeno cascades (a ball pressed against a rail with ``e_cushion = 0``, touching chains)
  are not regularised: the events pile up at one instant until ``max_events`` raises
  :class:`ReferenceSimulationError`. The reference is meant for scenes with a few impacts.

The reference is a test oracle: it is O(N^2) per event and slow, but a 3-ball, 3-collision
scene takes ~10 ms.

The modules, one concern each: :mod:`.model` (numbers, types, vectors), :mod:`.roots` (exact
event roots), :mod:`.pieces` (a ball's trajectory between events), :mod:`.jaw_cushions` (a jaw
table's cushion pieces), :mod:`.simulator` (the event loop and the impact laws),
:mod:`.result` (:class:`ReferenceResult`) and :mod:`.simulate` (:func:`reference_simulate`,
the entry point).
"""

from pool_env.testing.reference.model import (
    DPS,
    INPUT_TOLERANCE,
    KIND_ORDER,
    TIE_TOLERANCE,
    ReferenceSimulationError,
)
from pool_env.testing.reference.result import ReferenceResult
from pool_env.testing.reference.simulate import reference_simulate

__all__ = [
    "DPS",
    "INPUT_TOLERANCE",
    "KIND_ORDER",
    "TIE_TOLERANCE",
    "ReferenceResult",
    "ReferenceSimulationError",
    "reference_simulate",
]
