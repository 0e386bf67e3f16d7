"""A hook that counts the simulator's root solves, for a benchmark of how many it makes.

The predictors of both model levels find the times of ball-ball impacts, captures and jaw
points with two solvers of :mod:`pool_env.sim.kernels.roots`: the bracketed quartic
(``first_contact``) and the quadratic of a pair with equal accelerations
(``equal_accel_contact``). :func:`install` wraps each where the predictors call it, so that
every solve adds to a counter: ``"quartic"`` and ``"quadratic"`` per call, and
``"quartic found"`` and ``"quadratic found"`` when the solve returns a time inside its
window (a candidate event).

The wrapping only takes effect with the kernels interpreted: set ``NUMBA_DISABLE_JIT=1``
before numba is first imported (``bench/prediction_count.py`` does), so that the predictors
are Python functions that look the solvers up in their module's namespace. The arithmetic
is the same. It stays installed for the life of the process.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable
from typing import Any

from pool_env.sim.kernels import roots
from pool_env.sim.kernels.roll import predict as roll_predict
from pool_env.sim.kernels.spin import jaw_events as spin_jaw_events
from pool_env.sim.kernels.spin import predict as spin_predict

__all__ = ["install"]


def _counting(
    counts: Counter[str], name: str, solver: Callable[..., float]
) -> Callable[..., float]:
    def wrapped(*args: Any) -> float:
        tau = solver(*args)
        counts[name] += 1
        counts[name + " found"] += tau < roots.INF
        return tau

    return wrapped


def install(counts: Counter[str]) -> None:
    """Wrap the solvers where the predictors call them, counting into ``counts``.

    Args:
        counts: The counter every solve adds to (cleared by the caller between measurements).
    """
    quartic = _counting(counts, "quartic", roots.first_contact)
    quadratic = _counting(counts, "quadratic", roots.equal_accel_contact)
    roll_predict.first_contact = quartic
    roll_predict.equal_accel_contact = quadratic
    spin_predict.first_contact = quartic
    spin_predict.equal_accel_contact = quadratic
    spin_jaw_events.first_contact = quartic
