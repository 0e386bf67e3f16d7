"""The built-in games, one package a family: :mod:`.solitaire` and :mod:`.wpa`.

Each package holds everything its games own (ruleset, rules section and reward terms,
compiled rules, ball in hand, game state, observation, ``info`` keys, parameter tail) and
a ``GAMES`` dict of its rulesets by name. Nothing outside a package imports it but the
registry, by name (:mod:`pool_env.game.registry`), and players that read a game's own
results; the games are independent of each other (``pyproject.toml``'s import contracts).
This module imports none of them.
"""
