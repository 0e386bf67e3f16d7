"""Learn what a WPA layout (9-ball, 8-ball) is worth to the shooter, from played racks.

Usage (from the repository root)::

    python -m agents.training.fit_layout_value collect --racks 600 --seed 70000 \
        --out runs/layout/g0.npz
    python -m agents.training.fit_layout_value fit runs/layout/g0.npz --out models/duel_value.npz
    python -m agents.training.fit_layout_value collect --runout --racks 1500 --seed 90000 \
        --noise 0.0021817,0.075,0.0175 --out runs/layout/ff0.npz
    python -m agents.training.fit_layout_value collect --env pool_env/EightBallGame-v1 \
        --runout --racks 2500 --seed 910000 --noise 0.0021817,0.075,0.0175 \
        --out runs/layout/eight_runout.npz

``collect`` plays two-player racks on :class:`pool_env.envs.multiagent.PoolDuelEnv` (the game of
``--env``, 9-ball by default; spin table, the duels' execution noise) through
:func:`agents.evaluation.duels.play_rack` (both sides built as the duels build them,
``players=2``: a search player plays for the rack, not for a run-out), rack ``k`` seeded
``seed + k`` (keep it away from the duels' evaluation racks, 20000..), the two sides
alternating breaks, and records every shot but the breaks: the layout's features from the
shooter's side (:func:`agents.learned.layout_value.layout_features`, read from the shooter's
observation alone) and whether that shooter went on to win the rack (a draw at the shot limit
counts as not won). With ``--runout`` it plays run-out mode on the single-player id instead
(``end_on_foul``: the first miss or foul ends the rack) and the label is whether the rack was
run out. ``--noise`` sets the execution noise (default the duels'); the features' pot chances
are taken at its aim error. Off 9-ball each layout also records the shooter's legal first
balls as its observation says them (``targets``, ``(M, T)`` padded with -1: 8-ball's group,
the 8), and the features are taken over them
(:func:`agents.learned.layout_value.layout_features`' ``targets``); 9-ball's
stay on the ball on.

Beside the features, ``collect`` saves every recorded layout raw, from the shooter's side, so
that other layout values (:mod:`agents.training.fit_set_value`) are fitted from the same files:
``positions`` ``(M, N, 2)``, ``on_table`` ``(M, N)``, ``in_hand`` ``(M,)``, ``fouls`` ``(M, 2)``
(the shooter's and the opponent's, 0..2), ``label`` ``(M,)`` (``won`` again under the name the
other fitters read), ``rack`` ``(M,)`` (the rack's seed: what a split by rack groups by), and
``sigma`` (the features' aim error) and ``noise``.

``fit`` (``--held-out`` files: scored, not fitted, against the training base rate) is a
logistic regression of the labels on the features
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
from agents.evaluation.players import make_agent
from agents.learned.envs import make_env
from agents.learned.layout_value import (
    LAYOUT_FEATURES,
    fit_layout_value,
    layout_features,
    observed_rack,
)
from agents.learned.legal_sets import target_sets
from agents.learned.lookahead import PLAY_SETTINGS, LookaheadAgent
from agents.policy import Policy
from pool_env import shot_constraints
from pool_env.envs.multiagent import PoolDuelEnv
from pool_env.game.codec import decode_observations, obs_layout
from pool_env.game.geometry import pocket_mouths

#: The aim error (rad) the features' pot chances are taken at: the duels' aim noise.
SIGMA = NOISE[0]


#: One recorded shot: the rack's seed, then :func:`observation_layout` of the shooter's view,
#: then the shooter's legal first balls.
Layout = tuple[int, NDArray[np.float64], NDArray[np.bool_], bool, tuple[int, int], tuple[int, ...]]


class _Recorder:
    """Wraps a player: records the layout of each observation it is asked to play."""

    def __init__(
        self, player: Policy, side: str, config: Any, rows: list[tuple[str, Layout]]
    ) -> None:
        self.player, self.side, self.rows = player, side, rows
        self.config = config
        self.rack = 0  # the seed of the rack being played (set by collect)

    def predict(
        self,
        observation: NDArray[np.floating],
        state: Any = None,
        episode_start: Any = None,
        deterministic: bool = True,
    ) -> tuple[Any, Any]:
        """The wrapped player's ``predict(observation)``, recording the layout first."""
        if not observed_rack(observation, self.config)[1]:  # not the break
            self.rows.append((self.side, _layout(self.rack, self.config, observation)))
        return self.player.predict(observation)


