"""Shared fixtures; loads the hypothesis profile (``tests/profiles.py``)."""

from __future__ import annotations

import pytest

from pool_env import Table
from tests import profiles

profiles.load()


@pytest.fixture
def table() -> Table:
    """The default 9-ft table with standard pockets."""
    return Table()


@pytest.fixture
def carom() -> Table:
    """The default table without pockets."""
    return Table(pockets="none")
