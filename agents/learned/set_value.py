"""A learned 9-ball layout value over the set of balls on the table (DeepSets).

:class:`SetValue` is the shooter's chance to run out (or win) the rack from a layout, as
:class:`agents.learned.layout_value.LayoutValue`, but read from every object ball on the
table rather than from the ball on alone. Each ball is a row (:data:`ROW_FEATURES`): where it
lies, whether it is the ball on or the last ball, its rank in the rotation after the ball on,
its best pot chances from the cue ball (:func:`pool_env.game.geometry.ghost_shots` at the aim
noise, as :func:`agents.learned.layout_value.layout_features` takes them), how far the cue
ball and the ball on are from it, the cue ball's position, and its best pot chances from
where the ball before it in the rotation lies (the run-out's pattern: one ball, then the
next from about where the last one was). A row network ``phi`` maps
each row alone, and the rows are pooled (masked mean and max), so that the value does not
depend on the rows' order; a head ``rho`` reads the pool beside :data:`CONTEXT_FEATURES`
(:data:`agents.learned.layout_value.LAYOUT_FEATURES` and the cue ball's position). The logit
is the head's output plus the logistic layout value's own term on
:func:`agents.learned.layout_value.design`, which the fit starts from (the head's last layer
at 0): the net starts as the logistic and early stopping keeps it where it is no worse on
held-out racks (:mod:`agents.training.fit_set_value`).

The network is evaluated in numpy (the core install plays without torch; torch only fits
it), float64, on ``B`` layouts at once: the geometry of all balls of all layouts is one
batched :func:`~pool_env.game.geometry.ghost_shots` call, then a few matrix products.
Weights are saved as ``.npz``; the fitter writes a ``<stem>_config.yaml`` beside them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from agents.learned.layout_value import (
    LAYOUT_FEATURES,
    aim_chances,
    ball_on,
    clear_tolerances,
    design,
    layout_features,
    load_arrays,
)
from pool_env.game.checks import parse_float
from pool_env.game.geometry import PocketMouths, ghost_shots
from pool_env.sim import Table

#: The columns of a ball's row (:func:`set_inputs`). Positions are scaled onto ``[-1, 1]``
#: along each side; offsets and distances in table lengths. The cue ball's terms are 0 with
#: the cue ball in hand (it will be placed: where it lies says nothing).
ROW_FEATURES = (
    "x",
    "y",
    "ball_on",  # the lowest ball on the table: the one to hit first
    "last_ball",  # the 9 (in 9-ball): potting it wins
    "rank",  # balls before it in the rotation, over N - 2 (0: the ball on)
    "p_best",  # its best pot chance from the cue ball, any pocket
    "p_second",  # the second best pocket's
    "cue_distance",
    "from_on_x",  # where it lies from the ball on: the next position to play for
    "from_on_y",
    "cue_x",
    "cue_y",
    "p_chain",  # its best pot chance from where the ball before it lies (the ball on: p_best)
    "p_chain_second",
    "chain_distance",  # how far that is
)
#: The columns beside the pooled rows: the logistic's features, then the cue ball's position.
CONTEXT_FEATURES = (*LAYOUT_FEATURES, "cue_x", "cue_y")
#: The weight arrays of a :class:`SetValue` (``phi`` the row network, ``rho`` the head,
#: ``skip`` the logistic term over :func:`design`'s columns).
WEIGHT_NAMES = ("phi0_w", "phi0_b", "phi1_w", "phi1_b", "rho0_w", "rho0_b", "rho1_w", "rho1_b",
                "skip")  # fmt: skip


class SetInputs(NamedTuple):
    """The network's inputs for ``B`` layouts of ``N`` balls (cue first)."""

    rows: NDArray[np.float64]  # (B, N - 1, len(ROW_FEATURES)): object ball j - 1 in row j - 1
    mask: NDArray[np.bool_]  # (B, N - 1): the ball is on the table (0 rows where not)
    context: NDArray[np.float64]  # (B, len(CONTEXT_FEATURES))