def observation_layout(
    config: Any, obs: NDArray[np.floating]
) -> tuple[NDArray[np.float64], NDArray[np.bool_], bool, tuple[int, int]]:
    """The layout a rule observation shows its viewer: ``(positions, on_table, in_hand, fouls)``.

    ``positions`` ``(N, 2)`` and ``on_table`` ``(N,)`` as decoded from the observation;
    ``fouls``: the viewer's and the opponent's successive fouls.
    """
    in_hand, _, fouls = observed_rack(obs, config)
    balls = np.asarray(obs)[obs_layout(config)["balls"]]
    positions, on = decode_observations(config.table, balls[None])
    return positions[0], on[0], in_hand, fouls


def _layout(rack: int, config: Any, obs: NDArray[np.floating]) -> Layout:
    """The :data:`Layout` of one observation, recorded for rack ``rack``."""
    legal = shot_constraints(config, obs).first_balls
    return (rack, *observation_layout(config, obs), legal)


def observation_features(
    config: Any, mouths: Any, obs: NDArray[np.floating], sigma: float = SIGMA
) -> NDArray[np.float64]:
    """:func:`layout_features` of one rule observation (``(F,)``), from its viewer's side."""
    positions, on, in_hand, fouls = observation_layout(config, obs)
    hand, counts = np.array([in_hand]), np.array([fouls])
    return layout_features(config.table, mouths, positions[None], on[None], hand, counts, sigma)[0]


def _records(
    config: Any, mouths: Any, layouts: list[Layout], labels: list[bool], sigma: float
) -> dict[str, NDArray[Any]]:
    """The saved arrays of recorded layouts: the raw layouts, their features (one batched call)."""
    n = config.n_balls
    positions = np.array([x[1] for x in layouts], dtype=np.float64).reshape(-1, n, 2)
    on = np.array([x[2] for x in layouts], dtype=np.bool_).reshape(-1, n)
    hand = np.array([x[3] for x in layouts], dtype=np.bool_)
    fouls = np.array([x[4] for x in layouts], dtype=np.int64).reshape(-1, 2)
    label = np.array(labels, dtype=np.bool_)
    legal = np.zeros((len(layouts), n), dtype=np.bool_)
    for row, x in enumerate(layouts):
        legal[row, list(x[5])] = True
    targets = target_sets(legal)
    game = config.game
    chosen = None if game == "nine" else targets  # 9-ball's features: the ball on, as fitted
    features = (
        layout_features(config.table, mouths, positions, on, hand, fouls, sigma, chosen, game)
        if layouts
        else np.zeros((0, len(LAYOUT_FEATURES)))  # every rack ended at its break
    )
    return {
        "features": features, "won": label, "positions": positions, "on_table": on,
        "in_hand": hand, "fouls": fouls, "label": label, "targets": targets,
        "rack": np.array([x[0] for x in layouts], dtype=np.int64),
    }  # fmt: skip


def collect(
    agent: str,
    opponent: str,
    racks: int,
    seed: int,
    runout: bool = False,
    noise: tuple[float, float, float] = NOISE,
    env_id: str = ENV_ID,
) -> dict[str, NDArray[Any]]:
    """Play ``racks`` racks: ``features``, ``won`` and the raw layouts (module doc).

    Args:
        agent: The player (:func:`agents.evaluation.players.make_agent`'s names and models).
        opponent: Its opponent in a duel (unused with ``runout``).
        racks: How many racks; rack ``k`` is seeded ``seed + k``.
        seed: The first rack's seed.
        runout: Run-out mode, one player (module doc).
        noise: The execution noise; the features' pot chances are taken at its aim error.
        env_id: The one-player spin game id (9-ball by default; the duel plays its game).

    Raises:
        ValueError: If ``racks < 1``.
    """
    if racks < 1:
        raise ValueError(f"racks must be >= 1, got {racks}")
    noise = (float(noise[0]), float(noise[1]), float(noise[2]))
    layouts: list[Layout] = []
    won: list[bool] = []
    if runout:
        env = make_env(env_id, {"noise": noise, "end_on_foul": True})
        config = env.unwrapped.config
        player = make_agent(agent, env)
        for k in range(racks):
            obs, _ = env.reset(seed=seed + k)
            rows: list[Layout] = []
            done, success = False, False
            while not done:
                if not observed_rack(obs, config)[1]:  # not the break
                    rows.append(_layout(seed + k, config, obs))
                action, _ = player.predict(obs)
                obs, _, terminated, truncated, info = env.step(action)
                done = terminated or truncated
                success = bool(info.get("is_success", False))
            layouts += rows
            won += [success] * len(rows)
        env.close()
    else:
        envs = [make_env(env_id, {"noise": noise}) for _ in range(2)]
        config = envs[0].unwrapped.config
        duel = PoolDuelEnv(game=config.game, model="spin", noise=noise)
        rows_k: list[tuple[str, Layout]] = []
        players = {
            side: _Recorder(make_agent(name, env, seed=seed, players=2), side, config, rows_k)
            for side, name, env in (("agent", agent, envs[0]), ("opponent", opponent, envs[1]))
        }
        for k in range(racks):
            rows_k.clear()
            for recorder in players.values():
                recorder.rack = seed + k
            winner = play_rack(duel, players, seed + k, k % 2 == 0)
            layouts += [layout for _, layout in rows_k]
            won += [side == winner for side, _ in rows_k]
        for env in envs:
            env.close()
    data = _records(config, pocket_mouths(config.table), layouts, won, noise[0])
    return {**data, "sigma": np.float64(noise[0]), "noise": np.array(noise),
            "env": np.array(env_id)}  # fmt: skip


