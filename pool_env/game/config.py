"""The fixed model of the decision process: every environment argument, parsed once.

:func:`make_config` parses a sectioned :class:`~pool_env.game.sections.PoolConfig` (with
keyword overrides: the ``gym.make`` keywords) into a frozen :class:`GameConfig`; the
changing part (ball positions, generators, shot counts) is :class:`pool_env.game.state.GameState`.
Every front builds its config here, so defaults, checks and messages exist once.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from pool_env.game import checks
from pool_env.game.checks import default_tip_limit, parse_tip_limit
from pool_env.game.frozen import FrozenMap
from pool_env.game.kernels import params as kp
from pool_env.game.kernels.outcome import CUE
from pool_env.game.registry import BUILTIN, ruleset_for
from pool_env.game.ruleset import Ruleset, RulesSection, Setup
from pool_env.game.scenes import ScenePlan, placement, plan_scene
from pool_env.game.sections import (
    DEFAULT_MODEL,
    DEFAULT_SPEED_RANGE,
    PoolConfig,
    TaskSection,
    default_config,
    resolve,
)
from pool_env.game.shot_features import OBSERVATIONS, shot_features_width
from pool_env.game.state import GameState, new_state
from pool_env.sim.table import Table

__all__ = [
    "AIM_MODES",
    "CUE",
    "DEFAULT_AIM_RANGE",
    "DEFAULT_MODEL",
    "DEFAULT_SPEED_RANGE",
    "GAMES",
    "OBSERVATIONS",
    "GameConfig",
    "PoolConfig",
    "TaskConfig",
    "default_config",
    "default_tip_limit",
    "kernel_params",
    "make_config",
    "parse_tip_limit",
]

AimMode = Literal["absolute", "relative", "cut"]

#: Aim modes, in the order of their codes in the kernels.
AIM_MODES: tuple[str, ...] = ("absolute", "relative", "cut")

#: Default range that action 0 maps to, per aim mode:
#:
#: * ``absolute``: radians from +x, a full turn.
#: * ``relative``: radians from the line to the nearest object ball, +-10 degrees. On
#:   random one-ball layouts 95% of ghost-ball pots need under 7 degrees, and the pottable
#:   layouts drop only from 83% to 81% against an unlimited cone, while a random angle pots
#:   1.5 times as often as with +-20 degrees.
#: * ``cut`` (the environment's default): where the cue ball meets the nearest object ball,
#:   as its offset from a full hit in units of a ball diameter ``2R``: 0 is a full hit, +-1
#:   a grazing one. The object ball leaves at ``asin(offset)`` from the cue ball's line,
#:   whatever the distance: every cut is in range and equally fine-grained, and at a fixed
#:   speed a random action pots 2-3 times as often as with ``relative``.
DEFAULT_AIM_RANGE: dict[str, tuple[float, float]] = {
    "absolute": (-math.pi, math.pi),
    "relative": (-math.radians(10.0), math.radians(10.0)),
    "cut": (-1.0, 1.0),
}

#: The built-in games' names (:func:`pool_env.game.registry.game_names` adds the user's).
GAMES: tuple[str, ...] = tuple(BUILTIN)


@dataclass(frozen=True)
class TaskConfig:
    """The task section parsed (:class:`~pool_env.game.sections.TaskSection`).

    Attributes:
        scene: The parsed scene (:class:`pool_env.game.scenes.ScenePlan`).
        aim: Aim mode.
        aim_range: What action[0] = -1 and +1 map to.
        speed_range: Speeds (m/s) of action[1] = -1 and +1.
        observation: ``"balls"`` or ``"shots"`` (:data:`OBSERVATIONS`): whether the
            observation ends with the ghost-ball shot features
            (:mod:`pool_env.game.shot_features`).
        tip_limit: Spin tables only (else ``None``): the largest axis offset of the cue
            tip (fraction of ``R``), the radius of the miscue circle the two tip action
            components map onto (:func:`default_tip_limit` by default).
        end_on_miss: A shot that pots nothing (or scratches) ends the episode (solitaire).
        max_shots: The raw environment's own shot limit, or ``None``.
    """

    scene: ScenePlan
    aim: AimMode
    aim_range: tuple[float, float]
    speed_range: tuple[float, float]
    observation: str
    tip_limit: float | None
    end_on_miss: bool
    max_shots: int | None


@dataclass(frozen=True)
class GameConfig:
    """Everything about the decision process that does not change while it runs.

    The sections parsed, each read where it is used; the numbers the kernels read are
    packed once in ``params``.

    Attributes:
        table: The table (the table section parsed).
        task: The task section parsed (:class:`TaskConfig`).
        noise: Execution noise sigmas ``(angle, speed)`` (spin: optionally ``(angle,
            speed, tip)``) or ``None``; a named model (``"fastfiz"``) parsed into its sigmas.
        rules: The game's rules section, checked by the game
            (:meth:`~pool_env.game.ruleset.Ruleset.parse_section`); ``rules.game`` names it.
        rewards: The reward scales by term, the game's defaults with the user's over them,
            in the game's order (:attr:`~pool_env.game.ruleset.Ruleset.reward_terms`).
        players: 1 (one agent shoots every shot) or 2 (the turn passes by the rules).
        shot_limit: Shots after which an episode is truncated (0: never): ``max_shots``,
            or the vector env's smaller of it and ``max_episode_steps``.
        params: What the kernels read, as one read-only float64 array: the shared head and
            the game's tail (:mod:`pool_env.game.kernels.params`).
        source: The sectioned config this was parsed from (``None``: built by hand).
        ruleset: The game's :class:`~pool_env.game.ruleset.Ruleset` (from ``rules.game``):
            what the step, the observation and the ``info`` ask wherever games differ.
    """

    table: Table
    task: TaskConfig
    noise: tuple[float, ...] | None
    rules: RulesSection
    rewards: Mapping[str, float]
    params: NDArray[np.float64]
    players: int = 1
    shot_limit: int = 0
    source: PoolConfig | None = field(default=None, repr=False, compare=False)
    ruleset: Ruleset = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "ruleset", ruleset_for(self.rules.game).variant(self.rules))

    @property
    def game(self) -> str:
        """The game's name (``rules.game``)."""
        return self.rules.game

    @property
    def scene(self) -> ScenePlan:
        """The parsed scene (``task.scene``)."""
        return self.task.scene

    @property
    def aim(self) -> AimMode:
        """The aim mode (``task.aim``)."""
        return self.task.aim

    @property
    def aim_range(self) -> tuple[float, float]:
        """What action[0] = -1 and +1 map to (``task.aim_range``)."""
        return self.task.aim_range

    @property
    def speed_range(self) -> tuple[float, float]:
        """Speeds (m/s) of action[1] = -1 and +1 (``task.speed_range``)."""
        return self.task.speed_range

    @property
    def tip_limit(self) -> float | None:
        """The spin table's tip limit, else ``None`` (``task.tip_limit``)."""
        return self.task.tip_limit

    @property
    def observation(self) -> str:
        """``"balls"`` or ``"shots"`` (``task.observation``)."""
        return self.task.observation

    @property
    def end_on_miss(self) -> bool:
        """A shot that pots nothing ends the episode (``task.end_on_miss``)."""
        return self.task.end_on_miss

    @property
    def max_shots(self) -> int | None:
        """The raw environment's own shot limit (``task.max_shots``)."""
        return self.task.max_shots

    @property
    def spin(self) -> bool:
        """Whether the table is the spin level: the action then ends with the cue tip."""
        return self.table.has_spin

    @property
    def tip_columns(self) -> tuple[int, int] | None:
        """The action columns of the tip ``(side, vertical)`` (the last two), or ``None``."""
        size = self.action_size
        return (size - 2, size - 1) if self.spin else None

    @property
    def observation_size(self) -> int:
        """Observation entries: ``3 N``; under rules also the legal-ball flags and more.

        The ruleset's :meth:`~pool_env.game.ruleset.Ruleset.observation_width`, and
        with ``observation="shots"`` the shot features
        (:func:`~pool_env.game.shot_features.shot_features_width`).
        """
        return self.ruleset.observation_width(self.n_balls) + self.shot_features_width

    @property
    def shot_features_width(self) -> int:
        """Entries of the ``"shots"`` observation's shot features (0 for ``"balls"``)."""
        return shot_features_width(self.table) if self.observation == "shots" else 0

    @property
    def action_size(self) -> int:
        """Action components: the game's, then a spin table's two tip components.

        2 (aim, speed) in solitaire; under rules 5 (and placement, pocket) in 8-ball, 6 in
        9-ball (and the option), 7 in 10-ball (and the called ball before it).
        """
        return self.ruleset.action_width + (2 if self.spin else 0)

    @property
    def n_object_balls(self) -> int:
        """Object balls of the scene."""
        return self.task.scene.n_objects

    @property
    def n_balls(self) -> int:
        """Balls of a layout, the cue ball included."""
        return self.task.scene.n_objects + 1

    def new_state(self, n_tables: int) -> GameState:
        """``n_tables`` empty tables of this config's balls and game state."""
        return new_state(n_tables, self.n_balls, self.ruleset.rack_width)

    def with_shot_limit(self, limit: int | None) -> GameConfig:
        """This config truncating after ``min(max_shots, limit)`` shots."""
        limits = [x for x in (self.max_shots, limit) if x is not None]
        shot_limit = min(limits) if limits else 0
        params = self.params.copy()
        params[kp.SHOT_LIMIT] = shot_limit
        params.setflags(write=False)
        return replace(self, shot_limit=shot_limit, params=params)


