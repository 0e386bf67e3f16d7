"""Tests of agents/: baselines, learned players, evaluation, training, integrations."""
