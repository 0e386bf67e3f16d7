"""The WPA games' section of the config, and their reward terms."""

from __future__ import annotations

from dataclasses import dataclass

from pool_env.game.ruleset import RulesSection

#: Default break speed range (m/s) of the rules' break shot: a pro breaks at 11-13 m/s,
#: amateurs lower (Dr. Dave's "typical speeds" FAQ; ``docs/physics.md``).
DEFAULT_BREAK_SPEED_RANGE = (8.0, 12.0)

#: The WPA games' reward terms and their default scales, in the judge's order: per object
#: ball potted on a legal shot that counts its pots, a foul, and the rack won (lost: minus
#: the scale).
REWARD_TERMS: dict[str, float] = {"pot": 1.0, "foul": -1.0, "win": 1.0}


@dataclass(frozen=True)
class WpaRules(RulesSection):
    """The rules section of 9-ball, 10-ball and 8-ball.

    Attributes:
        game: ``"nine"``, ``"ten"`` or ``"eight"``.
        end_on_foul: A foul, or a legal shot that does not keep the table, ends the
            episode (run-out mode), but for a legal push-out, after which the agent shoots
            on; else play goes on (practice mode).
        break_speed_range: Speeds (m/s) of ``action[1] = -1`` and ``+1`` on a break.
        push_out: The shot after a legal break may be a push-out, the opponent then having
            the option. ``None``: the game's rule (yes in 9-ball and 10-ball; 8-ball has
            none). ``False`` (9-ball only) plays 9-ball as ``pool_env/NineBallGame-v1``
            did before the push-out came, with the action and observation of that time
            (no option column, no option features).
    """

    game: str = "nine"
    end_on_foul: bool = False
    break_speed_range: tuple[float, float] = DEFAULT_BREAK_SPEED_RANGE
    push_out: bool | None = None