def kernel_params(
    table: Table,
    task: TaskConfig,
    noise: tuple[float, ...] | None,
    shot_limit: int,
    players: int,
    tail: NDArray[np.float64],
    action_width: int,
) -> NDArray[np.float64]:
    """The read-only parameter array of :mod:`pool_env.game.kernels.params`.

    Args:
        table: The parsed table.
        task: The parsed task section.
        noise: The parsed sigmas, or ``None``.
        shot_limit: Shots after which an episode is truncated (0: never).
        players: 1 or 2.
        tail: The game's tail (:meth:`~pool_env.game.ruleset.Ruleset.configure`).
        action_width: The game's action columns (the tip's follow).
    """
    params = placement(table)
    params[kp.AIM_MODE] = AIM_MODES.index(task.aim)
    params[[kp.AIM_LOW, kp.AIM_HIGH]] = task.aim_range
    params[[kp.SPEED_LOW, kp.SPEED_HIGH]] = task.speed_range
    if noise is not None:
        params[[kp.NOISE, kp.SIGMA_ANGLE, kp.SIGMA_SPEED]] = (1.0, *noise[:2])
        params[kp.SIGMA_TIP] = noise[2] if len(noise) > 2 else 0.0
    if table.has_spin:
        params[kp.SPIN] = 1.0
        params[[kp.BALL_MASS, kp.CUE_END_MASS, kp.CUE_TIP_RADIUS]] = (
            table.ball_mass, table.cue_end_mass, table.cue_tip_radius
        )  # fmt: skip
    if task.tip_limit is not None:
        params[kp.TIP_LIMIT] = task.tip_limit
    params[kp.SHOT_LIMIT] = shot_limit
    params[kp.PLAYERS] = players
    params[kp.TIP_COLUMN] = action_width
    params[kp.TAIL :] = tail
    params.setflags(write=False)
    return params


