"""The search player's file (``models/search_player.yaml``): its schema, checked at load.

A player file is a YAML mapping of :data:`KEYS`: ``kind: search``, the game its values were
fitted for (``game``: ``nine`` when left out), the ``.npz`` models the player values its
outcomes with, and its ``settings`` (:class:`SearchSettings`, each key
one of :data:`~agents.learned.search_player.SETTINGS`). :func:`read_player_file` refuses,
with one ``ValueError`` that names the file and the key (dotted below the top level,
``settings.samples``) or the model path as written, and the valid type, range or choices:

- a file that is missing, a directory, not YAML, or not a mapping;
- an unknown key at any level (a misspelt ``setvalue`` is not ignored), or a key given
  twice in one mapping (YAML would keep the last one silently);
- a value of the wrong type (a count that is not an integer, ``2.7`` or ``true``; a
  number that is a bool, a string, NaN or infinite) or out of its range (a budget
  <= 0, a break off the table for the player's table, :func:`check_break`);
- a model path that is not a string, is missing or a directory, or is not a readable
  ``.npz`` of the real-number arrays the model needs
  (:func:`~agents.learned.layout_value.load_arrays`);
- a ``game`` that is not one of :data:`GAMES`, a ``set_value`` off 9-ball (the set network
  reads the ball on), and, when a player is made (:func:`load_search_player`), an env of
  another game than the file's (its values would be another game's).

**Paths**: a relative model path is read from the player file's folder
(``layout_value: runout_value.npz`` beside ``models/search_player.yaml`` is
``models/runout_value.npz``, whatever the current directory); an absolute path as it
stands. Nothing else is tried: a path that names no file is an error showing the path as
written and where it was looked for.
"""

from __future__ import annotations

import difflib
import inspect
import reprlib
from collections.abc import Callable, Hashable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from agents.learned.layout_value import LayoutValue
from agents.learned.leaf_value import SetLeaf
from agents.learned.lookahead import PLAY_SETTINGS, LookaheadAgent
from agents.learned.search_player import (
    GAME_IDS,
    SETTINGS,
    SearchPlayer,
    SearchSettings,
    check_break,
    check_setting,
)
from agents.learned.set_value import SetValue
from pool_env.extras import require
from pool_env.sim import Table

#: The keys of a player file and what each holds.
KEYS = {
    "kind": "search (the only kind)",
    "game": "the game the values are for: nine (the default), ten or eight",
    "layout_value": "the path of the run-out layout value (a LayoutValue .npz)",
    "duel_value": "the path of the duel layout value (a LayoutValue .npz)",
    "set_value": "the path of the set network (a SetValue .npz), the run-out leaf value",
    "settings": "the search's settings (a mapping; defaults for those left out)",
}

#: The games a player file may name (the rulesets' names), and the env ids that play them.
GAMES = GAME_IDS

Model = TypeVar("Model", LayoutValue, SetValue)


@dataclass(frozen=True)
class PlayerFile:
    """A checked player file: its models read, its settings made.

    Attributes:
        path: The file, as given.
        layout_value: The run-out layout value.
        duel_value: The duel layout value (``None`` if the file names none).
        set_value: The set network (``None`` if the file names none).
        settings: The search's settings.
        game: The game the values are for (:data:`GAMES`).
    """

    path: Path
    layout_value: LayoutValue
    duel_value: LayoutValue | None
    set_value: SetValue | None
    settings: SearchSettings
    game: str = "nine"


def read_player_file(path: str | Path, table: Table, duel: bool = False) -> PlayerFile:
    """Read and check the player file at ``path`` (module doc), its models too.

    Args:
        path: The ``.yaml`` file.
        table: The table the player will play on (the break is checked against it).
        duel: The player will play an opponent: ``duel_value`` is required.

    Raises:
        ValueError: ``player file '<path>': ...`` naming the key or the model path as
            written, and what it must be (module doc).
    """
    try:
        return _read(Path(path), table, duel)
    except ValueError as err:
        raise ValueError(f"player file {str(path)!r}: {err}") from None


