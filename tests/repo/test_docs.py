"""The docs say what the code does: documented defaults, ids and code blocks.

The code blocks themselves run through sybil (``conftest.py``); here: every default that a
docstring or a page writes down equals the code's, and every fenced block is of a kind the
suite runs (or plain text).
"""

from __future__ import annotations

import ast
import dataclasses
import inspect
import re
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import pool_env
from pool_env import Table
from pool_env.envs.registration import CURRENT_IDS
from pool_env.game.config import DEFAULT_AIM_RANGE, DEFAULT_SPEED_RANGE, make_config
from pool_env.game.games.solitaire import REWARD_TERMS as SOLITAIRE_REWARDS
from pool_env.game.games.wpa import REWARD_TERMS as WPA_REWARDS
from pool_env.game.games.wpa import WpaRules
from pool_env.game.registry import BUILTIN, ruleset_for
from pool_env.game.ruleset import RulesSection
from pool_env.game.sections import (
    DEFAULT_MODEL,
    KEYS,
    SECTIONS,
    NoiseSection,
    TableSection,
    TaskSection,
    default_config,
)

#: Every keyword the specification documents, and its section: the shared sections' keys,
#: the built-in games' rules keys and their reward terms.
#: Every built-in game's rules section and reward terms (WPA's first: where games share a
#: key, the specification quotes the WPA games' default and names the others' in words).
GAME_SECTIONS = [WpaRules] + [ruleset_for(g).section for g in BUILTIN]
GAME_REWARDS = [SOLITAIRE_REWARDS, WPA_REWARDS] + [ruleset_for(g).reward_terms for g in BUILTIN]
DOCUMENTED_KEYS = {
    **KEYS,
    **{f.name: "rules" for section in GAME_SECTIONS for f in dataclasses.fields(section)},
    **{f"reward_{t}": "rewards" for terms in GAME_REWARDS for t in terms},
}

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
RUN_LANGUAGES = {"python", "bash"}  # run by conftest.py
TEXT_LANGUAGES = {"text"}  # output or layouts, nothing to run


def table_rows(text: str, header: str) -> list[list[str]]:
    """The cells of the markdown table whose header row starts with ``header``."""
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.strip().startswith(header))
    rows = []
    for line in lines[start + 2 :]:
        if not line.strip().startswith("|"):
            break
        rows.append([cell.strip() for cell in line.strip().strip("|").split("|")])
    return rows


def literal(cell: str) -> object:
    """A documented value (``"cut"``, ``(0.45, 4.5)``, ``None``) as Python data."""
    return ast.literal_eval(cell.replace("``", "").replace("`", ""))


# Documented defaults that are not literals, and what the code's default must be for them.
NON_LITERAL = {
    '`Table(model="spin")`': None,  # None: make_config builds Table(model=DEFAULT_MODEL)
    "scene's": None,  # None: the scene decides
    "by `aim`": None,  # None: DEFAULT_AIM_RANGE[aim]
}


SPEC = ROOT / "docs" / "environments" / "specification.md"


def _section_defaults() -> dict[str, object]:
    """Every config key's default, from the section dataclasses (the one signature source)."""
    defaults: dict[str, object] = {}
    for section in (TableSection, TaskSection, WpaRules, RulesSection):  # game: solitaire's
        defaults.update((f.name, f.default) for f in dataclasses.fields(section))
    for section in GAME_SECTIONS:  # the other games' own keys
        for f in dataclasses.fields(section):
            defaults.setdefault(f.name, f.default)
    defaults["noise"] = NoiseSection().sigmas
    for terms in (SOLITAIRE_REWARDS, WPA_REWARDS):
        defaults.update((f"reward_{term}", scale) for term, scale in terms.items())
    for terms in GAME_REWARDS:
        for term, scale in terms.items():
            defaults.setdefault(f"reward_{term}", scale)
    return defaults


