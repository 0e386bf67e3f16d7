"""Shared fixtures; loads the hypothesis profile (``tests/profiles.py``)."""

from __future__ import annotations

import os
from collections.abc import Iterator

import pytest

from pool_env import Table
from tests import profiles

profiles.load()

# Ray (tests/test_rllib*.py) binds the machine's interface address on Linux, even for a local
# ray.init(); with this it binds 127.0.0.1, so the tests' traffic stays on loopback. Ray reads
# it once, when it is imported: so here, before any test module imports ray.
os.environ["RAY_ENABLE_WINDOWS_OR_OSX_CLUSTER"] = "0"


@pytest.fixture
def table() -> Table:
    """The default 9-ft table with standard pockets."""
    return Table()


@pytest.fixture
def carom() -> Table:
    """The default table without pockets."""
    return Table(pockets="none")


@pytest.fixture(autouse=True)
def _gymnasium_stays_unpatched() -> Iterator[None]:
    """Fail the test that leaves Gymnasium's ``TimeLimit`` replaced for the rest of the run.

    ``gym.make`` wraps every id in Gymnasium's ``TimeLimit``; a library that
    swaps it on import (rl_zoo3 does) changes every later test's ``info``, so a test that
    imports one must do so in a child process.
    """
    import gymnasium.envs.registration as registration
    import gymnasium.wrappers as wrappers

    def current() -> tuple[object, object]:
        return wrappers.TimeLimit, getattr(registration, "TimeLimit", None)

    before = current()
    yield
    assert current() == before, "a test replaced Gymnasium's TimeLimit"
