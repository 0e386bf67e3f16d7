"""Tests of the fronts (pool_env/envs, pool_env/render): Gymnasium and PettingZoo APIs."""
