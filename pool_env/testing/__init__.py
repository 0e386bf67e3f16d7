"""Helpers for tests and benchmarks: random legal scenes and the named invariant checks.

Not part of the environment API; shipped so that ``bench/`` and downstream tests can use them.
"""
