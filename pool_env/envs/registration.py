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

from pool_env.sim.presets import PRESETS
from pool_env.sim.table import roll_keywords

ENTRY_POINT = "pool_env.envs.env:PoolEnv"

#: ``Table.preset("carom")``'s arguments, the model left to the id (a spin-only task: a
#: roll table of them is refused by the game, with its reason, not by the table).
_CAROM: dict[str, Any] = {k: v for k, v in PRESETS["carom"].items() if k != "model"}
#: The snooker table (``Table.preset("snooker")``) as ``table=`` arguments, less its model:
#: each id sets the model (the roll twin plays the same table on the roll level).
_SNOOKER_TABLE = {k: v for k, v in PRESETS["snooker"].items() if k != "model"}

#: ``gymnasium.make_vec(id, num_envs=n)`` builds this batched env (one compiled call per
#: step for all tables); ``vectorization_mode="sync"`` / ``"async"`` still wrap PoolEnvs.
VECTOR_ENTRY_POINT = "pool_env.envs.vector:PoolVectorEnv"

# How the ids are named, and why. Every task is played on two models of one table: the spin
# table (``model="spin"``: sliding, draw, follow, english, throw, squirt; the action ends with
# the cue tip's offsets) and the roll table (``model="roll"``: constant rolling deceleration,
# the cheap model, kept on purpose for scenes that need no spin). They are two models of one
# task, not a version and its successor, so they get two names at one version:
# ``pool_env/<Task>-v1`` is the spin table, the realistic default, and
# ``pool_env/<Task>Roll-v1`` the roll table. Gymnasium reads ``-vN`` as "N replaces N-1" and
# warns on every make() of a lower version of a name, so the roll table can no longer be
# ``<Task>-v0`` beside the spin table's ``<Task>-v1`` without a false "out of date" warning.
# The old ``pool_env/<Task>-v0`` ids stay registered as aliases of ``<Task>Roll-v1`` (the
# same arguments, the same episodes bit for bit: tests/envs/test_registration.py), so old code
# and saved configs keep working; Gymnasium's warning on them is now true (a newer spelling
# exists). ``model=`` stays an argument of every id: ``gym.make("pool_env/OneBall-v1",
# model="roll")`` is ``pool_env/OneBallRoll-v1`` under the spin id's name.
# A task whose spaces or dynamics change takes the next version on both tables
# (:data:`VERSIONS`); its earlier versions stay registered, playing as they did
# (:data:`EARLIER_VERSIONS`), and Gymnasium reports them out of date.

#: task -> (make() keyword arguments, max_episode_steps), the model left out.
TASKS: dict[str, tuple[dict[str, Any], int]] = {
    # The configurable one: 3 random object balls by default; every argument via make().
    "Pool": ({}, 50),
    # One shot per episode (a miss ends it, a pot clears the table): a clean contextual
    # bandit whose success rate is the pot rate. end_on_miss=False makes it multi-shot.
    "OneBall": ({"scene": "one_ball", "end_on_miss": True}, 10),
    # Break, then keep shooting until the table is clear: 50 shots is ~5 a ball.
    "NineBall": ({"scene": "nine_ball"}, 50),
    "EightBall": ({"scene": "eight_ball"}, 80),
    # The games under their rules (pool_env.game.games.wpa), one agent at the table:
    # fouls, ball in hand, called pockets (10-ball: and balls), the push-out (9-ball and
    # 10-ball), a break at break speed; the episode ends when the rack is won or lost
    # (end_on_foul=True: at the first foul or missed turn).
    "NineBallGame": ({"scene": "nine_ball", "game": "nine"}, 100),
    "TenBallGame": ({"scene": "ten_ball", "game": "ten"}, 110),
    "EightBallGame": ({"scene": "eight_ball", "game": "eight"}, 150),
    # Three-cushion (pool_env.game.games.three_cushion) on the UMB carom table: one
    # player, an episode is one inning (it ends at the first miss); 100 shots is a run
    # twice the world record's. Spin level only (SPIN_ONLY).
    "ThreeCushion": ({"scene": "three_cushion", "game": "three_cushion", "table": _CAROM}, 100),
    # Snooker (pool_env.game.games.snooker) on the WPBSA table: one visit to the table
    # (reds spread at random, the colours on their spots; the reward is the points of the
    # break), then a frame whose both sides one agent plays. SnookerFrame comes last: the
    # duel front plays game="snooker" with its arguments.
    "SnookerBreak": (
        {
            "scene": "snooker_break",
            "game": "snooker",
            "table": _SNOOKER_TABLE,
            "end_on_foul": True,
            "reward_foul": 0.0,
        },
        60,
    ),
    "SnookerFrame": (
        {"scene": "snooker", "game": "snooker", "table": _SNOOKER_TABLE},
        400,
    ),
}

#: Tasks played on the spin table only: no roll twin (nor a ``-v0`` alias) is registered,
#: and ``model="roll"`` is refused by the game with its reason (three-cushion is decided
#: by the cue ball's spin off the cushions).
SPIN_ONLY: frozenset[str] = frozenset({"ThreeCushion"})

