"""The hypothesis profiles: CI is derandomized, nightly looks ten times further."""

from __future__ import annotations

import os

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
