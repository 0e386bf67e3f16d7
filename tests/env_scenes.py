"""Constructed shots whose outcome is worked out by hand: rewards, observations, info.

Shared by the expectation tests of the three fronts (``PoolEnv``, ``PoolVectorEnv`` and
the SB3 adapter), so that each is checked against numbers derived from the documented
rules (README, PoolEnv's docstring) and the closed forms of the physics, never against
another front built from the same code.

Documented rules used: action ``a`` in [-1, 1] maps linearly to ``low + (a + 1) / 2 * (high
- low)``; speeds 0.5 .. 10 m/s (set explicitly: see ``TABLE_KWARGS``); absolute aim -pi ..
pi; cut aim 0 is a full hit on the nearest object ball. Observation per ball ``(2 x / L -
1, 2 y / W - 1, 1)``, a potted ball ``(0, 0, 0)``. Reward ``+1`` per object ball potted,
``-1`` for a scratch, plus the optional ``reward_no_contact`` and ``reward_shaping`` times
the change of ``-sum(distance of each object ball to its nearest pocket) / diagonal``. A
scratched cue ball goes back to the head spot ``(L / 4, W / 2)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

L, W, R = 2.54, 1.27, 0.028575
A = 0.01 * 9.81  # rolling deceleration mu g
E_BALL = 0.95
SPEED_LOW, SPEED_HIGH = 0.5, 10.0
# The table and speed range these outcomes were worked out on: capture circles (a ball is
# potted when its centre enters the circle) and the earlier cushion restitution. They are
# passed to every env explicitly, so the expectations pin the decision process, not defaults.
TABLE_KWARGS: dict[str, Any] = {
    "table": {"pockets": "circles", "e_cushion": 0.85},
    "speed_range": (SPEED_LOW, SPEED_HIGH),
}
HEAD_SPOT = (L / 4, W / 2)
CORNERS = [(0.0, 0.0), (L, 0.0), (0.0, W), (L, W)]
# Capture circles' centres (for the shaping potential): corners and sides R behind the rail.
POCKET_CENTRES = [*CORNERS, (L / 2, -R), (L / 2, W + R)]


def speed_of(action: float) -> float:
    """The speed an action component decodes to (float32 as the action space holds it)."""
    a = float(np.float32(action))
    return SPEED_LOW + (a + 1.0) / 2.0 * (SPEED_HIGH - SPEED_LOW)


def action_for_speed(speed: float) -> float:
    return 2.0 * (speed - SPEED_LOW) / (SPEED_HIGH - SPEED_LOW) - 1.0


def observe(positions: list[tuple[float, float]], on_table: list[bool]) -> np.ndarray:
    out = []
    for (x, y), on in zip(positions, on_table, strict=True):
        out += [2 * x / L - 1, 2 * y / W - 1, 1.0] if on else [0.0, 0.0, 0.0]
    return np.array(out, dtype=np.float32)


def potential(positions: list[tuple[float, float]], on_table: list[bool]) -> float:
    total = 0.0
    for (x, y), on in list(zip(positions, on_table, strict=True))[1:]:
        if on:
            total += min(math.hypot(x - px, y - py) for px, py in POCKET_CENTRES)
    return -total / math.hypot(L, W)


@dataclass
class Shot:
    """A layout, an action and what must come out of one step."""

    name: str
    env_id: str
    kwargs: dict[str, Any]
    positions: list[tuple[float, float]]
    on_table: list[bool]
    action: tuple[float, float]
    reward: float
    final_positions: list[tuple[float, float]]  # after the shot (and any re-spot)
    final_on_table: list[bool]
    terminated: bool
    truncated: bool
    info: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.kwargs = {**TABLE_KWARGS, **self.kwargs}

    @property
    def observation(self) -> np.ndarray:
        return observe(self.final_positions, self.final_on_table)


def _straight_pot(name: str, object_ball: int, n_balls: int, shaping: float) -> Shot:
    """A full hit sends the object ball along the line cue -> corner (L, 0) into the pocket.

    The cue ball stops ``((1 - e) / 2 v_hit)^2 / 2a`` past the contact point. With two
    object balls, ball 1 is already potted and the shot is the last allowed one: the
    episode terminates (cleared) and is truncated at once.
    """
    cue = np.array([1.8, 0.5])
    u = (np.array([L, 0.0]) - cue) / math.hypot(L - 1.8, 0.5)
    obj = cue + 0.3 * u
    speed_action = action_for_speed(2.0)
    v = speed_of(speed_action)
    v_hit = math.sqrt(v * v - 2 * A * (0.3 - 2 * R))
    v_cue = (1 - E_BALL) / 2 * v_hit
    cue_rest = obj - 2 * R * u + v_cue**2 / (2 * A) * u
    positions = [tuple(cue), (0.3, 1.0), (0.6, 1.0)][: n_balls + 1]
    positions[object_ball] = tuple(obj)
    on = [True] * (n_balls + 1)
    if object_ball == 2:
        on[1] = False  # ball 1 already potted: the batch sees only balls 0 and 2
    before = potential(positions, on)
    final = list(positions)
    final[0] = tuple(cue_rest)
    final_on = list(on)
    final_on[object_ball] = False
    cleared = not any(final_on[1:])
    return Shot(
        name,
        "pool_env/OneBallRoll-v1" if n_balls == 1 else "pool_env/PoolRoll-v1",
        {"reward_shaping": shaping} if n_balls == 1 else {"n_balls": n_balls, "max_shots": 1},
        positions,
        on,
        (0.0, speed_action),
        1.0 + shaping * (potential(final, final_on) - before),
        final,
        final_on,
        terminated=cleared,
        truncated=n_balls > 1,
        info={"potted": (object_ball,), "scratch": False, "first_contact": object_ball},
    )


def _pot_and_scratch() -> Shot:
    """With e_ball = 0 the full hit leaves cue and object ball together: both drop in.

    The pair sticks (an inelastic impact leaves them pressed together) and rolls along the
    line into corner (L, 0): ball 1 is potted (+1) and the cue ball follows (-1) and goes
    back to the head spot; ball 2 stays. ``end_on_miss``: the scratch ends the episode.
    """
    cue = np.array([1.8, 0.5])
    u = (np.array([L, 0.0]) - cue) / math.hypot(L - 1.8, 0.5)
    positions = [tuple(cue), tuple(cue + 0.3 * u), (0.3, 1.0)]
    return Shot(
        "pot-and-scratch",
        "pool_env/PoolRoll-v1",
        {"n_balls": 2, "end_on_miss": True, "table": {"e_ball": 0.0}},
        positions,
        [True, True, True],
        (0.0, action_for_speed(2.0)),
        0.0,
        [HEAD_SPOT, positions[1], (0.3, 1.0)],
        [True, False, True],
        terminated=True,
        truncated=False,
        info={"potted": (1,), "scratch": True, "first_contact": 1},
    )


def _scratch() -> Shot:
    """Absolute aim -3 pi / 4 from (0.3, 0.3): down the diagonal into corner 0 at 1.45 m/s."""
    positions = [(0.3, 0.3), (2.0, 1.0)]
    return Shot(
        "scratch",
        "pool_env/OneBallRoll-v1",
        {"aim": "absolute"},
        positions,
        [True, True],
        (-0.75, -0.8),
        -1.0,
        [HEAD_SPOT, (2.0, 1.0)],
        [True, True],
        terminated=True,  # OneBall: a shot that pots nothing ends the episode
        truncated=False,
        info={"potted": (), "scratch": True, "first_contact": -1},
    )


def _miss() -> Shot:
    """Absolute aim 0 at the lowest speed: the cue ball rolls 0.5^2 / 2a along +x, alone."""
    positions = [(0.6, 0.635), (1.0, 1.1)]
    v = speed_of(-1.0)
    rest = (0.6 + v * v / (2 * A), 0.635)
    return Shot(
        "miss",
        "pool_env/PoolRoll-v1",
        {"aim": "absolute", "n_balls": 1, "max_shots": 1, "reward_no_contact": -0.5},
        positions,
        [True, True],
        (0.0, -1.0),
        -0.5,
        [rest, (1.0, 1.1)],
        [True, True],
        terminated=False,
        truncated=True,  # max_shots = 1
        info={"potted": (), "scratch": False, "first_contact": -1},
    )


SHOTS = [
    _straight_pot("pot", 1, 1, 0.0),
    _straight_pot("pot-shaped", 1, 1, 1.0),
    _straight_pot("pot-after-a-pot", 2, 2, 0.0),
    _pot_and_scratch(),
    _scratch(),
    _miss(),
]
