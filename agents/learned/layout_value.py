"""What a WPA layout is worth to the player about to shoot: features and a learned win chance.

:func:`layout_features` describes B layouts from the shooter's side in a few numbers that
the rules and the aim noise make matter: the ball on (the lowest ball) and its best pot
chances from where the cue ball lies, or from a straight-in placement when the shooter has
the cue ball in hand, whether the ball on is the 9, how many balls are left, and each
player's successive fouls (the third loses the rack). All of it is computed in one batched
call of the game's own geometry (:func:`pool_env.game.geometry.ghost_shots`), so that a
planner can value hundreds of simulated outcomes per shot. Given the shooter's legal first
balls (``targets``: 8-ball's groups, the 8), the features read over those balls instead
(:func:`layout_features`).

:class:`LayoutValue` maps them to the chance that the shooter wins the rack: a logistic
model on :func:`design` (the features and the products that matter: a pot chance counts
for more when the ball on is the 9, and with the cue ball in hand), fitted by
:func:`fit_layout_value` on layouts from played racks labelled by who won
(:mod:`agents.training.fit_layout_value`).
"""

from __future__ import annotations

import math
import zipfile
import zlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env import GameConfig, obs_layout, shot_constraints
from pool_env.game.geometry import (
    AIM_X,
    AIM_Y,
    CLEAR_PATH,
    GX,
    GY,
    TOLERANCE,
    VALID,
    PocketMouths,
    ghost_shots,
)
from pool_env.sim import Table

#: The columns of :func:`layout_features`.
LAYOUT_FEATURES = (
    "in_hand",  # the shooter has the cue ball in hand
    "p_best",  # the best pot chance on the ball on (from the cue ball, or placed)
    "p_second",  # the second best pocket's chance
    "last_ball",  # the ball on is the 9: a pot wins
    "balls_left_over_9",
    "fouls_self_over_2",  # the shooter's successive fouls
    "fouls_opponent_over_2",
)
#: How far behind the ghost-ball point a cue ball in hand is placed for a straight-in shot.
PLACE_DISTANCE = 0.25


def observed_rack(
    obs: NDArray[np.floating], config: GameConfig
) -> tuple[bool, bool, tuple[int, int]]:
    """What a rule observation says of the rack: ``(in_hand, breaking, fouls)``.

    Read through the game's public views (:func:`pool_env.shot_constraints`,
    :func:`pool_env.obs_layout`); ``fouls`` are the viewer's and the opponent's successive
    fouls (0..2), which the observation stores halved.
    """
    rules = shot_constraints(config, obs)
    layout = obs_layout(config)
    own, other = (float(obs[layout[name]][0]) for name in ("fouls", "opponent_fouls"))
    fouls = (round(2 * own), round(2 * other))
    return rules.ball_in_hand, rules.breaking, fouls


def ball_on(on_table: NDArray[np.bool_]) -> NDArray[np.int64]:
    """``(B,)`` the lowest object ball on each table (9-ball's ball on), -1 for none."""
    objects = on_table[:, 1:]
    first = np.argmax(objects, axis=1) + 1
    return np.where(objects.any(axis=1), first, -1).astype(np.int64)


def clear_tolerances(rows: NDArray[np.float64]) -> NDArray[np.float64]:
    """The tolerances (rad) of ghost-shot rows ``(..., NG)``: 0 unless valid with clear paths."""
    ok = (rows[..., VALID] > 0.5) & (rows[..., CLEAR_PATH] > 0.5)
    return np.where(ok, rows[..., TOLERANCE], 0.0)


def aim_chances(tolerance: NDArray[np.float64], sigma: float) -> NDArray[np.float64]:
    """``erf(tolerance / (sigma sqrt 2))``: the chance that an aim error of ``sigma`` (rad) pots.

    As :func:`agents.baselines.spin_play.pot_chance`, elementwise; the erf is only taken
    where the tolerance is not 0 (most shots of a layout are not on), as it costs a Python
    call per element.
    """
    tol = np.asarray(tolerance, dtype=np.float64)
    out = np.zeros_like(tol)
    some = tol != 0.0
    if some.any():
        out[some] = np.vectorize(math.erf)(tol[some] / (sigma * math.sqrt(2.0)))
    return out


