"""Train :class:`~agents.learned.rack_play.RackAgent`: play racks, fit the candidates' value.

Two commands (run from the repository root):

    python -m agents.training.racks collect --racks 600 --seed 0 --out runs/racks/d0.npz
    python -m agents.training.racks fit runs/racks/d0.npz --out models/rack_value.npz

(:mod:`agents.training.duel_racks` collects two-player racks against the ghost-ball agent
for the same ``fit``: its rewards are the rack's outcome, its config says so.)

``collect`` plays 9-ball racks in run-out mode with the evaluation's execution noise (the
racks' seeds from ``--seed``, kept apart from the evaluation's 10000..), a uniformly random
break arm (:data:`~agents.learned.rack_play.BREAK_ARMS`) per rack and, on every shot, a random
candidate with chance ``--explore``, else the best by ``--model`` (or the planner's score
without one). It saves every shot's candidate features, the one played, the legal pots,
whether the rack went on, and the break arms with their pots.

``fit`` is fitted Q evaluation: ``Q(candidate) = r + gamma V(next shot)``, with ``r`` the
shot's legal pots plus :data:`WIN_BONUS` for the 9, ``0`` for a foul (which ends a
run-out), iterated to its fixed point. ``V(next shot)`` is by default (``--target
planner``) the value of the candidate the planner's own score ranks first there: ``Q`` is
then the planner policy's action value and the agent, greedy on it, is one step of
policy iteration from the planner. ``--target played`` takes the candidate the collecting
policy played (SARSA: the collecting policy's value, exploration included); ``--target
max`` the best candidate's (Q-learning), which diverged here: the net's error on the many
candidates never played is maximised at every shot (a target mean of 55 legal pots after
12 rounds, where at most 9 balls and the bonus are left). A
state where nothing was planned (the planner's fallback) is worth the mean return seen
from such states. Then each break arm is valued by its racks' mean
``r_break + gamma V(after the break)`` and the best is saved as the model's break.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from numpy.typing import NDArray

from agents.learned.envs import make_env
from agents.learned.rack_play import BREAK_ARMS, FEATURES, RackAgent, ValueNet, load_rack_agent

ENV_ID = "pool_env/NineBallGame-v2"
#: The evaluation's run-out mode and execution noise (results/games.md, the spin ids).
ENV_KWARGS: dict[str, Any] = {"end_on_foul": True, "noise": [0.003, 0.05, 0.05]}
#: What potting the 9 is worth beyond its own pot: a won rack, not just one more ball.
WIN_BONUS = 2.0
GAMMA = 0.95
#: What ``V(next shot)`` is taken from (module doc).
TARGETS = ("planner", "played", "max")
_PLANNER = FEATURES.index("planner_score")


def shot_reward(info: dict[str, Any]) -> float:
    """Legal pots of a shot (0 for a foul), plus :data:`WIN_BONUS` when it wins the rack."""
    if not info["legal"] or info["foul"] is not None:
        return 0.0
    return float(len(info["potted"])) + (WIN_BONUS if info["winner"] == 0 else 0.0)


def collect(racks: int, seed: int, explore: float, model: str | None) -> dict[str, NDArray]:
    """Play ``racks`` racks (seeds ``seed..``) and return the transitions (module doc)."""
    env = make_env(ENV_ID, ENV_KWARGS)
    agent = load_rack_agent(model, env) if model else RackAgent(env)
    agent.explore, agent.rng = explore, np.random.default_rng(seed)
    feats, offsets, picks, rewards, dones, rack_of = [], [0], [], [], [], []
    arms, break_rewards, break_dones = [], [], []
    for k in range(racks):
        obs, _ = env.reset(seed=seed + k)
        agent.break_arm = int(agent.rng.integers(len(BREAK_ARMS)))
        action, _ = agent.predict(obs)
        obs, _, terminated, truncated, info = env.step(action)
        arms.append(agent.break_arm)
        break_rewards.append(shot_reward(info))
        done = terminated or truncated or info["turn_over"]
        break_dones.append(done)
        while not done:
            action, _ = agent.predict(obs)
            cands = agent.last_candidates if agent.last_plan.get("kind") == "learned" else None
            obs, _, terminated, truncated, info = env.step(action)
            done = terminated or truncated or info["turn_over"]
            f, pick = cands if cands is not None else (np.zeros((0, len(FEATURES))), -1)
            feats.append(f)
            offsets.append(offsets[-1] + f.shape[0])
            picks.append(pick)
            rewards.append(shot_reward(info))
            dones.append(done)
            rack_of.append(k)
    env.close()
    return {
        "features": np.concatenate(feats) if feats else np.zeros((0, len(FEATURES))),
        "offsets": np.array(offsets),
        "picks": np.array(picks),
        "rewards": np.array(rewards),
        "dones": np.array(dones),
        "rack": np.array(rack_of),
        "arms": np.array(arms),
        "break_rewards": np.array(break_rewards),
        "break_dones": np.array(break_dones),
    }


def merge(paths: list[str]) -> dict[str, NDArray]:
    """The transitions of several ``collect`` files as one (racks renumbered apart)."""
    out: dict[str, list[NDArray]] = {}
    base, rack_base = 0, 0
    for p in paths:
        with np.load(p) as d:
            data = {k: d[k] for k in d.files}
        data["offsets"] = data["offsets"][1:] + base if out else data["offsets"] + base
        base = int(data["offsets"][-1]) if data["offsets"].size else base
        data["rack"] = data["rack"] + rack_base
        rack_base += int(data["arms"].shape[0])
        for k, v in data.items():
            out.setdefault(k, []).append(v)
    return {k: np.concatenate(v) for k, v in out.items()}


def _next_index(data: dict[str, NDArray]) -> NDArray[np.int64]:
    """For each shot, the index of the rack's next shot (-1 after the last)."""
    rack, dones = data["rack"], data["dones"]
    nxt = np.arange(1, rack.shape[0] + 1)
    last = dones | (np.append(rack[1:], -1) != rack)
    return np.where(last, -1, nxt)