def load_search_player(path: str | Path, env: Any, players: int | None = None) -> SearchPlayer:
    """The :class:`SearchPlayer` the player file at ``path`` describes.

    The objective is the run-out alone (``layout_value``'s leaves, or ``set_value``'s
    when the file names it), or the duel when the player is told it plays an opponent
    (``players=2``, as the duels build it; ``duel_value``'s leaves).

    Raises:
        ValueError: As :func:`read_player_file`; an env of another game than the file's
            ``game``; or from :class:`SearchPlayer` (an env that is not a WPA game).
    """
    config = env.unwrapped.config
    duel = (players if players is not None else config.players) == 2
    file = read_player_file(path, config.table, duel=duel)
    if config.game not in GAMES:  # not a WPA game at all: no file of ours plays it
        ids = ", ".join(GAMES.values())
        spec = getattr(env, "spec", None)
        given = spec.id if spec is not None else f"game={config.game!r}"
        raise ValueError(
            f"player file {str(path)!r} cannot play {given}: the search player plays the WPA "
            f"game ids ({ids})"
        )
    if config.game != file.game:
        fitted = {"nine": "9-ball", "ten": "10-ball (9-ball's values)", "eight": "8-ball"}
        raise ValueError(
            f"player file {str(path)!r}: game {file.game!r} (values for {fitted[file.game]} "
            f"layouts) cannot play game={config.game!r}: use a file with game: "
            f"{config.game} for {GAMES[config.game]}"
        )
    value = file.duel_value if duel else file.layout_value
    assert value is not None  # read_player_file requires it for a duel
    player = SearchPlayer(env, value, "duel" if duel else "runout", file.settings,
                          players=players)  # fmt: skip
    if file.set_value is not None and not duel:  # the set network predicts run-outs
        player.leaf = SetLeaf(file.set_value, player.config.table, player.mouths, player.sigma)
    return player


def load_lookahead_agent(
    path: str | Path, env: Any, config: dict[str, Any], players: int | None = None
) -> SearchPlayer:
    """The lookahead of a layout value saved at ``path``: the search player at depth 1.

    ``config`` is the value's ``<stem>_config.yaml`` (``kind: lookahead``): its objective
    and :data:`~agents.learned.lookahead.PLAY_SETTINGS` (the planner's pots kept, the plays
    of every candidate and of the finalists, the break arm) become the player's settings
    (:class:`SearchSettings` ``depth=1``), so that a lookahead file and a player file make
    the same player, at two settings. ``players``: as :class:`SearchPlayer`.

    Raises:
        ValueError: On a game other than 9-ball and 10-ball (the values are 9-ball's).
    """
    game = env.unwrapped.config.game
    if game not in ("nine", "ten"):  # as the lookahead class: 9-ball's values, rotation
        hint = ": 8-ball's player is models/search_player_eight.yaml" if game == "eight" else ""
        raise ValueError(
            f"lookahead file {str(path)!r} holds 9-ball layout values (10-ball reads them the "
            f"same way), not game={game!r}{hint}"
        )
    # The config's settings over the lookahead's own defaults (a config may leave any out).
    own = inspect.signature(LookaheadAgent.__init__).parameters
    given = {k: config.get(k, own[k].default) for k in PLAY_SETTINGS}
    objective, arm = given.pop("objective"), given.pop("break_arm")
    settings = SearchSettings(depth=1, break_arm=-1 if arm is None else arm, **given)
    return SearchPlayer(env, LayoutValue.load(path), objective, settings, players=players)


def _read(path: Path, table: Table, duel: bool) -> PlayerFile:
    """:func:`read_player_file`'s checks; messages without the file's name."""
    yaml = require("yaml", "train", "a player file")
    _check_file(path, "")
    try:
        config = _load_unique(yaml, path.read_text())
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as err:
        raise ValueError(f"cannot be read as YAML: {' '.join(str(err).split())}") from None
    _check_keys(config, KEYS, "", "the file")
    if config.get("kind") != "search":
        raise ValueError(f"kind must be 'search', got {config.get('kind')!r}")
    game = config.get("game", "nine")
    if not isinstance(game, str) or game not in GAMES:
        raise ValueError(f"game must be one of {', '.join(GAMES)}, got {game!r}")
    raw = config.get("settings", {})
    _check_keys(raw, SETTINGS, "settings.", "settings")
    values = {name: check_setting(name, v, f"settings.{name}") for name, v in raw.items()}
    settings = SearchSettings(**values)  # type: ignore[arg-type]
    check_break(settings, table, "settings.")
    base = path.parent  # the file's own values first, then the models it names
    layout_value = _model(config, "layout_value", base, LayoutValue.load, required="")
    against = " to play an opponent (players=2)" if duel else None
    duel_value = _model(config, "duel_value", base, LayoutValue.load, required=against)
    if game != "nine" and config.get("set_value") is not None:
        raise ValueError(
            f"set_value is 9-ball's (the set network reads the ball on): game {game!r} "
            "values its leaves with layout_value and duel_value only"
        )
    set_value = _model(config, "set_value", base, SetValue.load, required=None)
    return PlayerFile(path, layout_value, duel_value, set_value, settings, game)


