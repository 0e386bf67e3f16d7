"""Deprecated alias of :mod:`pool_env.envs.env` (see :mod:`pool_env._moved`)."""

from pool_env._moved import alias

alias(__name__, "pool_env.envs.env")
