"""Gymnasium registration of the pool environments (idempotent: safe to call again).

``import pool_env`` registers the ids without importing Gymnasium itself, so that the
simulator (``import pool_env.sim``, which runs ``pool_env/__init__.py``) stands alone:
:func:`register_on_gymnasium_import` registers them at once if Gymnasium is loaded, and
otherwise the moment its import completes.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
from types import ModuleType
from typing import Any

ENTRY_POINT = "pool_env.env:PoolEnv"

#: ``gymnasium.make_vec(id, num_envs=n)`` builds this batched env (one compiled call per
#: step for all tables); ``vectorization_mode="sync"`` / ``"async"`` still wrap PoolEnvs.
VECTOR_ENTRY_POINT = "pool_env.vector:PoolVectorEnv"

#: id -> (make() keyword arguments, max_episode_steps).
ENV_IDS: dict[str, tuple[dict[str, Any], int]] = {
    # The configurable one: 3 random object balls by default; every argument via make().
    "pool_env/Pool-v0": ({}, 50),
    # One shot per episode (a miss ends it, a pot clears the table): a clean contextual
    # bandit whose success rate is the pot rate. end_on_miss=False makes it multi-shot.
    "pool_env/OneBall-v0": ({"scene": "one_ball", "end_on_miss": True}, 10),
    # Break, then keep shooting until the table is clear: 50 shots is ~5 a ball.
    "pool_env/NineBall-v0": ({"scene": "nine_ball"}, 50),
    "pool_env/EightBall-v0": ({"scene": "eight_ball"}, 80),
    # The games under their rules (pool_env.game.kernels.wpa), one agent at the table:
    # fouls, ball in hand (Box(5) actions), a break at break speed; the episode ends when
    # the rack is won or lost (end_on_foul=True: at the first foul or missed turn).
    "pool_env/NineBallGame-v0": ({"scene": "nine_ball", "game": "nine"}, 100),
    "pool_env/EightBallGame-v0": ({"scene": "eight_ball", "game": "eight"}, 150),
}

#: The v1 ids: each v0 task on the spin table (``model="spin"``), with the cue tip's side
#: and vertical offsets as the action's last two components (``Box(4)``, rules
#: ``Box(7)``). Gymnasium bumps the version when the dynamics change, and they change for
#: every task alike: the spin table is the realistic physics of all six (sliding, draw,
#: follow, throw, squirt), and a tip action is as meaningful on a 3-ball practice table
#: (``Pool``) or a solitaire run (``NineBall``, ``EightBall``) as in the games. So every v0
#: id gets its v1 (the same scene, rules and time limit), and ``-v0`` -> ``-v1`` is the one
#: rule a user or a tool needs; the v0 ids stay as they were, bit for bit.
SPIN_IDS: dict[str, tuple[dict[str, Any], int]] = {
    env_id.replace("-v0", "-v1"): ({**kwargs, "model": "spin"}, steps)
    for env_id, (kwargs, steps) in ENV_IDS.items()
}
ENV_IDS.update(SPIN_IDS)


def register_envs() -> None:
    """Register every id of :data:`ENV_IDS` that is not registered yet."""
    import gymnasium as gym  # here, not at the top: see the module's docstring

    for env_id, (kwargs, max_steps) in ENV_IDS.items():
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point=ENTRY_POINT,
                vector_entry_point=VECTOR_ENTRY_POINT,
                kwargs=kwargs,
                max_episode_steps=max_steps,
            )


#: The ids played under the 9-ball or 8-ball rules (``Box(5)`` actions, ``Box(7)`` on v1);
#: the others are solitaire (``Box(2)``, ``Box(4)`` on v1).
GAME_IDS: tuple[str, ...] = tuple(k for k, (kw, _) in ENV_IDS.items() if "game" in kw)


class _RegisteringLoader(importlib.abc.Loader):
    """Gymnasium's own loader, followed by :func:`register_envs` once its module is complete."""

    def __init__(self, loader: importlib.abc.Loader) -> None:
        self._loader = loader

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> ModuleType | None:
        """Whatever Gymnasium's loader creates (None: the default module)."""
        return self._loader.create_module(spec)

    def exec_module(self, module: ModuleType) -> None:
        """Run Gymnasium's ``__init__``, then register the ids."""
        module.__loader__ = self._loader  # Gymnasium keeps its own loader, as if never wrapped
        if module.__spec__ is not None:
            module.__spec__.loader = self._loader
        self._loader.exec_module(module)
        _remove_hook()
        register_envs()


class _GymnasiumHook(importlib.abc.MetaPathFinder):
    """Finds Gymnasium through the other finders and hands back its spec, loader wrapped."""

    def find_spec(
        self, fullname: str, path: Any = None, target: ModuleType | None = None
    ) -> importlib.machinery.ModuleSpec | None:
        """Gymnasium's spec with a registering loader; None (not ours) for any other name."""
        if fullname != "gymnasium":
            return None
        for finder in sys.meta_path:
            if finder is self or not hasattr(finder, "find_spec"):
                continue
            spec = finder.find_spec(fullname, path, target)
            if spec is not None:
                if spec.loader is not None:
                    spec.loader = _RegisteringLoader(spec.loader)
                return spec
        return None


def _remove_hook() -> None:
    sys.meta_path[:] = [f for f in sys.meta_path if not isinstance(f, _GymnasiumHook)]


def register_on_gymnasium_import() -> None:
    """Register the ids now if Gymnasium is loaded, else as soon as its import completes.

    ``import pool_env`` calls this, so ``gymnasium.make("pool_env/...")`` works whether
    Gymnasium or pool_env was imported first, while ``import pool_env.sim`` loads no
    Gymnasium. Idempotent: at most one hook waits in ``sys.meta_path``.
    """
    if "gymnasium" in sys.modules:
        register_envs()
    elif not any(isinstance(f, _GymnasiumHook) for f in sys.meta_path):
        sys.meta_path.insert(0, _GymnasiumHook())
