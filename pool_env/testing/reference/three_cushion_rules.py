"""Three-cushion's rules in plain Python, from the rule text, for checking the game package.

Written from the UMB World Rules of Carom Billiard (art. 23, 24, 25, 27, 29, 41, 83) and
sharing no code with :mod:`pool_env.game.games.three_cushion`: it judges one shot from its
event list (as pooltool's ``three_cushion.is_point`` does), not from the simulator's
per-ball rows, so comparing the two checks the rows as well as the rules.

A state is a dict: ``shooter`` (0 white, 1 yellow), ``score`` and ``innings`` (per
player), ``run``, ``breaking``, ``equalizing``, ``winner`` (-1, 0, 1, or 2 for a draw).
"""

from __future__ import annotations

from typing import Any

RED = 2


def is_point(events: list[tuple[float, str, int, int]], cue: int) -> tuple[bool, int, int, int]:
    """Art. 83: the cue ball met both object balls, three cushions before the second.

    Returns:
        ``(point, first ball, second ball, cushions before the second)`` (-1: none).
    """
    met: list[int] = []
    when = None
    for time, kind, i, j in events:
        if kind == "ball" and cue in (i, j):
            other = j if i == cue else i
            if other not in met:
                met.append(other)
                if len(met) == 2:
                    when = time
                    break
    first = met[0] if met else -1
    if when is None:
        return False, first, -1, -1
    rails = sum(
        1
        for time, kind, i, _ in events
        if kind in ("cushion", "jaw", "point") and i == cue and time <= when
    )
    return rails >= 3, first, met[1], rails


def judge_shot(
    state: dict[str, Any],
    events: list[tuple[float, str, int, int]],
    target: int,
    inning_limit: int,
    equalizing_inning: bool,
    players: int,
) -> dict[str, Any]:
    """The state after one shot, with ``point``, ``foul``, ``over`` (the episode's end)."""
    new = {k: (list(v) if isinstance(v, list | tuple) else v) for k, v in state.items()}
    striker = state["shooter"]
    point, first, _, _ = is_point(events, striker)
    foul = bool(state["breaking"]) and first != RED  # art. 23: the red first on the break
    point = point and not foul  # art. 41: a foul's point does not count
    new["breaking"] = False
    if point:
        new["score"][striker] += 1
        new["run"] += 1
    else:
        new["run"] = 0
    at_target = point and new["score"][striker] >= target
    over = False
    if players == 1:  # one inning: over at the miss (or the target)
        over = (not point) or at_target
        if at_target:
            new["winner"] = 0
        return {**new, "point": point, "foul": foul, "over": over}
    opponent = 1 - striker
    if at_target:
        if striker == 1:
            new["winner"] = 2 if state["equalizing"] else 1
            over = True
        elif equalizing_inning:  # the second player's inning to equal the innings
            new["equalizing"] = True
            new["shooter"] = 1
            new["innings"][1] += 1
            new["run"] = 0
        else:
            new["winner"] = 0
            over = True
    elif not point:
        if striker == 1 and state["equalizing"]:
            new["winner"] = 0
            over = True
        elif striker == 1 and inning_limit > 0 and state["innings"][1] >= inning_limit:
            s0, s1 = new["score"]
            new["winner"] = 0 if s0 > s1 else 1 if s1 > s0 else 2
            over = True
        else:
            new["shooter"] = opponent
            new["innings"][opponent] += 1
    return {**new, "point": point, "foul": foul, "over": over}