def state_values(
    net: Any, data: dict[str, NDArray], fallback: float, target: str = "played"
) -> NDArray[np.float64]:
    """Each shot's value: ``Q`` of the candidate played, the planner's first or the best.

    ``fallback`` where nothing was planned.
    """
    feats, off, picks = data["features"], data["offsets"], data["picks"]
    q = net(feats) if feats.shape[0] else np.zeros(0)
    values = np.full(off.shape[0] - 1, fallback)
    for i in range(off.shape[0] - 1):
        if off[i + 1] > off[i]:
            rows = slice(off[i], off[i + 1])
            if target == "max":
                values[i] = float(np.max(q[rows]))
            elif target == "planner":
                values[i] = float(q[rows][np.argmax(feats[rows, _PLANNER])])
            else:
                values[i] = float(q[off[i] + picks[i]])
    return values


def fit(
    data: dict[str, NDArray],
    gamma: float,
    rounds: int,
    hidden: int,
    seed: int,
    target: str = "planner",
) -> tuple[ValueNet, float, dict[str, Any]]:
    """Fitted Q on the candidates played (module doc); ``(net, fallback value, report)``.

    Raises:
        ValueError: On an unknown ``target``.
    """
    if target not in TARGETS:
        raise ValueError(f"target must be one of {TARGETS}, got {target!r}")
    import torch

    torch.set_num_threads(1)  # the shared machine: one thread, as train.py's runs
    torch.manual_seed(seed)
    feats, off, picks = data["features"], data["offsets"], data["picks"]
    rewards, dones = data["rewards"], data["dones"]
    nxt = _next_index(data)
    planned = picks >= 0
    x = np.stack([feats[off[i] + picks[i]] for i in np.flatnonzero(planned)])
    mean, scale = x.mean(axis=0), x.std(axis=0) + 1e-6
    xt = torch.tensor((x - mean) / scale, dtype=torch.float32)
    model = torch.nn.Sequential(
        torch.nn.Linear(len(FEATURES), hidden), torch.nn.ReLU(),
        torch.nn.Linear(hidden, hidden), torch.nn.ReLU(), torch.nn.Linear(hidden, 1),
    )  # fmt: skip
    optim = torch.optim.Adam(model.parameters(), lr=3e-3, weight_decay=1e-4)

    def as_net() -> ValueNet:
        w = {"mean": mean, "scale": scale}
        for k, layer in enumerate(m for m in model if isinstance(m, torch.nn.Linear)):
            w[f"W{k}"] = layer.weight.detach().numpy().T.astype(np.float64)
            w[f"b{k}"] = layer.bias.detach().numpy().astype(np.float64)
        return ValueNet(w)

    fallback = 0.0
    report: dict[str, Any] = {"rounds": []}
    for r in range(rounds):
        net = as_net()
        v = state_values(net, data, fallback, target)
        v_next = np.where(nxt >= 0, v[np.maximum(nxt, 0)], 0.0)
        goal = rewards + gamma * np.where(dones, 0.0, v_next)
        if (~planned).any():
            fallback = float(goal[~planned].mean())
        y = torch.tensor(goal[planned], dtype=torch.float32)[:, None]
        for _ in range(300):
            optim.zero_grad()
            loss = torch.nn.functional.mse_loss(model(xt), y)
            loss.backward()
            optim.step()
        mse, mean_target = float(loss.detach()), float(y.mean())
        report["rounds"].append({"round": r, "mse": mse, "target_mean": mean_target})
    net = as_net()
    return net, fallback, report


