"""The baselines and their evaluation run on the core install: no SB3, torch, pyyaml, matplotlib.

A subprocess blocks those packages with a meta-path finder that raises ``ImportError`` (as if
they were not installed), then runs ``python -m agents.evaluate`` on the ghost-ball and random
agents. Its table must equal the one computed here with everything installed, so the
baselines play the same episodes without the training stack (issue 21 item 3).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

from agents.evaluation.evaluate import evaluate_agent
from agents.evaluation.table import format_table

ROOT = Path(__file__).resolve().parents[2]
#: The train extra's packages (and Ray): absent from a core install.
BLOCKED = ("stable_baselines3", "torch", "yaml", "matplotlib", "ray")

BLOCKER = textwrap.dedent(
    f"""
    import importlib.abc, runpy, sys

    BLOCKED = {BLOCKED!r}

    class NotInstalled(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in BLOCKED:
                raise ImportError(f"{{name}} is not in the core install (blocked by the test)")
            return None

    sys.meta_path.insert(0, NotInstalled())
    """
)


def _run_blocked(body: str) -> subprocess.CompletedProcess[str]:
    code = BLOCKER + textwrap.dedent(body)
    return subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=600
    )


def test_the_blocker_blocks() -> None:
    """The finder works: importing SB3 behind it fails (else the next test proves nothing)."""
    out = _run_blocked("import stable_baselines3\n")
    assert out.returncode != 0
    assert "stable_baselines3 is not in the core install" in out.stderr


def test_evaluate_runs_the_baselines_without_the_train_extra() -> None:
    env_id, episodes, seed = "pool_env/OneBallRoll-v1", 4, 10_000
    out = _run_blocked(
        f"""
        sys.argv = ["agents.evaluate", "--env", "{env_id}", "--agent", "random", "ghost",
                    "--episodes", "{episodes}", "--seed", "{seed}"]
        try:
            runpy.run_module("agents.evaluate", run_name="__main__", alter_sys=True)
        except SystemExit as exit:
            assert exit.code == 0, exit.code
        import agents
        assert callable(agents.load) and callable(agents.run_episodes)
        loaded = [m for m in sys.modules if m.split(".")[0] in BLOCKED]
        assert not loaded, loaded
        """
    )
    assert out.returncode == 0, out.stderr
    expected = format_table(
        {name: evaluate_agent(name, env_id, episodes, seed) for name in ("random", "ghost")},
        episodes,
    )
    assert expected in out.stdout, out.stdout
