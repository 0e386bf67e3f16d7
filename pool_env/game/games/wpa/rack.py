"""The WPA rack state at reset: ``options["rules"]`` parsed, and checked against the balls.

A rack state (:mod:`pool_env.game.games.wpa.rack_state`'s row) is given at reset or made
for a racked scene; :func:`check_rack` refuses one that the rules could never finish (no 9
in 9-ball, no 8 in 8-ball, an open table with nothing but the 8) or that no game reaches (groups on
the break), so that ``info`` and the observation never show a state the rules document
as impossible. :func:`rack_dict` reads a row back as the keys of ``options["rules"]``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.checks import is_integer
from pool_env.game.games.wpa import rack_state as wpa

if TYPE_CHECKING:
    from pool_env.game.config import GameConfig

#: ``options["rules"]`` group names, by code.
GROUP_NAMES = ("open", "solids", "stripes")

#: The keys of ``options["rules"]``.
RULE_KEYS = (
    "break", "ball_in_hand", "behind_head_string", "groups", "fouls", "shooter", "push_out",
    "option",
)  # fmt: skip


def rack_option(config: GameConfig, given: Any, rack_scene: bool) -> NDArray[np.int64]:
    """The rack-state row an episode starts from, from ``options["rules"]`` if given.

    Without it: a named rack scene starts with the break (player 0, the cue ball in hand
    behind the head string); any other layout with player 0 to shoot, the cue ball where it
    lies, an open table and no fouls. ``options["rules"]`` (a dict) sets any of ``break``
    (bool), ``ball_in_hand`` (bool), ``behind_head_string`` (bool), ``groups`` (two of
    ``"open"``, ``"solids"``, ``"stripes"``, players 0 and 1), ``fouls`` (each player's
    successive fouls, integers 0-2; Python or numpy integers, not bools), with two
    players ``shooter`` (0 or 1), and in 9-ball and 10-ball ``push_out`` (bool: the shot
    may be a push-out, as right after a legal break) and, with two players, ``option``
    (bool: the shooter may hand the table back). The row is checked against the balls by
    :func:`check_rack`.

    Raises:
        ValueError: On an unknown key or a bad value, naming it.
    """
    row = np.zeros(wpa.N_RACK, dtype=np.int64)
    breaking = rack_scene and isinstance(config.scene.spec, str) and config.scene.n_new == 1
    wpa.new_rack(row, breaking)
    if given is None:
        return row
    if not isinstance(given, dict):
        raise ValueError(f"options['rules'] must be a dict, got {given!r}")
    unknown = set(given) - set(RULE_KEYS)
    if unknown:
        raise ValueError(f"unknown options['rules'] keys {sorted(unknown)}: use {list(RULE_KEYS)}")
    for key, column in (("break", wpa.BREAKING), ("ball_in_hand", wpa.IN_HAND),
                        ("behind_head_string", wpa.BEHIND), ("push_out", wpa.PUSH_OUT),
                        ("option", wpa.OPTION)):  # fmt: skip
        if key in given:
            if not isinstance(given[key], bool | np.bool_):
                raise ValueError(f"options['rules'][{key!r}] must be a bool, got {given[key]!r}")
            row[column] = int(given[key])
    if "groups" in given:
        groups = given["groups"]
        if (
            config.ruleset.name != "eight"
            or not isinstance(groups, tuple | list)
            or len(groups) != 2
            or any(not isinstance(g, str) or g not in GROUP_NAMES for g in groups)
            or (groups[0] == "open") != (groups[1] == "open")
            or (groups[0] != "open" and groups[0] == groups[1])
        ):
            raise ValueError(
                "options['rules']['groups'] (8-ball only) must be ('open', 'open') or one "
                f"player 'solids' and the other 'stripes', got {groups!r}"
            )
        row[wpa.GROUP_0], row[wpa.GROUP_1] = (GROUP_NAMES.index(g) for g in groups)
    if "fouls" in given:
        fouls = given["fouls"]
        if not (isinstance(fouls, tuple | list) and len(fouls) == 2
                and all(is_integer(f) and 0 <= f <= 2 for f in fouls)):  # fmt: skip
            raise ValueError(
                f"options['rules']['fouls'] must be two integers in 0..2, got {fouls!r}"
            )
        row[wpa.FOULS_0], row[wpa.FOULS_1] = (int(f) for f in fouls)
    if "shooter" in given:
        shooter = given["shooter"]
        if not is_integer(shooter) or shooter not in (0, 1) or (config.players == 1 and shooter):
            raise ValueError(
                f"options['rules']['shooter'] must be 0 or 1 (0 with one player), got {shooter!r}"
            )
        row[wpa.SHOOTER] = int(shooter)
    if row[wpa.BEHIND] and not row[wpa.IN_HAND]:
        raise ValueError("options['rules']: behind_head_string needs ball_in_hand")
    check_option(config, row)
    return row


def check_option(config: GameConfig, row: NDArray[np.int64]) -> None:
    """Refuse a push-out or an option the game or the rack cannot have.

    Both need a game with them (9-ball, 10-ball); the push-out is the shot right after a
    legal break (no break pending, no ball in hand, no option); the option needs two
    players and no ball in hand.

    Raises:
        ValueError: Naming the key.
    """
    if not (row[wpa.PUSH_OUT] or row[wpa.OPTION]):
        return
    key = "push_out" if row[wpa.PUSH_OUT] else "option"
    if not getattr(config.ruleset, "has_option", False):
        raise ValueError(f"options['rules'][{key!r}]: game={config.ruleset.name!r} has no push-out")
    if row[wpa.PUSH_OUT] and (row[wpa.BREAKING] or row[wpa.IN_HAND] or row[wpa.OPTION]):
        raise ValueError(
            "options['rules']['push_out'] is the shot right after a legal break: no break, "
            "ball in hand or option with it"
        )
    if row[wpa.OPTION] and (config.players != 2 or row[wpa.BREAKING] or row[wpa.IN_HAND]):
        raise ValueError(
            "options['rules']['option'] needs two players, and no break or ball in hand"
        )


def check_rack(config: GameConfig, row: NDArray[np.int64], on_table: NDArray[np.bool_]) -> None:
    """Refuse a rack state the rules could never finish on these balls.

    * 9-ball without the 9 on the table (10-ball: the 10): no shot can win the rack.
    * 8-ball without the 8: no shot can win it either (every shot at the 8 is a foul).
    * 8-ball on an open table with no object ball but the 8: every first contact is a
      foul (the 8 is never a legal first ball on an open table) and 8-ball has no
      three-foul rule.
    * Groups assigned on the break: groups are assigned after the break only.
    * Fouls outside 0-2 or a shooter other than 0 or 1 (the third foul ends a 9-ball
      rack; :func:`rack_option` refuses them as given, this refuses any other source).

    Args:
        config: The rules config.
        row: The rack-state row.
        on_table: ``(K, N)`` the balls on each table to start from.

    Raises:
        ValueError: Saying which and why (the first table that fails, for a batch).
    """
    if not (0 <= row[wpa.FOULS_0] <= 2 and 0 <= row[wpa.FOULS_1] <= 2):
        raise ValueError(f"the rack's fouls must lie in 0..2, got {row[wpa.FOULS_0 : wpa.WINNER]}")
    if row[wpa.SHOOTER] not in (0, 1):
        raise ValueError(f"the rack's shooter must be 0 or 1, got {row[wpa.SHOOTER]}")
    groups = (row[wpa.GROUP_0], row[wpa.GROUP_1])
    if row[wpa.BREAKING] and groups != (wpa.OPEN, wpa.OPEN):
        raise ValueError("options['rules']: groups are assigned after the break, not on it")
    key = config.ruleset.money_ball  # type: ignore[attr-defined]
    for k in range(on_table.shape[0]):
        on = on_table[k]
        where = "" if on_table.shape[0] == 1 else f"table {k}: "
        if not on[key]:
            raise ValueError(
                f"{where}the {key} must be on the table in game={config.ruleset.name!r}: "
                "without it no shot can win the rack (options['on_table'])"
            )
        if (
            config.ruleset.name == "eight"
            and groups[0] == wpa.OPEN
            and not on[1:8].any()
            and (not on[9:].any())
        ):
            raise ValueError(
                f"{where}an open 8-ball table needs an object ball other than the 8: the 8 "
                "is never a legal first ball on an open table, so every shot would be a foul"
            )


def rack_dict(row: NDArray[np.int64]) -> dict[str, Any]:
    """A rack-state row as a dict of the keys of ``options["rules"]`` and ``winner``.

    ``winner`` is -1 while the rack is undecided; ``groups`` are names (8-ball).
    """
    return {
        "shooter": int(row[wpa.SHOOTER]),
        "break": bool(row[wpa.BREAKING]),
        "ball_in_hand": bool(row[wpa.IN_HAND]),
        "behind_head_string": bool(row[wpa.BEHIND]),
        "groups": (GROUP_NAMES[row[wpa.GROUP_0]], GROUP_NAMES[row[wpa.GROUP_1]]),
        "fouls": (int(row[wpa.FOULS_0]), int(row[wpa.FOULS_1])),
        "push_out": bool(row[wpa.PUSH_OUT]),
        "option": bool(row[wpa.OPTION]),
        "winner": int(row[wpa.WINNER]),
    }


def rack_row(rack: dict[str, Any]) -> NDArray[np.int64]:
    """The row of a dict as :func:`rack_dict` gives it (its inverse; keys left out default).

    Unlike :func:`rack_option` it checks nothing against what a reset may start from: a
    rack read from a running game (8-ball fouls beyond 2, a decided winner) comes back
    as it was.
    """
    row = np.zeros(wpa.N_RACK, dtype=np.int64)
    wpa.new_rack(row, bool(rack.get("break", False)))
    row[wpa.BREAKING] = int(bool(rack.get("break", False)))
    row[wpa.IN_HAND] = int(bool(rack.get("ball_in_hand", row[wpa.IN_HAND])))
    row[wpa.BEHIND] = int(bool(rack.get("behind_head_string", row[wpa.BEHIND])))
    row[wpa.SHOOTER] = int(rack.get("shooter", 0))
    groups = rack.get("groups", ("open", "open"))
    row[wpa.GROUP_0], row[wpa.GROUP_1] = (GROUP_NAMES.index(g) for g in groups)
    row[wpa.FOULS_0], row[wpa.FOULS_1] = (int(f) for f in rack.get("fouls", (0, 0)))
    row[wpa.WINNER] = int(rack.get("winner", row[wpa.WINNER]))
    row[wpa.PUSH_OUT] = int(bool(rack.get("push_out", False)))
    row[wpa.OPTION] = int(bool(rack.get("option", False)))
    return row


def rack_of(config: GameConfig, given: Any) -> NDArray[np.int64]:
    """The rack row of ``given``: a row, a dict as ``PoolEnv.rack`` gives, or ``None``.

    ``None`` is a reset's default for a given layout (:func:`rack_option`).

    Raises:
        ValueError: On a row of another shape.
    """
    if given is None:
        return rack_option(config, None, rack_scene=False)
    if isinstance(given, dict):
        return rack_row(given)
    row = np.array(given, dtype=np.int64)
    if row.shape != (wpa.N_RACK,):
        raise ValueError(
            f"rack must be PoolEnv.rack's dict or a ({wpa.N_RACK},) row, got {given!r}"
        )
    return row
