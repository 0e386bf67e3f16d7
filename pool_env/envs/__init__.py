"""The fronts: Gymnasium's and PettingZoo's APIs over the decision process of :mod:`pool_env.game`.

Modules: :mod:`.env` (:class:`~pool_env.PoolEnv`, one table), :mod:`.vector`
(:class:`~pool_env.PoolVectorEnv`, many tables in one step), :mod:`.multiagent` (two
players: PettingZoo's AEC env and a one-agent env against a fixed policy),
:mod:`.registration` (the ids), :mod:`.record` (video of every shot), :mod:`.checks` (the
fronts' own arguments: seeds, reset masks, render modes) and :mod:`.seeding` (Gymnasium's
generators for the tables). Importing this package imports none of them, so that
``import pool_env`` registers the ids without loading Gymnasium.
"""
