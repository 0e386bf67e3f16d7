"""Distil the 9-ball search player into the rack network (:mod:`agents.learned.rack_net`).

The commands that made ``models/rack_net.npz`` (``results/rack_net.md``)::

    # collect: a driver plays racks; on every shot from a layout (no break, no ball in
    # hand), the rack network's candidates, the search's first-ply value of each (16
    # noisy plays at FastFiz x1, valued by the search's leaf) and the driver's own action
    # valued the same way are recorded. Round 0: the search player at 0.1 s a shot, in
    # practice mode (the rack goes on after a miss: more layouts per rack).
    python -m agents.training.distill_rack collect --driver runs/rack_net/search_fast.yaml \
        --write-fast-player 0.1 --racks 200 --seed 800000 --out runs/rack_net/r0.npz
    # fit: cross-entropy to softmax(values / tau) (--loss ce), or the squared error to the
    # values (--loss mse)
    python -m agents.training.distill_rack fit runs/rack_net/r0.npz --out runs/rack_net/net_r0.npz
    # round 1 (expert iteration): the network's own racks, labelled the same way
    python -m agents.training.distill_rack collect --driver runs/rack_net/net_r0.npz \
        --racks 500 --seed 810000 --out runs/rack_net/r1.npz
    # the features recomputed from the kept layouts (after a column was added)
    python -m agents.training.distill_rack refeature runs/rack_net/r1.npz \
        --out runs/rack_net/r1g.npz
    python -m agents.training.distill_rack fit runs/rack_net/r1g.npz \
        --out runs/rack_net/net_r1g.npz --loss mse
    # round 2, kept as it ran out more of the held-out racks 955000.. than round 1:
    # models/rack_net.npz is fit_C.npz (its config's player: search_player_net.yaml)
    python -m agents.training.distill_rack collect --driver runs/rack_net/net_r1g.npz \
        --racks 300 --seed 820000 --out runs/rack_net/r2.npz
    python -m agents.training.distill_rack fit runs/rack_net/r1g.npz runs/rack_net/r2.npz \
        --out runs/rack_net/fit_C.npz --loss mse

``runs/rack_net/search_fast.yaml`` is ``models/search_player_net.yaml`` with ``budget: 0.1``
and its models' paths made relative to ``runs/rack_net/`` (the collect command writes it
with ``--write-fast-player``). Every rack ``k`` is reset with ``seed + k``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from agents.evaluation.noise_flag import parse_noise
from agents.evaluation.players import make_agent
from agents.learned.envs import make_env
from agents.learned.rack_net import FEATURES, RackNetPlayer, eligible
from agents.learned.rack_play import ValueNet

ENV_ID = "pool_env/NineBallGame-v2"
#: The search player file whose leaf values the candidates and whose break the net takes.
PLAYER = "models/search_player_net.yaml"


def collect(
    driver_name: str,
    racks: int,
    seed: int,
    practice: bool = True,
    samples: int = 16,
    noise: str = "fastfiz",
    player: str = PLAYER,
    log_every: int = 25,
) -> dict[str, NDArray[Any]]:
    """Play ``racks`` racks with the driver and record the teacher's values (module doc).

    Returns:
        Arrays: ``features`` ``(total, F)`` every decision's candidates in a row,
        ``values`` ``(total,)`` their teacher values, ``starts`` ``(D + 1,)`` where each
        decision's rows begin, ``rack`` ``(D,)`` its rack seed, ``driver_action`` ``(D, A)``
        the driver's action, ``driver_value`` ``(D,)`` its teacher value (on the same
        noise as the candidates'), ``seconds`` ``(D,)`` the driver's decision time, and
        the layouts: ``positions`` ``(D, N, 2)``, ``on_table`` ``(D, N)``, ``fouls``
        ``(D, 2)`` (the features can be recomputed from them).
    """
    kwargs: dict[str, Any] = {"end_on_foul": not practice}
    sigmas = parse_noise(noise)
    if sigmas is not None:
        kwargs["noise"] = sigmas
    env = make_env(ENV_ID, kwargs, None)
    driver = make_agent(driver_name, env, seed)
    labeler = RackNetPlayer(env, player, samples=samples, seed=seed)
    feats: list[NDArray[np.float64]] = []
    values: list[NDArray[np.float64]] = []
    starts, rack_ids, actions, driver_values, seconds = [0], [], [], [], []
    layouts: list[tuple[NDArray[np.float64], NDArray[np.bool_], tuple[int, int]]] = []
    started = time.perf_counter()
    try:
        for k in range(racks):
            obs, _ = env.reset(seed=seed + k)
            done = False
            while not done:
                t0 = time.perf_counter()
                action = np.asarray(driver.predict(obs, deterministic=True)[0], dtype=np.float64)
                spent = time.perf_counter() - t0
                seen = labeler.observe(obs)
                if seen is not None:
                    positions, on, reference = seen
                    found = labeler.candidate_table(positions, on, reference)
                    if len(found.actions):
                        both = np.vstack([found.actions, action[None]])
                        v = labeler.teacher_values(positions, on, both)
                        feats.append(found.features)
                        values.append(v[:-1])
                        starts.append(starts[-1] + len(found.actions))
                        rack_ids.append(seed + k)
                        actions.append(action)
                        driver_values.append(v[-1])
                        seconds.append(spent)
                        layouts.append((positions, on, labeler._fouls))
                obs, _, terminated, truncated, _ = env.step(action.astype(np.float32))
                done = terminated or truncated
            if log_every and (k + 1) % log_every == 0:
                print(f"rack {k + 1}/{racks}: {len(rack_ids)} decisions, "
                      f"{time.perf_counter() - started:.0f} s", flush=True)  # fmt: skip
    finally:
        env.close()
    width = env.action_space.shape[0]
    return {
        "features": np.concatenate(feats) if feats else np.zeros((0, len(FEATURES))),
        "values": np.concatenate(values) if values else np.zeros(0),
        "starts": np.asarray(starts, dtype=np.int64),
        "rack": np.asarray(rack_ids, dtype=np.int64),
        "driver_action": np.asarray(actions).reshape(-1, width),
        "driver_value": np.asarray(driver_values, dtype=np.float64),
        "seconds": np.asarray(seconds, dtype=np.float64),
        "positions": np.asarray([p for p, _, _ in layouts]).reshape(-1, *env_balls(env), 2),
        "on_table": np.asarray([o for _, o, _ in layouts]).reshape(-1, *env_balls(env)),
        "fouls": np.asarray([f for _, _, f in layouts], dtype=np.int64).reshape(-1, 2),
    }


def refeature(
    data: dict[str, NDArray[Any]], noise: str = "fastfiz", player: str = PLAYER
) -> dict[str, NDArray[Any]]:
    """``data`` with every decision's features recomputed from its layout (new columns).

    The candidates are listed again from each decision's layout (``positions``,
    ``on_table``, ``fouls``); they must be the ones the teacher valued, in the same order
    (the listing is deterministic), so that the values still belong to them.

    Raises:
        ValueError: If the data holds no layouts or a decision's candidates differ in number.
    """
    if "positions" not in data:
        raise ValueError("these decisions hold no layouts (collected before they were kept)")
    sigmas = parse_noise(noise)
    env = make_env(ENV_ID, {"noise": sigmas} if sigmas is not None else {}, None)
    labeler = RackNetPlayer(env, player)
    starts = data["starts"]
    rows = []
    for d in range(starts.size - 1):
        positions, on = data["positions"][d], data["on_table"][d]
        labeler._targets = [int(np.flatnonzero(on[1:])[0]) + 1]  # 9-ball: the lowest ball
        labeler._fouls = tuple(int(x) for x in data["fouls"][d])
        reference = np.zeros_like(on)
        reference[0] = True
        reference[labeler._targets] = True
        found = labeler.candidate_table(positions, on, reference)
        if len(found.actions) != starts[d + 1] - starts[d]:
            raise ValueError(f"decision {d}: {len(found.actions)} candidates, the teacher "
                             f"valued {starts[d + 1] - starts[d]}")  # fmt: skip
        rows.append(found.features)
    env.close()
    return {**data, "features": np.concatenate(rows)}


def env_balls(env: Any) -> tuple[int]:
    """``(N,)``: the balls of the env's layouts, cue ball first."""
    return (int(env.unwrapped.config.n_balls),)


