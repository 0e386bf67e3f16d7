"""The scoreboard: a policy on the smoke suite end to end, its results files, and its page.

``python -m agents.scoreboard`` is run here on the ``smoke`` suite (a few episodes a task),
against the committed results files of ``results/scoreboard/`` as references, so that the
command keeps working and the committed files stay reproducible: random play, re-played,
gives the first episodes of its committed file exactly.
"""

from __future__ import annotations

import contextlib
import io
import json
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from gymnasium import spaces

from agents.baselines.random_agent import ConstantAgent
from agents.evaluation.duels import play_duels
from agents.evaluation.runouts import play_racks
from agents.scoreboard.command import PAGE, main
from agents.scoreboard.figures import figure, normalized
from agents.scoreboard.leaderboard import leaderboard_page, score_table
from agents.scoreboard.policies import resolve_policy
from agents.scoreboard.results import (
    dump_results,
    load_results,
    merge_results,
    references,
    score_policy,
)
from agents.scoreboard.suite import SUITES, TASKS, suite_tasks

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "results" / "scoreboard"
THIS = "tests.agents.test_scoreboard"


class _Fixed:
    """An agent that declares the OneBall-v1 spaces and always plays one action."""

    observation_space = spaces.Box(-1.0, 1.0, (6,), np.float32)
    action_space = spaces.Box(-1.0, 1.0, (4,), np.float32)

    def predict(self, obs: Any, state: Any = None, episode_start: Any = None,
                deterministic: bool = True) -> tuple[Any, Any]:  # fmt: skip
        return np.array([0.0, 0.5, 0.0, 0.0], dtype=np.float32), state


def oneball_only(env: Any) -> _Fixed:
    """A factory (the module:attr protocol) whose agent reads OneBall-v1's spaces only."""
    return _Fixed()


def refuses_games(env: Any) -> ConstantAgent:
    """A factory that refuses every game id by its ValueError, and plays the others."""
    if getattr(env.unwrapped.config.ruleset, "has_rack", False):
        raise ValueError("refuses_games plays no rack")
    return ConstantAgent(env, (0.0, 1.0, 0.0, 0.0))


def not_an_agent(env: Any) -> int:
    """A factory that breaks the protocol: it returns no agent."""
    return 3


@pytest.fixture(scope="module")
def committed() -> dict[str, dict[str, Any]]:
    return load_results(RESULTS)


@pytest.fixture(scope="module")
def random_smoke(tmp_path_factory: pytest.TempPathFactory) -> tuple[dict[str, Any], str]:
    """``python -m agents.scoreboard random --suite smoke --save FILE``, its file and output."""
    out = tmp_path_factory.mktemp("smoke") / "random.smoke.json"
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed):
        code = main(["random", "--suite", "smoke", "--results", str(RESULTS), "--save", str(out)])
    assert code == 0
    return json.loads(out.read_text()), printed.getvalue()


def test_random_replays_its_committed_episodes(random_smoke, committed) -> None:
    """Every figure is a rate in [0, 1]; random's smoke run is its committed file's start."""
    data, _ = random_smoke
    full = committed[str(RESULTS / "random.json")]
    assert list(data["tasks"]) == [task.name for task in TASKS]
    for task, n in suite_tasks("smoke"):
        entry = data["tasks"][task.name]
        assert entry["status"] == "ok" and entry["episodes"] == n
        for key in (task.figure, *task.beside):
            estimate = figure(key, entry["record"], n)
            assert 0.0 <= estimate.low <= estimate.value <= estimate.high <= 1.0
        # the same seeds and the same actions: the committed record's first n episodes
        for name, values in entry["record"].items():
            assert values == full["tasks"][task.name]["record"][name][:n], (task.name, name)


def test_random_scores_zero_only_where_the_best_beats_it(random_smoke, committed) -> None:
    data, printed = random_smoke
    zeros = undefined = 0
    for task, n in suite_tasks("smoke"):
        random, best = references(committed, task, n)
        value = figure(task.figure, data["tasks"][task.name]["record"], n).value
        assert value == random
        score = normalized(value, random, best)
        if best > random:
            assert score == 0.0
            zeros += 1
        else:  # a tie on so few episodes: no score of a zero divisor
            assert score is None
            undefined += 1
    assert zeros >= 1  # ghost-ball pots where random does not on OneBall's first episodes
    assert "| oneball | `pool_env/OneBall-v1` | none | 700000..700003 | 4 |" in printed
    assert printed.count("| 0.00 |") == zeros and printed.count("| - |") == undefined


