"""Every figure of the README's headline list is read from the report it links to.

A headline bullet quotes numbers and links the ``results/`` (or ``models/``) file that
measured them; each number must stand in one of the files the bullet links, as written
there (a thousands separator aside), so a re-run that changes a figure fails here until
the README says the new one.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
NUMBER = re.compile(r"(?<![\w.])\d[\d,]*(?:\.\d+)?(?:e-?\d+)?")
LINK = re.compile(r"\[[^\]]*\]\(([^)#\s]+)(?:#[^)]*)?\)")


def headline_bullets() -> list[str]:
    """The bullets of the README's "Headline figures" section."""
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Headline figures\n", 1)[1].split("\n## ", 1)[0]
    return [b for b in re.split(r"\n- ", section)[1:] if b.strip()]


def quoted_numbers(bullet: str) -> list[str]:
    """The numbers a bullet states: outside its links and inline code (names, commands)."""
    prose = re.sub(r"\[[^\]]*\]\([^)]*\)", "", bullet)
    prose = re.sub(r"`[^`]*`", "", prose)
    return NUMBER.findall(prose)


@pytest.mark.parametrize("bullet", headline_bullets(), ids=lambda b: b[:40])
def test_each_headline_figure_stands_in_its_report(bullet: str) -> None:
    reports = [ROOT / link for link in LINK.findall(bullet) if not link.startswith("http")]
    assert reports, "a headline figure without the report that measured it"
    text = "\n".join(path.read_text() for path in reports)
    missing = [
        n for n in quoted_numbers(bullet) if n not in text and n.replace(",", "") not in text
    ]
    assert not missing, f"not in {[str(r.relative_to(ROOT)) for r in reports]}: {missing}"


def test_the_headlines_are_read() -> None:
    bullets = headline_bullets()
    assert len(bullets) >= 10
    assert sum(len(quoted_numbers(b)) for b in bullets) > 50
