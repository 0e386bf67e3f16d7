"""Compiled kernels: arrays and scalars in, arrays and scalars out; no package imports."""
