"""Every command the docs show refuses a bad flag or name with one line and status 2.

The commands are collected from the code of README.md and docs/*.md (``python train.py
...``, ``python -m <module> ...``); each is run with a misspelled flag added, then a table
of misspelled names (env id, agent, ``--set`` key, ``--algo``, noise) per command. Every
refusal must come before any heavy work (no game is played, nothing trains): the whole
file runs at ``--help`` speed, one interpreter start per case.
"""

from __future__ import annotations

import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

#: Modules the docs name that are not this repository's commands.
FOREIGN = ("pip", "pytest", "rl_zoo3.train")

#: The required arguments of a command whose docs show it bare (the flag is then the error).
REQUIRED = {
    "agents.duels": ["--agent", "ghost"],
    "agents.evaluation.runouts": ["--agents", "ghost"],
    "agents.training.fit_layout_value": ["fit", "--out", "/tmp/value.npz"],
}

#: A command in a code span or block: ``python train.py ...`` or ``python -m module ...``.
COMMAND = re.compile(r"python3? (train\.py|-m [\w.]+)([^`\n;&|#]*)")


def documented_commands() -> dict[str, list[str]]:
    """Each documented command (its script or module) with its longest documented arguments."""
    found: dict[str, list[str]] = {}
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = page.read_text().replace("\\\n", " ")
        for match in COMMAND.finditer(text):
            target = match.group(1).removeprefix("-m ")
            rest = re.split(r"[(),]|-->", match.group(2))[0]  # prose after an inline command
            try:
                args = shlex.split(rest)
            except ValueError:  # a quote the span cut off
                args = []
            args = [a.replace("$DOCS_TMP", "/tmp") for a in args]  # the docs test's folder
            if target not in FOREIGN and len(args) >= len(found.get(target, [])):
                found[target] = args
    return found


def run(args: list[str]) -> subprocess.CompletedProcess[str]:
    """Run ``python <args>`` from the repository's root, as the docs do."""
    return subprocess.run(
        [sys.executable, "-W", "ignore", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )


def assert_usage_error(result: subprocess.CompletedProcess[str], *words: str) -> None:
    """Status 2, no traceback, and one ``error:`` line naming ``words``."""
    assert result.returncode == 2, (result.returncode, result.stdout, result.stderr)
    assert "Traceback" not in result.stderr, result.stderr
    errors = [line for line in result.stderr.splitlines() if ": error: " in line]
    assert len(errors) == 1, result.stderr
    assert result.stderr.rstrip().endswith(errors[0]), result.stderr  # the last line
    for word in words:
        assert word in errors[0], (word, errors[0])


def test_the_docs_show_the_commands_checked_here() -> None:
    commands = documented_commands()
    # The commands of the issue: a doc that stops showing one would leave it unchecked.
    for name in ("train.py", "agents.evaluate", "agents.duels", "agents.evaluation.runouts"):
        assert name in commands, sorted(commands)
    assert len(commands) >= 15, sorted(commands)


@pytest.mark.parametrize("target", sorted(documented_commands()))
def test_a_misspelled_flag_is_a_usage_error(target: str) -> None:
    script = [target] if target.endswith(".py") else ["-m", target]
    args = documented_commands()[target] or REQUIRED.get(target, [])
    result = run([*script, *args, "--epsiodes", "3"])
    assert_usage_error(result, "--epsiodes")


#: Misspelled names, per command: the arguments, and words the one error line must name.
MISSPELLED = [
    (["train.py", "--env", "pool_env/NineBallGame-v9"], ["NineBallGame-v9", "did you mean"]),
    (["train.py", "--env", "pool_env/OneBal-v1"], ["did you mean pool_env/OneBall-v1"]),
    (["train.py", "--set", "n_step=64"], ["n_step", "did you mean n_steps", "batch_size"]),
    (["train.py", "--set", "n_envs=4"], ["n_envs", "--n-envs"]),
    (["train.py", "--algo", "sax"], ["sax", "sac"]),
    (["train.py", "--timesteps", "0"], ["--timesteps", ">= 1"]),
    (["train.py", "--aim", "cuts"], ["cuts", "relative"]),
    (["train.py", "--wrapper", "ghost_featurs"], ["ghost_featurs", "ghost_features"]),
    (["train.py", "--env-kwargs", "{nois: 1}"], ["nois", "noise"]),
    (["-m", "agents.evaluate", "--agent", "gohst"], ["gohst", "did you mean ghost"]),
    (["-m", "agents.evaluate", "--env", "pool_env/OneBalRoll-v1"], ["did you mean"]),
    (["-m", "agents.evaluate", "--noise", "fastfizz"], ["fastfizz", "fastfiz"]),
    (
        [
            "-m",
            "agents.evaluate",
            "--env",
            "pool_env/TenBallGame-v1",
            "--agent",
            "models/search_player.yaml",
        ],
        ["models/search_player.yaml", "TenBallGame-v1", "9-ball"],
    ),
    (["-m", "agents.evaluate", "--agent", "rack-planner"], ["rack-planner", "game ids"]),
    (
        [
            "-m",
            "agents.evaluate",
            "--env",
            "pool_env/NineBallGame-v2",
            "--agent",
            "models/ppo_oneball.zip",
        ],
        ["models/ppo_oneball.zip", "shape"],
    ),
    (["-m", "agents.duels", "--agent", "gohst"], ["gohst", "did you mean ghost"]),
    (["-m", "agents.duels", "--agent", "ghost", "--noise", "0.1"], ["--noise", "0.1"]),
    (["-m", "agents.duels", "--agent", "ghost", "--env", "pool_env/OneBall-v1"], ["game ids"]),
    (
        [
            "-m",
            "agents.duels",
            "--agent",
            "models/search_player.yaml",
            "--env",
            "pool_env/TenBallGame-v1",
        ],
        ["9-ball"],
    ),
    (["-m", "agents.evaluation.runouts", "--agents", "gost"], ["gost", "did you mean ghost"]),
    (["-m", "agents.evaluation.runouts", "--agents", "ghost", "--noise", "x"], ["'x'", "none"]),
    (
        ["-m", "agents.evaluation.runouts", "--agents", "ghost", "--env", "pool_env/Pool-v1"],
        ["game ids", "Pool-v1"],
    ),
    (
        ["-m", "agents.evaluation.runouts", "--agents", "ghost", "--env", "NineBallGame-v2"],
        ["did you mean pool_env/NineBallGame-v2"],
    ),
]


@pytest.mark.parametrize(("args", "words"), MISSPELLED, ids=lambda v: " ".join(v)[:60])
def test_a_misspelled_name_is_a_usage_error(args: list[str], words: list[str]) -> None:
    assert_usage_error(run(args), *words)
