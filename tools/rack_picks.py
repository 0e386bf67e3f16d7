"""What the learned rack agent plays differently from the planner, shot by shot.

Usage (from the repository root)::

    python -m tools.rack_picks --model models/rack_value.npz --racks 60
    python -m tools.rack_picks --model models/rack_duel.npz --racks 60 --seed 20000 --duel

On evaluation racks (seeds ``--seed``..; run-out mode, the evaluation's noise; with
``--duel`` two-player racks against the ghost-ball agent as ``python -m agents.duels`` plays them,
the model breaking the even racks) it plays the model and, at every planned shot after the
break, compares its pick with the candidate the planner's own score ranks first: how often
they are the same, the mean features of both where they differ, and how often the picks
potted.
"""

from __future__ import annotations

import argparse
from typing import Any

import gymnasium as gym
import numpy as np

import pool_env  # noqa: F401  (registers the ids)
from agents.evaluation.duels import NOISE, play_rack
from agents.evaluation.players import make_agent
from agents.learned.rack_play import FEATURES, RackAgent, load_rack_agent
from pool_env.envs.multiagent import PoolDuelEnv

SHOWN = ("p_now", "p_next", "planner_score", "strike_speed_over_top", "tip_side",
         "tip_vertical", "arrival_speed_m_s", "cut_over_90deg")  # fmt: skip


def _row(agent: RackAgent, info: dict[str, Any]) -> tuple[bool, Any, Any, bool] | None:
    """A planned shot's (same as the planner's first, pick's and first's features, potted)."""
    if agent.last_plan.get("kind") != "learned" or not agent.last_candidates:
        return None
    features, pick = agent.last_candidates
    top = int(np.argmax(features[:, FEATURES.index("planner_score")]))
    potted = bool(info["potted"]) and info["foul"] is None
    return pick == top, features[pick], features[top], potted


def main(argv: list[str] | None = None) -> int:
    """The command line (module doc)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    parser.add_argument("--model", default="models/rack_value.npz")
    parser.add_argument("--racks", type=int, default=60)
    parser.add_argument("--seed", type=int, default=10_000)
    parser.add_argument("--duel", action="store_true", help="against the ghost-ball agent")
    args = parser.parse_args(argv)
    noise = tuple(NOISE)
    env = gym.make("pool_env/NineBallGame-v1", end_on_foul=not args.duel, noise=noise)
    agent = load_rack_agent(args.model, env)
    rows = []
    if args.duel:
        duel = PoolDuelEnv(game="nine", model="spin", noise=noise)
        ghost = make_agent("ghost", gym.make("pool_env/NineBallGame-v1", noise=noise))
        players = {"agent": agent, "opponent": ghost}
        for k in range(args.racks):
            breaks, shots = k % 2 == 0, [0]

            def hook(side: str, info: dict[str, Any], breaks: bool = breaks,
                     shots: list[int] = shots) -> None:  # fmt: skip
                if side == "agent":
                    shots[0] += 1
                    row = None if breaks and shots[0] == 1 else _row(agent, info)
                    if row is not None:
                        rows.append(row)

            play_rack(duel, players, args.seed + k, breaks, hook)
    for k in range(0 if args.duel else args.racks):
        obs, _ = env.reset(seed=args.seed + k)
        done, shot = False, 0
        while not done:
            action, _ = agent.predict(obs)
            obs, _, terminated, truncated, info = env.step(action)
            done, shot = terminated or truncated, shot + 1
            row = None if shot == 1 else _row(agent, info)
            if row is not None:
                rows.append(row)
    differ = [r for r in rows if not r[0]]
    print(f"{len(rows)} planned shots after the break; the planner's first played on "
          f"{len(rows) - len(differ)}")  # fmt: skip
    for name in SHOWN:
        i = FEATURES.index(name)
        learned = np.mean([r[1][i] for r in differ])
        first = np.mean([r[2][i] for r in differ])
        print(f"{name}: learned {learned:.3f}, planner's first {first:.3f} (where they differ)")
    print(f"potted: {np.mean([r[3] for r in differ]):.2f} where they differ, "
          f"{np.mean([r[3] for r in rows if r[0]]):.2f} where the same")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
