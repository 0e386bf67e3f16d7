"""The API pages read right: a docstring section renders as the one item it is.

griffe (mkdocstrings' parser) reads a Google-style ``Returns:`` section as one item per
unindented line by default: a description wrapped over three lines became a table of three
rows, each with a made-up type. The site's parser options live in ``mkdocs.yml``; here every
docstring of both packages is parsed with exactly those options, and each ``Returns:`` and
``Yields:`` section must come out as a single item holding all of its text.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import griffe
import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
SECTIONS = {
    "Returns": griffe.DocstringSectionKind.returns,
    "Yields": griffe.DocstringSectionKind.yields,
}


def site_options() -> dict[str, Any]:
    """The options of the python handler in ``mkdocs.yml``."""
    text = (ROOT / "mkdocs.yml").read_text()
    config = yaml.load(text, Loader=yaml.BaseLoader)  # BaseLoader: tags such as !ENV as text
    handler = next(p["mkdocstrings"] for p in config["plugins"] if "mkdocstrings" in p)
    return handler["handlers"]["python"]["options"]


def site_docstring_options() -> dict[str, Any]:
    """The site's ``docstring_options``, as Python values."""
    options = site_options()["docstring_options"]
    return {k: v == "true" if v in ("true", "false") else v for k, v in options.items()}


def documented_objects(package: str) -> list[griffe.Object]:
    """Every object of ``package`` with a docstring, loaded with the site's extensions."""
    specs = [str(ROOT / spec) for spec in site_options()["extensions"]]
    root = griffe.load(
        package,
        search_paths=[str(ROOT)],
        docstring_parser="google",
        extensions=griffe.load_extensions(*specs),
    )
    found, stack = [], [root]
    while stack:
        obj = stack.pop()
        if obj.docstring is not None:
            found.append(obj)
        stack.extend(m for m in obj.members.values() if not m.is_alias)
    return found


def section_text(docstring: str, title: str) -> list[str]:
    """The non-empty lines of the ``title:`` section of a Google-style docstring."""
    lines = docstring.splitlines()
    start = next((i for i, line in enumerate(lines) if line.strip() == f"{title}:"), None)
    if start is None:
        return []
    indent = len(lines[start]) - len(lines[start].lstrip())
    body = []
    for line in lines[start + 1 :]:
        if line.strip() and len(line) - len(line.lstrip()) <= indent:
            break
        if line.strip():
            body.append(line.strip())
    return body


@pytest.mark.parametrize("package", ["pool_env", "agents"])
def test_no_returns_section_is_split_into_rows(package: str) -> None:
    """One item per section, and no item cut at a role's colon.

    griffe splits an item's first line at its first colon into ``type: description``; a
    first line such as ``The :class:`X` of ...`` was cut after ``The``, which rendered as a
    row named "The". A Google type never ends in a space before its colon.
    """
    options = site_docstring_options()
    broken = []
    checked = 0
    for obj in documented_objects(package):
        parsed = griffe.parse_google(obj.docstring, **options, warnings=False)
        for title, kind in SECTIONS.items():
            lines = section_text(obj.docstring.value, title)
            if not lines:
                continue
            checked += 1
            items = [s for s in parsed if s.kind is kind]
            count = len(items[0].value) if items else 0
            head, colon, _ = lines[0].partition(":")
            if count != 1:
                broken.append(f"{obj.path} {title}: {count} items")
            elif colon and (head != head.rstrip() or not head.strip()):
                broken.append(f"{obj.path} {title}: cut at a colon after {head!r}")
    assert checked > 20, checked  # the probe reads the docstrings at all
    assert not broken, "\n".join(broken)


CODE_WIDTH = 88  # characters a code block shows on the site's page without scrolling
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_code_line_runs_off_the_page(page: Path) -> None:
    long, fenced = [], False
    for number, line in enumerate(page.read_text().splitlines(), 1):
        if line.startswith("```"):
            fenced = not fenced
        elif fenced and len(line) > CODE_WIDTH:
            long.append(f"line {number}: {len(line)} characters")
    assert not long, long
