"""Other RL libraries on pool_env: Ray RLlib and RL Zoo.

Ray RLlib: ``rllib_env``, ``rllib_train`` (behind ``python train.py --backend rllib``).
RL Zoo: ``zoo`` writes ``zoo/<algo>.yml`` from ``agents/training/hyperparams.yml``.
"""
