"""Every game by its name: the built-in game packages, the user's, registered once each.

A game is a :class:`~pool_env.game.ruleset.Ruleset` living in a package of its own. The
built-in ones (:mod:`pool_env.game.games`) are imported the first time their name is looked
up, so no shared module of the game layer imports a game (an import contract in
``pyproject.toml``). A user's game joins with one call, :func:`register_game`, or from an
installed package through the entry point group :data:`ENTRY_POINT_GROUP`:

.. code-block:: toml

    [project.entry-points."pool_env.games"]
    carom_drill = "my_pool_games.carom:GAME"

where ``GAME`` is a ruleset (or a dict of them by name). ``docs/own_game.md`` builds one.
"""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Mapping
from dataclasses import fields, is_dataclass
from importlib.metadata import entry_points

from pool_env.game.ruleset import Ruleset, RulesSection

#: The entry point group through which installed packages add games.
ENTRY_POINT_GROUP = "pool_env.games"

#: The built-in games: name -> the package whose ``GAMES`` dict holds it.
BUILTIN: dict[str, str] = {
    "solitaire": "pool_env.game.games.solitaire",
    "nine": "pool_env.game.games.wpa",
    "eight": "pool_env.game.games.wpa",
    "ten": "pool_env.game.games.wpa",
    "three_cushion": "pool_env.game.games.three_cushion",
}

_games: dict[str, Ruleset] = {}
_entry_points_loaded = False


def register_game(ruleset: Ruleset, replace: bool = False) -> Ruleset:
    """Make ``ruleset`` playable as ``game=ruleset.name`` (``PoolEnv``, ``PoolVectorEnv``, ids).

    Args:
        ruleset: The game: a :class:`~pool_env.game.ruleset.Ruleset` instance whose
            ``name`` is new (a built-in name is refused), with a rules section type
            (a frozen dataclass subclassing ``RulesSection``) and reward terms (names
            and default scales).
        replace: Allow a name registered before to be taken over (a notebook re-running
            its cell); built-in names stay refused.

    Returns:
        ``ruleset``, so that a module may write ``GAME = register_game(MyGame())``.

    Raises:
        ValueError: On anything that is not a complete game, naming what is wrong.
    """
    _check_game(ruleset)
    name = ruleset.name
    if name in BUILTIN:
        raise ValueError(f"game name {name!r} is a built-in game's: choose another name")
    known = _games.get(name)
    if known is not None and known is not ruleset and not replace:
        raise ValueError(
            f"game {name!r} is registered already ({known!r}); pass replace=True to take it over"
        )
    _games[name] = ruleset
    return ruleset


def ruleset_for(game: object) -> Ruleset:
    """The ruleset named ``game`` (a built-in one is imported on first use).

    Raises:
        ValueError: For a name that is no game.
    """
    if isinstance(game, str):
        found = _games.get(game)
        if found is not None:
            return found
        if game in BUILTIN:
            _load_builtin(BUILTIN[game])
            return _games[game]
        _load_entry_points()
        if game in _games:
            return _games[game]
    raise ValueError(f"game must be one of {list(game_names())}, got {game!r}")


def game_names() -> tuple[str, ...]:
    """Every game's name: the built-in ones, then those registered or installed."""
    _load_entry_points()
    return (*BUILTIN, *(name for name in _games if name not in BUILTIN))


def every_game() -> dict[str, Ruleset]:
    """Every game by name (each built-in package imported)."""
    return {name: ruleset_for(name) for name in game_names()}


def _load_builtin(package: str) -> None:
    module = importlib.import_module(package)
    for name, ruleset in module.GAMES.items():
        _check_game(ruleset)
        _games[name] = ruleset


def _load_entry_points() -> None:
    global _entry_points_loaded
    if _entry_points_loaded:
        return
    _entry_points_loaded = True
    for point in entry_points(group=ENTRY_POINT_GROUP):
        # One broken package must not break every game's lookup (an unknown keyword asks
        # every game), nor hide the packages after it: it is named in a warning, and left.
        try:
            loaded = point.load()
            games = loaded.values() if isinstance(loaded, Mapping) else [loaded]
            for ruleset in games:
                if getattr(ruleset, "name", None) not in _games:
                    register_game(ruleset)
        except Exception as exc:  # any failure of a third-party package
            warnings.warn(
                f"pool_env: the game of entry point {point.name!r} ({ENTRY_POINT_GROUP}) "
                f"was not registered: {exc}",
                RuntimeWarning,
                stacklevel=2,
            )


def _check_game(ruleset: object) -> None:
    """Refuse what cannot be played as a game (``ValueError``, naming the first defect)."""
    if not isinstance(ruleset, Ruleset):
        raise ValueError(f"a game is a pool_env.game.ruleset.Ruleset instance, got {ruleset!r}")
    name = ruleset.name
    if not isinstance(name, str) or not name.isidentifier():
        raise ValueError(f"a game's name must be an identifier, got {name!r}")
    section = ruleset.section
    if not (isinstance(section, type) and issubclass(section, RulesSection)
            and is_dataclass(section)):  # fmt: skip
        raise ValueError(
            f"game {name!r}: section must be a dataclass subclassing RulesSection, got {section!r}"
        )
    reserved = [f.name for f in fields(section) if f.name.startswith("reward_")]
    if reserved:  # reward_<x> keywords set the rewards section
        raise ValueError(f"game {name!r}: rules keys {reserved} take the reward_ prefix")
    terms = ruleset.reward_terms
    if not isinstance(terms, Mapping) or not all(
        isinstance(t, str) and t.isidentifier() and _is_number(v) for t, v in terms.items()
    ):
        raise ValueError(
            f"game {name!r}: reward_terms must map term names to default scales, got {terms!r}"
        )
    if not (_is_int(ruleset.rack_width) and ruleset.rack_width >= 0):
        raise ValueError(f"game {name!r}: rack_width must be an int >= 0")
    if not (_is_int(ruleset.action_width) and ruleset.action_width >= 2):
        raise ValueError(f"game {name!r}: action_width must be an int >= 2 (aim and speed first)")
    scenes = ruleset.scenes
    if not isinstance(scenes, Mapping) or not all(isinstance(k, str) for k in scenes):
        raise ValueError(f"game {name!r}: scenes must map names to layouts or callables")
    if type(ruleset).info_columns is not Ruleset.info_columns and not ruleset.info_keys:
        raise ValueError(f"game {name!r} reports info_columns: name them in its info_keys")


def _is_int(value: object) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)
