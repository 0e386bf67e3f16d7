"""pool_env: an exact, analytic, event-based pool table simulator and Gymnasium environment.

Layers, imports pointing down only: :mod:`pool_env.sim` (the simulator), :mod:`pool_env.game`
(the decision process over B tables), and the Gymnasium fronts (:class:`PoolEnv`,
:class:`PoolVectorEnv`, registration, rendering). This module is the public API.
"""

from pool_env._version import __version__
from pool_env.env import PoolEnv
from pool_env.game.config import AIM_MODES, DEFAULT_AIM_RANGE, DEFAULT_SPEED_RANGE, GameConfig
from pool_env.game.kernels.actions import decode_shots, nearest_object_ball
from pool_env.game.kernels.observe import encode_observations
from pool_env.game.scenes import SCENES, check_layout, free_spot
from pool_env.registration import ENV_IDS, register_envs
from pool_env.sim import Event, ShotResult, Table, shoot, simulate
from pool_env.vector import PoolVectorEnv

register_envs()

__all__ = [
    "AIM_MODES",
    "DEFAULT_AIM_RANGE",
    "DEFAULT_SPEED_RANGE",
    "ENV_IDS",
    "SCENES",
    "Event",
    "GameConfig",
    "PoolEnv",
    "PoolVectorEnv",
    "ShotResult",
    "Table",
    "__version__",
    "check_layout",
    "decode_shots",
    "encode_observations",
    "free_spot",
    "nearest_object_ball",
    "register_envs",
    "shoot",
    "simulate",
]
