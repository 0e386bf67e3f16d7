"""The decision process over B tables: scenes, actions, shots, settling, rewards, rules.

One copy serves both Gymnasium fronts (:class:`pool_env.PoolEnv` with B = 1 and
:class:`pool_env.PoolVectorEnv` with B = N). Knows the simulator, not Gymnasium.
"""
