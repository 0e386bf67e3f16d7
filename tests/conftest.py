"""Shared fixtures; loads the hypothesis profile (``tests/profiles.py``)."""

from __future__ import annotations

import os

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
