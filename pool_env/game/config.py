"""The fixed model of the decision process: every environment argument, parsed once.

:func:`make_config` turns the ``gym.make`` keywords into a frozen :class:`GameConfig`; the
changing part (ball positions, generators, shot counts) is :class:`pool_env.game.state.GameState`.
Both fronts build their config here, so defaults, checks and messages exist once.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from pool_env.game import checks
from pool_env.game.scenes import Placement, ScenePlan, SceneSpec, placement, plan_scene
from pool_env.sim.table import Table

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

#: Default cue speed range (m/s): from a soft touch (rolls ~1.3 m) to a hard break.
DEFAULT_SPEED_RANGE = (0.5, 10.0)

#: The cue ball's row in every layout.
CUE = 0


@dataclass(frozen=True)
class GameConfig:
    """Everything about the decision process that does not change while it runs.

    Attributes:
        table: The table.
        scene: The parsed scene (:class:`pool_env.game.scenes.ScenePlan`).
        aim: Aim mode.
        aim_code: Its code in the kernels (index in :data:`AIM_MODES`).
        aim_range: What action[0] = -1 and +1 map to.
        speed_range: Speeds (m/s) of action[1] = -1 and +1.
        noise: Execution noise sigmas ``(angle, speed)`` or ``None``.
        sigmas: The same as a ``(2,)`` array, ``(0,)`` without noise (for the kernels).
        end_on_miss: A shot that pots nothing (or scratches) ends the episode.
        max_shots: The raw environment's own shot limit, or ``None``.
        shot_limit: Shots after which an episode is truncated (0: never); ``max_shots``,
            or the vector env's smaller of it and ``max_episode_steps``.
        reward_weights: ``(pot, scratch, no contact, shaping)``.
        weights: The same as an array (for the kernels).
        place: Where balls may be placed on this table.
        diagonal: The table's diagonal (m), the shaping potential's scale.
    """

    table: Table
    scene: ScenePlan
    aim: AimMode
    aim_code: int
    aim_range: tuple[float, float]
    speed_range: tuple[float, float]
    noise: tuple[float, float] | None
    sigmas: NDArray[np.float64]
    end_on_miss: bool
    max_shots: int | None
    shot_limit: int
    reward_weights: tuple[float, float, float, float]
    weights: NDArray[np.float64]
    place: Placement
    diagonal: float

    @property
    def n_object_balls(self) -> int:
        """Object balls of the scene."""
        return self.scene.n_objects

    @property
    def n_balls(self) -> int:
        """Balls of a layout, the cue ball included."""
        return self.scene.n_objects + 1

    @property
    def shaping(self) -> bool:
        """Whether the reward includes the potential's change (it costs two evaluations)."""
        return self.reward_weights[3] != 0.0

    def with_shot_limit(self, limit: int | None) -> GameConfig:
        """This config truncating after ``min(max_shots, limit)`` shots."""
        limits = [x for x in (self.max_shots, limit) if x is not None]
        return _replace(self, shot_limit=min(limits) if limits else 0)


def _replace(config: GameConfig, **changes: Any) -> GameConfig:
    fields = {**config.__dict__, **changes}
    return GameConfig(**fields)


def _read_only(values: Any) -> NDArray[np.float64]:
    out = np.array(values, dtype=np.float64)
    out.setflags(write=False)
    return out


def make_config(
    table: Table | dict[str, Any] | None = None,
    scene: SceneSpec = "random",
    n_balls: int | None = None,
    aim: AimMode = "cut",
    aim_range: tuple[float, float] | None = None,
    speed_range: tuple[float, float] = DEFAULT_SPEED_RANGE,
    noise: tuple[float, float] | None = None,
    end_on_miss: bool = False,
    max_shots: int | None = None,
    reward_pot: float = 1.0,
    reward_scratch: float = -1.0,
    reward_no_contact: float = 0.0,
    reward_shaping: float = 0.0,
) -> GameConfig:
    """Parse and check the environment arguments (see :class:`pool_env.PoolEnv`).

    Raises:
        ValueError: Naming the first bad argument; a scene that cannot fit on the table is
            refused here, never at a reset.
    """
    parsed_table = checks.parse_table(table)
    if aim not in AIM_MODES:
        raise ValueError(f"aim must be one of {list(AIM_MODES)}, got {aim!r}")
    noise_sigmas = checks.parse_noise(noise)
    weights = tuple(
        checks.parse_float(name, value)
        for name, value in (
            ("reward_pot", reward_pot),
            ("reward_scratch", reward_scratch),
            ("reward_no_contact", reward_no_contact),
            ("reward_shaping", reward_shaping),
        )
    )
    shots = checks.parse_count("max_shots", max_shots)
    config = GameConfig(
        table=parsed_table,
        scene=plan_scene(scene, parsed_table, n_balls),
        aim=aim,
        aim_code=AIM_MODES.index(aim),
        aim_range=checks.parse_range("aim_range", aim_range or DEFAULT_AIM_RANGE[aim], None),
        speed_range=checks.parse_range("speed_range", speed_range, 0.0),
        noise=noise_sigmas,
        sigmas=_read_only(noise_sigmas if noise_sigmas is not None else ()),
        end_on_miss=checks.parse_bool("end_on_miss", end_on_miss),
        max_shots=shots,
        shot_limit=shots or 0,
        reward_weights=weights,  # type: ignore[arg-type]
        weights=_read_only(weights),
        place=placement(parsed_table),
        diagonal=math.hypot(parsed_table.length, parsed_table.width),
    )
    return config
