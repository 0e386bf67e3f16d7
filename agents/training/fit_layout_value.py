"""Learn what a 9-ball layout is worth to the shooter, from played racks.

Usage (from the repository root)::

    python -m agents.training.fit_layout_value collect --racks 600 --seed 70000 \
        --out runs/layout/g0.npz
    python -m agents.training.fit_layout_value fit runs/layout/g0.npz --out models/duel_value.npz

``collect`` plays two-player racks on :class:`pool_env.envs.multiagent.PoolDuelEnv` (9-ball, spin
table, the duels' execution noise) through :func:`agents.evaluation.duels.play_rack`, rack ``k``
seeded ``seed + k`` (keep it away from the duels' evaluation racks, 20000..), the two
sides alternating breaks, and records every shot but the breaks: the layout's features
from the shooter's side (:func:`agents.learned.layout_value.layout_features`, read from the
shooter's observation alone) and whether that shooter went on to win the rack (a draw at
the shot limit counts as not won). With ``--runout`` it plays run-out mode on the
single-player id instead (``end_on_foul``: the first miss or foul ends the rack) and the
label is whether the rack was run out.

``fit`` is a logistic regression of the labels on the features
(:func:`agents.learned.layout_value.fit_layout_value`): the chance that the player to shoot wins
(or runs out) from such a layout, *under the policies that played the racks*. It writes
the model and a ``<stem>_config.yaml`` that makes ``--agent models/<stem>.npz`` a
:class:`agents.learned.lookahead.LookaheadAgent` in :mod:`agents.evaluation.evaluate` and
:mod:`agents.evaluation.duels`.
"""

from __future__ import annotations

import argparse
import inspect
import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from numpy.typing import NDArray

from agents.evaluation.duels import ENV_ID, NOISE, play_rack
from agents.evaluation.evaluate import make_agent
from agents.learned.envs import make_env
from agents.learned.layout_value import (
    LAYOUT_FEATURES,
    fit_layout_value,
    layout_features,
    observed_rack,
)
from agents.learned.lookahead import PLAY_SETTINGS, LookaheadAgent
from agents.policy import Policy
from pool_env.envs.multiagent import PoolDuelEnv
from pool_env.game.codec import decode_observations, obs_layout
from pool_env.game.geometry import pocket_mouths

#: The aim error (rad) the features' pot chances are taken at: the duels' aim noise.
SIGMA = NOISE[0]


class _Recorder:
    """Wraps a player: records the features of each observation it is asked to play."""

    def __init__(self, player: Policy, side: str, config: Any, rows: list[tuple[str, Any]]) -> None:
        self.player, self.side, self.rows = player, side, rows
        self.config = config
        self.mouths = pocket_mouths(config.table)

    def predict(
        self,
        observation: NDArray[np.floating],
        state: Any = None,
        episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[Any, Any]:
        """The wrapped player's ``predict(observation)``, recording the layout first."""
        if not observed_rack(observation, self.config)[1]:  # not the break
            features = observation_features(self.config, self.mouths, observation)
            self.rows.append((self.side, features))
        return self.player.predict(observation)


def observation_features(
    config: Any, mouths: Any, obs: NDArray[np.floating]
) -> NDArray[np.float64]:
    """:func:`layout_features` of one rule observation (``(F,)``), from its viewer's side."""
    in_hand, _, fouls = observed_rack(obs, config)
    table = config.table
    balls = np.asarray(obs)[obs_layout(config)["balls"]]
    positions, on = decode_observations(table, balls[None])
    hand, counts = np.array([in_hand]), np.array([fouls])
    return layout_features(table, mouths, positions, on, hand, counts, SIGMA)[0]


def collect(
    agent: str, opponent: str, racks: int, seed: int, runout: bool = False
) -> dict[str, NDArray[Any]]:
    """Play ``racks`` racks and return ``features`` ``(S, F)`` and ``won`` ``(S,)``."""
    if racks < 1:
        raise ValueError(f"racks must be >= 1, got {racks}")
    features: list[NDArray[np.float64]] = []
    won: list[bool] = []
    if runout:
        env = make_env(ENV_ID, {"noise": NOISE, "end_on_foul": True})
        config = env.unwrapped.config
        player = make_agent(agent, env)
        mouths = pocket_mouths(config.table)
        for k in range(racks):
            obs, _ = env.reset(seed=seed + k)
            rows: list[NDArray[np.float64]] = []
            done, success = False, False
            while not done:
                if not observed_rack(obs, config)[1]:  # not the break
                    rows.append(observation_features(config, mouths, obs))
                action, _ = player.predict(obs)
                obs, _, terminated, truncated, info = env.step(action)
                done = terminated or truncated
                success = bool(info.get("is_success", False))
            features += rows
            won += [success] * len(rows)
        env.close()
    else:
        duel = PoolDuelEnv(game="nine", model="spin", noise=NOISE)
        envs = [make_env(ENV_ID, {"noise": NOISE}) for _ in range(2)]
        config = envs[0].unwrapped.config
        rows_k: list[tuple[str, Any]] = []
        players = {
            side: _Recorder(make_agent(name, env, seed=seed), side, config, rows_k)
            for side, name, env in (("agent", agent, envs[0]), ("opponent", opponent, envs[1]))
        }
        for k in range(racks):
            rows_k.clear()
            winner = play_rack(duel, players, seed + k, k % 2 == 0)
            features += [f for _, f in rows_k]
            won += [side == winner for side, _ in rows_k]
        for env in envs:
            env.close()
    return {"features": np.array(features).reshape(-1, len(LAYOUT_FEATURES)), "won": np.array(won)}


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("collect", help="play racks, save layout features and outcomes")
    c.add_argument("--agent", default="ghost")
    c.add_argument("--opponent", default="ghost")
    c.add_argument("--racks", type=int, default=300)
    c.add_argument("--seed", type=int, default=70_000)
    c.add_argument("--runout", action="store_true", help="run-out mode, one player")
    c.add_argument("--out", required=True)
    f = sub.add_parser("fit", help="fit the layout value, save it with its config")
    f.add_argument("data", nargs="+")
    f.add_argument("--objective", choices=("duel", "runout"), default="duel")
    f.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    if args.command == "collect":
        data = collect(args.agent, args.opponent, args.racks, args.seed, args.runout)
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        np.savez(args.out, **data)
        print(f"{args.racks} racks, {data['won'].size} layouts, won {data['won'].mean():.3f} "
              f"({time.perf_counter() - start:.0f} s)")  # fmt: skip
        return 0
    parts = [np.load(p) for p in args.data]
    x = np.concatenate([p["features"] for p in parts])
    y = np.concatenate([p["won"] for p in parts])
    model = fit_layout_value(x, y)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    model.save(out)
    p = model(x)
    loss = -np.mean(y * np.log(p + 1e-12) + (1 - y) * np.log(1 - p + 1e-12))
    settings = inspect.signature(LookaheadAgent).parameters
    config = {
        "kind": "lookahead",
        "env_id": ENV_ID,
        "objective": args.objective,
        **{k: settings[k].default for k in PLAY_SETTINGS if k != "objective"},
        "features": list(LAYOUT_FEATURES),
        "data": [str(p) for p in args.data],
        "layouts": int(y.size),
        "log_loss": float(loss),
        "base_rate": float(y.mean()),
    }
    out.with_name(f"{out.stem}_config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    print(f"{y.size} layouts, base rate {y.mean():.3f}, log loss {loss:.4f}; weights "
          f"{np.round(model.weights, 3).tolist()}")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
