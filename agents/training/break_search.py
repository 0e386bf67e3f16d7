"""Search the WPA break: where to place the cue ball, the aim, the speed and the tip.

Usage (from the repository root)::

    python -m agents.training.break_search --racks 96 --seed 960000 --noise fastfiz \
        --out results/break_search.json
    python -m agents.training.break_search --env pool_env/EightBallGame-v1 --racks 200 \
        --out results/break_search_eight.json

Every arm of a grid (:data:`GRID`: the cue ball's offset from the head spot along the head
string, the aim off a full hit on the apex ball, the speed action over the break speed
range, the vertical tip) breaks the same ``--racks`` racks (random WPA racks of ``--env``,
reset with ``seed + k``) on the batched game (``gym.make_vec``, the execution noise of
``--noise``), as :meth:`agents.learned.search_player.SearchPlayer.break_action` plays it.
Each arm is scored by what a run-out needs from a break: no foul, a ball made, and a layout
with a shot; its *value* is the mean over racks of ``legal, made and not won yet x the
run-out value of the layout left`` (the logistic run-out value of the game,
:data:`VALUES`, valued over the breaker's legal balls off 9-ball) plus the racks the break
wins outright. The table prints scratches (fouls), balls made and the value of every arm,
best first. The :data:`FINALISTS` best are then scored again on ``--check-racks`` fresh racks
(seeds from ``--check-seed``), which pick the break: its settings go into
the game's player file (``models/search_player.yaml``, ``_ten``, ``_eight``) by hand, with
the figures.
"""

from __future__ import annotations

import argparse
import itertools
import json
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from agents.evaluation.metrics import wilson
from agents.evaluation.noise_flag import parse_noise
from agents.learned.layout_value import LayoutValue
from agents.learned.leaf_value import LogisticLeaf
from agents.learned.legal_sets import target_sets
from agents.learned.search_player import SearchPlayer, SearchSettings
from pool_env.game.codec import decode_observations, obs_layout
from pool_env.game.geometry import pocket_mouths

#: The run-out value that scores the layout a break leaves, by game (10-ball: 9-ball's,
#: as its player file values its leaves).
VALUES = {
    "nine": "models/runout_value.npz",
    "ten": "models/runout_value.npz",
    "eight": "models/eight_runout_value.npz",
}
#: 9-ball's (the default game's).
VALUE = VALUES["nine"]
#: The grid: head-string offset (m), aim off a full hit (rad), speed action, vertical tip.
GRID = {
    "break_y": (-0.45, -0.3, -0.15, 0.0, 0.15, 0.3, 0.45),
    "break_cut": (-0.01, 0.0, 0.01),
    "break_speed": (-0.5, 0.0, 0.5, 1.0),
    "break_tip": ((0.0, -0.75), (0.0, -0.5), (0.0, -0.25), (0.0, 0.0), (0.0, 0.25)),
}
#: Arms of the screen re-scored on fresh racks (the screen's best is biased upwards).
FINALISTS = 8


def score_arm(
    player: SearchPlayer, settings: SearchSettings, vec: Any, seed: int, leaf: LogisticLeaf
) -> dict[str, Any]:
    """Break every table of ``vec`` with one arm; count fouls, balls made, wins and value."""
    config = player.config
    obs, _ = vec.reset(seed=seed)
    positions, on = decode_observations(config.table, obs[:, obs_layout(config)["balls"]])
    player.settings = settings
    actions = np.stack([player.break_action(positions[b], on[b]) for b in range(len(obs))])
    obs, _, _, _, info = vec.step(actions.astype(np.float32))
    after, left = decode_observations(config.table, obs[:, obs_layout(config)["balls"]])
    foul = np.array([f is not None for f in info["foul"]])
    made = np.array([len(p) > 0 for p in info["potted"]])
    won = np.asarray(info["winner"]) == 0
    go = ~foul & made & ~won
    value = won.astype(np.float64)
    if go.any():
        hand = np.zeros(int(go.sum()), dtype=np.bool_)
        fouls = np.zeros((int(go.sum()), 2), np.int64)
        if config.game == "nine":  # the ball on, as 9-ball's value was fitted
            value[go] = leaf(after[go], left[go], hand, fouls)
        else:  # the breaker's legal balls, as its observation says them
            legal = np.zeros_like(left)
            legal[:, 1:] = obs[:, obs_layout(config)["legal"]] > 0.5
            value[go] = leaf(after[go], left[go], hand, fouls, target_sets(legal[go]))
    n = len(obs)
    return {
        "foul": int(foul.sum()), "made": int(made.sum()), "won": int(won.sum()),
        "value": float(value.mean()), "racks": n,
    }  # fmt: skip


