"""Tests of the simulator (pool_env/sim, pool_env/interop).

Physics, references, hard cases, the compile cache.
"""
