"""What the scoreboard scores: a committed player, an SB3 model, or a ``module:attr`` factory.

A policy is given as text, one of:

- a player as ``agents.evaluate --agent`` takes it (:mod:`agents.evaluation.players`:
  ``random``, ``ghost``, ``search``, ``models/search_player.yaml``,
  ``models/runout_value.npz``, ...), built by
  :func:`~agents.evaluation.players.make_agent` on each task's env and checked by
  :func:`~agents.evaluation.players.check_agents`;
- an SB3 model ``.zip`` with its saved config (``<stem>_config.yaml`` or ``config.yaml``
  beside it), loaded once by :func:`agents.load`, so its observation wrapper applies and
  its saved ``env_kwargs`` are played under the task's own (an ``observation="shots"``
  model plays the task with that observation; the task's noise and rules stand);
- ``module:attr``: a **factory**, ``attr(env) -> agent``, called with each task's
  Gymnasium env (made with the task's id, keywords and noise) and returning an
  :class:`~agents.policy.Policy`: an object with SB3's ``predict(obs, state=None,
  episode_start=None, deterministic=True) -> (action, state)`` (an SB3 model is one). A
  plain function of the observation is wrapped so in two lines (``docs/leaderboard.md``).
  A factory refuses a task it cannot play by raising ``ValueError`` (its message is the
  task's "n/a" reason); an agent with ``observation_space`` and ``action_space`` is also
  refused where their shapes differ from the env's.

A policy that cannot play a task gets "n/a" with one line saying why
(:meth:`ScoredPolicy.refusal`); text that names no policy is a ``ValueError`` at
:func:`resolve_policy`, before anything is played.
"""

from __future__ import annotations

import argparse
import importlib
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NoReturn

from agents.evaluation.evaluate import PLAYERS_HELP
from agents.evaluation.noise_flag import parse_noise
from agents.evaluation.players import FILE_KINDS, agent_kind, check_agents
from agents.learned.envs import make_env
from agents.learned.pretrained import load, model_config
from agents.policy import Policy
from agents.scoreboard.suite import Task

__all__ = ["PolicyError", "ScoredPolicy", "resolve_policy", "task_kwargs"]

#: ``module:attr``: a dotted module path, a colon, an attribute name.
MODULE_ATTR = re.compile(r"^[A-Za-z_][\w]*(\.[A-Za-z_][\w]*)*:[A-Za-z_][\w]*$")


def task_kwargs(task: Task) -> dict[str, Any]:
    """The task's ``gymnasium.make`` keywords: its own and its noise (``None``: exact)."""
    return {**task.env_kwargs, "noise": parse_noise(task.noise)}


class PolicyError(ValueError):
    """A factory that breaks the protocol: a usage error, never a task's "n/a"."""


class _Refusal(argparse.ArgumentParser):
    """:func:`check_agents`' parser: the one line it would exit with, raised instead."""

    def error(self, message: str) -> NoReturn:
        raise ValueError(message)


