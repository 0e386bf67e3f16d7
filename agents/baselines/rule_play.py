"""The rules' own choices, made one way for every agent of the game ids: calls, option, push-out.

What the game ids let a shooter decide besides the strike, written once for
:class:`agents.baselines.game_agents.GameGhostBallAgent` and every agent built on it (the
search, the learned rack agent, the lookahead):

* **The action's columns** (:func:`rule_action`): the strike ``(aim, speed[, side,
  vertical])`` laid out in the game's action, with the placement of a cue ball in hand,
  the called pocket, 10-ball's called ball and 9-ball and 10-ball's option column, the tip
  where ``config.tip_columns`` puts it (8-ball 5 columns, 9-ball 6, 10-ball 7, and 2 more
  on a spin id).
* **Calls** (10-ball): an agent calls the object ball it aims to pot and that ball's
  pocket; a shot planned at no pocket (a safety, the fallback's full hit) calls the ball on
  and pocket 0, a call it does not expect to make.
* **The option** (:func:`take_table`): the incoming player after the opponent's push-out,
  or in 10-ball after a legal shot that potted a ball without its call, plays on when the
  layout's best pot chance (the most forgiving clear shot under the aim noise:
  :meth:`~agents.baselines.game_agents.GameGhostBallAgent.best_chance`, one estimate for
  every agent built on it) is at least :data:`TAKE_CHANCE`, else hands the table back. Why
  one half: with the same estimate for both players, shooting is worth about ``p`` to the
  chooser and handing back about ``1 - p`` (the opponent then shoots the same shot), so the
  chooser plays exactly when ``p >= 1/2``.
* **The push-out** (:func:`push_value`, :func:`push_outcomes`): on the shot right after a
  legal break, against an opponent, the agent compares its best shot's chance with the
  best of a few soft hits across the ball on's face (:data:`PUSH_OFFSETS` x
  :data:`PUSH_SPEEDS`, each played out on the simulator without noise; the cut aim of the
  game ids can only aim at the ball on, and a push-out may touch it or whatever lies in the
  way), each valued by the leave's best pot chance ``c`` (for the ball on then) and the
  opponent's option as above: the opponent hands back a leave with ``c < 1/2`` (the pusher
  then shoots it: worth ``c``) and takes one with ``c >= 1/2`` (worth ``1 - c`` to the
  pusher), so a push is worth at most one half, most for a leave as hard for either
  player. It pushes when that beats its shot. With one player it never pushes: the agent
  shoots on after its own push-out (in run-out mode too), so it would be a free second
  shot with nobody to take the option, not the game; so every one-player figure is the
  game's without it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from pool_env import GameConfig, shoot
from pool_env.game.codec import encode_ball, encode_pocket

#: The rotation games (the ball on is the lowest; the money ball wins).
ROTATION = ("nine", "ten")
#: The option: play on at this chance or more, else hand the table back (module doc).
TAKE_CHANCE = 0.5
#: Where the push-out's cue ball passes the ball on, in ball diameters across its face
#: (the lookahead's grid too): from a full hit to a thin graze either side.
PUSH_OFFSETS = (-0.85, -0.6, -0.3, 0.0, 0.3, 0.6, 0.85)
#: Cue speeds (m/s) of the push-outs: soft, to move the cue ball a metre or two and the
#: ball on little.
PUSH_SPEEDS = (0.6, 0.9, 1.3)


def rule_action(
    config: GameConfig,
    strike_part: NDArray[np.floating],
    place: tuple[float, float] | NDArray[np.floating] = (0.0, 0.0),
    pocket: int = -1,
    ball: int | None = None,
    option: bool = False,
) -> NDArray[np.float64]:
    """The game's full action for a strike and the rules' parts.

    Args:
        config: The env's config (its ruleset and tip columns).
        strike_part: ``(aim, speed)`` or, on a spin env, ``(aim, speed, side, vertical)``
            action components (a roll strike on a spin env plays centre ball).
        place: The placement components (``action[2]``, ``action[3]``; used with the cue
            ball in hand).
        pocket: The called pocket (-1: none; the column is then 0, a call that does not count).
        ball: 10-ball: the called ball, required (ignored by the other games).
        option: 9-ball and 10-ball: declare a push-out, or hand the table back when the
            shooter has the option (:func:`take_table`).

    Returns:
        ``(config.action_size,)`` float64.

    Raises:
        ValueError: On 10-ball without a called ball (a column left at 0 would call the
            middle ball, not the one planned).
    """
    ruleset = config.ruleset
    if ruleset.calls_ball and ball is None:
        raise ValueError(f"game={config.game!r} calls a ball on every shot: pass ball")
    out = np.zeros(config.action_size)
    part = np.asarray(strike_part, dtype=np.float64)
    out[0], out[1] = part[0], part[1]
    out[2], out[3] = place[0], place[1]
    if pocket >= 0:
        out[4] = encode_pocket(config, pocket)
    if ruleset.calls_ball:
        out[ruleset.ball_column] = encode_ball(config, int(ball))
    if ruleset.has_option:
        out[ruleset.option_column] = 1.0 if option else -1.0
    if config.tip_columns is not None and part.shape[0] >= 4:
        out[list(config.tip_columns)] = part[2:4]
    return out


def take_table(chance: float) -> bool:
    """The option: play on (``True``) or hand the table back, by the best shot's chance."""
    return chance >= TAKE_CHANCE


