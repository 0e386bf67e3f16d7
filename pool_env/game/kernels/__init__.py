"""Compiled kernels of the decision process: actions, layouts, settling, observations, rng."""
