"""The fixed model of the decision process: every environment argument, parsed once.

:func:`make_config` parses a sectioned :class:`~pool_env.game.sections.PoolConfig` (with
keyword overrides: the ``gym.make`` keywords) into a frozen :class:`GameConfig`; the
changing part (ball positions, generators, shot counts) is :class:`pool_env.game.state.GameState`.
Every front builds its config here, so defaults, checks and messages exist once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from pool_env.game import checks
from pool_env.game.kernels import params as kp
from pool_env.game.rules import CUE as RULES_CUE
from pool_env.game.rulesets import RULESETS, Ruleset, ruleset_for
from pool_env.game.rulesets.wpa import DEFAULT_BREAK_SPEED_RANGE
from pool_env.game.scenes import ScenePlan, placement, plan_scene
from pool_env.game.sections import DEFAULT_SPEED_RANGE, PoolConfig, default_config, resolve
from pool_env.game.shot_features import OBSERVATIONS, shot_features_width
from pool_env.sim.table import Table

__all__ = [
    "AIM_MODES",
    "CUE",
    "DEFAULT_AIM_RANGE",
    "DEFAULT_BREAK_SPEED_RANGE",
    "DEFAULT_SPEED_RANGE",
    "GAMES",
    "OBSERVATIONS",
    "GameConfig",
    "PoolConfig",
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

#: The games (:data:`pool_env.game.rulesets.RULESETS`), in the order of their codes in the
#: kernels (:mod:`.kernels.wpa`).
GAMES: tuple[str, ...] = tuple(RULESETS)

#: The cue ball's row in every layout (the rules' constant).
CUE = RULES_CUE

#: The contact offset (fraction of R) beyond which a real tip miscues: about half a radius
#: (pooltool and Dr. Dave's miscue-limit FAQ). The default tip limit is the axis offset
#: that gives it (:func:`default_tip_limit`).
MISCUE_CONTACT_OFFSET = 0.5


def default_tip_limit(table: Table) -> float:
    """The default tip limit of a spin table: the axis offset of a half-radius contact.

    The tip's contact point lies ``1 / (1 + r_tip / R)`` of the axis offset from the ball's
    centre line (:mod:`pool_env.sim.kernels.spin.strike`), so the axis offset of a contact
    offset ``c`` is ``c (1 + r_tip / R)``: 0.685 for the default 10.6 mm tip (capped at 1).
    """
    return min(1.0, MISCUE_CONTACT_OFFSET * (1.0 + table.cue_tip_radius / table.ball_radius))


@dataclass(frozen=True)
class GameConfig:
    """Everything about the decision process that does not change while it runs.

    Attributes:
        table: The table.
        scene: The parsed scene (:class:`pool_env.game.scenes.ScenePlan`).
        aim: Aim mode.
        aim_range: What action[0] = -1 and +1 map to.
        speed_range: Speeds (m/s) of action[1] = -1 and +1.
        noise: Execution noise sigmas ``(angle, speed)`` (spin: optionally ``(angle,
            speed, tip)``) or ``None``; a named model (``"fastfiz"``) parsed into its sigmas.
        end_on_miss: A shot that pots nothing (or scratches) ends the episode.
        max_shots: The raw environment's own shot limit, or ``None``.
        shot_limit: Shots after which an episode is truncated (0: never): ``max_shots``,
            or the vector env's smaller of it and ``max_episode_steps``.
        reward_weights: ``(pot, scratch, no contact, shaping)``.
        game: The rule: ``"solitaire"``, ``"nine"``, ``"ten"`` or ``"eight"``.
        players: 1 (one agent shoots every shot) or 2 (the turn passes by the rules).
        end_on_foul: Rules only (solitaire: False): a foul, or a shot that does not keep
            the table, ends the episode (run-out mode).
        break_speed_range: Rules only (solitaire, which has no break: ``(0, 0)``): speeds
            (m/s) of action[1] = -1 and +1 on a break.
        rule_rewards: Rules only (solitaire: ``(0, 0)``): ``(foul, win)`` (a lost rack
            gives ``-win``). The game's :meth:`~pool_env.game.rulesets.base.Ruleset.parse_rules`.
        observation: ``"balls"`` or ``"shots"`` (:data:`OBSERVATIONS`): whether the
            observation ends with the ghost-ball shot features
            (:mod:`pool_env.game.shot_features`).
        tip_limit: Spin tables only (else ``None``): the largest axis offset of the cue
            tip (fraction of ``R``), the radius of the miscue circle the two tip action
            components map onto (:func:`default_tip_limit` by default).
        params: All of the above that the kernels read, as one read-only float64 array
            (:mod:`pool_env.game.kernels.params` names its entries).
        source: The sectioned config this was parsed from (``None``: built by hand).
        ruleset: The game's :class:`~pool_env.game.rulesets.base.Ruleset` (from ``game``):
            what the step, the observation and the ``info`` ask wherever games differ.
    """

    table: Table
    scene: ScenePlan
    aim: AimMode
    aim_range: tuple[float, float]
    speed_range: tuple[float, float]
    noise: tuple[float, ...] | None
    end_on_miss: bool
    max_shots: int | None
    shot_limit: int
    reward_weights: tuple[float, float, float, float]
    params: NDArray[np.float64]
    game: str = "solitaire"
    players: int = 1
    end_on_foul: bool = False
    break_speed_range: tuple[float, float] = DEFAULT_BREAK_SPEED_RANGE
    rule_rewards: tuple[float, float] = (-1.0, 1.0)
    tip_limit: float | None = None
    observation: str = "balls"
    source: PoolConfig | None = field(default=None, repr=False, compare=False)
    ruleset: Ruleset = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "ruleset", ruleset_for(self.game))

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
    def rules(self) -> bool:
        """Whether a game with a rack state (9-ball or 8-ball) applies, not solitaire."""
        return self.ruleset.has_rack

    @property
    def observation_size(self) -> int:
        """Observation entries: ``3 N``; under rules also the legal-ball flags and more.

        The ruleset's :meth:`~pool_env.game.rulesets.base.Ruleset.observation_width`, and
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
        return self.scene.n_objects

    @property
    def n_balls(self) -> int:
        """Balls of a layout, the cue ball included."""
        return self.scene.n_objects + 1

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
    aim: str,
    aim_range: tuple[float, float],
    speed_range: tuple[float, float],
    noise: tuple[float, ...] | None,
    weights: tuple[float, float, float, float],
    end_on_miss: bool,
    shot_limit: int,
) -> NDArray[np.float64]:
    """The read-only parameter array of :mod:`pool_env.game.kernels.params`."""
    params = placement(table)
    params[kp.AIM_MODE] = AIM_MODES.index(aim)
    params[[kp.AIM_LOW, kp.AIM_HIGH]] = aim_range
    params[[kp.SPEED_LOW, kp.SPEED_HIGH]] = speed_range
    if noise is not None:
        params[[kp.NOISE, kp.SIGMA_ANGLE, kp.SIGMA_SPEED]] = (1.0, *noise[:2])
        params[kp.SIGMA_TIP] = noise[2] if len(noise) > 2 else 0.0
    if table.has_spin:
        params[kp.SPIN] = 1.0
        params[[kp.BALL_MASS, kp.CUE_END_MASS, kp.CUE_TIP_RADIUS]] = (
            table.ball_mass, table.cue_end_mass, table.cue_tip_radius
        )  # fmt: skip
    params[[kp.W_POT, kp.W_SCRATCH, kp.W_NO_CONTACT, kp.W_SHAPING]] = weights
    params[kp.END_ON_MISS] = float(end_on_miss)
    params[kp.SHOT_LIMIT] = shot_limit
    params[[kp.BALL_COLUMN, kp.OPTION_COLUMN, kp.TIP_COLUMN]] = (-1.0, -1.0, 2.0)  # rules: theirs
    params.setflags(write=False)
    return params


