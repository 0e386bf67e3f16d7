"""The scoreboard's tables: one policy's (printed by the command) and the leaderboard page.

:func:`score_table` is one results file as a Markdown table: each task's id, noise, seeds,
episodes, figure with its 95% interval, the figures beside it and the normalized score.
:func:`leaderboard_page` is ``docs/leaderboard.md``: from every results file of the folder,
an overall table (each player's mean normalized score over the tasks it can play) and one
table per task, players ranked by the task's figure, each row linked to its file.
``tests/agents/test_scoreboard.py`` checks that the committed page is what this writes
from the committed files.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

from agents.scoreboard.results import label, row_figures, task_by_name
from agents.scoreboard.suite import TASKS, Task

__all__ = ["leaderboard_page", "score_table"]

#: The command that writes the page (its first line says so).
COMMAND = "python -m agents.scoreboard --leaderboard"


def _score(value: float | None) -> str:
    """A normalized score, or ``-`` where it is undefined (a reference missing or tied)."""
    return "-" if value is None else f"{value:.2f}"


def _seeds(task: Task, n: int) -> str:
    return f"{task.seed}..{task.seed + n - 1}"


def _env(task: Task) -> str:
    kwargs = ", ".join(f"{k}: {json.dumps(v)}" for k, v in task.env_kwargs.items())
    return f"`{task.env_id}`" + (f" `{{{kwargs}}}`" if kwargs else "")


def _beside(entry: dict[str, Any], task: Task) -> str:
    return "; ".join(f"{label(key)} {entry['figures'][key]}" for key in task.beside)


def score_table(data: dict[str, Any], files: dict[str, dict[str, Any]]) -> str:
    """One results file's tasks as a Markdown table, normalized against ``files``."""
    lines = [
        "| task | env | noise | seeds | episodes | figure [95%] | beside | normalized |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, entry in data["tasks"].items():
        task = task_by_name(name)
        if task is None:
            continue
        n = entry["episodes"]
        head = f"| {name} | {_env(task)} | {task.noise} | {_seeds(task, n)} | {n} |"
        if entry["status"] != "ok":
            lines.append(f"{head} n/a: {entry['reason']} | | |")
            continue
        estimate, score = row_figures(entry, task, files)
        lines.append(
            f"{head} {label(task.figure)} {estimate.as_percent()} | {_beside(entry, task)} "
            f"| {_score(score)} |"
        )
    return "\n".join(lines)


def _link(path: str, page: Path) -> str:
    """``path`` relative to the page's folder, with ``/`` (a link that reads on GitHub)."""
    return Path(os.path.relpath(Path(path).absolute(), page.absolute().parent)).as_posix()


def leaderboard_page(files: dict[str, dict[str, Any]], page: Path) -> str:
    """``docs/leaderboard.md`` from the results ``files`` (by path), links relative to ``page``."""
    scores: dict[str, list[float]] = {path: [] for path in files}
    sections = []
    for task in TASKS:
        rows, refused = [], []
        for path, data in files.items():
            entry = data["tasks"].get(task.name)
            if entry is None or entry.get("spec") is None:
                continue
            who = f"[{data['player']}]({_link(path, page)})"
            if entry["status"] != "ok":
                refused.append(f"{who} ({entry['reason']})")
                continue
            estimate, score = row_figures(entry, task, files)
            if score is not None:
                scores[path].append(score)
            rows.append((estimate, score, who, data["suite"], entry))
        rows.sort(key=lambda r: (-r[0].value, r[2]))
        lines = [
            f"## {task.name}: {task.what}",
            "",
            f"{_env(task)}, noise {task.noise}, seeds from {task.seed}; figure: "
            f"{label(task.figure)}.",
            "",
            "| rank | player | suite | episodes | figure [95%] | beside | normalized |",
            "|---|---|---|---|---|---|---|",
        ]
        for rank, (estimate, score, who, suite, entry) in enumerate(rows, 1):
            lines.append(
                f"| {rank} | {who} | {suite} | {entry['episodes']} | {estimate.as_percent()} "
                f"| {_beside(entry, task)} | {_score(score)} |"
            )
        if refused:
            lines += ["", "Cannot play it: " + "; ".join(refused) + "."]
        sections.append("\n".join(lines))
    overall = sorted(
        ((sum(s) / len(s) if s else math.nan, len(s), path) for path, s in scores.items()),
        key=lambda r: (-r[0] if not math.isnan(r[0]) else math.inf, r[2]),
    )
    head = [
        "# Leaderboard",
        "",
        f"Written by `{COMMAND}` from the results files of `results/scoreboard/` (one per",
        "scored player, each with its command, date, load and git revision); do not edit it",
        "by hand. How to score a policy, the suites and the normalized score:",
        "[the scoreboard](#the-scoreboard) below.",
        "",
        "## Overall",
        "",
        "The mean normalized score over the tasks a player can play (0: random play, 1: the",
        "best results file on the task; `-` where a reference is missing or ties random).",
        "",
        "| rank | player | suite | tasks scored | mean normalized score |",
        "|---|---|---|---|---|",
    ]
    for rank, (mean, count, path) in enumerate(overall, 1):
        who = f"[{files[path]['player']}]({_link(path, page)})"
        head.append(
            f"| {rank} | {who} | {files[path]['suite']} | {count} | "
            f"{_score(None if math.isnan(mean) else mean)} |"
        )
    return "\n".join(head) + "\n\n" + "\n\n".join(sections) + "\n"