#: task -> its current version, where it is not 1. An id takes a new version when its
#: spaces or dynamics change (Gymnasium's rule); the earlier versions stay registered and
#: play as they did (:data:`EARLIER_VERSIONS`). 9-ball's push-out (and the opponent's
#: option) added an action column and two observation entries: ``-v2``.
VERSIONS: dict[str, int] = {"NineBallGame": 2}

#: (task, earlier version) -> the keywords that play it as it was, over the task's own.
#: ``NineBallGame-v1``: 9-ball before the push-out, bit for bit
#: (``tests/envs/test_id_versions.py`` replays a trace of that time's code).
EARLIER_VERSIONS: dict[tuple[str, int], dict[str, Any]] = {
    ("NineBallGame", 1): {"push_out": False, "rack_order": "fixed"},
}


def spin_id(task: str, version: int | None = None) -> str:
    """The id of ``task`` on the spin table: ``pool_env/<task>-v<N>`` (N: the current)."""
    return f"pool_env/{task}-v{VERSIONS.get(task, 1) if version is None else version}"


def roll_id(task: str, version: int | None = None) -> str:
    """The id of ``task`` on the roll table: ``pool_env/<task>Roll-v<N>`` (N: the current)."""
    return f"pool_env/{task}Roll-v{VERSIONS.get(task, 1) if version is None else version}"


def _versions(task: str, kwargs: dict[str, Any]) -> dict[int, dict[str, Any]]:
    """Every registered version of ``task``: version -> its keywords."""
    earlier = {v: {**kwargs, **extra} for (t, v), extra in EARLIER_VERSIONS.items() if t == task}
    return {**earlier, VERSIONS.get(task, 1): dict(kwargs)}


#: The spin table's ids, the realistic physics of every task (``model="spin"``): every
#: version.
SPIN_IDS: dict[str, tuple[dict[str, Any], int]] = {
    spin_id(task, v): ({**kw, "model": "spin"}, steps)
    for task, (kwargs, steps) in TASKS.items()
    for v, kw in _versions(task, kwargs).items()
}


def _on_roll(kwargs: dict[str, Any]) -> dict[str, Any]:
    """A task's arguments on the roll table: a preset's spin-only values dropped.

    As ``Table.preset(name, model="roll")`` drops them (the snooker preset's ``mu_slide``,
    cushion friction and height mean nothing on the roll level, which refuses them).
    """
    table = kwargs.get("table")
    if isinstance(table, dict):
        kwargs = {**kwargs, "table": roll_keywords(table)}
    return {**kwargs, "model": "roll"}


#: The roll table's ids (``model="roll"``): every version. The model is registered, not
#: left to ``make_config``'s default, which is the spin table
#: (:data:`pool_env.game.sections.DEFAULT_MODEL`, the spin ids' model).
ROLL_IDS: dict[str, tuple[dict[str, Any], int]] = {
    roll_id(task, v): (_on_roll(kw), steps)
    for task, (kwargs, steps) in TASKS.items()
    if task not in SPIN_ONLY
    for v, kw in _versions(task, kwargs).items()
}

#: Every supported id -> (make() keyword arguments, max_episode_steps).
ENV_IDS: dict[str, tuple[dict[str, Any], int]] = {**SPIN_IDS, **ROLL_IDS}

#: The current version of every task's ids (spin and roll), the ones to use in new work.
CURRENT_IDS: tuple[str, ...] = tuple(
    i for task in TASKS for i in (spin_id(task), roll_id(task)) if i in ENV_IDS
)

#: The tasks that had ``-v0`` ids (the roll table's, before the spin table came); a task
#: added since has none.
V0_TASKS: tuple[str, ...] = (
    "Pool", "OneBall", "NineBall", "EightBall", "NineBallGame", "TenBallGame", "EightBallGame",
)  # fmt: skip

#: The old names of the roll ids (``pool_env/<task>-v0`` -> ``pool_env/<task>Roll-v1``),
#: registered with the same arguments; Gymnasium reports them out of date.
LEGACY_IDS: dict[str, str] = {f"pool_env/{task}-v0": roll_id(task, 1) for task in V0_TASKS}


def register_envs() -> None:
    """Register every id of :data:`ENV_IDS` and :data:`LEGACY_IDS` not registered yet."""
    import gymnasium as gym  # here, not at the top: see the module's docstring

    legacy = {old: ENV_IDS[new] for old, new in LEGACY_IDS.items()}
    for env_id, (kwargs, max_steps) in {**ENV_IDS, **legacy}.items():
        if env_id not in gym.registry:
            gym.register(
                id=env_id,
                entry_point=ENTRY_POINT,
                vector_entry_point=VECTOR_ENTRY_POINT,
                # One keyword, so that the env tells the id's defaults from the caller's own
                # keywords (Gymnasium merges the two): a config= given replaces them whole
                # (pool_env.game.sections.resolve).
                kwargs={"id_defaults": kwargs},
                max_episode_steps=max_steps,
            )


#: The ids played under the 9-ball, 10-ball or 8-ball rules (``Box(8)``, ``Box(9)``,
#: ``Box(7)`` actions on the spin table, two fewer on the roll table); the others are
#: solitaire (``Box(4)``, ``Box(2)``).
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