def test_specification_table_matches_the_config_sections() -> None:
    rows = table_rows(SPEC.read_text(), "| Section | Key | Type | Default |")
    documented = {row[1].strip("`"): (row[0], row[3]) for row in rows}
    assert set(documented) == set(DOCUMENTED_KEYS)  # every key, no other
    defaults = _section_defaults()
    for name, (section, cell) in documented.items():
        assert section.split()[0] == DOCUMENTED_KEYS[name], (name, section)
        code = defaults[name]
        expected = NON_LITERAL[cell] if cell in NON_LITERAL else literal(cell)
        assert code == expected, (name, cell, code)
        if isinstance(expected, tuple):  # and the same type: a tuple, not a list
            assert isinstance(code, tuple), name
    config = make_config()
    default = Table(model=DEFAULT_MODEL)  # 'Table(model="spin")': its numbers and pockets
    assert DEFAULT_MODEL == "spin"
    for field in dataclasses.fields(Table):
        if field.init and field.name != "pockets":
            assert getattr(config.table, field.name) == getattr(default, field.name), field.name
    np.testing.assert_array_equal(config.table.pockets, default.pockets)
    assert config.aim_range == DEFAULT_AIM_RANGE["cut"]  # "by aim"


#: The games a row of the specification's table names in its section's parentheses.
ROW_GAMES = {
    "9": "nine", "10": "ten", "8": "eight", "solitaire": "solitaire", "snooker": "snooker",
    "three-cushion": "three_cushion",
}  # fmt: skip


def _documented_games(section: str) -> set[str]:
    """``rules (9/10/8-ball)`` -> {"nine", "ten", "eight"}; ``(all games)``: every game."""
    inside = section.partition("(")[2].rstrip(")")
    if inside == "all games":
        return set(BUILTIN)
    return {
        ROW_GAMES[name]
        for part in inside.split(", ")  # "9/10/8-ball, snooker"
        for name in part.removesuffix("-ball").split("/")
    }


def test_specification_names_every_game_and_each_keys_games() -> None:
    """The ``game`` row lists the registry's games; a rules or reward row, the games of its key.

    Issue 48: the row had listed ``"nine"`` or ``"eight"`` while the code took ``"ten"``.
    """
    rows = table_rows(SPEC.read_text(), "| Section | Key | Type | Default |")
    game_row = next(row for row in rows if row[1] == "`game`")
    assert set(re.findall(r'`"(\w+)"`', game_row[4])) == set(BUILTIN)
    assert "`register_game`" in game_row[4]  # and the user's games
    for section, key, *_ in rows:
        name = key.strip("`")
        if section.split()[0] == "rules" and "(" in section:
            owners = {g for g in BUILTIN if name in _field_names(ruleset_for(g).section)}
        elif section.split()[0] == "rewards":
            term = name.removeprefix("reward_")
            owners = {g for g in BUILTIN if term in ruleset_for(g).reward_terms}
        else:
            continue
        assert _documented_games(section) == owners, (section, name, owners)


def _field_names(section_type: type) -> set[str]:
    return {f.name for f in dataclasses.fields(section_type)}


def test_default_configs_docstring_names_every_key_and_no_other() -> None:
    """``default_config``'s docstring lists the keys it takes, as the code has them."""
    doc = inspect.getdoc(default_config) or ""
    assert "Args:" in doc and "Returns:" in doc  # issue 48: it named no key
    listed = doc.split("Args:")[1].split("Returns:")[0]
    named = set(re.findall(r"``(\w+)``", listed))
    rule_keys = {f.name for g in BUILTIN for f in dataclasses.fields(ruleset_for(g).section)}
    assert set(KEYS) | set(SECTIONS) | {"game"} <= named  # every key, every section
    assert rule_keys - {"game"} <= named  # the built-in games' rules keys
    assert named <= set(KEYS) | set(SECTIONS) | rule_keys | {"reward_<term>"}, named
    assert "``reward_<term>``" in listed and "docs/environments/specification.md" in doc


