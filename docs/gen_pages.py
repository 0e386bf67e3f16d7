"""Pages the docs site generates at build time (mkdocs-gen-files runs this file).

* ``reference/``: one page per module of ``pool_env`` and ``agents``, found by walking the
  source tree, so modules that others add or move appear without an edit here; each page is
  the module's docstrings through mkdocstrings. A package's page lists its public names
  (``__all__``) with links to where each is defined, and the build fails if one of them
  has no page.
* ``results/`` and ``models/``: the measurement reports and the pretrained model's
  evaluation, copied as they stand, so that the pages link to them and the site never
  holds a second copy that could drift.
* ``changelog.md``: ``CHANGELOG.md``.

The pages link to these as the repository holds them (``../results/agents.md``), which
``docs/site_links.py`` maps to the copies here when a page is rendered.
"""

from __future__ import annotations

import re
import shutil
import sys
from pathlib import Path

import griffe
import mkdocs_gen_files

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "docs"))  # site_links, beside this file

from site_links import COPIED, page_of  # noqa: E402  (one copy of what the site holds)

PACKAGES = ("pool_env", "agents")


def module_names(package: str) -> list[tuple[str, ...]]:
    """Dotted module paths (as tuples) of ``package``, packages first, private ones left out."""
    names = []
    for path in sorted((ROOT / package).rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        elif parts[-1].startswith("_"):
            continue  # private (_version) and __main__
        if any(part.startswith("_") for part in parts) or "__pycache__" in parts:
            continue
        names.append(parts)
    return names


def resolve_export(package: griffe.Module, name: str) -> griffe.Object:
    """What ``package.name`` is: a member, or (a lazy export) the one submodule defining it."""
    if name in package.members:
        member = package.members[name]
        return member.final_target if member.is_alias else member
    # A lazy export (module __getattr__): one of the submodules the package's code imports.
    source = Path(package.filepath).read_text()
    imported = {
        sub or names.split()[0]
        for sub, names in re.findall(rf"from {package.path}(?:\.(\w+))? import (\w+)", source)
    }
    found = [
        module.members[name]
        for module_name, module in package.modules.items()
        if module_name in imported and name in module.members and not module.members[name].is_alias
    ]
    if len(found) != 1:
        raise SystemExit(f"{package.path}.__all__ names {name!r}: defined in {len(found)} places")
    return found[0]


def exports_table(package: griffe.Module, documented: set[str]) -> str:
    """A table of a package's ``__all__``: each name linked to the page that defines it."""
    names = [str(name) for name in (package.exports or [])]
    if not names:
        return ""
    rows = ["| name | defined in |", "|---|---|"]
    for name in names:
        target = resolve_export(package, name)
        module = target.module.path if not target.is_module else target.path
        public_module = module
        while public_module not in documented and "." in public_module:
            public_module = public_module.rsplit(".", 1)[0]  # a private module: its package
        if public_module not in documented:
            raise SystemExit(f"{package.path}.{name}: no reference page for {module}")
        if module in documented and target.docstring is not None:
            link = f"[`{name}`][{target.path}]"
        else:  # a constant without a docstring of its own: link its module
            link = f"[`{name}`][{public_module}]"
        rows.append(f"| {link} | `{public_module}` |")
    return "\n".join(["", "Public names:", "", *rows, ""])


def load_packages() -> dict[str, griffe.Module]:
    """The packages as griffe reads them from the source (nothing is imported)."""
    return {name: griffe.load(name, search_paths=[str(ROOT)]) for name in PACKAGES}


def write_reference() -> None:
    """``reference/**.md`` and the reference's navigation (``reference/SUMMARY.md``)."""
    nav = mkdocs_gen_files.Nav()
    documented = set()
    modules = []
    for package in PACKAGES:
        for parts in module_names(package):
            documented.add(".".join(parts))
            modules.append(parts)
    loader = load_packages()
    for parts in modules:
        dotted = ".".join(parts)
        obj = loader[parts[0]]
        for part in parts[1:]:
            obj = obj.members[part]
        is_package = (ROOT.joinpath(*parts) / "__init__.py").is_file()
        page = page_of(parts, is_package)
        nav[parts] = page
        with mkdocs_gen_files.open(f"reference/{page}", "w") as out:
            if is_package:
                out.write(f"::: {dotted}\n    options:\n      members: false\n")
                out.write(exports_table(obj, documented))
            else:
                out.write(f"::: {dotted}\n")
        source = ROOT.joinpath(*parts) / "__init__.py" if is_package else None
        source = source or ROOT.joinpath(*parts).with_suffix(".py")
        mkdocs_gen_files.set_edit_path(f"reference/{page}", source.relative_to(ROOT))
    with mkdocs_gen_files.open("reference/SUMMARY.md", "w") as out:
        out.writelines(nav.build_literate_nav())


def list_simulator_modules(loader: dict[str, griffe.Module]) -> None:
    """Append every module of ``pool_env.sim`` and its first docstring paragraph to physics.md.

    So a module others add to the simulator (spin, say) shows on the physics page without an
    edit here.
    """
    rows = ["", "| module | what it is |", "|---|---|"]
    for parts in module_names("pool_env"):
        if parts[:2] != ("pool_env", "sim"):
            continue
        obj = loader["pool_env"]
        for part in parts[1:]:
            obj = obj.members[part]
        is_package = (ROOT.joinpath(*parts) / "__init__.py").is_file()
        doc = obj.docstring.value if obj.docstring else ""
        summary = " ".join(doc.split("\n\n")[0].split()).replace("|", "\\|")
        link = f"[`{'.'.join(parts)}`](reference/{page_of(parts, is_package)})"
        rows.append(f"| {link} | {summary} |")
    with mkdocs_gen_files.open("physics.md", "a") as out:
        out.write("\n".join(rows) + "\n")


def page_title(path: Path) -> str:
    """The first heading of a Markdown file (its name if it has none), for the menu."""
    for line in path.read_text().splitlines():
        if line.startswith("# "):
            return line[2:].strip().replace("[", "(").replace("]", ")")
    return path.stem


def copy_reports() -> None:
    """``results/`` and ``models/`` reports into the site, as they stand, each in the menu.

    Each folder gets a ``SUMMARY.md`` (literate-nav) listing its pages by their titles, so a
    report that others add shows in the site's menu without an edit here.
    """
    for folder, patterns in COPIED.items():
        nav = []
        for pattern in patterns:
            for path in sorted((ROOT / folder).glob(pattern)):
                name = path.relative_to(ROOT / folder).as_posix()
                with (
                    path.open("rb") as src,
                    mkdocs_gen_files.open(f"{folder}/{name}", "wb") as dst,
                ):
                    shutil.copyfileobj(src, dst)
                if path.suffix == ".md":
                    nav.append(f"* [{page_title(path)}]({name})\n")
        with mkdocs_gen_files.open(f"{folder}/SUMMARY.md", "w") as out:
            out.writelines(nav)
    with mkdocs_gen_files.open("changelog.md", "w") as out:
        out.write((ROOT / "CHANGELOG.md").read_text())


write_reference()
list_simulator_modules(load_packages())
copy_reports()