def load_decisions(paths: list[str]) -> dict[str, NDArray[Any]]:
    """The collected files joined (their decisions in order, ``starts`` re-based).

    Only the arrays every file holds are kept.
    """
    parts = [dict(np.load(p)) for p in paths]
    common = set.intersection(*(set(p) for p in parts))
    starts, offset = [np.zeros(1, dtype=np.int64)], 0
    for part in parts:
        starts.append(part["starts"][1:] + offset)
        offset += int(part["starts"][-1])
    out = {k: np.concatenate([p[k] for p in parts]) for k in common if k != "starts"}
    out["starts"] = np.concatenate(starts)
    return out


def soft_targets(values: NDArray[np.float64], tau: float) -> NDArray[np.float64]:
    """``softmax(values / tau)`` of one decision's candidates (``tau`` 0: the argmax, ties split).

    ``tau`` is in the values' units (chances to run out): 0.02 weighs a candidate two
    points worse ``1/e`` as much as the best.
    """
    if tau <= 0.0:
        best = values == values.max()
        return best / best.sum()
    z = (values - values.max()) / tau
    e = np.exp(z)
    return e / e.sum()


def fit(
    data: dict[str, NDArray[Any]],
    hidden: tuple[int, ...] = (64, 32),
    tau: float = 0.02,
    epochs: int = 60,
    seed: int = 0,
    held_out: float = 0.2,
    lr: float = 3e-3,
    loss_kind: str = "ce",
) -> tuple[ValueNet, dict[str, Any]]:
    """Fit the candidate scorer by cross-entropy to the soft targets (module doc).

    Each decision's targets and picks are over its :func:`~agents.learned.rack_net.eligible`
    candidates, as the player chooses.

    The decisions are split by rack (a seeded ``held_out`` share of the racks held out);
    the epoch whose held-out decisions' picks are worth the most to the teacher is kept.

    Returns:
        The network and what the fit measured (``held_out``: the teacher's mean value of
        the network's pick, of the trivial rule's and of the best candidate; the share of
        decisions where the pick is the teacher's best).
    """
    import torch

    torch.set_num_threads(1)
    torch.manual_seed(seed)
    starts = data["starts"]
    racks = np.unique(data["rack"])
    rng = np.random.default_rng(seed)
    test_racks = set(rng.choice(racks, size=max(1, int(held_out * racks.size)), replace=False))
    is_test = np.array([r in test_racks for r in data["rack"]])
    x_all = data["features"]
    mean = x_all.mean(axis=0)
    scale = np.where(x_all.std(axis=0) > 1e-8, x_all.std(axis=0), 1.0)
    width = int(np.diff(starts).max())

    def padded(idx: NDArray[np.int64]) -> tuple[Any, Any, Any, NDArray[np.float64]]:
        x = np.zeros((idx.size, width, x_all.shape[1]))
        q = np.zeros((idx.size, width))
        v = np.full((idx.size, width), -np.inf)
        mask = np.zeros((idx.size, width), dtype=bool)
        for row, d in enumerate(idx):
            a, b = starts[d], starts[d + 1]
            ok = eligible(x_all[a:b])  # the candidates the player chooses among
            x[row, : b - a] = (x_all[a:b] - mean) / scale
            q[row, : b - a][ok] = soft_targets(data["values"][a:b][ok], tau)
            v[row, : b - a] = data["values"][a:b]
            mask[row, : b - a] = ok
        return torch.tensor(x, dtype=torch.float32), torch.tensor(q, dtype=torch.float32), \
            torch.tensor(mask), v  # fmt: skip

    train_idx = np.flatnonzero(~is_test)
    test_idx = np.flatnonzero(is_test)
    x_tr, q_tr, m_tr, v_tr = padded(train_idx)
    value_tr = torch.tensor(np.where(np.isfinite(v_tr), v_tr, 0.0), dtype=torch.float32)
    x_te, _, m_te, v_te = padded(test_idx)
    sizes = (x_all.shape[1], *hidden, 1)
    layers: list[Any] = []
    for k in range(len(sizes) - 1):
        layers.append(torch.nn.Linear(sizes[k], sizes[k + 1]))
        if k < len(sizes) - 2:
            layers.append(torch.nn.ReLU())
    model = torch.nn.Sequential(*layers)
    opt = torch.optim.Adam(model.parameters(), lr=lr, weight_decay=1e-5)

    def pick_values(x: Any, m: Any, v: NDArray[np.float64]) -> float:
        with torch.no_grad():
            s = model(x)[..., 0].masked_fill(~m, -1e9).numpy()
        return float(v[np.arange(v.shape[0]), s.argmax(axis=1)].mean())

    best_value, best_state, best_epoch = -np.inf, None, -1
    batch = 256
    for epoch in range(epochs):
        order = torch.randperm(x_tr.shape[0])
        for b in range(0, order.numel(), batch):
            i = order[b : b + batch]
            logits = model(x_tr[i])[..., 0].masked_fill(~m_tr[i], -1e9)
            if loss_kind == "ce":
                loss = -(q_tr[i] * torch.log_softmax(logits, dim=1)).sum(dim=1).mean()
            else:  # the teacher's value itself, on the eligible candidates
                error = (model(x_tr[i])[..., 0] - value_tr[i]) ** 2 * m_tr[i]
                loss = error.sum() / m_tr[i].sum()
            opt.zero_grad()
            loss.backward()
            opt.step()
        value = pick_values(x_te, m_te, v_te)
        if value > best_value:
            best_value, best_epoch = value, epoch
            best_state = {k: t.clone() for k, t in model.state_dict().items()}
    assert best_state is not None
    model.load_state_dict(best_state)
    linears = [m for m in model if isinstance(m, torch.nn.Linear)]
    weights: dict[str, NDArray[np.float64]] = {"mean": mean, "scale": scale}
    for k, lin in enumerate(linears):
        weights[f"W{k}"] = lin.weight.detach().numpy().T.astype(np.float64)
        weights[f"b{k}"] = lin.bias.detach().numpy().astype(np.float64)
    net = ValueNet(weights, n_features=len(FEATURES))
    # Held-out figures from the numpy net (what plays).
    picked, trivial, best, hits = [], [], [], 0
    col = {name: k for k, name in enumerate(FEATURES)}
    for d in test_idx:
        a, b = starts[d], starts[d + 1]
        v = data["values"][a:b]
        f = x_all[a:b]
        ok = eligible(f)
        p = int(np.argmax(np.where(ok, net(f), -np.inf)))
        rule = f[:, col["p_aim"]] * f[:, col["leave_value"]] + f[:, col["wins"]]
        rule = np.where(ok, rule, -np.inf)
        picked.append(v[p])
        trivial.append(v[int(np.argmax(rule))])
        best.append(v.max())
        hits += int(v[p] == v.max())
    report = {
        "decisions": {"fit": int(train_idx.size), "held_out": int(test_idx.size)},
        "racks": {"fit": int(racks.size - len(test_racks)), "held_out": len(test_racks)},
        "loss": loss_kind, "tau": tau, "hidden": list(hidden),
        "epochs": {"run": epochs, "kept": best_epoch + 1},
        "seed": seed,
        "held_out": {
            "net_pick_value": float(np.mean(picked)),
            "rule_pick_value": float(np.mean(trivial)),
            "best_candidate_value": float(np.mean(best)),
            "driver_value": float(data["driver_value"][test_idx].mean()),
            "net_pick_is_best": hits / max(test_idx.size, 1),
        },
        "parameters": int(sum(w.size for k, w in weights.items() if k[0] in "Wb")),
    }  # fmt: skip
    return net, report