def make_config(config: PoolConfig | None = None, players: int = 1, **overrides: Any) -> GameConfig:
    """Check and parse an environment's config (see :class:`pool_env.PoolEnv`).

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
    task, rules = source.task, source.rules
    parsed_table = checks.parse_table(source.table.table, source.table.model)
    if task.aim not in AIM_MODES:
        raise ValueError(f"aim must be one of {list(AIM_MODES)}, got {task.aim!r}")
    if task.observation not in OBSERVATIONS:
        raise ValueError(
            f"observation must be one of {list(OBSERVATIONS)}, got {task.observation!r}"
        )
    aims = checks.parse_range("aim_range", task.aim_range or DEFAULT_AIM_RANGE[task.aim], None)
    speeds = checks.parse_range("speed_range", task.speed_range, 0.0)
    sigmas = checks.parse_noise(source.noise.sigmas, parsed_table)
    limit = parse_tip_limit(parsed_table, task.tip_limit)
    miss = checks.parse_bool("end_on_miss", task.end_on_miss)
    shots = checks.parse_count("max_shots", task.max_shots)
    weights = tuple(
        checks.parse_float(name, getattr(task, name))
        for name in ("reward_pot", "reward_scratch", "reward_no_contact", "reward_shaping")
    )
    ruleset = ruleset_for(rules.game)
    if players not in (1, 2) or isinstance(players, bool):
        raise ValueError(f"players must be 1 or 2, got {players!r}")
    foul_ends, breaks, rule_rewards = ruleset.parse_rules(rules)
    plan = plan_scene(task.scene, parsed_table, task.n_balls, task.rack_order)
    ruleset.check(plan, parsed_table, miss, foul_ends, players)
    params = kernel_params(parsed_table, task.aim, aims, speeds, sigmas, weights, miss, shots or 0)  # type: ignore[arg-type]
    if limit is not None:
        params = params.copy()
        params[kp.TIP_LIMIT] = limit
        params.setflags(write=False)
    params = ruleset.rule_params(params, parsed_table, players, foul_ends, breaks, rule_rewards)
    return GameConfig(
        table=parsed_table,
        scene=plan,
        aim=task.aim,  # type: ignore[arg-type]
        aim_range=aims,
        speed_range=speeds,
        noise=sigmas,
        end_on_miss=miss,
        max_shots=shots,
        shot_limit=shots or 0,
        reward_weights=weights,  # type: ignore[arg-type]
        params=params,
        game=rules.game,
        players=players,
        end_on_foul=foul_ends,
        break_speed_range=breaks,
        rule_rewards=rule_rewards,
        tip_limit=limit,
        observation=task.observation,
        source=source,
    )


def parse_tip_limit(table: Table, tip_limit: object) -> float | None:
    """The tip limit of a spin table (``None``: :func:`default_tip_limit`); ``None`` on roll.

    Raises:
        ValueError: Unless a number in ``(0, 1]``, or when given for a roll table.
    """
    if not table.has_spin:
        if tip_limit is not None:
            raise ValueError("tip_limit needs a spin table: model='spin' (the spin ids)")
        return None
    if tip_limit is None:
        return default_tip_limit(table)
    limit = checks.parse_float("tip_limit", tip_limit)
    if not 0.0 < limit <= 1.0:
        raise ValueError(f"tip_limit must lie in (0, 1] (a fraction of R), got {tip_limit!r}")
    return limit
