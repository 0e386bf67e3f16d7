"""The table simulator: tables, layouts, exact shots and batches of them.

This layer knows nothing of Gymnasium: arrays and a frozen :class:`Table` in, a
:class:`ShotResult` (or batched arrays) out. Its compiled code lives in :mod:`.kernels`.
"""

from pool_env.sim.batch import simulate_batch, simulate_batch_threads
from pool_env.sim.cue import from_pooltool
from pool_env.sim.kernels.spin.state import STATE_NAMES
from pool_env.sim.result import Event, ShotResult, SpinShotResult
from pool_env.sim.rollout import rollout
from pool_env.sim.simulate import check_positions, shoot, simulate
from pool_env.sim.table import Table

__all__ = [
    "STATE_NAMES",
    "Event",
    "ShotResult",
    "SpinShotResult",
    "Table",
    "check_positions",
    "from_pooltool",
    "rollout",
    "shoot",
    "simulate",
    "simulate_batch",
    "simulate_batch_threads",
]
