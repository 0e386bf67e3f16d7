"""Shared fixtures."""

from __future__ import annotations

import pytest

from pool_env import Table


@pytest.fixture
def table() -> Table:
    """The default 9-ft table with standard pockets."""
    return Table()


@pytest.fixture
def carom() -> Table:
    """The default table without pockets."""
    return Table(pockets="none")
