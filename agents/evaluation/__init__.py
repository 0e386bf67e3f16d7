"""Evaluation: play agents on the envs and count, with 95% intervals.

``episodes`` (``run_episodes``: play and count, for every evaluation), ``metrics``
(``EpisodeLog``, ``Estimate`` and their intervals), ``constant_scan`` (the best constant
action of a grid, the ``best-const`` baseline), ``three_cushion`` (innings of
``ThreeCushion-v1``: points per inning; ``python -m agents.evaluation.three_cushion``),
``evaluate`` (agents by name on the same seeds; ``python -m agents.evaluate``) and ``duels``
(head-to-head 9-ball racks; ``python -m agents.duels``). Needs no stable-baselines3 unless a
model is loaded.
"""
