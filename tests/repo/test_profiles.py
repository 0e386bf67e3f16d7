"""The hypothesis profiles: CI is derandomized, nightly looks ten times further."""

from __future__ import annotations

import os
import re
from pathlib import Path

from hypothesis import settings

from tests import profiles


def test_ci_is_derandomized_and_nightly_draws_ten_times_as_many() -> None:
    ci, nightly = settings.get_profile("ci"), settings.get_profile("nightly")
    assert ci.derandomize and not nightly.derandomize
    assert nightly.max_examples == 10 * ci.max_examples
    assert ci.deadline is None and nightly.deadline is None


def test_the_loaded_profile_is_the_one_named_by_the_environment() -> None:
    name = os.environ.get("HYPOTHESIS_PROFILE", "ci")
    assert settings.default.derandomize == settings.get_profile(name).derandomize
    assert profiles.examples(400) == 400 * settings.get_profile(name).max_examples // 100


def test_every_property_test_scales_its_examples_with_the_profile() -> None:
    """A fixed ``max_examples`` would ignore the nightly profile's ten times as many."""
    fixed = re.compile(r"max_examples=(?!examples\()")
    tests = Path(__file__).parents[1]
    offenders = [
        f"{path.name}:{number}"
        for path in sorted(tests.rglob("test_*.py"))
        for number, line in enumerate(path.read_text().splitlines(), 1)
        if fixed.search(line) and not line.lstrip().startswith(("#", "fixed ="))
    ]
    assert offenders == []
