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
  or in 10-ball after a legal shot that potted a ball without its call, plays on when its
  best shot's chance (a pot chance for ghost-ball, a win chance for the lookahead) is at
  least :data:`TAKE_CHANCE`, else hands the table back. Why one half: with the same
  estimate for both players, shooting is worth about ``p`` to the chooser and handing back
  about ``1 - p`` (the opponent then shoots the same shot), so the chooser plays exactly
  when ``p >= 1/2``.
* **The push-out** (:func:`push_value`, :func:`push_rolls`): on the shot right after a
  legal break, against an opponent, the agent compares its best shot's chance with the
  best soft roll of the cue ball (no contact, no scratch: a legal push-out) it can find,
  each valued by the leave's best pot chance ``c`` on the ball on and the opponent's
  option as above: the opponent hands back a leave with ``c < 1/2`` (the pusher then
  shoots it: worth ``c``) and takes one with ``c >= 1/2`` (worth ``1 - c`` to the
  pusher), so a roll is worth ``min(c, 1 - c)``-like, at most one half, best for a leave
  that is as hard for either player. It pushes when that beats its shot.
  With one player it never pushes: in run-out mode a push-out ends the run (it does not
  keep the table), and in practice it would be a free second placement with nobody to
  take the option, not the game; so every one-player figure is the game's without it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from agents.baselines.cue_path import after_contact, strike
from agents.baselines.geometry import PocketMouths, path_clear
from agents.baselines.trace import Trace, roll_trace
from pool_env import GameConfig
from pool_env.game.codec import encode_pocket
from pool_env.game.rulesets.wpa import encode_ball

#: The rotation games (the ball on is the lowest; the money ball wins).
ROTATION = ("nine", "ten")
#: The option: play on at this chance or more, else hand the table back (module doc).
TAKE_CHANCE = 0.5
#: Directions of the push-out rolls (evenly around the cue ball).
PUSH_DIRECTIONS = 24
#: Cue speeds (m/s) of the push-out rolls: soft, so that the cue ball goes where it is
#: traced (a rolling ball a metre or two, no rail or one).
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
        ball: 10-ball: the called ball (ignored by the other games).
        option: 9-ball and 10-ball: declare a push-out, or hand the table back when the
            shooter has the option (:func:`take_table`).

    Returns:
        ``(config.action_size,)`` float64.
    """
    ruleset = config.ruleset
    out = np.zeros(config.action_size)
    part = np.asarray(strike_part, dtype=np.float64)
    out[0], out[1] = part[0], part[1]
    out[2], out[3] = place[0], place[1]
    if pocket >= 0:
        out[4] = encode_pocket(config, pocket)
    if ruleset.calls_ball and ball is not None:
        out[ruleset.ball_column] = encode_ball(ruleset.n_objects, int(ball))
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


@dataclass(frozen=True)
class PushRoll:
    """A soft roll of the cue ball that touches no ball and stays out of the pockets.

    Attributes:
        angle: Its direction (rad from +x).
        speed: Its cue speed (m/s).
        rest: Where the cue ball stops, ``(2,)``.
    """

    angle: float
    speed: float
    rest: NDArray[np.float64]


def push_rolls(
    config: GameConfig,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
) -> list[PushRoll]:
    """The push-out rolls that touch no ball: :data:`PUSH_DIRECTIONS` x :data:`PUSH_SPEEDS`.

    Each traced centre ball in closed form (:func:`agents.baselines.cue_path.after_contact`
    from the strike on a spin table, :func:`agents.baselines.trace.roll_trace` on a roll
    table), kept when every leg clears the other balls by a diameter and the cue ball does
    not drop: no ball moves, so the layout after it is the same with the cue ball at
    ``rest``.
    """
    table = config.table
    r = table.ball_radius
    others = np.array([positions[j] for j in range(1, positions.shape[0]) if on_table[j]]).reshape(
        -1, 2
    )
    low, high = config.speed_range
    out: list[PushRoll] = []
    for k in range(PUSH_DIRECTIONS):
        angle = 2.0 * math.pi * k / PUSH_DIRECTIONS
        heading = np.array([math.cos(angle), math.sin(angle)])
        for speed in PUSH_SPEEDS:
            if not low <= speed <= high:
                continue
            trace = _roll(config, mouths, positions[0], angle, heading, speed)
            if trace.pocket >= 0:
                continue
            # A diameter and a little: the traced path is the model's, the cue ball's true
            # one a few millimetres off it, and a touch would make the push a shot.
            if all(path_clear(p, q, others, 2.1 * r) for p, q in trace.legs):
                out.append(PushRoll(angle, speed, np.array(trace.rest)))
    return out


def _roll(
    config: GameConfig,
    mouths: PocketMouths,
    start: NDArray[np.float64],
    angle: float,
    heading: NDArray[np.float64],
    speed: float,
) -> Trace:
    """The cue ball's path from a centre-ball strike, as the table's model plays it."""
    if config.spin:
        return after_contact(
            config.table, mouths, start, strike(config.table, angle, speed, (0.0, 0.0))
        )
    return roll_trace(config.table, mouths, start, speed * heading)
