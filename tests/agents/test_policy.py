"""Every agent of the package is a :class:`agents.policy.Policy`; the planners are Planners."""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import gymnasium as gym
import pytest

import agents
from agents.policy import Planner, Policy, last_plan

#: The Protocol's own signature, less ``self``: what SB3's callers pass by keyword.
PROTOCOL = list(inspect.signature(Policy.predict).parameters.values())[1:]


def _agent_classes() -> dict[str, type]:
    """Every class defined in ``agents`` with a ``predict`` (the protocols excepted)."""
    found: dict[str, type] = {}
    for info in pkgutil.walk_packages(agents.__path__, "agents."):
        module = importlib.import_module(info.name)
        for name, cls in vars(module).items():
            if (
                inspect.isclass(cls)
                and cls.__module__ == module.__name__
                and callable(getattr(cls, "predict", None))
                and cls not in (Policy, Planner)
            ):
                found[f"{module.__name__}.{name}"] = cls
    return found


AGENT_CLASSES = _agent_classes()


def test_the_walk_finds_the_agents() -> None:
    """The discovery below is not empty: it finds the baselines and the 9-ball players."""
    for name in (
        "agents.baselines.random_agent.RandomAgent",
        "agents.baselines.ghost_ball.GhostBallAgent",
        "agents.learned.rack_play.RackAgent",
        "agents.learned.lookahead.LookaheadAgent",
        "agents.learned.pretrained.PretrainedPolicy",
    ):
        assert name in AGENT_CLASSES


@pytest.mark.parametrize("name", sorted(AGENT_CLASSES))
def test_every_agent_class_has_the_policy_signature(name: str) -> None:
    """``predict(observation, state=None, episode_start=None, deterministic=True)``."""
    params = list(inspect.signature(AGENT_CLASSES[name].predict).parameters.values())[1:]
    assert len(params) == len(PROTOCOL), name
    first, *rest = params
    assert first.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD, name
    assert first.default is inspect.Parameter.empty, name
    assert [(p.name, p.default) for p in rest] == [(p.name, p.default) for p in PROTOCOL[1:]]


def test_a_class_without_the_signature_is_caught() -> None:
    """The check above fails on a ``predict(obs)`` (what a hand-written wrapper tends to be)."""

    class Bare:
        def predict(self, obs: object) -> tuple[object, None]:
            return obs, None

    params = list(inspect.signature(Bare.predict).parameters.values())[1:]
    assert len(params) != len(PROTOCOL)


def test_planners_report_their_plan_and_policies_none() -> None:
    env = gym.make("pool_env/OneBallRoll-v1")
    obs, _ = env.reset(seed=0)
    ghost = agents.GhostBallAgent(env)
    rand = agents.RandomAgent(env, seed=0)
    assert isinstance(ghost, Planner) and isinstance(rand, Policy)
    assert not isinstance(rand, Planner)
    ghost.predict(obs)
    assert last_plan(ghost)["kind"] in ("ghost", "traced", "fallback")
    assert last_plan(rand) == {}
