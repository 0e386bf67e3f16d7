"""Verdicts of one shot, in one form: pooltool's, the rule text's, and our games'.

A verdict is a dict: three-cushion ``{"point"}``; snooker ``{"foul", "penalty", "points",
"turn_over"}`` (``penalty``: the points the opponent receives for a foul, 0 for none;
``points``: the striker's points for a legal shot).

:func:`rule_text` is a third opinion written here from the rule texts alone (UMB article
on the point, WPBSA Section 3 rules on fouls and scoring), used only to say which engine a
disagreement proves wrong; it shares no code with either engine's rules.
"""

from __future__ import annotations

from typing import Any

from bench.verdict_outcomes import Summary
from bench.verdict_shots import YELLOW, Case


def value(ball: int) -> int:
    """A snooker ball's value (our numbering): red 1, yellow 2 .. black 7; the white 4.

    The white is not a scoring ball: it is given 4, the least penalty, so that a foul's
    penalty is the largest value involved.
    """
    if ball == 0:
        return 4
    return 1 if ball < YELLOW else ball - YELLOW + 2


def rule_text(case: Case, outcome: Summary) -> dict[str, Any]:
    """The verdict of the rule texts on ``outcome`` from ``case``'s state.

    Three-cushion (UMB): a point when the cue ball has met both object balls and touched
    at least three cushions before it meets the second one (an impact at the instant of
    that meeting counts, as it cannot be told apart).

    Snooker (WPBSA Section 3): a foul when the cue ball is potted, touches no ball, first
    touches a ball not on, or a ball not on is potted; the penalty is the value of the
    ball on (the nominated colour, the lowest colour in the sequence, 1 on reds), of the
    ball first touched or of any ball potted, whichever is highest, and at least 4. A fair
    stroke scores the reds potted (on reds) or the colour on's value, and the striker plays
    on while a ball was potted fairly.
    """
    if case.game == "three_cushion":
        point = outcome.second >= 0 and outcome.cushions_second + outcome.circular_second >= 3
        return {"point": bool(point)}
    on = set(case.state["on"])
    potted = [b for b, _ in outcome.potted]
    foul = (
        0 in potted
        or outcome.first < 0
        or outcome.first not in on
        or any(b not in on for b in potted)
    )
    if foul:
        ball_on = 1 if case.state["phase"] == "reds" else value(case.state["on"][0])
        involved = [ball_on, *(value(b) for b in potted)]
        if outcome.first >= 0:
            involved.append(value(outcome.first))
        return {"foul": True, "penalty": max(4, *involved), "points": 0, "turn_over": True}
    points = sum(value(b) for b in potted)
    return {"foul": False, "penalty": 0, "points": points, "turn_over": not potted}


def pooltool_verdict(game: str, verdict: dict[str, Any]) -> dict[str, Any]:
    """Pooltool's ``build_shot_info`` read by the worker, in this module's form."""
    if game == "three_cushion":
        return {"point": verdict["point"]}
    return {
        "foul": not verdict["legal"],
        "penalty": verdict["penalty"],
        "points": verdict["points"],
        "turn_over": verdict["turn_over"],
    }