def _chances(rows: NDArray[np.float64], sigma: float) -> NDArray[np.float64]:
    """Pot chances of ghost-shot rows ``(..., NG)`` under an aim error of ``sigma`` (rad).

    ``erf(tolerance / (sigma sqrt 2))`` for a valid shot with clear paths, else 0 (as
    :func:`agents.baselines.spin_play.pot_chance`).
    """
    return aim_chances(clear_tolerances(rows), sigma)


#: The money ball of each game :func:`layout_features` describes.
MONEY_BALLS = {"nine": 9, "ten": 10, "eight": 8}


def layout_features(
    table: Table,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    in_hand: NDArray[np.bool_],
    fouls: NDArray[np.int64],
    sigma: float,
    targets: NDArray[np.int64] | None = None,
    game: str = "nine",
) -> NDArray[np.float64]:
    """:data:`LAYOUT_FEATURES` of ``B`` layouts, from the side of the player to shoot.

    Without ``targets``, 9-ball's (and 10-ball's) features on the ball on (the lowest
    ball). With ``targets``, the shooter's legal first balls: ``p_best`` and ``p_second``
    are the two best pot chances over every legal ball x pocket, ``last_ball`` says that
    the only legal ball is the money ball (:data:`MONEY_BALLS`), and ``balls_left`` counts
    the shooter's balls: in 8-ball its group's balls left and the 8 (one: the 8 alone);
    on an open table the smaller group's and the 8, the fewest the shooter can run out
    with (it chooses its group by its first legal pot); in 9-ball and 10-ball every
    object ball left.

    Args:
        table: The table.
        mouths: Its pockets (:func:`pool_env.game.geometry.pocket_mouths`).
        positions: ``(B, N, 2)`` ball centres, cue first.
        on_table: ``(B, N)`` which balls are on the table.
        in_hand: ``(B,)`` the shooter has the cue ball in hand (anywhere).
        fouls: ``(B, 2)`` successive fouls of the shooter and of the opponent (0..2).
        sigma: The aim error (rad) the pot chances are taken at.
        targets: ``(B, T)`` the shooter's legal first balls, padded with -1
            (:func:`agents.learned.legal_sets.target_sets`); ``None``: the ball on
            (9-ball's features, as fitted).
        game: ``"nine"``, ``"ten"`` or ``"eight"`` (8-ball needs ``targets``).

    Returns:
        ``(B, F)`` float64.

    Raises:
        ValueError: On shapes that do not fit, a layout with no object ball (no legal
            ball), an unknown game, or 8-ball without targets.
    """
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    on = np.ascontiguousarray(on_table, dtype=np.bool_)
    b, n = on.shape
    hand = np.asarray(in_hand, dtype=np.bool_).reshape(b)
    fouls = np.asarray(fouls).reshape(b, 2)
    if pos.shape != (b, n, 2):
        raise ValueError(f"positions must be {(b, n, 2)}, got {pos.shape}")
    if game not in MONEY_BALLS:
        raise ValueError(f"game must be one of {tuple(MONEY_BALLS)}, got {game!r}")
    if targets is None:
        if game == "eight":
            raise ValueError("8-ball layouts need targets: the shooter's legal balls")
        target = ball_on(on)
        if (target < 0).any():
            raise ValueError("a layout has no object ball: nothing is left to shoot at")
        chosen = target[:, None]
    else:
        chosen = np.asarray(targets, dtype=np.int64).reshape(b, -1)
        if (chosen[:, 0] < 0).any():
            raise ValueError("a layout has no legal ball: nothing is left to shoot at")
    t = chosen.shape[1]
    rows = ghost_shots(table, mouths, pos, on, chosen)  # (B, T, K, NG)
    chances = _chances(rows, sigma)  # (B, T, K)
    if hand.any():
        for slot in range(t):
            chances[hand, slot] = _placed_chances(
                table, mouths, pos[hand], on[hand], chosen[hand, slot], rows[hand, slot], sigma
            )
    ranked = -np.sort(-chances.reshape(b, -1), axis=1)
    legal = (chosen >= 0).sum(axis=1)
    out = np.empty((b, len(LAYOUT_FEATURES)))
    out[:, 0] = hand
    out[:, 1] = ranked[:, 0]
    out[:, 2] = ranked[:, 1]
    out[:, 3] = (legal == 1) & (chosen[:, 0] == MONEY_BALLS[game])
    out[:, 4] = _balls_left(on, chosen, game) / 9.0
    out[:, 5:7] = np.minimum(fouls, 2) / 2.0
    return out


