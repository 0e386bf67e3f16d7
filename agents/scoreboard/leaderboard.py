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
    """The seeds of a task's first ``n`` episodes, ``first..last``."""
    return f"{task.seed}..{task.seed + n - 1}"


def _env(task: Task) -> str:
    """The task's id and keywords (besides the noise), as code."""
    kwargs = ", ".join(f"{k}: {json.dumps(v)}" for k, v in task.env_kwargs.items())
    return f"`{task.env_id}`" + (f" `{{{kwargs}}}`" if kwargs else "")


def _beside(entry: dict[str, Any], task: Task) -> str:
    """The figures shown beside the scored one, as the results file states them."""
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
        f"Written by `{COMMAND}` from the results files of",
        "`results/scoreboard/` (one per scored player, each task with its command, date, load",
        "and git revision); do not edit it by hand. How to score a policy, the suites and the",
        "normalized score: [the scoreboard](#the-scoreboard) below; what the committed runs",
        "cost: [results/scoreboard.md](../results/scoreboard.md).",
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
    return "\n".join(head) + "\n\n" + "\n\n".join(sections) + "\n\n" + about() + "\n"


#: How to use the scoreboard: the page's last section (the suite's table is added to it).
ABOUT = """## The scoreboard

`python -m agents.scoreboard` (`agents/scoreboard/`) plays a policy on every task below
and prints each task's id, noise, seeds, episodes, figure with its 95% interval (Wilson)
and normalized score. Score a model, save its results file, rewrite this page:

<!-- run: python -m agents.scoreboard random --suite smoke --tasks oneball -->
```bash
python -m agents.scoreboard models/sac_oneball_spin.zip
```

<!-- run: python -m agents.scoreboard const --suite smoke --tasks oneball \
--save $DOCS_TMP/r.json -->
```bash
python -m agents.scoreboard runs/RUN/model.zip --suite full --save
```

<!-- run: python -m agents.scoreboard --leaderboard $DOCS_TMP/leaderboard.md -->
```bash
python -m agents.scoreboard --leaderboard
```

`--suite` is `short` by default (a first look; `smoke` is CI's), `full` for the results
files; `--save` writes `results/scoreboard/<player>.json` (`<player>.<suite>.json` off
the full suite); `--tasks` plays some tasks only (with `--save`, into the player's file
beside its other tasks). The time each takes:
[results/scoreboard.md](../results/scoreboard.md).

**A policy** is one of: a player as `python -m agents.evaluate --agent` takes it
(`random`, `ghost`, `models/search_player.yaml`, `models/runout_value.npz`, ...); an SB3
model `.zip` with its saved config beside it (`<stem>_config.yaml` or `config.yaml`),
loaded as `agents.load` loads it, its saved `env_kwargs` under the task's (the task's noise
and rules stand); or `module:attr`, a factory called with each task's env that returns an
agent with SB3's `predict`. A factory refuses a task by raising `ValueError`; an agent
with `observation_space` and `action_space` is refused where their shapes are not the
env's. A function of the observation is wrapped in two lines:

```python
import numpy as np


class Straight:
    \"\"\"Full hit, medium pace, centre ball: SB3's predict.\"\"\"

    def predict(self, obs, state=None, episode_start=None, deterministic=True):
        return np.array([0.0, 0.5, 0.0, 0.0], dtype=np.float32), state


# In a module of yours, my_agents.pool; scored by
# python -m agents.scoreboard my_agents.pool:make_agent
def make_agent(env):
    if env.action_space.shape != (4,):
        raise ValueError("plays the solitaire ids' action (4 numbers) only")
    return Straight()
```

A task that a policy cannot play (the spaces differ, the player refuses the game) reads
"n/a" with the reason.

**The normalized score** of a figure is (figure - random's) / (best's - random's): random
play's results file scores 0 and the best results file on the task 1, each measured on the
same seeds. Episode `k` of a task is reset with seed `seed + k` in every suite, and a results
file keeps each episode's outcome, so the figures of any first episodes are known: a
player scored on the short suite is compared with the others' first episodes. Where a
reference is missing, or the best file is no better than random on those episodes, the
score is `-`. The overall score is the mean over the tasks a player can play.

**The suite** (seeds 700000 and up: no training run, model selection or other results file
uses them):
"""


def about() -> str:
    """The page's last section: :data:`ABOUT` and the suite's tasks as a table."""
    lines = [
        "| task | env | noise | seeds from | smoke | short | full | runner | figure |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for task in TASKS:
        runner = task.runner + (f" against {task.opponent}" if task.opponent else "")
        counts = " | ".join(str(task.episodes[suite]) for suite in ("smoke", "short", "full"))
        lines.append(
            f"| {task.name} | {_env(task)} | {task.noise} | {task.seed} | {counts} | {runner} "
            f"| {label(task.figure)} |"
        )
    return ABOUT + "\n" + "\n".join(lines)