def print_arms(rows: list[dict[str, Any]]) -> None:
    """The arms as a Markdown table, with 95% intervals on the rates."""
    print("| y (m) | cut (rad) | speed | tip | fouls | ball made | won | value |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        n = r["racks"]
        print(
            f"| {r['break_y']} | {r['break_cut']} | {r['break_speed']} | {r['break_tip']} | "
            f"{wilson(r['foul'], n).as_percent()} | {wilson(r['made'], n).as_percent()} | "
            f"{r['won']} | {r['value']:.3f} |"
        )


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--env", default="pool_env/NineBallGame-v2")
    parser.add_argument("--racks", type=int, default=96)
    parser.add_argument("--seed", type=int, default=960000)
    parser.add_argument("--noise", default="fastfiz", help="as agents.evaluate's --noise")
    parser.add_argument("--check-racks", type=int, default=1000)
    parser.add_argument("--check-seed", type=int, default=970000)
    parser.add_argument("--out", default=None, help="write every arm's counts as JSON here")
    parser.add_argument("--value", default=None, help="the run-out value (default: VALUES)")
    args = parser.parse_args(argv)
    kwargs: dict[str, Any] = {"end_on_foul": True, "noise": parse_noise(args.noise)}
    vec = gym.make_vec(args.env, num_envs=args.racks, vectorization_mode="vector_entry_point",
                       **kwargs)  # fmt: skip
    env = gym.make(args.env, **kwargs)
    game = env.unwrapped.config.game
    path = args.value or VALUES.get(game, VALUE)
    player = SearchPlayer(env, LayoutValue.load(path))
    config = player.config
    sigma = float(config.noise[0]) if config.noise else 0.0
    leaf = LogisticLeaf(LayoutValue.load(path), config.table, pocket_mouths(config.table),
                        max(sigma, player.sigma), game)  # fmt: skip
    start = time.perf_counter()
    rows = []
    for values in itertools.product(*GRID.values()):
        arm = dict(zip(GRID, values, strict=True))
        counts = score_arm(player, replace(SearchSettings(), **arm), vec, args.seed, leaf)
        rows.append({**arm, **counts})
    rows.sort(key=lambda r: -r["value"])
    print(f"{len(rows)} arms x {args.racks} racks in {time.perf_counter() - start:.0f} s\n")
    print_arms(rows[:15])
    check = gym.make_vec(args.env, num_envs=args.check_racks,
                         vectorization_mode="vector_entry_point", **kwargs)  # fmt: skip
    checked = []
    for r in rows[:FINALISTS]:
        arm = {k: r[k] for k in GRID}
        counts = score_arm(player, replace(SearchSettings(), **arm), check, args.check_seed, leaf)
        checked.append({**arm, **counts})
    checked.sort(key=lambda r: -r["value"])
    print(f"\nThe {FINALISTS} best on {args.check_racks} fresh racks (seeds {args.check_seed}+):\n")
    print_arms(checked)
    check.close()
    if args.out:
        out = {
            "env": args.env, "value": path, "seed": args.seed, "noise": args.noise, "arms": rows,
            "check_seed": args.check_seed, "checked": checked,
        }  # fmt: skip
        Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    vec.close()
    env.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