def make_config(config: PoolConfig | None = None, players: int = 1, **overrides: Any) -> GameConfig:
    """Check and parse an environment's config (see :class:`pool_env.PoolEnv`).

    Each section is parsed on its own: the table, the task, the noise; then the game
    (``rules.game``) checks its rules section against them and gives its tail of the
    kernel parameters, with the reward scales (its terms' defaults, the user's over them).

    Args:
        config: The sectioned config (``None``: :func:`~pool_env.game.sections.default_config`).
        players: 1 (one agent shoots every shot) or 2 (the turn passes by the rules): the
            front's, not a user's choice.
        **overrides: Keyword overrides of ``config`` (:meth:`PoolConfig.override`).

    Raises:
        ValueError: Naming the first bad argument; a scene that cannot fit on the table is
            refused here, never at a reset.
    """
    source = resolve(config, overrides)
    ruleset = ruleset_for(source.rules.game)
    if ruleset.spin_only and source.table.model == "roll":  # before a roll table is made
        raise ValueError(f"model='roll' for game={ruleset.name!r}: {ruleset.spin_only}")
    table = checks.parse_table(source.table.table, source.table.model, DEFAULT_MODEL)
    task = parse_task(source.task, table, ruleset.scenes)
    sigmas = checks.parse_noise(source.noise.sigmas, table)
    speeds = checks.SpeedCeiling(table, task.tip_limit, sigmas[1] if sigmas else 0.0,
                                 source.noise.sigmas)  # fmt: skip
    speeds.check("speed_range", source.task.speed_range, task.speed_range[1])
    if players not in (1, 2) or isinstance(players, bool):
        raise ValueError(f"players must be 1 or 2, got {players!r}")
    rewards = FrozenMap(parse_rewards(ruleset, source.rewards.scales))  # read, never changed
    rules = ruleset.parse_section(source.rules)
    ruleset = ruleset.variant(rules)
    # The section as given (Setup's contract): the game checks it, naming values as written.
    setup = Setup(table, task.scene, source.rules, rewards, task.end_on_miss, players,
                  ruleset.action_width, speeds)  # fmt: skip
    tail = ruleset.configure(setup)
    shots = task.max_shots or 0
    params = kernel_params(table, task, sigmas, shots, players, tail, ruleset.action_width)
    return GameConfig(
        table=table, task=task, noise=sigmas, rules=rules, rewards=rewards, params=params,
        players=players, shot_limit=shots, source=source,
    )  # fmt: skip


