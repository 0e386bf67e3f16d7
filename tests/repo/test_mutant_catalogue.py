"""The mutation catalogue (tools/mutant_catalogue/) stays anchored in the current tree.

The mutation runner itself is not part of CI (it takes minutes); this fast check makes sure
that every planted bug still points at code that exists, exactly once, so that an edit which
moves a snippet shows up here instead of as a silently skipped mutant.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.mutant_catalogue import CATALOGUE, Mutant

ROOT = Path(__file__).resolve().parents[2]


def test_the_catalogue_is_large_and_its_names_unique() -> None:
    names = [m.name for m in CATALOGUE]
    assert len(names) >= 25
    assert len(set(names)) == len(names)


@pytest.mark.parametrize("mutant", CATALOGUE, ids=lambda m: m.name)
def test_every_snippet_occurs_exactly_once(mutant: Mutant) -> None:
    source = (ROOT / mutant.file).read_text()
    assert source.count(mutant.original) == 1, f"{mutant.name}: re-anchor it in {mutant.file}"
    assert mutant.mutated != mutant.original
    mutated = source.replace(mutant.original, mutant.mutated)
    assert mutated != source


@pytest.mark.parametrize("mutant", CATALOGUE, ids=lambda m: m.name)
def test_every_subset_names_existing_tests(mutant: Mutant) -> None:
    assert mutant.tests
    for target in mutant.tests:
        assert (ROOT / target.split("::")[0]).is_file(), target