def _check_file(path: Path, what: str, why: str = "") -> None:
    """Refuse a ``path`` that names no file: ``what`` (the key and path as written) first."""
    if path.is_dir():
        raise ValueError(f"{what}is a directory, not a file ({path.absolute()})")
    if not path.is_file():
        raise ValueError(f"{what}not found (looked for {path.absolute()}{why})")


def _load_unique(yaml: Any, text: str) -> Any:
    """``yaml.safe_load(text)``, refusing a key given twice in one mapping, at any level.

    PyYAML keeps the last of two equal keys without a word; a player file that says
    ``samples`` twice is a mistake to show, not a value to pick.

    Raises:
        ValueError: ``duplicate key settings.samples (lines 7 and 9)``.
        yaml.YAMLError: On text that is not YAML.
    """

    class UniqueKeyLoader(yaml.SafeLoader):  # type: ignore[name-defined,misc]
        def construct_document(self, node: Any) -> Any:
            _check_unique(yaml, self, node, "")
            return super().construct_document(node)

    loader = UniqueKeyLoader(text)
    try:
        return loader.get_single_data()
    finally:
        loader.dispose()


def _check_unique(yaml: Any, loader: Any, node: Any, prefix: str) -> None:
    """Walk the composed ``node``: a mapping's keys (as YAML reads them) must be distinct."""
    if isinstance(node, yaml.SequenceNode):
        for k, item in enumerate(node.value):
            _check_unique(yaml, loader, item, f"{prefix.rstrip('.')}[{k}].")
    if not isinstance(node, yaml.MappingNode):
        return
    seen: dict[Any, int] = {}
    for key_node, value_node in node.value:
        key = loader.construct_object(key_node, deep=True)
        if key == "<<" or not isinstance(key, Hashable):  # a merge, or YAML's own error
            continue
        line = key_node.start_mark.line + 1
        if key in seen:
            where = (
                f"twice on line {line}" if seen[key] == line else f"lines {seen[key]} and {line}"
            )
            raise ValueError(f"duplicate key {prefix}{key} ({where}): give each key once")
        seen[key] = line
        _check_unique(yaml, loader, value_node, f"{prefix}{key}.")


def _check_keys(mapping: object, keys: Iterable[str], prefix: str, what: str) -> None:
    """Refuse a value that is not a mapping, or a key that is not one of ``keys``."""
    keys = list(keys)
    if not isinstance(mapping, Mapping):
        raise ValueError(
            f"{what} must be a mapping of {', '.join(keys)}, got {reprlib.repr(mapping)}"
        )
    for key in mapping:
        if key not in keys:
            close = difflib.get_close_matches(str(key), keys, n=1)
            hint = f" (did you mean {prefix}{close[0]}?)" if close else ""
            raise ValueError(f"unknown key {prefix}{key}{hint}: the keys are {', '.join(keys)}")


def _model(
    config: Mapping[str, Any],
    key: str,
    base: Path,
    load: Callable[[Path], Model],
    required: str | None,
) -> Model | None:
    """The model ``config[key]`` names, its path read from ``base`` (module doc).

    ``required``: ``None`` if the key may be left out (or null), else why it may not
    (``""``: always).
    """
    written = config.get(key)
    if written is None:
        if required is not None:
            raise ValueError(f"{key} is required{required}: {KEYS[key]}")
        return None
    if not isinstance(written, str) or not written.strip():
        raise ValueError(f"{key} must be the path of an .npz (a string), got {written!r}")
    found = base / written  # an absolute path stays as it is
    _check_file(
        found, f"{key} {written!r} ", ": a relative path is read from the player file's folder"
    )
    try:
        return load(found)
    except ValueError as err:
        raise ValueError(f"{key} {written!r}: {err}") from None
