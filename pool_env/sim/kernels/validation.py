"""Validation of a scene (compiled): the one check every entry point runs before a shot.

:func:`validate` names the first problem of a scene as a code and the balls (or the pocket)
involved; Python turns the code into its ``ValueError``
(:func:`~pool_env.sim.inputs.raise_invalid`). The codes are shared by the single shot, the
batches and the spin level (whose two codes, ``BAD_SPIN`` and ``SPIN_TOO_FAST``, are
listed here too: one enumeration), so one code never means two things.
"""

from __future__ import annotations

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.jaw_geometry import LOC_CIRCLE, LOC_FALL, LOC_FREE, locate
from pool_env.sim.kernels.limits import MAX_MASS, MIN_MASS, reachable_speed2, speed_allowed
from pool_env.sim.kernels.params import P_DECEL, P_RADIUS

# Tolerance of input validation: rounding in a rack or a position read back from a result
# may leave a ball a hair over a rail or another ball.
POS_TOL = 1e-9

# Validation codes.
OK, BAD_POSITION, BAD_VELOCITY, BAD_MASS, OFF_TABLE, OVERLAP, IN_POCKET, TOO_FAST = range(8)
IN_JAW, BEHIND_LINE, TOO_ENERGETIC = 8, 9, 10
#: The spin level's: a non-finite angular velocity, a surface speed ``R |w|`` beyond
#: ``limits.MAX_SPEED`` (:func:`pool_env.sim.kernels.spin.level.validate_spins`).
BAD_SPIN, SPIN_TOO_FAST = 11, 12


@kernel
def validate(positions, velocities, masses, params, pockets):
    """Check a scene; return ``(code, i, j)`` naming the first problem (``OK`` if none)."""
    radius = params[P_RADIUS]
    n = positions.shape[0]
    for i in range(n):
        if not (np.isfinite(positions[i, 0]) and np.isfinite(positions[i, 1])):
            return BAD_POSITION, i, -1
        if not (np.isfinite(velocities[i, 0]) and np.isfinite(velocities[i, 1])):
            return BAD_VELOCITY, i, -1
        speed2 = velocities[i, 0] * velocities[i, 0] + velocities[i, 1] * velocities[i, 1]
        if not speed_allowed(speed2, params[P_DECEL]):
            return TOO_FAST, i, -1
        if masses.shape[0] and not (MIN_MASS <= masses[i] <= MAX_MASS):  # also NaN
            return BAD_MASS, i, -1
    reach2, lightest = reachable_speed2(velocities, masses)  # speeds impacts can produce
    if not speed_allowed(reach2, params[P_DECEL]):
        return TOO_ENERGETIC, lightest, -1
    for i in range(n):
        where, k = locate(positions[i, 0], positions[i, 1], params, pockets, POS_TOL)
        if where != LOC_FREE:
            if where == LOC_CIRCLE:
                return IN_POCKET, i, k
            if where == LOC_FALL:
                return BEHIND_LINE, i, k
            if k >= 0:
                return IN_JAW, i, k
            return OFF_TABLE, i, -1
    min_d2 = (2.0 * radius - POS_TOL) ** 2
    for i in range(n):
        for j in range(i + 1, n):
            dx = positions[j, 0] - positions[i, 0]
            dy = positions[j, 1] - positions[i, 1]
            if dx * dx + dy * dy < min_d2:
                return OVERLAP, i, j
    return OK, -1, -1
