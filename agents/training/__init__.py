"""Training on stable-baselines3: the library behind ``python train.py`` (``agents.train``).

``train_lib`` (vectorized envs, periodic evaluation, a folder per run), ``run_config`` (what
defines a run: its config, the algorithms by name), ``hyperparams`` with its data
``hyperparams.yml`` (keyed by env id, then algorithm), ``runs`` (run folders),
``vec_features`` (the ghost-ball features on an SB3 ``VecEnv``), ``summarize`` and ``plots``
(learning curves across runs). Needs the ``train`` extra (SB3, torch, pyyaml, matplotlib).
"""
