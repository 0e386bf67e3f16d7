"""What one action plays, and what the rules let the next one play: two public value types.

:class:`Shot` is an action's image on the table (:func:`pool_env.game.codec.decode_action`
returns it and :func:`~pool_env.game.codec.encode_action` takes it). :class:`ShotConstraints`
is the rules' answer to "what may the next shot do" (the game's
:meth:`~pool_env.game.ruleset.Ruleset.constraints`, read from an observation, as
pooltool's ``ShotConstraints`` is read from its game state): the agents ask it instead of
restating a game's rules.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from pool_env.game.checks import is_integer, parse_bool


def _index(name: str, value: Any, low: int) -> int:
    """``value`` as an ``int`` if it is an integer (not a bool) ``>= low``, else ValueError."""
    if not is_integer(value) or value < low:
        raise ValueError(f"Shot.{name} must be an integer >= {low}, got {value!r}")
    return int(value)


@dataclass(frozen=True)
class Shot:
    """A shot as the table sees it (the inverse image of an action).

    Attributes:
        angle: The cue's aim, radians counter-clockwise from +x (on a spin table the ball
            leaves at it plus the squirt of side english).
        speed: The cue ball's speed (m/s).
        tip: The cue tip's axis offset ``(side, vertical)`` in fractions of R (spin
            tables; ``(0.0, 0.0)`` on a roll table).
        cue: Rules, cue ball in hand: where it is placed (m); ``None`` otherwise.
        pocket: Rules: the called pocket (an integer index into ``table.pockets``): the 8's
            in 8-ball, the called ball's in 10-ball.
        ball: 10-ball: the called ball (an integer, ``None`` when encoding: the ball on);
            ``None`` in the other games.
        push_out: 9-ball and 10-ball: the shot is declared a push-out (only on the shot
            right after a legal break: :attr:`ShotConstraints.push_out`).
        pass_back: 9-ball and 10-ball: the incoming player uses the option to hand the
            table back instead of shooting (:attr:`ShotConstraints.option`); the other
            parts are then ignored, no shot is played.
    """

    angle: float
    speed: float
    tip: tuple[float, float] = (0.0, 0.0)
    cue: tuple[float, float] | None = None
    pocket: int = 0
    ball: int | None = None
    push_out: bool = False
    pass_back: bool = False

    def __post_init__(self) -> None:
        """Refuse a call that is no index (``pocket=2.5``, ``pocket=True``) or flag.

        The ranges (a pocket of the table, a ball of the game) are the encoder's to check
        (:func:`pool_env.encode_action`): a shot does not know its table.

        Raises:
            ValueError: Naming the field and what it takes.
        """
        object.__setattr__(self, "pocket", _index("pocket", self.pocket, 0))
        if self.ball is not None:
            object.__setattr__(self, "ball", _index("ball", self.ball, 1))
        object.__setattr__(self, "push_out", parse_bool("Shot.push_out", self.push_out))
        object.__setattr__(self, "pass_back", parse_bool("Shot.pass_back", self.pass_back))


@dataclass(frozen=True)
class ShotConstraints:
    """What the next shot may do under the game's rules, from the shooter's seat.

    Attributes:
        first_balls: The object balls the cue ball may legally hit first, ascending
            (solitaire: every object ball on the table; 9-ball: the ball on; 8-ball: the
            shooter's group, or the 8 once it is cleared; the break: as the rules say).
        ball_in_hand: The shooter places the cue ball (``Shot.cue``) before the shot.
        behind_head_string: Ball in hand behind the head string only (the kitchen).
        placement: With the cue ball in hand, the box its centre may go in,
            ``((x_low, x_high), (y_low, y_high))`` in metres (behind the head string:
            ``x_high`` is the string); ``None`` without ball in hand.
        breaking: The shot is a break (its speed range is the break's).
        speed_range: The cue speeds (m/s) that the action's speed component spans for
            this shot.
        call_pocket: The called pocket (``Shot.pocket``) counts: 8-ball's 8, every 10-ball
            shot after the break.
        push_out: The shooter may declare a push-out (``Shot.push_out``): 9-ball and
            10-ball, the shot right after a legal break.
        call_ball: The shot calls a ball (``Shot.ball``): 10-ball after the break.
        option: The shooter may hand the table back instead of shooting
            (``Shot.pass_back``): after the opponent's push-out, or a 10-ball shot that
            potted a ball without its call.
    """

    first_balls: tuple[int, ...]
    speed_range: tuple[float, float]
    ball_in_hand: bool = False
    behind_head_string: bool = False
    placement: tuple[tuple[float, float], tuple[float, float]] | None = None
    breaking: bool = False
    call_pocket: bool = False
    push_out: bool = False
    call_ball: bool = False
    option: bool = False
