"""pool_env: an exact, analytic, event-based pool table simulator and Gymnasium environment.

Layers, imports pointing down only: :mod:`pool_env.sim` (the simulator), :mod:`pool_env.game`
(the decision process over B tables), and the Gymnasium fronts (:class:`PoolEnv`,
:class:`PoolVectorEnv`, registration, rendering). This module is the public API.

Importing it loads the simulator only: the decision process and the fronts load (and with
them Gymnasium) on first use of one of their names, so ``import pool_env.sim`` needs no
Gymnasium. The ids are registered with Gymnasium all the same, whichever of the two is
imported first (:func:`pool_env.envs.registration.register_on_gymnasium_import`).
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

from pool_env._version import __version__
from pool_env.envs.registration import ENV_IDS, register_envs, register_on_gymnasium_import
from pool_env.sim import Event, ShotResult, Table, shoot, simulate

if TYPE_CHECKING:  # the names below are imported on first use, by __getattr__
    from pool_env.envs.env import PoolEnv
    from pool_env.envs.vector import PoolVectorEnv
    from pool_env.game.codec import (
        decode_action,
        decode_observations,
        encode_action,
        encode_shots,
        obs_layout,
        shot_constraints,
    )
    from pool_env.game.config import (
        AIM_MODES,
        DEFAULT_AIM_RANGE,
        DEFAULT_SPEED_RANGE,
        GameConfig,
    )
    from pool_env.game.kernels.actions import decode_shots, nearest_object_ball
    from pool_env.game.kernels.observe import encode_observations
    from pool_env.game.kernels.tips import onto_tip_circle
    from pool_env.game.scenes import SCENES, check_layout
    from pool_env.game.sections import PoolConfig, default_config
    from pool_env.game.shots import Shot, ShotConstraints
    from pool_env.game.spots import free_spot

#: Public names of the game layer and the fronts -> the module defining each.
_LAZY: dict[str, str] = {
    "AIM_MODES": "pool_env.game.config",
    "DEFAULT_AIM_RANGE": "pool_env.game.config",
    "DEFAULT_SPEED_RANGE": "pool_env.game.config",
    "GameConfig": "pool_env.game.config",
    "PoolConfig": "pool_env.game.sections",
    "PoolEnv": "pool_env.envs.env",
    "PoolVectorEnv": "pool_env.envs.vector",
    "SCENES": "pool_env.game.scenes",
    "Shot": "pool_env.game.shots",
    "ShotConstraints": "pool_env.game.shots",
    "obs_layout": "pool_env.game.codec",
    "shot_constraints": "pool_env.game.codec",
    "decode_action": "pool_env.game.codec",
    "default_config": "pool_env.game.sections",
    "decode_observations": "pool_env.game.codec",
    "encode_action": "pool_env.game.codec",
    "encode_shots": "pool_env.game.codec",
    "check_layout": "pool_env.game.scenes",
    "decode_shots": "pool_env.game.kernels.actions",
    "encode_observations": "pool_env.game.kernels.observe",
    "free_spot": "pool_env.game.spots",
    "nearest_object_ball": "pool_env.game.kernels.actions",
    "onto_tip_circle": "pool_env.game.kernels.tips",
}

__all__ = [
    "AIM_MODES",
    "DEFAULT_AIM_RANGE",
    "DEFAULT_SPEED_RANGE",
    "ENV_IDS",
    "SCENES",
    "Event",
    "GameConfig",
    "PoolConfig",
    "PoolEnv",
    "PoolVectorEnv",
    "Shot",
    "ShotConstraints",
    "ShotResult",
    "Table",
    "__version__",
    "check_layout",
    "decode_action",
    "decode_observations",
    "decode_shots",
    "default_config",
    "encode_action",
    "encode_observations",
    "encode_shots",
    "free_spot",
    "nearest_object_ball",
    "obs_layout",
    "onto_tip_circle",
    "register_envs",
    "shoot",
    "shot_constraints",
    "simulate",
]


#: The fronts' modules that moved into pool_env.envs: ``pool_env.<name>`` is their deprecated
#: alias (:mod:`pool_env._moved`), as an attribute of the package too.
_MOVED_MODULES = ("env", "vector", "multiagent", "record", "registration")


def __getattr__(name: str) -> Any:
    """Import a name of the game layer or a front on its first use (PEP 562)."""
    if name in _MOVED_MODULES:  # the import binds it on the package, with its warning
        return importlib.import_module(f"pool_env.{name}")
    if name not in _LAZY:
        raise AttributeError(f"module 'pool_env' has no attribute {name!r}")
    value = getattr(importlib.import_module(_LAZY[name]), name)
    globals()[name] = value  # later uses find it without this call
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


register_on_gymnasium_import()
