"""WPA 9-ball, 10-ball and 8-ball, as one package: everything the family owns.

Its ruleset (:mod:`.game`: :data:`NINE`, :data:`TEN`, :data:`EIGHT`), rules section and
reward terms (:mod:`.section`), compiled rules (:mod:`.rules`, over the rack state of
:mod:`.rack_state`) and judge (:mod:`.judge`), ball in hand and calls (:mod:`.shots`),
first contact (:mod:`.first_contact`), rack state at reset (:mod:`.rack`), observation
(:mod:`.observe`), ``info`` keys (:mod:`.info`) and its tail of the kernel parameters
(:mod:`.params`). The games register under ``"nine"``, ``"ten"`` and ``"eight"``
(:mod:`pool_env.game.registry`). The names below are the package's public face; a player
that reads the rules' results reads their columns where they are defined (the judge's
``FOUL``, ``KEEPS``, ``WINNER`` in :mod:`.judge`; the rack state's ``IN_HAND``,
``SHOOTER`` in :mod:`.rack_state`).
"""

from __future__ import annotations

from pool_env.game.games.wpa.game import EIGHT, NINE, TEN, WpaGame
from pool_env.game.games.wpa.info import OPTION_KEYS, RULE_KEYS
from pool_env.game.games.wpa.rack import GROUP_NAMES, rack_dict, rack_row
from pool_env.game.games.wpa.section import DEFAULT_BREAK_SPEED_RANGE, REWARD_TERMS, WpaRules

#: The rulesets this package registers, by name.
GAMES = {game.name: game for game in (NINE, EIGHT, TEN)}

__all__ = [
    "DEFAULT_BREAK_SPEED_RANGE",
    "EIGHT",
    "GAMES",
    "GROUP_NAMES",
    "NINE",
    "OPTION_KEYS",
    "REWARD_TERMS",
    "RULE_KEYS",
    "TEN",
    "WpaGame",
    "WpaRules",
    "rack_dict",
    "rack_row",
]