def test_the_saved_file_round_trips(random_smoke, committed, tmp_path: Path) -> None:
    data, printed = random_smoke
    text = dump_results(data)
    assert json.loads(text) == data and dump_results(json.loads(text)) == text
    (tmp_path / "random.smoke.json").write_text(text)
    loaded = load_results(tmp_path)
    assert list(loaded.values()) == [data]
    assert score_table(loaded[str(tmp_path / "random.smoke.json")], committed) in printed
    entry = data["tasks"]["oneball"]
    assert entry["command"].startswith("python -m agents.scoreboard random --suite smoke")
    assert len(entry["load"]) == 6 and entry["git"] and entry["date"].endswith("UTC")


def test_a_task_the_policy_cannot_play_reads_na() -> None:
    """The factory's spaces (OneBall-v1's) against the others': n/a, each with its reason."""
    data = score_policy(resolve_policy(f"{THIS}:oneball_only"), "smoke", "test")
    tasks = data["tasks"]
    assert tasks["oneball"]["status"] == "ok"
    assert tasks["position-3"] == {**tasks["position-3"], "status": "n/a"}
    assert "observations of shape (6,)" in tasks["position-3"]["reason"]
    assert "(12,)" in tasks["position-3"]["reason"]
    assert "(48,)" in tasks["nine-duel"]["reason"] and "record" not in tasks["nine-duel"]
    table = score_table(data, {})
    assert "| position-5 | `pool_env/Pool-v1` `{n_balls: 5, end_on_miss: true}` |" in table
    assert "n/a: tests.agents.test_scoreboard:oneball_only takes observations" in table


def test_a_refusing_factory_and_player_read_na() -> None:
    policy = resolve_policy(f"{THIS}:refuses_games")
    games = [task for task in TASKS if task.runner != "episodes"]
    assert all(policy.refusal(task) == "refuses_games plays no rack" for task in games)
    assert policy.refusal(TASKS[0]) is None
    search = resolve_policy(str(ROOT / "models" / "search_player.yaml"))
    reason = search.refusal(TASKS[0])  # OneBall-v1: the player's own words, its name first
    assert "search_player.yaml' cannot play pool_env/OneBall-v1" in reason
    assert "the search player plays the WPA game ids (pool_env/NineBallGame-v2" in reason
    assert search.refusal(next(t for t in TASKS if t.name == "nine-runout")) is None


def test_a_model_is_loaded_with_its_config() -> None:
    pytest.importorskip("stable_baselines3")
    policy = resolve_policy(str(ROOT / "models" / "sac_oneball_spin.zip"))
    assert policy.kind == "model" and policy.slug == "sac_oneball_spin"
    oneball = TASKS[0]
    assert policy.env_kwargs(oneball) == {"observation": "shots", "noise": None}
    assert policy.refusal(oneball) is None
    reason = policy.refusal(TASKS[1])  # Pool-v1, 3 balls
    assert "trained on pool_env/OneBall-v1" in reason and "cannot play pool_env/Pool-v1" in reason
    duel = next(t for t in TASKS if t.runner == "duel")
    assert "the duel plays" in policy.refusal(duel)


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["random", "--suite", "tiny"], ["unknown suite 'tiny'", "smoke, short, full"]),
        (["ghosty"], ["unknown policy 'ghosty'", "module:attr"]),
        (["os.path:"], ["policy 'os.path:'", "module:attr takes"]),
        (["no_such_module_xyz:make"], ["cannot import module 'no_such_module_xyz'"]),
        (["os:no_such_attr"], ["module 'os' has no attribute 'no_such_attr'"]),
        (["os:sep"], ["'sep' is a str, not a factory"]),
        (["no_such_model.zip"], ["policy 'no_such_model.zip'", "an SB3 model not found"]),
        ([f"{THIS}:not_an_agent", "--suite", "smoke"], ["returned int", "predict"]),
        (["random", "--tasks", "oneball", "nine"], ["unknown task 'nine'", "nine-runout"]),
        ([], ["give a policy to score, or --leaderboard"]),
        (["random", "--leaderboard"], ["not both"]),
    ],
)
def test_bad_input_is_a_usage_error_naming_it(argv, words, capsys) -> None:
    with pytest.raises(SystemExit) as exit_:
        main([*argv, "--results", str(RESULTS)])
    assert exit_.value.code == 2
    err = capsys.readouterr().err
    assert all(word in err for word in words), err
    assert "Traceback" not in err