def test_specification_quotes_the_code_defaults() -> None:
    doc = SPEC.read_text()
    low, high = DEFAULT_SPEED_RANGE
    row = f"| `speed_range[0]` | `speed_range[1]` | {low} .. {high} m/s |"
    assert row in doc
    table = Table()
    for name in ("mu_roll", "e_ball", "e_cushion"):
        assert f"`{name} = {getattr(table, name)}`" in doc, name
    description = doc.split("## Action Space")[0]
    assert "pockets with jaws" in description and "as capture circles" not in description
    assert table.jaws is not None and len(table.jaws) == 6


def test_physics_page_table_defaults_match_the_code() -> None:
    text = (ROOT / "docs" / "physics.md").read_text()
    rows = table_rows(text, "| parameter | default |")
    fields = {f.name: f.default for f in dataclasses.fields(Table) if f.init}
    documented = {row[0].strip("`"): row[1] for row in rows}
    assert set(documented) == set(fields)
    for name, cell in documented.items():
        assert literal(cell) == fields[name], (name, cell, fields[name])


@pytest.mark.parametrize("page", ["README.md", "docs/environments/solitaire.md"])
def test_id_tables_match_the_registry(page: str) -> None:
    text = (ROOT / page).read_text()
    rows = table_rows(text, "| id | scene | episode | max_episode_steps |")
    if page == "README.md":  # the current ids (the earlier versions: a sentence below)
        assert {row[0].strip("`") for row in rows} == set(CURRENT_IDS)
    for row in rows:
        assert gym.spec(row[0].strip("`")).max_episode_steps == int(row[3]), row


def test_readme_test_command_is_what_ci_runs() -> None:
    readme = (ROOT / "README.md").read_text()
    command = 'python -m pip install -e ".[dev]" && python -m pytest -q'
    assert f"```bash\n{command}\n```" in readme
    ci = (ROOT / ".ci" / "run").read_text().strip().splitlines()
    assert ci[-1] == command  # CI ends with it, so its last lines are pytest's summary


def test_readme_first_screen() -> None:
    lines = (ROOT / "README.md").read_text().splitlines()
    assert len(lines) <= 150
    first = "\n".join(lines[:40])
    assert "![" in first and "```python" in first and "train.py" in first
    assert not re.search(r"load (average )?\d|20\d\d-\d\d-\d\d", first)  # no load, no dates


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_every_fenced_block_is_run_or_text(page: Path) -> None:
    fences = re.findall(r"^```(\S*)$", page.read_text(), flags=re.MULTILINE)
    openings = fences[::2]  # a fence opens, the next closes
    assert len(fences) % 2 == 0
    unknown = [lang for lang in openings if lang not in RUN_LANGUAGES | TEXT_LANGUAGES]
    assert not unknown, f"{page.name}: blocks that nothing runs: {unknown}"


def test_every_public_name_is_documented() -> None:
    """The reference lists ``__all__`` of both packages (docs/gen_pages.py fails otherwise)."""
    import agents

    for package in (pool_env, agents):
        for name in package.__all__:
            obj = getattr(package, name)
            doc = inspect.getdoc(obj) if callable(obj) or inspect.ismodule(obj) else "constant"
            assert doc, f"{package.__name__}.{name} has no docstring"


def test_one_version_everywhere() -> None:
    """pool_env.__version__ is the one source: the metadata, CITATION.cff and CHANGELOG agree."""
    from importlib.metadata import version

    assert version("pool_env") == pool_env.__version__
    citation = (ROOT / "CITATION.cff").read_text()
    assert f"\nversion: {pool_env.__version__}\n" in citation
    assert f"## {pool_env.__version__} (" in (ROOT / "CHANGELOG.md").read_text()
    pyproject = (ROOT / "pyproject.toml").read_text()
    assert 'dynamic = ["version"]' in pyproject and "pool_env._version.__version__" in pyproject
