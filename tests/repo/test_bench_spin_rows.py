"""The spin level's rows of ``bench.speed_vs_error``, with pooltool absent (pool_env only)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import bench.speed_vs_error as sve
from bench.spin_rows import run_spin_suite, spin_section, spin_table_lines
from bench.spin_vs_pooltool import final_distance


@pytest.fixture(scope="module")
def suite(tmp_path_factory: pytest.TempPathFactory) -> object:
    missing = tmp_path_factory.mktemp("no-pooltool") / "venv"
    return run_spin_suite(3, 1, use_pooltool=True, venv=missing)


def test_without_pooltool_the_rows_are_pool_envs_and_agree_with_the_reference(
    suite: object,
) -> None:
    assert [row.engine for row in suite.rows] == ["pool_env", "pool_env"]
    assert not suite.pooltool["available"]
    assert "setup_pooltool.sh" in suite.pooltool["reason"]
    assert suite.shots == 3
    for row in suite.rows:
        assert len(row.times) == len(row.errors) == 3
        assert all(t > 0.0 for t in row.times)
        # pool_env's spin level is exact: 50-digit reference within float64 rounding.
        assert max(row.errors) < 1e-12
    lines = spin_table_lines(suite)
    assert len(lines) == 2 + 2  # header, rule, the two pool_env rows
    assert "| 3 (100.0%) |" in lines[2]
    text = "\n".join(spin_section(suite, "cmd", "today", "abc1234"))
    assert "pooltool did not run" in text
    assert "load average" in text


def test_final_distance_is_the_largest_ball_distance() -> None:
    a = np.array([[0.0, 0.0], [1.0, 1.0]])
    b = np.array([[3e-3, 4e-3], [1.0, 1.0 + 1e-3]])
    assert final_distance(a, b) == pytest.approx(5e-3)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (  # replaced in place, the next section kept
            "# R\n\n## A\na\n\n## Spin level: old\nold\n\n## Breaks (chaotic)\nb\n",
            "# R\n\n## A\na\n\n## Spin level: new\nnew\n\n## Breaks (chaotic)\nb\n",
        ),
        (  # none yet: in before the breaks
            "# R\n\n## A\na\n\n## Breaks (chaotic)\nb\n",
            "# R\n\n## A\na\n\n## Spin level: new\nnew\n\n## Breaks (chaotic)\nb\n",
        ),
        (  # nothing to put it before: at the end
            "# R\n\n## A\na\n",
            "# R\n\n## A\na\n\n## Spin level: new\nnew\n",
        ),
        (  # the last section: replaced to the end, ### subsections included
            "# R\n\n## Spin level: old\nold\n### sub\nx\n",
            "# R\n\n## Spin level: new\nnew\n",
        ),
    ],
)
def test_splice_section(text: str, expected: str) -> None:
    assert sve.splice_section(text, ["## Spin level: new", "new"]) == expected


def test_spin_only_rewrites_the_spin_section_alone(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(sve, "QUICK", replace(sve.QUICK, spin_shots=2, repeats=1))
    report = tmp_path / "speed_vs_error.md"
    report.write_text("# Speed against error\n\n## Shots\nroll rows\n\n## Breaks (chaotic)\nb\n")
    assert sve.main(["--spin-only", "--quick", "--no-pooltool", "--out", str(tmp_path)]) == 0
    text = report.read_text()
    assert text.startswith("# Speed against error\n\n## Shots\nroll rows\n\n## Spin level")
    assert text.endswith("## Breaks (chaotic)\nb\n")
    assert "`python -m bench.speed_vs_error --quick --spin-only --no-pooltool`" in text
    assert "pooltool did not run: disabled with --no-pooltool" in text
    assert (tmp_path / "speed_vs_error_spin.png").stat().st_size > 1000
