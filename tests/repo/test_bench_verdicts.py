"""The verdict comparison with pooltool (``bench/verdicts_vs_pooltool.py``) and its parts."""

from __future__ import annotations

import numpy as np
import pytest

from bench.engines.pooltool_engine import pooltool_python, run_worker
from bench.verdict_outcomes import from_pooltool, ours, summarise
from bench.verdict_rules import pooltool_verdict, rule_text
from bench.verdict_shots import YELLOW, Case, make_cases, pooltool_job, table_of
from bench.verdicts_vs_pooltool import SPACER, WORKER

BLACK, PINK = YELLOW + 5, YELLOW + 4


def _carom() -> Case:
    return Case("three_cushion", 0, (0, 1, 2), np.zeros((3, 2)), 0, 0.0, 1.0, (0.0, 0.0))


def _snooker(phase: str, on: list[int], nominated: int = -1) -> Case:
    state = {"phase": phase, "on": on, "nominated": nominated}
    return Case("snooker", 0, (0, 1, 2), np.zeros((3, 2)), 0, 0.0, 1.0, (0.0, 0.0), state)


def test_a_cushion_at_the_instant_of_the_second_contact_counts():
    """As ``is_point`` counts them (``time <= t``): the third rail ties with the contact."""
    events = [
        [0.5, "linear", 0, -1],
        [1.0, "ball", 0, 1],
        [2.0, "linear", 0, -1],
        [3.0, "ball", 0, 2],
        [3.0, "linear", 0, -1],  # logged after the contact, at the same instant
        [4.0, "linear", 0, -1],
    ]
    s = summarise(events, (0, 1, 2), 0, {})
    assert (s.first, s.second, s.cushions_second, s.circular_second) == (1, 2, 3, 0)
    assert s.rows["cushions_at_second"][0] == 3
    assert s.rows["cushions_after_contact"][0] == 3  # the rail before the first contact not
    assert rule_text(_carom(), s) == {"point": True}
    s2 = summarise(events[:3] + [[3.0, "ball", 0, 2]], (0, 1, 2), 0, {})
    assert rule_text(_carom(), s2) == {"point": False}  # two cushions only


def test_rule_text_snooker_penalties_and_points():
    """The WPBSA values: the highest of the ball on, the first ball hit and the balls potted."""
    pot = [[1.0, "ball", 0, BLACK], [2.0, "ball", BLACK, 1], [3.0, "pocket", 1, 4]]
    reds = _snooker("reds", [1, 2])
    verdict = rule_text(reds, summarise(pot, (0, 1, 2, BLACK), 0, {}))
    assert verdict == {"foul": True, "penalty": 7, "points": 0, "turn_over": True}
    fair = [[1.0, "ball", 0, 1], [2.0, "pocket", 1, 0], [2.5, "ball", 0, 2], [3.0, "pocket", 2, 1]]
    verdict = rule_text(reds, summarise(fair, (0, 1, 2), 0, {}))
    assert verdict == {"foul": False, "penalty": 0, "points": 2, "turn_over": False}
    miss = summarise([], (0, PINK, BLACK), 0, {})
    assert rule_text(_snooker("sequence", [PINK]), miss)["penalty"] == 6
    assert rule_text(_snooker("sequence", [YELLOW]), miss)["penalty"] == 4
    called = _snooker("colour", [PINK], PINK)
    pink_in = summarise([[1.0, "ball", 0, PINK], [2.0, "pocket", PINK, 5]], (0, PINK), 0, {})
    assert rule_text(called, pink_in) == {"foul": False, "penalty": 0, "points": 6,
                                          "turn_over": False}  # fmt: skip
    scratch = summarise([[1.0, "ball", 0, PINK], [2.0, "pocket", 0, 5]], (0, PINK), 0, {})
    assert rule_text(called, scratch)["penalty"] == 6


@pytest.mark.parametrize("game", ["three_cushion", "snooker"])
def test_pooltool_judges_a_few_shots_as_the_rule_text_does(game):
    """The ruleset of pooltool on its outcomes equals the rule text.

    And three-cushion's physics equals ours (pocketless tables of the same models: every
    contact and final position).
    """
    if pooltool_python() is None:
        pytest.skip(
            "no pooltool virtualenv at .bench-venvs/pooltool (bash bench/setup_pooltool.sh)"
        )
    table = table_of(game)
    cases = make_cases(game, 6, 7, lambda case: ours(case, table).point_made())
    out = run_worker(WORKER, pooltool_job(game, cases, min_dist=SPACER), total_timeout=600.0)
    assert out["available"], out.get("reason")
    assert out["pooltool"] == "0.6.0"
    for case, res in zip(cases, out["results"], strict=True):
        assert res["error"] is None
        theirs = from_pooltool(case, table, res)
        assert pooltool_verdict(game, res["verdict"]) == rule_text(case, theirs), case.index
        if game == "three_cushion":
            mine = ours(case, table)
            assert mine.key(game) == theirs.key(game)
            gap = max(np.hypot(*np.subtract(mine.final[b], theirs.final[b])) for b in case.balls)
            assert gap < 1e-6


@pytest.mark.parametrize("game", ["three_cushion", "snooker"])
def test_our_game_judges_pooltools_outcomes_as_pooltool_does(game):
    """Our game's rules, through its env, on pooltool's own outcomes: pooltool's verdicts.

    And on our own physics, where the outcome is the same, the same verdict too.
    """
    from bench.verdict_games import game_judge

    if pooltool_python() is None:
        pytest.skip("no pooltool virtualenv (bash bench/setup_pooltool.sh)")
    judge = game_judge(game)
    if judge is None:
        pytest.skip(f"game={game!r} is not in this tree")
    table = table_of(game)
    cases = make_cases(game, 8, 11, lambda case: ours(case, table).point_made())
    out = run_worker(WORKER, pooltool_job(game, cases, min_dist=SPACER), total_timeout=600.0)
    assert out["available"], out.get("reason")
    for case, res in zip(cases, out["results"], strict=True):
        theirs = from_pooltool(case, table, res)
        expected = pooltool_verdict(game, res["verdict"])
        assert judge(case, theirs) == expected, case.index
        if ours(case, table).key(game) == theirs.key(game):
            assert judge(case, None) == expected, case.index
