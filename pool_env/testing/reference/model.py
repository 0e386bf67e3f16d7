"""The reference's numbers, types, error and 2-D vector arithmetic, shared by its modules."""

from __future__ import annotations

from mpmath import mpf

#: Working precision in significant decimal digits.
DPS = 50

#: Candidate events closer than this (in seconds) are simultaneous in the ideal model.
#: 50-digit rounding separates true ties by ~1e-48 s; distinct events in the hard cases are
#: at least 1e-15 s apart, so 1e-30 s sits safely between the two.
TIE_TOLERANCE = "1e-30"

#: Initial overlaps and rail violations up to this many metres are accepted (float inputs
#: built as ``x + 2R`` can overlap by ~1e-17 m); the contact rule then resolves them.
INPUT_TOLERANCE = 1e-9

#: Processing order of event kinds at equal times.
KIND_ORDER: dict[str, int] = {
    "pocket": 0,
    "ball": 1,
    "cushion": 2,
    "stop": 3,
    "jaw": 4,
    "point": 5,
}

Vec = tuple[mpf, mpf]
Event = tuple[mpf, str, int, int]


class ReferenceSimulationError(RuntimeError):
    """The scene leaves what the reference can resolve (event cap, sustained contact)."""


def dot(p: Vec, q: Vec) -> mpf:
    """Return the dot product ``p . q``."""
    return p[0] * q[0] + p[1] * q[1]


def sub(p: Vec, q: Vec) -> Vec:
    """Return ``p - q``."""
    return (p[0] - q[0], p[1] - q[1])


def axpy(alpha: mpf, u: Vec, p: Vec) -> Vec:
    """Return ``p + alpha * u``."""
    return (p[0] + alpha * u[0], p[1] + alpha * u[1])
