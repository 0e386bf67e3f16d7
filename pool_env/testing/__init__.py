"""Helpers for tests and benchmarks: random scenes, invariant checks, 50-digit references.

:mod:`.reference` (rolling balls) and :mod:`.spin_reference` (the spin level) are the
independent mpmath simulators the compiled kernels are compared with (they need ``mpmath``,
in the ``bench`` and ``dev`` extras).

Not part of the environment API; shipped so that ``bench/`` and downstream tests can use them.
"""
