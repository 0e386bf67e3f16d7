"""The docs read on GitHub as on the site: every link and picture resolves in the repository.

GitHub renders each Markdown file from its own path, so a link must name a file that the
repository holds, relative to the page. The site holds reports and API pages elsewhere;
``docs/site_links.py`` maps such links when the site is built (and ``mkdocs build --strict``
fails on any that it cannot resolve there).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "docs"))

import make_picture  # noqa: E402  (docs/make_picture.py)
from site_links import LINK, rewrite  # noqa: E402  (docs/site_links.py)

PAGES = [ROOT / "README.md", ROOT / "CHANGELOG.md", *sorted((ROOT / "docs").rglob("*.md"))]
FENCE = re.compile(r"^```.*?^```", re.S | re.M)


def relative_links(page: Path) -> list[str]:
    """The link and picture targets of ``page`` that point into the repository."""
    text = FENCE.sub("", page.read_text())
    targets = [m.group(2) for m in LINK.finditer(text)]
    return [t for t in targets if not re.match(r"^[a-z][a-z0-9+.-]*:", t) and t[0] != "#"]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_link_and_picture_resolves_in_the_repository(page: Path) -> None:
    missing = [t for t in relative_links(page) if not (page.parent / t.split("#")[0]).exists()]
    assert not missing, missing


def test_the_probe_finds_links() -> None:
    assert len(relative_links(ROOT / "docs" / "benchmarks.md")) > 10


@pytest.mark.parametrize(
    ("page", "link", "site"),
    [
        ("agents.md", "../results/agents.md#x", "results/agents.md#x"),
        ("environments/vector.md", "../../results/vector_speed.md", "../results/vector_speed.md"),
        ("agents.md", "../models/ppo_oneball_eval.md", "models/ppo_oneball_eval.md"),
        ("physics.md", "../pool_env/sim/table.py", "reference/pool_env/sim/table.md"),
        ("physics.md", "../pool_env/sim/", "reference/pool_env/sim/index.md"),
        ("index.md", "../pool_env/__init__.py", "reference/pool_env/index.md"),
        ("index.md", "../CHANGELOG.md", "changelog.md"),
        ("environments/games.md", "../break.png", "../break.png"),  # in docs/: as it is
        ("index.md", "https://example.org/a.md", "https://example.org/a.md"),
    ],
)
def test_repository_links_become_site_links(page: str, link: str, site: str) -> None:
    assert rewrite(f"see [it]({link}) and ![x]({link})", page) == (
        f"see [it]({site}) and ![x]({site})"
    )


@pytest.mark.parametrize(
    ("picture", "draw"),
    [
        ("shot.png", lambda: make_picture.cut_shot_env()),
        ("break.png", lambda: make_picture.break_env(800)),
    ],
)
def test_committed_pictures_are_what_the_renderer_draws(picture: str, draw) -> None:
    import imageio.v3 as iio

    committed = iio.imread(ROOT / "docs" / picture)
    np.testing.assert_array_equal(committed, draw().render())


def test_every_page_of_the_site_is_in_its_menu(tmp_path: Path) -> None:
    """The reports and model cards too: mkdocs names each page left out of the menu."""
    pytest.importorskip("mkdocs")
    env = {**os.environ, "NO_MKDOCS_2_WARNING": "1", "DISABLE_MKDOCS_2_WARNING": "true"}
    build = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(tmp_path)],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr[-3000:]
    assert "not included in the" not in build.stderr, build.stderr[-3000:]
    assert (tmp_path / "results" / "agents" / "index.html").is_file()
