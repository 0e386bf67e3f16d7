"""Bridges to other simulators: a scene and a shot in their terms, both ways.

Each module imports its simulator only when one of its functions needs it, so importing
:mod:`pool_env.interop` (or building the API reference) needs none of them. Today:
:mod:`pool_env.interop.pooltool` (pooltool 0.6.0's ``System``).
"""