def parse_task(
    task: TaskSection, table: Table, game_scenes: Mapping[str, Any] | None = None
) -> TaskConfig:
    """The task section checked and parsed (``ValueError``, naming the first bad value).

    ``game_scenes`` are the game's own named scenes (:attr:`Ruleset.scenes`): a name of
    theirs stands for its layout or callable.
    """
    if task.aim not in AIM_MODES:
        raise ValueError(f"aim must be one of {list(AIM_MODES)}, got {task.aim!r}")
    if task.observation not in OBSERVATIONS:
        raise ValueError(
            f"observation must be one of {list(OBSERVATIONS)}, got {task.observation!r}"
        )
    return TaskConfig(
        scene=plan_scene(_own_scene(task.scene, game_scenes), table, task.n_balls, task.rack_order),
        aim=task.aim,  # type: ignore[arg-type]
        aim_range=checks.parse_range(
            "aim_range", task.aim_range or DEFAULT_AIM_RANGE[task.aim], None
        ),
        speed_range=checks.parse_range("speed_range", task.speed_range, 0.0),
        observation=task.observation,
        tip_limit=parse_tip_limit(table, task.tip_limit),
        end_on_miss=checks.parse_bool("end_on_miss", task.end_on_miss),
        max_shots=checks.parse_count("max_shots", task.max_shots),
    )


def parse_rewards(ruleset: Ruleset, given: Mapping[str, Any]) -> dict[str, float]:
    """The game's reward scales: its defaults, with the given ones checked over them.

    Raises:
        ValueError: On a term the game has not, or a scale that is no finite number.
    """
    unknown = [term for term in given if term not in ruleset.reward_terms]
    if unknown:
        terms = ", ".join(f"reward_{t}" for t in ruleset.reward_terms)
        raise ValueError(
            f"reward_{unknown[0]}: game={ruleset.name!r} has no reward term {unknown[0]!r} "
            f"(its terms: {terms})"
        )
    return {
        term: checks.parse_float(f"reward_{term}", given.get(term, default))
        for term, default in ruleset.reward_terms.items()
    }


def _own_scene(scene: Any, game_scenes: Mapping[str, Any] | None) -> Any:
    """A game's own scene for its name, else ``scene`` as given."""
    if isinstance(scene, str) and game_scenes and scene in game_scenes:
        return game_scenes[scene]
    return scene
