r"""What every agent is: a :class:`Policy`, SB3's ``predict``; a :class:`Planner` also says why.

Every agent of this package, a baseline, a 9-ball player or a loaded model, plays through one
method with the signature of stable-baselines3's ``PolicyPredictor``, so that SB3's
``evaluate_policy``, :func:`agents.run_episodes`, :func:`agents.evaluate_agent` and the duels
take any of them unchanged::

    action, state = agent.predict(obs)  # one observation (D,) or a batch (B, D)

The planners (the ghost-ball and search baselines, the 9-ball players) are also
:class:`Planner`\ s: after each ``predict`` their ``last_plan`` says what they chose (its
``"kind"``: ``"break"``, a pot, ``"fallback"`` when no clear pot was found, ...). The
evaluation reads it through :func:`last_plan`, which gives ``{}`` for a policy that does not
plan. ``tests/agents/test_policy.py`` checks that every agent class of the package is a
:class:`Policy`, and that the planners are :class:`Planner`\ s.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

__all__ = ["Planner", "Policy", "last_plan"]


@runtime_checkable
class Policy(Protocol):
    """An agent: SB3's ``predict`` (``stable_baselines3.common.type_aliases.PolicyPredictor``)."""

    def predict(
        self,
        observation: Any,
        state: Any = None,
        episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[Any, Any]:
        """The action for an observation ``(D,)`` (or actions for a batch ``(B, D)``).

        Args:
            observation: One observation or a batch.
            state: A recurrent policy's state (returned updated; ``None`` otherwise).
            episode_start: A recurrent policy's episode starts.
            deterministic: Whether to act without exploration noise.

        Returns:
            ``(action, state)``.
        """
        ...


@runtime_checkable
class Planner(Policy, Protocol):
    """A policy that says what it chose: ``last_plan``, set by each ``predict``."""

    #: The last ``predict``'s choice: ``"kind"`` and what the planner adds (shot, pocket, ...).
    last_plan: dict[str, Any]


def last_plan(policy: Policy) -> dict[str, Any]:
    """``policy``'s :attr:`Planner.last_plan`, or ``{}`` for a policy that does not plan."""
    plan = policy.last_plan if isinstance(policy, Planner) else None
    return plan or {}
