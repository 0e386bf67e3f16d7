"""Vector-env adapters of ``pool_env.PoolVectorEnv`` (every table in one compiled call).

``native_vec``: SB3's ``VecEnv`` (needs stable-baselines3); ``gym_vec``: Gymnasium's
same-step vector stack for CleanRL-style loops.
"""