def _noise(text: str) -> tuple[float, float, float]:
    """``--noise``: three comma-separated sigmas (aim rad, speed m/s, tip R)."""
    values = tuple(float(v) for v in text.split(","))
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"--noise takes three sigmas a,b,c; got {text!r}")
    return values  # type: ignore[return-value]


def log_loss(p: NDArray[np.float64], y: NDArray[Any]) -> float:
    """The mean log loss of chances ``p`` on outcomes ``y``."""
    y = np.asarray(y, dtype=np.float64)
    return float(-np.mean(y * np.log(p + 1e-12) + (1 - y) * np.log(1 - p + 1e-12)))


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("collect", help="play racks, save layout features and outcomes")
    c.add_argument("--env", default=ENV_ID, help="the one-player spin game id")
    c.add_argument("--agent", default="ghost")
    c.add_argument("--opponent", default="ghost")
    c.add_argument("--racks", type=int, default=300)
    c.add_argument("--seed", type=int, default=70_000)
    c.add_argument("--runout", action="store_true", help="run-out mode, one player")
    c.add_argument("--noise", type=_noise, default=NOISE, help="aim,speed,tip sigmas")
    c.add_argument("--out", required=True)
    f = sub.add_parser("fit", help="fit the layout value, save it with its config")
    f.add_argument("data", nargs="+")
    f.add_argument("--objective", choices=("duel", "runout"), default="duel")
    f.add_argument("--held-out", nargs="*", default=[], help="collected files scored, not fitted")
    f.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    start = time.perf_counter()
    if args.command == "collect":
        data = collect(
            args.agent, args.opponent, args.racks, args.seed, args.runout, args.noise, args.env
        )
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        np.savez(args.out, **data)
        print(f"{args.racks} racks, {data['won'].size} layouts, won {data['won'].mean():.3f} "
              f"({time.perf_counter() - start:.0f} s)")  # fmt: skip
        return 0
    parts = [np.load(p) for p in args.data]
    envs = {str(p["env"]) if "env" in p.files else ENV_ID for p in parts}
    if len(envs) != 1:
        raise SystemExit(f"fit: the data files hold layouts of several games: {sorted(envs)}")
    x = np.concatenate([p["features"] for p in parts])
    y = np.concatenate([p["won"] for p in parts])
    model = fit_layout_value(x, y)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    model.save(out)
    loss = log_loss(model(x), y)
    held: dict[str, Any] = {}
    if args.held_out:
        tests = [np.load(p) for p in args.held_out]
        hx = np.concatenate([p["features"] for p in tests])
        hy = np.concatenate([p["won"] for p in tests])
        held = {
            "held_out": [str(p) for p in args.held_out], "held_out_layouts": int(hy.size),
            "held_out_log_loss": float(log_loss(model(hx), hy)),
            "held_out_base_rate_loss": float(log_loss(np.full(hy.size, y.mean()), hy)),
        }  # fmt: skip
    settings = inspect.signature(LookaheadAgent).parameters
    config = {
        "kind": "lookahead",
        "env_id": envs.pop(),
        "objective": args.objective,
        **{k: settings[k].default for k in PLAY_SETTINGS if k != "objective"},
        "features": list(LAYOUT_FEATURES),
        "data": [str(p) for p in args.data],
        "layouts": int(y.size),
        "log_loss": float(loss),
        "base_rate": float(y.mean()),
        **held,
    }
    out.with_name(f"{out.stem}_config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    print(f"{y.size} layouts, base rate {y.mean():.3f}, log loss {loss:.4f}; weights "
          f"{np.round(model.weights, 3).tolist()}")  # fmt: skip
    if held:
        print(f"held out: {held['held_out_layouts']} layouts, log loss "
              f"{held['held_out_log_loss']:.4f} (the training base rate's: "
              f"{held['held_out_base_rate_loss']:.4f})")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
