"""Tests of the simulator layer (``pool_env.sim``)."""