def _balls_left(on: NDArray[np.bool_], chosen: NDArray[np.int64], game: str) -> NDArray[np.int64]:
    """``(B,)`` the shooter's balls left (:func:`layout_features`)."""
    if game != "eight":
        return on[:, 1:].sum(axis=1)
    solids, stripes = on[:, 1:8].sum(axis=1), on[:, 9:16].sum(axis=1)
    legal = chosen >= 0
    has_solid = (legal & (chosen < 8)).any(axis=1)
    has_stripe = (legal & (chosen > 8)).any(axis=1)
    group = np.where(
        has_solid & has_stripe, np.minimum(solids, stripes), np.where(has_solid, solids, stripes)
    )
    eight_only = ~has_solid & ~has_stripe
    return np.where(eight_only, 1, group + 1)


def _placed_chances(
    table: Table,
    mouths: PocketMouths,
    pos: NDArray[np.float64],
    on: NDArray[np.bool_],
    target: NDArray[np.int64],
    rows: NDArray[np.float64],
    sigma: float,
) -> NDArray[np.float64]:
    """``(B, K)`` the pot chance of a straight-in shot per pocket, the cue ball placed for it.

    The cue ball goes :data:`PLACE_DISTANCE` behind the ghost-ball point on the line from
    the pocket's aim point; a point off the cloth or on another ball gives 0.
    """
    b = on.shape[0]
    k = rows.shape[1]  # rows: the ghost shots on the ball on from where the cue ball lies
    ghost = rows[..., [GX, GY]]
    away = ghost - rows[..., [AIM_X, AIM_Y]]
    norm = np.hypot(away[..., 0], away[..., 1])
    norm = np.where(norm > 0.0, norm, 1.0)
    cue = ghost + away / norm[..., None] * PLACE_DISTANCE  # (B, K, 2)
    r = table.ball_radius
    inside = (
        (cue[..., 0] > r) & (cue[..., 0] < table.length - r)
        & (cue[..., 1] > r) & (cue[..., 1] < table.width - r)
    )  # fmt: skip
    gaps = np.hypot(*(cue[:, :, None, :] - pos[:, None, 1:, :]).transpose(3, 0, 1, 2))
    free = ((gaps > 2.0 * r) | ~on[:, None, 1:]).all(axis=2)
    moved = np.repeat(pos, k, axis=0)
    moved[:, 0] = cue.reshape(-1, 2)
    targets = np.repeat(target, k)[:, None]
    placed = ghost_shots(table, mouths, moved, np.repeat(on, k, axis=0), targets)
    own = placed[:, 0].reshape(b, k, k, -1)[:, np.arange(k), np.arange(k)]  # pocket k from cue k
    return np.where(inside & free & (rows[..., VALID] > 0.5), _chances(own, sigma), 0.0)


def design(features: NDArray[np.float64]) -> NDArray[np.float64]:
    """The logistic model's inputs: a constant, the features, and the products that matter."""
    f = np.asarray(features, dtype=np.float64)
    hand, p, last, left = f[:, 0], f[:, 1], f[:, 3], f[:, 4]
    extra = np.stack([p * p, p * last, p * hand, p * left, last * hand], axis=1)
    return np.concatenate([np.ones((f.shape[0], 1)), f, extra], axis=1)


class LayoutValue:
    """The shooter's chance to win the rack from a layout: ``sigmoid(design(x) @ w)``.

    Args:
        weights: ``(D,)`` the logistic model's weights over :func:`design`'s columns.

    Raises:
        ValueError: If the weights do not fit :data:`LAYOUT_FEATURES`.
    """

    def __init__(self, weights: NDArray[np.float64]) -> None:
        w = np.asarray(weights, dtype=np.float64).reshape(-1)
        width = design(np.zeros((1, len(LAYOUT_FEATURES)))).shape[1]
        if w.shape != (width,) or not np.isfinite(w).all():
            raise ValueError(f"weights must be {width} finite numbers, got shape {w.shape}")
        self.weights = w

    def __call__(self, features: NDArray[np.float64]) -> NDArray[np.float64]:
        """``(B,)`` win chances of ``(B, F)`` layout features."""
        z = design(features) @ self.weights
        return 1.0 / (1.0 + np.exp(-np.clip(z, -40.0, 40.0)))

    def save(self, path: str | Path) -> None:
        """Write the weights as ``.npz``."""
        np.savez(path, weights=self.weights)

    @classmethod
    def load(cls, path: str | Path) -> LayoutValue:
        """Read a model written by :meth:`save`.

        Raises:
            ValueError: Naming ``path``, as :func:`load_arrays`, or on weights that do not fit.
        """
        weights = load_arrays(path, ("weights",))["weights"]
        try:
            return cls(weights)
        except ValueError as err:
            raise ValueError(f"{path}: {err}") from None