@dataclass
class ScoredPolicy:
    """A policy resolved from its text, ready to be built on each task.

    Attributes:
        spec: The policy as written.
        kind: ``"player"`` (built by ``make_agent``), ``"model"`` (an SB3 ``.zip``) or
            ``"factory"`` (``module:attr``).
        slug: The stem of its results file (``results/scoreboard/<slug>.json``).
        build: ``env -> Policy`` for a model or a factory; ``None`` for a player, which the
            runners build by name as their commands do.
        saved_kwargs: A model's saved ``env_kwargs`` (played under the task's).
    """

    spec: str
    kind: str
    slug: str
    build: Callable[[Any], Policy] | None = None
    saved_kwargs: dict[str, Any] = field(default_factory=dict)

    def env_kwargs(self, task: Task) -> dict[str, Any]:
        """The keywords the policy plays ``task`` with: a model's saved ones under the task's."""
        return {**self.saved_kwargs, **task_kwargs(task)}

    def refusal(self, task: Task) -> str | None:
        """Why the policy cannot play ``task`` (one line), or ``None`` if it can."""
        kwargs = self.env_kwargs(task)
        if task.runner == "runouts":
            kwargs["end_on_foul"] = True  # as play_racks makes its env
        players = 2 if task.runner == "duel" else None
        if task.runner == "duel" and set(self.saved_kwargs) - {"noise"}:
            return (
                f"{self.spec} was trained with env_kwargs {self.saved_kwargs}; the duel "
                f"plays {task.env_id}'s own observations"
            )
        try:
            if self.kind == "factory":
                return self._factory_refusal(task, kwargs)
            check_agents(_Refusal(), [self.spec], task.env_id, kwargs, players)
        except PolicyError:
            raise
        except ValueError as err:
            return " ".join(str(err).split())
        return None

    def _factory_refusal(self, task: Task, kwargs: dict[str, Any]) -> str | None:
        """Build the factory's agent on the task's env: its ``ValueError``, or the spaces.

        Raises:
            PolicyError: If the factory returns no agent (nothing with ``predict``).
        """
        assert self.build is not None
        env = make_env(task.env_id, {"noise": kwargs["noise"]} if task.runner == "duel" else kwargs)
        try:
            agent = self.build(env)
            if not callable(getattr(agent, "predict", None)):
                raise PolicyError(
                    f"policy {self.spec!r}: the factory returned {type(agent).__name__}, "
                    "not an agent with predict(obs) -> (action, state)"
                )
            for what in ("observation", "action"):
                space = getattr(agent, f"{what}_space", None)
                want = getattr(space, "shape", None)
                got = getattr(env, f"{what}_space").shape
                if want is not None and tuple(want) != tuple(got):
                    return (
                        f"{self.spec} takes {what}s of shape {tuple(want)}; {task.env_id} "
                        f"gives {tuple(got)}"
                    )
        finally:
            env.close()
        return None


def _slug(text: str) -> str:
    """A file stem from ``text``: runs of other characters than ``[A-Za-z0-9._-]`` as ``_``."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("_") or "policy"


def resolve_policy(spec: str) -> ScoredPolicy:
    """The policy ``spec`` names (module docstring).

    Raises:
        ValueError: Naming ``spec`` as written and what is wrong: a file that does not
            exist, a model without its config, malformed ``module:attr``, a module that
            does not import, an attribute it lacks or that is not callable, or text that
            is none of these.
    """
    kind = agent_kind(spec)
    if kind == ".zip":
        path = Path(spec)
        if not path.is_file():
            raise ValueError(f"policy {spec!r}: {FILE_KINDS[kind]} not found ({path.absolute()})")
        try:
            policy = load(path)
        except (FileNotFoundError, ValueError) as err:  # no config beside it, say
            raise ValueError(f"policy {spec!r}: {err}") from None
        saved = dict(model_config(path).get("env_kwargs") or {})
        return ScoredPolicy(spec, "model", _slug(path.stem), lambda env: policy, saved)
    if kind is not None:
        path = Path(spec)
        if kind != "baseline" and not path.is_file():
            raise ValueError(f"policy {spec!r}: {FILE_KINDS[kind]} not found ({path.absolute()})")
        return ScoredPolicy(spec, "player", _slug(path.stem if kind != "baseline" else spec))
    if ":" in spec:
        return ScoredPolicy(spec, "factory", _slug(spec.replace(":", ".")), _factory(spec))
    raise ValueError(
        f"unknown policy {spec!r}: a policy is a player ({PLAYERS_HELP}), an SB3 model .zip "
        "with its saved config, or module:attr (a factory: env -> agent with predict)"
    )


def _factory(spec: str) -> Callable[[Any], Policy]:
    """``module:attr``'s attribute, checked to be callable.

    Raises:
        ValueError: On malformed text, a module that does not import, a missing or
            uncallable attribute.
    """
    if not MODULE_ATTR.match(spec):
        raise ValueError(
            f"policy {spec!r}: module:attr takes a dotted module path, one colon and an "
            "attribute name (e.g. my_agents.pool:make_agent)"
        )
    module_name, _, attr = spec.partition(":")
    try:
        module = importlib.import_module(module_name)
    except ImportError as err:
        raise ValueError(f"policy {spec!r}: cannot import module {module_name!r} ({err})") from None
    factory = getattr(module, attr, None)
    if factory is None:
        raise ValueError(f"policy {spec!r}: module {module_name!r} has no attribute {attr!r}")
    if not callable(factory):
        raise ValueError(
            f"policy {spec!r}: {attr!r} is a {type(factory).__name__}, not a factory "
            "(env -> agent with predict)"
        )
    return factory
