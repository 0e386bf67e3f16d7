"""A missing optional dependency is named by the extra of this package that installs it."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from pool_env.extras import require

ROOT = Path(__file__).resolve().parents[2]

# Each case runs in a fresh process with the package blocked (None in sys.modules makes its
# import raise ModuleNotFoundError, as if it were not installed).
CASES = {
    "train.py without the train extra": (
        "stable_baselines3",
        "from agents.train import main; main(['--timesteps', '64'])",
        "train",
    ),
    "train.py without pyyaml": (
        "yaml",
        "from agents.train import parse_sets; parse_sets([])",
        "train",
    ),
    "rllib backend without ray": (
        "ray",
        "from agents.train import main; main(['--backend', 'rllib'])",
        "rllib",
    ),
    "two players without pettingzoo": (
        "pettingzoo",
        "import pool_env.envs.multiagent",
        "multiagent",
    ),
    "RecordShots without moviepy": (
        "moviepy",
        "import gymnasium as gym, pool_env; from pool_env.envs.record import RecordShots;"
        "RecordShots(gym.make('pool_env/OneBall-v1', render_mode='rgb_array_list'), '/tmp')",
        "render",
    ),
    "a window without pygame": (
        "pygame",
        "from pool_env.render.window import Window; Window((10, 10))",
        "render",
    ),
    "a saved model without stable-baselines3": (
        "stable_baselines3",
        "from agents.learned.pretrained import algo_class; algo_class('ppo')",
        "train",
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_missing_extra_is_named(case: str) -> None:
    blocked, code, extra = CASES[case]
    run = subprocess.run(
        [sys.executable, "-c", f"import sys; sys.modules[{blocked!r}] = None\n{code}"],
        cwd=ROOT,
        capture_output=True,
        text=True,
    )
    assert run.returncode != 0
    last = run.stderr.strip().splitlines()[-1]
    assert f'pip install "pool_env[{extra}]"' in last, run.stderr
    assert "gymnasium[other]" not in run.stderr


def test_an_installed_module_is_returned() -> None:
    assert require("numpy", "core", "this test").__name__ == "numpy"


def test_a_broken_install_is_not_called_missing(tmp_path: Path) -> None:
    (tmp_path / "brokenpkg").mkdir()
    (tmp_path / "brokenpkg" / "__init__.py").write_text("import no_such_module_anywhere\n")
    sys.path.insert(0, str(tmp_path))
    try:
        with pytest.raises(ModuleNotFoundError, match="no_such_module_anywhere") as info:
            require("brokenpkg", "core", "this test")
        assert "pool_env[" not in str(info.value)
    finally:
        sys.path.remove(str(tmp_path))
        sys.modules.pop("brokenpkg", None)


def test_the_error_type_is_the_callers() -> None:
    class MissingError(Exception):
        pass

    with pytest.raises(MissingError, match=r'pip install "pool_env\[render\]"'):
        require("no_such_module_anywhere", "render", "this test", MissingError)