def test_bad_input_raises_value_error_at_the_entry_points() -> None:
    with pytest.raises(ValueError, match="unknown suite 'ful' \\(did you mean full\\?\\)"):
        suite_tasks("ful")
    with pytest.raises(ValueError, match="module:attr takes"):
        resolve_policy("a b:c")
    with pytest.raises(ValueError, match="the record holds 4"):
        figure("pots_per_shot", {"shots": [1] * 4, "pots": [0] * 4}, 5)


def test_the_normalized_score() -> None:
    assert normalized(0.5, 0.1, 0.9) == pytest.approx(0.5)
    assert normalized(0.1, 0.1, 0.9) == 0.0 and normalized(0.9, 0.1, 0.9) == 1.0
    assert normalized(1.0, 0.1, 0.9) == pytest.approx(1.125)  # above the best file
    assert normalized(0.2, 0.3, 0.3) is None and normalized(0.2, None, 0.9) is None


def test_figures_of_the_first_episodes() -> None:
    record = {"endings": ["run-out", "foul", "run-out", "missed pot"], "break_made": [1, 0, 1, 1]}
    assert figure("run_out_rate", record, 4).value == 0.5
    assert figure("run_out_rate", record, 3).value == pytest.approx(2 / 3)
    assert figure("foul_rate", record, 2).value == 0.5
    assert figure("break_made_rate", record, 2).value == 0.5
    duel = {"winners": ["agent", None, "opponent", "agent"]}
    assert figure("win_rate", duel, 4).value == 0.5 and figure("draw_rate", duel, 2).value == 0.5


def test_merging_keeps_the_other_tasks_and_the_suite_order() -> None:
    old = {"player": "p", "suite": "full", "tasks": {"nine-duel": 1, "oneball": 2}}
    new = {"player": "p", "suite": "full", "tasks": {"oneball": 3, "position-3": 4}}
    merged = merge_results(old, new)
    assert merged["tasks"] == {"oneball": 3, "position-3": 4, "nine-duel": 1}
    assert list(merged["tasks"]) == ["oneball", "position-3", "nine-duel"]
    with pytest.raises(ValueError, match="cannot be merged"):
        merge_results(old, {**new, "suite": "short"})


def test_the_runners_keep_each_racks_outcome() -> None:
    racks = play_racks("random", "pool_env/NineBallGame-v2", 3, 730_000, {"noise": "fastfiz"})
    assert len(racks["break_per_rack"]) == 3
    assert sum(racks["break_per_rack"]) == racks["break_made"]
    duels = play_duels("random", "random", 2, 740_000, "fastfiz")
    assert len(duels["per_rack"]) == 2
    assert duels["per_rack"].count("agent") == duels["wins"]
    assert duels["per_rack"].count("opponent") == duels["losses"]


def test_the_committed_files_are_the_full_suite(committed) -> None:
    """Every committed file: the full suite's definitions and counts; random's plays all."""
    assert set(SUITES) == {"smoke", "short", "full"}
    for path, data in committed.items():
        assert data["suite"] == "full", path
        for task, n in suite_tasks("full"):
            entry = data["tasks"][task.name]
            assert entry["spec"] == json.loads(json.dumps(task.spec())), (path, task.name)
            assert entry["episodes"] == n
    assert all(
        e["status"] == "ok" for e in committed[str(RESULTS / "random.json")]["tasks"].values()
    )


def test_the_leaderboard_page_is_what_the_command_writes(committed, tmp_path: Path) -> None:
    page = ROOT / PAGE
    assert page.read_text() == leaderboard_page(committed, page)
    out = tmp_path / "leaderboard.md"
    assert main(["--leaderboard", str(out), "--results", str(RESULTS)]) == 0
    oneball = out.read_text().split("\n## oneball")[1].split("\n## ")[0]
    rows = [line for line in oneball.splitlines() if re.match(r"\| \d+ \| ", line)]
    values = [float(line.split("|")[5].split("%")[0]) for line in rows]
    assert len(rows) >= 2 and values == sorted(values, reverse=True)  # ranked by the figure
    assert "[random](" in oneball and "[ghost](" in oneball
