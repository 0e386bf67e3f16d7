"""Fit the set value (:class:`agents.learned.set_value.SetValue`) on recorded 9-ball layouts.

Usage (from the repository root)::

    python -m agents.training.fit_layout_value collect --runout --racks 2500 --seed 90000 \
        --noise 0.0021817,0.075,0.0175 --out runs/set_value/ghost_ff_a.npz
    python -m agents.training.fit_set_value fit runs/set_value/ghost_ff_*.npz runs/ei/r1.npz \
        --out models/set_value.npz --seed 0

(``runs/ei/r1.npz``: the search player's racks, expert iteration's first round; the
commands are in ``results/search_player.md``.)

The data are :mod:`agents.training.fit_layout_value`'s files (their raw layouts: ``positions``,
``on_table``, ``in_hand``, ``fouls``, ``label``, ``rack``); :func:`load_records` joins several,
keeping their racks apart. :func:`fit_set_value` splits the layouts by rack (a seeded
:data:`HOLD_OUT` of the racks held out, a :data:`VALIDATION` share of the rest for early
stopping), fits the logistic layout value
(:func:`agents.learned.layout_value.fit_layout_value`) on the training racks, starts the net
from it (its ``skip`` term; the head's last layer 0) and trains it with Adam on minibatches,
keeping the epoch of the lowest validation log loss (epoch 0, the logistic itself, included).
It reports the held-out racks' log loss of the net, of the logistic fitted on all the
training racks (the same ones the net saw, validation included) and of the training base
rate, and ``fit`` writes them into the model's ``<stem>_config.yaml``.

An expert-iteration round refits on the racks its player leaves::

    python -m agents.training.fit_layout_value collect --runout --agent <player> \
        --racks 2500 --seed 95000 --noise 0.0021817,0.075,0.0175 --out runs/set_value/it1.npz
    python -m agents.training.fit_set_value fit runs/set_value/it1.npz --out models/<stem>.npz

or, in Python, ``fit_set_value(load_records(paths), seed)``.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
import yaml
from numpy.typing import NDArray

from agents.evaluation.duels import ENV_ID
from agents.learned.envs import make_env
from agents.learned.layout_value import LAYOUT_FEATURES, design, fit_layout_value
from agents.learned.set_value import (
    CONTEXT_FEATURES,
    ROW_FEATURES,
    WEIGHT_NAMES,
    SetInputs,
    SetValue,
    set_inputs,
)
from pool_env.game.geometry import pocket_mouths
from pool_env.sim import Table

#: The raw layout arrays a record set holds (:mod:`agents.training.fit_layout_value`).
RECORD_KEYS = ("positions", "on_table", "in_hand", "fouls", "label", "rack")
#: The share of racks held out of the fit (reported on).
HOLD_OUT = 0.2
#: The share of the remaining racks that decides early stopping.
VALIDATION = 0.2


def load_records(paths: list[str | Path]) -> dict[str, NDArray[Any]]:
    """The raw layouts of several collected files, concatenated (:data:`RECORD_KEYS`, ``sigma``).

    Racks are renumbered ``0..`` across the files, so that two files that reused a seed
    keep their racks apart.

    Raises:
        ValueError: On no file, a file without raw layouts, or files collected at different
            aim errors.
    """
    if not paths:
        raise ValueError("no data file given")
    parts: dict[str, list[NDArray[Any]]] = {k: [] for k in RECORD_KEYS}
    sigmas = set()
    offset = 0
    for path in paths:
        with np.load(path) as data:
            missing = [k for k in RECORD_KEYS if k not in data]
            if missing:
                raise ValueError(f"{path} has no raw layouts ({missing}): collect it again")
            for key in RECORD_KEYS[:-1]:
                parts[key].append(data[key])
            racks, index = np.unique(data["rack"], return_inverse=True)
            parts["rack"].append(index.reshape(-1) + offset)
            offset += racks.size
            if "sigma" in data:
                sigmas.add(float(data["sigma"]))
    if len(sigmas) > 1:
        raise ValueError(f"the files were collected at different aim errors {sorted(sigmas)}")
    out = {k: np.concatenate(v) for k, v in parts.items()}
    out["label"] = out["label"].astype(np.bool_)
    if sigmas:
        out["sigma"] = np.float64(sigmas.pop())
    return out


def log_loss(p: NDArray[np.float64], y: NDArray[np.bool_]) -> float:
    """The mean negative log-likelihood of labels ``y`` under chances ``p`` (nats)."""
    p = np.clip(np.asarray(p, dtype=np.float64), 1e-12, 1.0 - 1e-12)
    return float(-np.mean(np.where(y, np.log(p), np.log1p(-p))))


def split_racks(
    racks: NDArray[np.int64], seed: int, hold_out: float = HOLD_OUT, validation: float = VALIDATION
) -> tuple[NDArray[np.bool_], NDArray[np.bool_], NDArray[np.bool_]]:
    """``(fit, valid, test)`` masks over the layouts: whole racks, by a seeded shuffle."""
    ids = np.unique(racks)
    order = np.random.default_rng(seed).permutation(ids)
    n_test = round(hold_out * ids.size)
    n_valid = round(validation * (ids.size - n_test))
    test = np.isin(racks, order[:n_test])
    valid = np.isin(racks, order[n_test : n_test + n_valid])
    return ~(test | valid), valid, test


def _net(value: SetValue) -> Any:
    """A torch module holding ``value``'s weights, with :meth:`SetValue.logits`'s forward."""
    import torch

    class Net(torch.nn.Module):
        def __init__(self) -> None:
            super().__init__()
            self.w = torch.nn.ParameterDict({
                k: torch.nn.Parameter(torch.tensor(v, dtype=torch.float32))
                for k, v in value.weights.items()
            })  # fmt: skip

        def forward(self, rows: Any, mask: Any, context: Any, skip_design: Any) -> Any:
            w = self.w
            h = torch.relu(rows @ w["phi0_w"] + w["phi0_b"])
            h = torch.relu(h @ w["phi1_w"] + w["phi1_b"]) * mask[..., None]
            pooled = torch.cat(
                [h.sum(dim=1) / mask.sum(dim=1, keepdim=True), h.amax(dim=1), context], dim=1
            )
            z = torch.relu(pooled @ w["rho0_w"] + w["rho0_b"]) @ w["rho1_w"] + w["rho1_b"]
            return z + skip_design @ w["skip"]

        def export(self) -> SetValue:
            return SetValue(
                {k: p.detach().numpy().astype(np.float64) for k, p in self.w.items()},
                sigma=value.sigma,
            )

    return Net()


def initial_value(hidden: int, skip: NDArray[np.float64], seed: int, sigma: float) -> SetValue:
    """A net that is the logistic of weights ``skip``: He-initialised layers, the last one 0."""
    rng = np.random.default_rng(seed)

    def layer(n_in: int, n_out: int) -> NDArray[np.float64]:
        return rng.normal(0.0, math.sqrt(2.0 / n_in), (n_in, n_out))

    h = hidden
    weights = {
        "phi0_w": layer(len(ROW_FEATURES), h), "phi0_b": np.zeros(h),
        "phi1_w": layer(h, h), "phi1_b": np.zeros(h),
        "rho0_w": layer(2 * h + len(CONTEXT_FEATURES), h), "rho0_b": np.zeros(h),
        "rho1_w": np.zeros(h), "rho1_b": np.zeros(()), "skip": skip,
    }  # fmt: skip
    return SetValue(weights, sigma=sigma)


def fit_set_value(
    records: dict[str, NDArray[Any]],
    seed: int,
    sigma: float | None = None,
    hidden: int = 32,
    epochs: int = 300,
    patience: int = 60,
    batch: int = 512,
    lr: float = 1e-3,
    weight_decay: float = 1e-3,
    hold_out: float = HOLD_OUT,
    table: Table | None = None,
) -> tuple[SetValue, dict[str, Any]]:
    """Fit a :class:`SetValue` on recorded layouts (module doc); ``(model, report)``.

    Args:
        records: :data:`RECORD_KEYS` arrays (:func:`load_records`), ``sigma`` optional.
        seed: Seeds the rack split, the initial weights and the minibatches.
        sigma: The aim error (rad) the pot chances are taken at (default: ``records``').
        hidden: The width ``H`` of every layer.
        epochs: Passes over the fit racks at most.
        patience: Epochs without a better validation loss before stopping.
        batch: Layouts per Adam step.
        lr: Adam's step size.
        weight_decay: L2 on every weight (Adam's).
        hold_out: The share of racks held out and reported on (0: none, all racks fit).
        table: The table (default: ``pool_env/NineBallGame-v2``'s).

    Returns:
        The model of the best validation epoch, and a report: layouts and racks per split,
        the log losses (``held_out`` and ``validation``: ``net``, ``logistic``,
        ``base_rate``), the epochs run and kept, the size.

    Raises:
        ValueError: On records without both outcomes in the fit racks, or no sigma.
    """
    import torch

    torch.set_num_threads(1)  # the shared machine: one thread, as train.py's runs
    torch.manual_seed(seed)
    start = time.perf_counter()
    if sigma is None:
        if "sigma" not in records:
            raise ValueError("the records carry no sigma: give the aim error")
        sigma = float(records["sigma"])
    table = table if table is not None else make_env(ENV_ID).unwrapped.config.table
    label = np.asarray(records["label"], dtype=np.bool_)
    inputs = set_inputs(
        table, pocket_mouths(table), records["positions"], records["on_table"],
        records["in_hand"], records["fouls"], sigma,
    )  # fmt: skip
    features = inputs.context[:, : len(LAYOUT_FEATURES)]  # layout_features of the same layouts
    fit, valid, test = split_racks(np.asarray(records["rack"]), seed, hold_out)
    if not valid.any():  # too few racks to set some aside: stop on the fit racks themselves
        valid = fit
    train = fit | valid
    logistic = fit_layout_value(features[train], label[train])
    start_value = fit_layout_value(features[fit], label[fit])  # the net's epoch 0
    net = _net(initial_value(hidden, start_value.weights, seed, sigma))

    def tensors(mask: NDArray[np.bool_]) -> tuple[Any, ...]:
        part = SetInputs(inputs.rows[mask], inputs.mask[mask], inputs.context[mask])
        return (
            torch.tensor(part.rows, dtype=torch.float32),
            torch.tensor(part.mask, dtype=torch.float32),
            torch.tensor(part.context, dtype=torch.float32),
            torch.tensor(design(features[mask]), dtype=torch.float32),
        )

    x_fit, x_valid = tensors(fit), tensors(valid)
    y_fit = torch.tensor(label[fit], dtype=torch.float32)
    y_valid = torch.tensor(label[valid], dtype=torch.float32)
    loss_fn = torch.nn.BCEWithLogitsLoss()
    optim = torch.optim.Adam(net.parameters(), lr=lr, weight_decay=weight_decay)
    gen = torch.Generator().manual_seed(seed)

    def valid_loss() -> float:
        with torch.no_grad():
            return float(loss_fn(net(*x_valid), y_valid))

    best, best_epoch, state = valid_loss(), 0, {k: v.clone() for k, v in net.state_dict().items()}
    epoch = 0
    for epoch in range(1, epochs + 1):
        for idx in torch.randperm(y_fit.shape[0], generator=gen).split(batch):
            optim.zero_grad()
            loss = loss_fn(net(*(x[idx] for x in x_fit)), y_fit[idx])
            loss.backward()
            optim.step()
        now = valid_loss()
        if now < best - 1e-6:
            best, best_epoch = now, epoch
            state = {k: v.clone() for k, v in net.state_dict().items()}
        elif epoch - best_epoch >= patience:
            break
    net.load_state_dict(state)
    model = net.export()
    rate = float(label[train].mean())

    def held_out(mask: NDArray[np.bool_]) -> dict[str, float]:
        part = SetInputs(inputs.rows[mask], inputs.mask[mask], inputs.context[mask])
        y = label[mask]
        return {
            "net": log_loss(model(part), y),
            "logistic": log_loss(logistic(features[mask]), y),
            "base_rate": log_loss(np.full(y.size, rate), y),
        }

    report: dict[str, Any] = {
        "seed": seed,
        "sigma": sigma,
        "layouts": {
            name: int(mask.sum())
            for name, mask in (("fit", fit), ("validation", valid), ("held_out", test))
        },
        "racks": {
            name: int(np.unique(records["rack"][mask]).size)
            for name, mask in (("fit", fit), ("validation", valid), ("held_out", test))
        },
        "base_rate": rate,
        # The early stopping's figures: the net, and where it started (the logistic on the
        # fit racks alone; the reported logistic saw the validation racks too).
        "validation": {
            "net": best,
            "epoch_0": float(log_loss(start_value(features[valid]), label[valid])),
        },
        "epochs": {"run": epoch, "kept": best_epoch},
        "parameters": model.n_parameters,
        "seconds": round(time.perf_counter() - start, 1),
    }
    if test.any():
        report["held_out"] = held_out(test)
    return model, report


def architecture(model: SetValue) -> dict[str, Any]:
    """What the config says of a model's shape."""
    return {
        "kind": "set_value",
        "hidden": model.hidden,
        "pooling": ["mean", "max"],
        "row_features": list(ROW_FEATURES),
        "context_features": list(CONTEXT_FEATURES),
        "weights": list(WEIGHT_NAMES),
        "parameters": model.n_parameters,
    }


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    argv = sys.argv[1:] if argv is None else argv
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    f = sub.add_parser("fit", help="fit the set value, save it with its config")
    f.add_argument("data", nargs="+", help="collected .npz files (fit_layout_value collect)")
    f.add_argument("--out", required=True, help="the model's .npz")
    f.add_argument("--seed", type=int, default=0)
    f.add_argument("--hidden", type=int, default=32)
    f.add_argument("--hold-out", type=float, default=HOLD_OUT)
    f.add_argument("--sigma", type=float, default=None, help="default: the data's")
    args = parser.parse_args(argv)
    records = load_records(args.data)
    model, report = fit_set_value(
        records, args.seed, sigma=args.sigma, hidden=args.hidden, hold_out=args.hold_out
    )
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    model.save(out)
    config = {
        **architecture(model),
        "env_id": ENV_ID,
        "objective": "runout",
        "sigma": report["sigma"],
        "data": [str(p) for p in args.data],
        "command": " ".join(["python -m agents.training.fit_set_value", *argv]),
        "fit": report,
        "bytes": out.stat().st_size,
    }
    out.with_name(f"{out.stem}_config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    if "held_out" in report:
        held = report["held_out"]
        print(f"seed {args.seed}: {report['layouts']}; held-out log loss net {held['net']:.4f}, "
              f"logistic {held['logistic']:.4f}, base rate {held['base_rate']:.4f} "
              f"(epoch {report['epochs']['kept']}, {report['seconds']} s)")  # fmt: skip
    else:
        print(f"seed {args.seed}: {report['layouts']}; validation log loss net "
              f"{report['validation']['net']:.4f} ({report['seconds']} s)")  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