def break_values(
    net: ValueNet, data: dict[str, NDArray], gamma: float, fallback: float, target: str
) -> list[dict[str, float]]:
    """Each break arm's racks' mean ``r + gamma V(after)``, with its standard error."""
    v = state_values(net, data, fallback, target)
    first = {}
    for i, k in enumerate(data["rack"]):
        first.setdefault(int(k), i)
    out = []
    for a in range(len(BREAK_ARMS)):
        racks = np.flatnonzero(data["arms"] == a)
        vals = [
            data["break_rewards"][k]
            + (0.0 if data["break_dones"][k] or k not in first else gamma * v[first[k]])
            for k in racks
        ]
        vals_a = np.array(vals) if vals else np.zeros(1)
        out.append({
            "arm": a, "speed_action": BREAK_ARMS[a][0], "tip_vertical": BREAK_ARMS[a][1],
            "racks": len(vals), "value": float(vals_a.mean()),
            "se": float(vals_a.std() / max(np.sqrt(len(vals)), 1.0)),
            "continued": float(np.mean(~data["break_dones"][racks])) if len(racks) else 0.0,
        })  # fmt: skip
    return out


def main(argv: list[str] | None = None) -> int:
    """The command line (module doc)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n", 1)[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("collect", help="play racks and save the transitions")
    c.add_argument("--racks", type=int, default=200)
    c.add_argument("--seed", type=int, default=0)
    c.add_argument("--explore", type=float, default=0.25)
    c.add_argument("--model", default=None, help="a rack model .npz to act by (default: planner)")
    c.add_argument("--out", required=True)
    f = sub.add_parser("fit", help="fit the value and choose the break")
    f.add_argument("data", nargs="+")
    f.add_argument("--gamma", type=float, default=GAMMA)
    f.add_argument("--rounds", type=int, default=12)
    f.add_argument("--hidden", type=int, default=32)
    f.add_argument("--seed", type=int, default=0)
    f.add_argument("--target", choices=TARGETS, default="planner")
    f.add_argument("--top-k", type=int, default=None, help="the agent chooses among the "
                   "planner's K best candidates (default: all)")  # fmt: skip
    f.add_argument("--out", required=True)
    args = parser.parse_args(argv)
    if args.cmd == "collect":
        if args.racks < 1 or not 0.0 <= args.explore <= 1.0:
            raise ValueError("--racks must be >= 1 and --explore in [0, 1]")
        start = time.perf_counter()
        data = collect(args.racks, args.seed, args.explore, args.model)
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(args.out, **data)
        print(f"{args.racks} racks, {data['picks'].shape[0]} shots after the break, "
              f"{time.perf_counter() - start:.0f} s -> {args.out}")  # fmt: skip
        return 0
    data = merge(args.data)
    net, fallback, report = fit(data, args.gamma, args.rounds, args.hidden, args.seed, args.target)
    arms = break_values(net, data, args.gamma, fallback, args.target)
    best = max((a for a in arms if a["racks"]), key=lambda a: a["value"])  # unplayed: unknown
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    np.savez(out, **net.weights())
    duel = "outcome" in data  # two-player racks (agents.training.duel_racks): the outcome
    config = {
        "kind": "rack_value",
        "returns": "duel outcome" if duel else "run-out pots",
        "env_id": ENV_ID,
        "env_kwargs": {"noise": ENV_KWARGS["noise"]} if duel else ENV_KWARGS,
        "gamma": args.gamma,
        "win_bonus": None if duel else WIN_BONUS,
        "rounds": args.rounds,
        "hidden": args.hidden,
        "seed": args.seed,
        "target": args.target,
        "top_k": args.top_k,
        "data": [str(p) for p in args.data],
        "racks": int(data["arms"].shape[0]),
        "shots": int(data["picks"].shape[0]),
        "fallback_value": fallback,
        "break_arm": int(best["arm"]),
        "break_arms": arms,
        "fit": report,
    }
    out.with_name(f"{out.stem}_config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    for a in arms:
        print(a)
    print(f"break arm {best['arm']} {BREAK_ARMS[best['arm']]}; fallback value {fallback:.3f}")
    print(report["rounds"][-1])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
