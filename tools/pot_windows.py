"""How often the search's planned pots drop under noise, as planned and re-aimed at their windows.

The figure of ``results/search_player_r2.md`` behind the search's ``fans`` setting
(:mod:`agents.learned.shot_fans`): on 9-ball layouts left by the search player's break
(racks from ``--seed``, FastFiz x1), every planned pot of the search's candidates (the
planner's pots and the ghost-ball agent's choice) is played ``--samples`` times on the
game's step with the execution noise, once as planned and once re-aimed at the middle of
its pot window (``--steps`` aims either side); common noise for both. A pot counts when it
keeps the table or wins the rack (no foul).

    python -m tools.pot_windows --racks 40 --seed 500000 --steps 8 --samples 128
"""

from __future__ import annotations

import argparse
import json
import sys

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.evaluation.metrics import mean_ci
from agents.evaluation.players import make_agent
from agents.learned.layout_value import observed_rack
from agents.learned.legal_sets import observed_row
from agents.learned.search_player import SearchPlayer
from agents.learned.shot_fans import AimWindows
from pool_env import obs_layout, shot_constraints
from pool_env.game.games.wpa.judge import FOUL, KEEPS, WINNER

PLAYER = "models/search_player.yaml"


def pot_rates(
    agent: SearchPlayer,
    positions: NDArray[np.float64],
    on: NDArray[np.bool_],
    actions: NDArray[np.float64],
    samples: int,
) -> NDArray[np.float64]:
    """``(C,)`` each action's share of noisy plays that pot and keep the table (or win)."""
    result, _, _ = agent.model.play(positions, on, agent._rack, actions, samples)
    hits = result.hits
    made = (hits[:, WINNER] == 0) | ((hits[:, FOUL] == 0) & (hits[:, KEEPS] != 0))
    return made.reshape(len(actions), samples).mean(axis=1)


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point: prints the rates and writes them as JSON with ``--out``."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--racks", type=int, default=40)
    parser.add_argument("--seed", type=int, default=500_000)
    parser.add_argument("--steps", type=int, default=8, help="aims either side of a pot")
    parser.add_argument("--samples", type=int, default=128, help="noisy plays of each pot")
    parser.add_argument("--out", default=None)
    args = parser.parse_args(argv)
    for name in ("racks", "steps", "samples"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} must be >= 1, got {getattr(args, name)}")
    env = gym.make("pool_env/NineBallGame-v2", noise="fastfiz")
    agent = make_agent(PLAYER, env, seed=0)
    assert isinstance(agent, SearchPlayer)
    windows = AimWindows(agent.config, args.steps)
    balls = obs_layout(agent.config)["balls"]
    planned: list[float] = []
    centred: list[float] = []
    layouts = 0
    for k in range(args.racks):
        obs, _ = env.reset(seed=args.seed + k)
        obs, _, terminated, truncated, _ = env.step(agent.act(obs[None])[0])  # the break
        rules = shot_constraints(agent.config, obs)
        if terminated or truncated or rules.ball_in_hand:
            continue
        positions, on = agent.ghost.source.layouts(obs[None][:, balls])[0]
        agent._fouls = observed_rack(obs, agent.config)[2]  # as the player's _plan reads them
        agent._rack = observed_row(obs, agent.config)
        agent._targets = list(rules.first_balls)
        reference = np.zeros_like(on)
        reference[0] = True
        reference[agent._targets] = on[agent._targets]
        actions, _, kinds = agent._candidates(positions, on, reference)
        pots = [a for a, kind in zip(actions, kinds, strict=True) if kind in ("pot", "ghost")]
        if not pots:
            continue
        layouts += 1
        acts = np.stack(pots)
        moved, _ = windows.centre(positions, on, reference, agent._rack, acts)
        planned += pot_rates(agent, positions, on, acts, args.samples).tolist()
        centred += pot_rates(agent, positions, on, moved, args.samples).tolist()
    before, after = np.array(planned), np.array(centred)
    given = sys.argv[1:] if argv is None else argv
    out = {
        "command": "python -m tools.pot_windows " + " ".join(given),
        "layouts": layouts, "pots": int(before.size),
        "planned": float(before.mean()), "centred": float(after.mean()),
        "better_by_5_points": int((after > before + 0.05).sum()),
        "worse_by_5_points": int((after < before - 0.05).sum()),
    }  # fmt: skip
    gain = mean_ci(after - before)  # paired over the pots (the same noise for both)
    out["gain"] = [gain.value, gain.low, gain.high]
    print(f"{layouts} layouts, {before.size} planned pots, {args.samples} noisy plays each")
    print(f"  pot chance as planned {before.mean():.3f}, re-aimed {after.mean():.3f}")
    print(f"  re-aimed minus planned, per pot: {gain.value:+.3f} [{gain.low:+.3f}, "
          f"{gain.high:+.3f}]")  # fmt: skip
    print(f"  better by 5 points or more: {out['better_by_5_points']}, worse: "
          f"{out['worse_by_5_points']}")  # fmt: skip
    if args.out:
        with open(args.out, "w") as f:
            json.dump(out, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
