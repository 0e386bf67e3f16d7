"""Links that read right twice: on GitHub, from the Markdown file, and on the docs site.

The pages in ``docs/`` link to what lies beside them in the repository as the repository
holds it, so GitHub (where the README's table of pages sends readers) resolves every link
and picture: ``../results/agents.md``, ``../models/ppo_oneball_eval.md``,
``../pool_env/sim/table.py``. The site holds those elsewhere: ``docs/gen_pages.py`` copies
``results/`` and ``models/`` into it and writes an API page per module under ``reference/``.
This mkdocs hook (``hooks:`` in ``mkdocs.yml``) rewrites each such link, before the page is
rendered, to the site's copy: a report to ``results/...`` or ``models/...``, a module or
package to its reference page, ``CHANGELOG.md`` to ``changelog.md``. Links inside
``docs/`` are left alone. ``tests/repo/test_docs_links.py`` checks that every link and picture
resolves in the repository; the strict build checks the site's.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
#: Folders gen_pages copies into the site as they stand, with the files it copies (a
#: pattern with a folder keeps it: the scoreboard's results files, which the leaderboard
#: page links to).
COPIED = {
    "results": ("*.md", "*.png", "scoreboard/*.json"),
    "models": ("*.md", "*.yaml"),
}
PACKAGES = ("pool_env", "agents")
LINK = re.compile(r"(!?\[[^\]]*\])\(([^)\s]+)\)")


def page_of(parts: tuple[str, ...], is_package: bool) -> str:
    """The reference page of a module: ``a/b/index.md`` for a package, ``a/b.md`` otherwise."""
    return "/".join(parts) + ("/index.md" if is_package else ".md")


def site_path(target: Path) -> str | None:
    """Where the site holds the repository path ``target`` outside ``docs/`` (or None)."""
    rel = target.relative_to(ROOT)
    parts = rel.parts
    if not parts or target.is_relative_to(DOCS):
        return None
    if parts[0] in COPIED:
        return rel.as_posix()
    if rel.as_posix() == "CHANGELOG.md":
        return "changelog.md"
    if parts[0] in PACKAGES:
        if target.is_dir():
            return "reference/" + page_of(parts, is_package=True)
        if target.suffix == ".py":
            module = parts[:-1] if target.name == "__init__.py" else (*parts[:-1], target.stem)
            return "reference/" + page_of(module, is_package=target.name == "__init__.py")
    return None


def rewrite(markdown: str, src_uri: str) -> str:
    """``markdown`` of the page at ``docs/<src_uri>`` with repository links made site links."""
    page_dir = (DOCS / src_uri).parent

    def one(match: re.Match[str]) -> str:
        label, target = match.group(1), match.group(2)
        if re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith(("#", "/")):
            return match.group(0)  # a URL, an anchor or an absolute path
        path, hash_, anchor = target.partition("#")
        resolved = Path(os.path.normpath(page_dir / path))
        if not resolved.is_relative_to(ROOT):
            return match.group(0)
        mapped = site_path(resolved)
        if mapped is None:
            return match.group(0)
        link = os.path.relpath(mapped, start=os.path.dirname(src_uri) or ".")
        return f"{label}({Path(link).as_posix()}{hash_}{anchor})"

    return LINK.sub(one, markdown)


def on_page_markdown(markdown: str, page: Any, **kwargs: Any) -> str:
    """Rewrite the page's repository links before it is rendered (an mkdocs hook)."""
    return rewrite(markdown, page.file.src_uri)
