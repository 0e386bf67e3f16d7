"""pool_env: an exact, analytic, event-based pool table simulator and Gymnasium environment."""

from pool_env.result import Event, ShotResult
from pool_env.simulate import shoot, simulate
from pool_env.table import Table

__all__ = ["Event", "ShotResult", "Table", "shoot", "simulate"]
__version__ = "0.1.0"