def push_value(leave_chance: float) -> float:
    """What a push-out leaving a shot of pot chance ``leave_chance`` is worth to the pusher.

    The opponent takes the table when the chance is at least :data:`TAKE_CHANCE` (the
    pusher is then left ``1 - c``) and hands it back otherwise (the pusher shoots: ``c``).
    """
    c = float(leave_chance)
    return c if not take_table(c) else 1.0 - c


def may_push(config: GameConfig, players: int) -> bool:
    """Whether an agent pushes out at all: against an opponent only (module doc)."""
    return config.ruleset.has_option and players == 2


def face_angles(
    positions: NDArray[np.float64], ball: int, radius: float, offsets: tuple[float, ...]
) -> list[float]:
    """Directions of the cue ball (ball 0) that pass ``ball`` at ``offsets`` across its face.

    Each offset is in ball diameters from a full hit (``+-1``: a graze); the cue ball touching
    ``ball`` has none (an empty list).
    """
    gap = positions[ball] - positions[0]
    dist = float(np.hypot(*gap))
    if dist <= 2.0 * radius:
        return []
    centre = math.atan2(gap[1], gap[0])
    return [centre + math.asin(min(1.0, f * 2.0 * radius / dist)) for f in offsets]


@dataclass(frozen=True)
class PushOutcome:
    """A push-out strike and the layout it leaves (the simulator's, without noise).

    Attributes:
        angle: Its direction (rad from +x).
        speed: Its cue speed (m/s).
        positions: ``(N, 2)`` the balls after it.
        on_table: ``(N,)`` the balls left on the table.
    """

    angle: float
    speed: float
    positions: NDArray[np.float64]
    on_table: NDArray[np.bool_]


def push_outcomes(
    config: GameConfig, positions: NDArray[np.float64], on_table: NDArray[np.bool_], ball: int
) -> list[PushOutcome]:
    """The push-outs tried: soft centre-ball hits across ``ball``'s face, played out.

    :data:`PUSH_OFFSETS` x :data:`PUSH_SPEEDS` toward the ball on (every aim mode can play a
    direction at it; the cut aim only those), each on the simulator without noise
    (:func:`pool_env.shoot`: a push-out may touch any ball, or none, and it moves what it
    touches). A strike that scratches (a foul even on a push-out) or pots the money ball
    (re-spotted: not followed here) is left out.
    """
    table, money = config.table, config.ruleset.money_ball
    rows = np.flatnonzero(on_table)
    low, high = config.speed_range
    out: list[PushOutcome] = []
    for angle in face_angles(positions, ball, table.ball_radius, PUSH_OFFSETS):
        for speed in PUSH_SPEEDS:
            if not low <= speed <= high:
                continue
            result = shoot(table, positions[rows], angle, speed, record=False)
            dropped = result.pocketed >= 0
            if dropped[0] or (money in rows and dropped[np.searchsorted(rows, money)]):
                continue
            after, left = positions.copy(), on_table.copy()
            after[rows] = result.positions
            left[rows[dropped]] = False
            out.append(PushOutcome(angle, speed, after, left))
    return out
