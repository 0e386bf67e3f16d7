"""The decision process over B tables: scenes, actions, shots, settling, rules, rewards.

One copy serves both Gymnasium fronts (:class:`pool_env.PoolEnv` with B = 1 and
:class:`pool_env.PoolVectorEnv` with B = N). Knows the simulator, not Gymnasium's API
(it borrows only Gymnasium's seeding, so that generators match ``Env.np_random``).

Modules: :mod:`.config` (the fixed model, parsed once), :mod:`.state` (B tables in arrays),
:mod:`.scenes` (starting layouts), :mod:`.ruleset` (a game's interface, which the step asks
wherever games differ), :mod:`.registry` (every game by name), :mod:`.games` (the built-in
games, a package each: their rules, what an outcome means), :mod:`.step` (one step, one
path for every game), :mod:`.info` (the step's info), :mod:`.checks` (every argument
check), and :mod:`.kernels` (the compiled parts every game shares).
"""