def set_inputs(
    table: Table,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    in_hand: NDArray[np.bool_],
    fouls: NDArray[np.int64],
    sigma: float,
) -> SetInputs:
    """The network's inputs for ``B`` layouts, from the shooter's side.

    The arguments are :meth:`SetValue.value`'s.

    Raises:
        ValueError: On shapes that do not fit, positions that are not finite, fouls outside
            0..2, ``sigma <= 0`` or a table with no object ball.
    """
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    on = np.ascontiguousarray(on_table, dtype=np.bool_)
    if on.ndim != 2 or on.shape[1] < 2:
        raise ValueError(f"on_table must be (B, N) with N >= 2, got shape {on.shape}")
    b, n = on.shape
    if pos.shape != (b, n, 2) or not np.isfinite(pos).all():
        raise ValueError(f"positions must be {(b, n, 2)} finite numbers, got shape {pos.shape}")
    hand = np.asarray(in_hand, dtype=np.bool_)
    fouls = np.asarray(fouls)
    if hand.shape != (b,) or fouls.shape != (b, 2):
        raise ValueError(
            f"in_hand must be ({b},) and fouls ({b}, 2), got {hand.shape}, {fouls.shape}"
        )
    if fouls.size and (fouls.min() < 0 or fouls.max() > 2):
        raise ValueError("fouls must be successive fouls, 0..2")
    if not (math.isfinite(sigma) and sigma > 0.0):
        raise ValueError(f"sigma must be a positive aim error (rad), got {sigma}")
    if b == 0:
        return SetInputs(np.zeros((0, n - 1, len(ROW_FEATURES))), np.zeros((0, n - 1), np.bool_),
                         np.zeros((0, len(CONTEXT_FEATURES))))  # fmt: skip
    # The logistic's features first: they check the layouts (and refuse an empty table).
    layout = layout_features(table, mouths, pos, on, hand, fouls, sigma)
    mask = on[:, 1:]
    balls = np.arange(1, n)
    targets = np.where(mask, balls, -1)
    # Pot chances of every ball from the cue ball: erf is monotone, so the best two pockets
    # are the two most forgiving shots, and only their erfs are taken.
    tol = clear_tolerances(ghost_shots(table, mouths, pos, on, targets))  # (B, N - 1, K)
    top = -np.sort(-tol, axis=2)[..., :2]
    chances = aim_chances(top, sigma)
    size = np.array([table.length, table.width])
    scaled = 2.0 * pos / size - 1.0
    target = ball_on(on)
    seen = ~hand[:, None]  # the cue ball's terms count only where it lies
    on_pos = pos[np.arange(b), target]  # (B, 2)
    rows = np.empty((b, n - 1, len(ROW_FEATURES)))
    rows[..., 0:2] = scaled[:, 1:]
    rows[..., 2] = balls == target[:, None]
    rows[..., 3] = balls == n - 1
    rows[..., 4] = (np.cumsum(mask, axis=1) - 1) / max(n - 2, 1)
    rows[..., 5:7] = chances * seen[..., None]
    rows[..., 7] = np.hypot(*(pos[:, 1:] - pos[:, :1]).transpose(2, 0, 1)) / table.length * seen
    rows[..., 8:10] = (pos[:, 1:] - on_pos[:, None]) / table.length
    rows[..., 10:12] = scaled[:, :1] * seen[..., None]
    chain, start = _chain_chances(table, mouths, pos, on, sigma)
    first = balls == target[:, None]
    rows[..., 12:14] = np.where(first[..., None], chances * seen[..., None], chain)
    away = np.hypot(*(pos[:, 1:] - start).transpose(2, 0, 1)) / table.length
    rows[..., 14] = np.where(first, rows[..., 7], away)
    rows *= mask[..., None]
    context = np.concatenate([layout, scaled[:, 0] * seen], axis=1)
    return SetInputs(rows, mask, context)