#: What reading an ``.npz`` raises on a file that is not one, or a damaged one.
_UNREADABLE = (OSError, ValueError, EOFError, zipfile.BadZipFile, zlib.error)


def load_arrays(
    path: str | Path, names: Sequence[str], optional: Sequence[str] = (), text: Sequence[str] = ()
) -> dict[str, NDArray[Any]]:
    """The arrays ``names`` (and those of ``optional`` it holds) of the ``.npz`` at ``path``.

    The layout values (:class:`LayoutValue`, :class:`~agents.learned.set_value.SetValue`)
    are read through here, so that a missing, damaged or foreign file is one
    ``ValueError`` naming it, whatever numpy or zipfile raise. Every array but those of
    ``text`` (saved names) must hold real numbers: weights saved as strings, bools or
    complex numbers would otherwise be cast to floats without a word.

    Raises:
        ValueError: Naming ``path``: not a readable ``.npz`` archive (missing, a plain
            ``.npy``, damaged, pickled objects), without one of ``names``, or an array
            (not of ``text``) whose dtype is not a real floating or integer type.
    """
    arrays: dict[str, NDArray[Any]] = {}
    try:
        # Opened here, so that the file is closed whatever numpy or zipfile make of it.
        with open(path, "rb") as handle:
            magic = handle.read(6)
            handle.seek(0)
            if magic.startswith(b"PK"):  # a zip file, as np.savez writes
                with np.load(handle) as data:  # a damaged member shows only when read
                    files = list(data.files)
                    arrays = {name: data[name] for name in (*names, *optional) if name in files}
    except _UNREADABLE as err:
        raise ValueError(f"{path} is not a readable .npz archive ({err})") from None
    if not magic.startswith(b"PK"):
        what = "a single .npy array" if magic == b"\x93NUMPY" else "not a zip file"
        raise ValueError(f"{path} is not an .npz archive of named arrays ({what})")
    missing = [name for name in names if name not in arrays]
    if missing:
        raise ValueError(f"{path} has no arrays {missing} (it holds {files})")
    for name, array in arrays.items():
        if name not in text and array.dtype.kind not in "fiu":  # not bool, complex, str
            raise ValueError(
                f"{path} array {name!r} must hold real numbers (a float or integer dtype), "
                f"got dtype {array.dtype}"
            )
    return arrays


def fit_layout_value(
    features: NDArray[np.float64], won: NDArray[np.bool_], l2: float = 1e-3, rounds: int = 50
) -> LayoutValue:
    """Maximum-likelihood logistic regression (Newton's method, a small ridge) of ``won``.

    Args:
        features: ``(S, F)`` layout features.
        won: ``(S,)`` whether the player to shoot there went on to win the rack.
        l2: Ridge on the weights (not the constant), per sample.
        rounds: Newton steps at most (it stops when a step changes no weight by 1e-10).

    Raises:
        ValueError: On shapes that do not fit or fewer than two outcomes.
    """
    x = design(features)
    y = np.asarray(won, dtype=np.float64).reshape(-1)
    if x.shape[0] != y.shape[0] or y.size < 2 or y.min() == y.max():
        raise ValueError("need (S, F) features and S labels with both outcomes")
    ridge = np.full(x.shape[1], l2 * y.size)
    ridge[0] = 0.0
    w = np.zeros(x.shape[1])
    for _ in range(rounds):
        p = 1.0 / (1.0 + np.exp(-np.clip(x @ w, -40.0, 40.0)))
        grad = x.T @ (p - y) + ridge * w
        hess = (x * (p * (1.0 - p))[:, None]).T @ x + np.diag(ridge + 1e-9)
        step = np.linalg.solve(hess, grad)
        w -= step
        if np.abs(step).max() < 1e-10:
            break
    return LayoutValue(w)
