"""Every headline figure is read from the report it links to.

The README's table of figures and the headline list of the benchmarks page quote numbers
and link the ``results/`` (or ``models/``) file that measured them; each number must stand
in one of the files its row or bullet links, as written there (a thousands separator
aside), so a re-run that changes a figure fails here until the page says the new one.
The figures of the install and the first shot, quoted in the README's prose and the
getting-started page too, are checked against their one source the same way. The README's
table has at most 8 rows, each linked to the ``results/`` or ``models/`` files that hold its
figures (a report, or a scoreboard results file ``results/scoreboard/*.json``); every link
names a file, and a heading of it where it has an anchor.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
NUMBER = re.compile(r"(?<![\w.])\d[\d,]*(?:\.\d+)?(?:e-?\d+)?")
LINK = re.compile(r"\[[^\]]*\]\(([^)#\s]+)(?:#[^)]*)?\)")
#: A link with its anchor: (path, anchor or "").
ANCHORED = re.compile(r"\[[^\]]*\]\(([^)#\s]+)(?:#([^)\s]*))?\)")
#: The files a figure may be read from: reports, and the scoreboard's results files.
REPORTS = (".md", ".json")


def headline_bullets() -> list[str]:
    """The bullets of the benchmarks page's "Headline figures" section."""
    text = (ROOT / "docs" / "benchmarks.md").read_text()
    section = text.split("\n## Headline figures\n", 1)[1].split("\n## ", 1)[0]
    return [b for b in re.split(r"\n- ", section)[1:] if b.strip()]


def readme_rows() -> list[str]:
    """The rows of the README's table of figures (after its header and rule)."""
    text = (ROOT / "README.md").read_text()
    section = text.split("\n## Figures\n", 1)[1].split("\n## ", 1)[0]
    return [line for line in section.splitlines() if line.startswith("| ")][1:]


def first_shot_quotes() -> list[str]:
    """Every sentence of the README and getting-started that quotes the first-shot figures."""
    quotes = []
    for page in ("README.md", "docs/getting-started.md"):
        text = re.sub(r"```.*?```", "", (ROOT / page).read_text(), flags=re.S)  # code
        prose = [ln for ln in text.splitlines() if not ln.startswith(("|", "!", "<!--", "#"))]
        for sentence in re.split(r"(?<=[.;:])\s", "\n".join(prose)):
            if re.search(r"precompile|first shot|compiles the simulator", sentence) and (
                quoted_numbers(sentence.replace("2-core", ""))
            ):
                quotes.append(sentence)
    return quotes


def quoted_numbers(bullet: str) -> list[str]:
    """The numbers a bullet states: outside its links and inline code (names, commands)."""
    prose = re.sub(r"\[[^\]]*\]\([^)]*\)", "", bullet)
    prose = re.sub(r"`[^`]*`", "", prose)
    return NUMBER.findall(prose)


def _linked_reports(text: str, page: Path) -> list[Path]:
    return [
        (page.parent / link).resolve()
        for link in LINK.findall(text)
        if not link.startswith(("http", "docs/", "../docs/")) and link.endswith(REPORTS)
    ]


def slug(heading: str) -> str:
    """GitHub's anchor of a Markdown heading: lower case, punctuation dropped, ``-`` for spaces."""
    text = re.sub(r"[`*_]|\[([^\]]*)\]\([^)]*\)", r"\1", heading.strip().lower())
    return re.sub(r"[^\w\- ]", "", text).replace(" ", "-")


def broken_links(text: str, page: Path) -> list[str]:
    """The links of ``text`` (on ``page``) that name no file, or no heading of the file."""
    broken = []
    for link, anchor in ANCHORED.findall(text):
        if link.startswith("http"):
            continue
        target = (page.parent / link).resolve()
        if not target.is_file():
            broken.append(f"{link}: no such file")
            continue
        if anchor:
            headings = re.findall(r"^#+\s+(.+)$", target.read_text(), flags=re.MULTILINE)
            if anchor not in {slug(h) for h in headings}:
                broken.append(f"{link}#{anchor}: no such heading")
    return broken


def _missing(text: str, reports: list[Path]) -> list[str]:
    source = "\n".join(path.read_text() for path in reports)
    return [n for n in quoted_numbers(text) if n not in source and n.replace(",", "") not in source]


@pytest.mark.parametrize("bullet", headline_bullets(), ids=lambda b: b[:40])
def test_each_headline_figure_stands_in_its_report(bullet: str) -> None:
    reports = _linked_reports(bullet, ROOT / "docs" / "benchmarks.md")
    assert reports, "a headline figure without the report that measured it"
    missing = _missing(bullet, reports)
    assert not missing, f"not in {[r.name for r in reports]}: {missing}"


@pytest.mark.parametrize("row", readme_rows(), ids=lambda r: r.split("|")[1].strip())
def test_each_readme_figure_stands_in_its_report(row: str) -> None:
    reports = _linked_reports(row, ROOT / "README.md")
    assert reports, "a figure without the report that measured it"
    missing = _missing(row.split("|")[2], reports)
    assert not missing, f"not in {[r.name for r in reports]}: {missing}"


@pytest.mark.parametrize("row", readme_rows(), ids=lambda r: r.split("|")[1].strip())
def test_each_readme_row_links_resolve(row: str) -> None:
    """Each link of a row names a file of the repository, and a heading of it if anchored."""
    assert broken_links(row, ROOT / "README.md") == []
    reports = _linked_reports(row, ROOT / "README.md")
    assert all(r.is_relative_to(ROOT / "results") or r.is_relative_to(ROOT / "models")
               for r in reports), reports  # fmt: skip


def test_the_link_check_finds_a_broken_link() -> None:
    page = ROOT / "README.md"
    assert broken_links("[a](results/agents.md#no-such-heading)", page) == [
        "results/agents.md#no-such-heading: no such heading"
    ]
    assert broken_links("[a](no_such_file.md)", page) == ["no_such_file.md: no such file"]
    anchor = "learners-on-the-envs-own-action-oneball-v1-and-oneballroll-v1"
    assert broken_links(f"[a](results/agents.md#{anchor})", page) == []
    assert _missing("12345.678 of 1,000 episodes", [ROOT / "results" / "agents.md"]) == [
        "12345.678"
    ]


@pytest.mark.parametrize("sentence", first_shot_quotes(), ids=lambda s: s[:40])
def test_install_and_first_shot_figures_come_from_one_report(sentence: str) -> None:
    report = ROOT / "results" / "first_shot.md"
    missing = _missing(sentence.replace("2-core", "").replace("2 cores", ""), [report])
    assert not missing, f"not in first_shot.md: {missing}"


def test_the_headlines_are_read() -> None:
    bullets = headline_bullets()
    assert len(bullets) >= 10
    assert sum(len(quoted_numbers(b)) for b in bullets) > 50
    rows = readme_rows()
    assert 5 <= len(rows) <= 8, "the README's table: at most 8 rows"
    assert sum(len(quoted_numbers(r.split("|")[2])) for r in rows) > 15
    assert len(first_shot_quotes()) >= 3
