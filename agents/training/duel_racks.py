"""Collect two-player racks for :class:`~agents.learned.rack_play.RackAgent` against ghost-ball.

Usage (from the repository root; ``fit`` is :mod:`agents.training.racks`' own)::

    python -m agents.training.duel_racks --racks 300 --seed 50000 --out runs/duel/d0.npz
    python -m agents.training.racks fit runs/duel/d0.npz --out models/rack_duel.npz

Rack ``k`` is :class:`pool_env.envs.multiagent.PoolDuelEnv` seeded ``seed + k`` (keep it away
from the duels' evaluation racks, 20000..), played by :func:`agents.evaluation.duels.play_rack`: the
agent breaks the even racks with a uniformly random break arm, the ghost-ball agent
(:class:`agents.baselines.game_agents.GameGhostBallAgent`, as the duels build it) the odd
ones. On each of its shots the agent plays a random candidate with chance ``--explore``,
else the best by ``--model`` (or the planner's score without one), and its candidates are
recorded as :func:`agents.training.racks.collect` records them, so ``fit`` reads the file.

The return is the rack's outcome, not pots (:func:`duel_rewards`): ``+1`` won, ``-1``
lost, ``0`` drawn, paid on the agent's last decision of the rack; every other decision
gets ``0`` and its transition runs to the agent's next decision, the opponent's turns in
between part of it. In 9-ball only the 9 wins, so pots minus the opponent's pots would
pay a run of 1..8 that hands the opponent the 9; the outcome is what the duels count.
``gamma`` then discounts per agent decision (fewer decisions to the win are worth more).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.evaluation.duels import NOISE, play_rack
from agents.evaluation.players import make_agent
from agents.learned.envs import make_env
from agents.learned.rack_play import BREAK_ARMS, FEATURES, RackAgent, load_rack_agent
from agents.training.racks import ENV_ID
from pool_env.envs.multiagent import PoolDuelEnv

#: The rack's outcome for the agent by the winning side (``None``: drawn at the shot limit).
OUTCOMES: dict[str | None, float] = {"agent": 1.0, "opponent": -1.0, None: 0.0}


def duel_rewards(decisions: int, winner: str | None) -> tuple[NDArray, NDArray]:
    """Rewards and ends of the agent's ``decisions`` in a rack won by ``winner``.

    Args:
        decisions: How many decisions the agent made in the rack (its break included).
        winner: ``"agent"``, ``"opponent"`` or ``None`` (a draw).

    Returns:
        ``(rewards, dones)``: all ``0`` / ``False`` but the last, which carries the
        outcome (:data:`OUTCOMES`) and ends the episode.

    Raises:
        ValueError: On a negative count or an unknown winner.
    """
    if decisions < 0 or winner not in OUTCOMES:
        raise ValueError(f"decisions must be >= 0 and winner one of {list(OUTCOMES)}")
    rewards, dones = np.zeros(decisions), np.zeros(decisions, dtype=bool)
    if decisions:
        rewards[-1], dones[-1] = OUTCOMES[winner], True
    return rewards, dones


class _Recorder:
    """The agent's candidates on each of its shots after its break (``play_rack``'s hook)."""

    def __init__(self, agent: RackAgent) -> None:
        self.agent = agent
        self.feats: list[NDArray] = []
        self.offsets, self.picks, self.rack_of = [0], [], []
        self.rack, self.breaks, self.decisions = 0, False, 0

    def start(self, rack: int, breaks: bool) -> None:
        """A new rack, the agent breaking it or not."""
        self.rack, self.breaks, self.decisions = rack, breaks, 0

    def __call__(self, side: str, info: dict[str, Any]) -> None:
        """Record the agent's shot (the break is a break arm, not a candidate)."""
        if side != "agent":
            return
        self.decisions += 1
        if self.breaks and self.decisions == 1:
            return
        agent = self.agent
        cands = agent.last_candidates if agent.last_plan.get("kind") == "learned" else None
        f, pick = cands if cands is not None else (np.zeros((0, len(FEATURES))), -1)
        self.feats.append(f)
        self.offsets.append(self.offsets[-1] + f.shape[0])
        self.picks.append(pick)
        self.rack_of.append(self.rack)


def collect_duels(
    racks: int, seed: int, explore: float, model: str | None, opponent: str = "ghost"
) -> dict[str, NDArray]:
    """Play ``racks`` racks against ``opponent`` and return the agent's transitions (module doc).

    The arrays are :func:`agents.training.racks.collect`'s; ``arms`` is ``-1`` on a
    rack the opponent broke (no break of the agent's to value), plus ``outcome`` per rack.
    """
    duel = PoolDuelEnv(game="nine", model="spin", noise=NOISE)
    envs = [make_env(ENV_ID, {"noise": NOISE}) for _ in range(2)]
    agent = load_rack_agent(model, envs[0]) if model else RackAgent(envs[0])
    agent.explore, agent.rng = explore, np.random.default_rng(seed)
    players = {"agent": agent, "opponent": make_agent(opponent, envs[1])}
    rec = _Recorder(agent)
    rewards: list[float] = []
    dones: list[bool] = []
    arms, break_rewards, break_dones, outcome = [], [], [], []
    for k in range(racks):
        breaks = k % 2 == 0
        agent.break_arm = int(agent.rng.integers(len(BREAK_ARMS))) if breaks else None
        rec.start(k, breaks)
        winner = play_rack(duel, players, seed + k, breaks, rec)
        r, d = duel_rewards(rec.decisions, winner)
        has_break = breaks and rec.decisions > 0
        arms.append(agent.break_arm if breaks else -1)
        break_rewards.append(float(r[0]) if has_break else 0.0)
        break_dones.append(bool(d[0]) if has_break else True)
        rewards.extend(r[int(has_break) :])
        dones.extend(d[int(has_break) :])
        outcome.append(OUTCOMES[winner])
    for env in envs:
        env.close()
    return {
        "features": np.concatenate(rec.feats) if rec.feats else np.zeros((0, len(FEATURES))),
        "offsets": np.array(rec.offsets),
        "picks": np.array(rec.picks, dtype=np.int64),
        "rewards": np.array(rewards, dtype=np.float64),
        "dones": np.array(dones, dtype=bool),
        "rack": np.array(rec.rack_of, dtype=np.int64),
        "arms": np.array(arms, dtype=np.int64),
        "break_rewards": np.array(break_rewards, dtype=np.float64),
        "break_dones": np.array(break_dones, dtype=bool),
        "outcome": np.array(outcome, dtype=np.float64),
    }


def main(argv: list[str] | None = None) -> int:
    """The command line (module doc)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--racks", type=int, default=200)
    parser.add_argument("--seed", type=int, default=50_000)
    parser.add_argument("--explore", type=float, default=0.25)
    parser.add_argument("--model", default=None, help="a rack model .npz to act by")
    parser.add_argument("--opponent", default="ghost")
    parser.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    if args.racks < 1 or not 0.0 <= args.explore <= 1.0:
        parser.error("--racks must be >= 1 and --explore in [0, 1]")
    start = time.perf_counter()
    data = collect_duels(args.racks, args.seed, args.explore, args.model, args.opponent)
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(args.out, **data)
    won = float(np.mean(data["outcome"] > 0))
    print(f"{args.racks} racks (won {won:.3f}), {data['picks'].shape[0]} agent shots after "
          f"its breaks, {time.perf_counter() - start:.0f} s -> {args.out}")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
