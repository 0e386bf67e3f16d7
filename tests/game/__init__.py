"""Tests of the decision process (pool_env/game): config, codec, scenes, rules, rulesets."""
