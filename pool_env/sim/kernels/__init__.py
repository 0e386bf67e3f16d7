"""Compiled kernels (through :mod:`pool_env.sim.jit`): arrays and scalars in and out."""