def write_fast_player(path: Path, budget: float) -> None:
    """``models/search_player_net.yaml`` at ``budget`` seconds, its models found from ``path``."""
    import yaml

    source = yaml.safe_load(Path(PLAYER).read_text())
    here = path.parent.resolve()
    for key in ("layout_value", "duel_value", "set_value"):
        target = (Path(PLAYER).parent / source[key]).resolve()
        source[key] = os.path.relpath(target, here)
    source["settings"]["budget"] = budget
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(
        f"# {PLAYER} at {budget} s a shot (agents.training.distill_rack)\n"
        + yaml.safe_dump(source, sort_keys=False)
    )


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    c = sub.add_parser("collect", help="play racks and record the teacher's values")
    c.add_argument("--driver", required=True, help="the player whose racks are recorded")
    c.add_argument("--racks", type=int, default=100)
    c.add_argument("--seed", type=int, default=800000)
    c.add_argument("--runout", action="store_true", help="run-out mode (default: practice)")
    c.add_argument("--samples", type=int, default=16, help="noisy plays per candidate")
    c.add_argument("--noise", default="fastfiz")
    c.add_argument(
        "--write-fast-player",
        type=float,
        default=None,
        metavar="BUDGET",
        help="first write --driver as the search player at BUDGET s a shot",
    )
    c.add_argument("--out", required=True)
    r = sub.add_parser("refeature", help="recompute a collected file's features")
    r.add_argument("data")
    r.add_argument("--out", required=True)
    f = sub.add_parser("fit", help="fit the network on collected files")
    f.add_argument("data", nargs="+")
    f.add_argument("--out", required=True)
    f.add_argument("--tau", type=float, default=0.02)
    f.add_argument(
        "--loss",
        choices=("ce", "mse"),
        default="ce",
        help="cross-entropy to the soft targets, or the squared error to the values",
    )
    f.add_argument("--epochs", type=int, default=60)
    f.add_argument("--hidden", default="64,32")
    f.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    if args.command == "collect":
        if args.racks < 1 or args.samples < 1:
            parser.error("--racks and --samples must be >= 1")
        if args.write_fast_player is not None:
            write_fast_player(Path(args.driver), args.write_fast_player)
        start = time.perf_counter()
        out = collect(args.driver, args.racks, args.seed, not args.runout, args.samples,
                      args.noise)  # fmt: skip
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(args.out, **out)
        n = out["rack"].size
        print(f"{n} decisions, {out['features'].shape[0]} candidates, "
              f"{time.perf_counter() - start:.0f} s -> {args.out}")  # fmt: skip
        if n:
            best = np.maximum.reduceat(out["values"], out["starts"][:-1])
            print(f"teacher value: driver's action {out['driver_value'].mean():.4f}, "
                  f"best candidate {best.mean():.4f}")  # fmt: skip
        return 0
    if args.command == "refeature":
        out = refeature(dict(np.load(args.data)))
        np.savez_compressed(args.out, **out)
        print(f"{out['rack'].size} decisions -> {args.out}")
        return 0
    import yaml

    hidden = tuple(int(h) for h in args.hidden.split(","))
    data = load_decisions(args.data)
    start = time.perf_counter()
    net, report = fit(data, hidden, args.tau, args.epochs, args.seed, loss_kind=args.loss)
    report["seconds"] = round(time.perf_counter() - start, 1)
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    np.savez(out, **net.weights())
    config = {
        "kind": "rack_net",
        "player": os.path.relpath(Path(PLAYER).resolve(), out.parent.resolve()),
        "env_id": ENV_ID,
        "features": list(FEATURES),
        "data": list(args.data),
        "command": "python -m agents.training.distill_rack "
        + " ".join(sys.argv[1:] if argv is None else argv),
        "fit": report,
    }
    out.with_name(f"{out.stem}_config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    print(json.dumps(report, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
