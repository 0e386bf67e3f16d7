"""pool_env: an exact, analytic, event-based pool table simulator and Gymnasium environment."""

from pool_env.env import PoolEnv
from pool_env.registration import register_envs
from pool_env.sim import Event, ShotResult, Table, shoot, simulate

register_envs()

__all__ = ["Event", "PoolEnv", "ShotResult", "Table", "register_envs", "shoot", "simulate"]
__version__ = "0.1.0"