def _chain_chances(
    table: Table,
    mouths: PocketMouths,
    pos: NDArray[np.float64],
    on: NDArray[np.bool_],
    sigma: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Each ball's two best pot chances from where the ball before it in the rotation lies.

    The rotation's pattern: once the balls before it are down, the cue ball is near where
    the last of them was. The cue ball is put there (the balls before taken off) and the
    ghost shots taken in one batched call over every (layout, ball) pair but the ball on.

    Returns:
        ``(B, N - 1, 2)`` the chances (0 for the ball on and balls off the table) and
        ``(B, N - 1, 2)`` the points they are taken from.
    """
    b, n = on.shape
    numbers = np.arange(n)
    # The ball before each ball: the highest-numbered ball on the table below it.
    below = np.maximum.accumulate(np.where(on, numbers, 0), axis=1)
    before = np.concatenate([np.zeros((b, 1), np.int64), below[:, :-1]], axis=1)[:, 1:]
    start = pos[np.arange(b)[:, None], before]  # (B, N - 1, 2)
    rows, slots = np.nonzero(on[:, 1:] & (before > 0))
    chances = np.zeros((b, n - 1, 2))
    if rows.size:
        moved = pos[rows].copy()
        moved[:, 0] = start[rows, slots]
        left = on[rows] & (numbers >= slots[:, None] + 1)
        left[:, 0] = True
        tol = clear_tolerances(ghost_shots(table, mouths, moved, left, slots[:, None] + 1))[:, 0]
        chances[rows, slots] = aim_chances(-np.sort(-tol, axis=1)[:, :2], sigma)
    return chances, start


class SetValue:
    """The shooter's chance to run out from a layout: a DeepSets network (module doc).

    Args:
        weights: The arrays :data:`WEIGHT_NAMES` (``phi0_w`` ``(len(ROW_FEATURES), H)``,
            ``phi0_b`` ``(H,)``, ``phi1_w`` ``(H, H)``, ``phi1_b`` ``(H,)``, ``rho0_w``
            ``(2 H + len(CONTEXT_FEATURES), H)``, ``rho0_b`` ``(H,)``, ``rho1_w`` ``(H,)``,
            ``rho1_b`` ``()``, ``skip`` ``(D,)`` over :func:`design`'s columns).
        sigma: The aim error (rad) the model was fitted at, if known (for its users: the
            value itself takes its ``sigma`` per call).

    Raises:
        ValueError: On missing, misshapen or non-finite weights.
    """

    def __init__(self, weights: Mapping[str, NDArray[Any]], sigma: float | None = None) -> None:
        missing = [k for k in WEIGHT_NAMES if k not in weights]
        if missing:
            raise ValueError(f"weights lack {missing}")
        w = {k: np.asarray(weights[k], dtype=np.float64) for k in WEIGHT_NAMES}
        h = w["phi0_b"].shape[0] if w["phi0_b"].ndim == 1 else 0
        width = design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1]
        shapes = {
            "phi0_w": (len(ROW_FEATURES), h), "phi0_b": (h,), "phi1_w": (h, h), "phi1_b": (h,),
            "rho0_w": (2 * h + len(CONTEXT_FEATURES), h), "rho0_b": (h,), "rho1_w": (h,),
            "rho1_b": (), "skip": (width,),
        }  # fmt: skip
        for k, shape in shapes.items():
            if h < 1 or w[k].shape != shape or not np.isfinite(w[k]).all():
                raise ValueError(f"weight {k} must be {shape} finite numbers, got {w[k].shape}")
        self.weights = w
        self.hidden = h
        self.sigma = sigma

    def logits(self, inputs: SetInputs) -> NDArray[np.float64]:
        """``(B,)`` the network's logits of :func:`set_inputs`' output."""
        w = self.weights
        b, s, f = inputs.rows.shape
        # One 2-D product over all rows of all layouts (a batched 3-D matmul is slower).
        h = np.maximum(inputs.rows.reshape(b * s, f) @ w["phi0_w"] + w["phi0_b"], 0.0)
        h = np.maximum(h @ w["phi1_w"] + w["phi1_b"], 0.0).reshape(b, s, self.hidden)
        m = inputs.mask[..., None]
        # The rows are >= 0 after the ReLU, so zeroing the empty slots leaves the max as is;
        # every layout has a ball on, so the mean divides by at least 1.
        h = h * m
        pooled = np.concatenate(
            [h.sum(axis=1) / m.sum(axis=1), h.max(axis=1), inputs.context], axis=1
        )
        z = np.maximum(pooled @ w["rho0_w"] + w["rho0_b"], 0.0) @ w["rho1_w"] + w["rho1_b"]
        return z + design(inputs.context[:, : len(LAYOUT_FEATURES)]) @ w["skip"]

    def __call__(self, inputs: SetInputs) -> NDArray[np.float64]:
        """``(B,)`` run-out chances of :func:`set_inputs`' output."""
        # +-30, not 40: sigmoid(40) rounds to 1.0 in float64, and a chance must stay in (0, 1).
        return 1.0 / (1.0 + np.exp(-np.clip(self.logits(inputs), -30.0, 30.0)))

    def value(
        self,
        table: Table,
        mouths: PocketMouths,
        positions: NDArray[np.float64],
        on_table: NDArray[np.bool_],
        in_hand: NDArray[np.bool_],
        fouls: NDArray[np.int64],
        sigma: float,
    ) -> NDArray[np.float64]:
        """``(B,)`` float64 chances in (0, 1) that the shooter runs out ``B`` layouts.

        Args:
            table: The table.
            mouths: Its pockets (:func:`pool_env.game.geometry.pocket_mouths`).
            positions: ``(B, N, 2)`` ball centres, cue first.
            on_table: ``(B, N)`` which balls are on the table.
            in_hand: ``(B,)`` the shooter has the cue ball in hand (anywhere).
            fouls: ``(B, 2)`` successive fouls of the shooter and of the opponent (0..2).
            sigma: The aim error (rad) the pot chances are taken at (the model's
                :attr:`sigma` is the one it was fitted at).

        Raises:
            ValueError: As :func:`set_inputs`.
        """
        return self(set_inputs(table, mouths, positions, on_table, in_hand, fouls, sigma))

    @property
    def n_parameters(self) -> int:
        """How many numbers the network holds."""
        return sum(int(v.size) for v in self.weights.values())

    def save(self, path: str | Path) -> None:
        """Write the weights (and the feature names, the fit's ``sigma``) as ``.npz``."""
        extra = {} if self.sigma is None else {"sigma": np.float64(self.sigma)}
        np.savez(path, **self.weights, row_features=np.array(ROW_FEATURES),
                 context_features=np.array(CONTEXT_FEATURES), **extra)  # fmt: skip

    @classmethod
    def load(cls, path: str | Path) -> SetValue:
        """Read a model written by :meth:`save`.

        Raises:
            ValueError: Naming ``path``: as :func:`~agents.learned.layout_value.load_arrays`,
                or if it was saved with other features than this code computes, or on
                weights that do not fit.
        """
        keys = ("row_features", "context_features")
        data = load_arrays(path, (*WEIGHT_NAMES, *keys), optional=("sigma",), text=keys)
        for key, names in zip(keys, (ROW_FEATURES, CONTEXT_FEATURES), strict=True):
            if tuple(data[key].tolist()) != names:
                raise ValueError(f"{path}: saved with {key} {data[key].tolist()}, not {names}")
        try:
            sigma = parse_float("sigma", data["sigma"]) if "sigma" in data else None
            return cls({k: data[k] for k in WEIGHT_NAMES}, sigma=sigma)
        except ValueError as err:
            raise ValueError(f"{path}: {err}") from None
