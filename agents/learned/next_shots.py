"""The search's deeper plies: every layout's best next shot, found in one batch on the model.

The rack agents' planner works out exact spin strikes one layout at a time in Python
(about 0.1 s a layout); a search that looks a shot further needs the best next shot of
hundreds of simulated outcomes per decision. :func:`next_shot_actions` lists candidates for
``L`` layouts at once from the compiled ghost-ball geometry: on the ball on (given the
shooter's legal balls, on those: 8-ball's group or the 8), the :data:`POCKETS_KEPT` most
forgiving clear ball x pocket pairs, each aimed at :data:`OFFSETS` across the
mouth (the collision's throw turns the object ball off the ghost-ball line by up to a few
degrees; rather than model it, the fan lets the simulation find the aim that drops), at
:data:`ARRIVALS` (how fast the object ball reaches the pocket: position by speed) and
:data:`TIPS` (stun, follow, draw). :func:`best_next_values` plays them all on the game's own
step (:class:`agents.learned.game_model.GameModel`), values the outcomes with a leaf value
(:func:`agents.learned.leaf_value.outcome_values`) and keeps, per layout, the best
candidate's mean: what the shooter can expect from the layout with one more shot searched.

The calls are the rules': 10-ball calls each candidate's ball and pocket, 8-ball its pocket
(the 8's call is the one that counts: the 8 in another pocket loses); 9-ball calls nothing.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from agents.baselines.rule_play import rule_action
from agents.learned.game_model import GameModel
from agents.learned.layout_value import ball_on
from agents.learned.leaf_value import LeafValue, outcome_values
from agents.learned.legal_sets import target_sets
from pool_env.game.codec import encode_ball, encode_pocket, encode_shots
from pool_env.game.config import GameConfig
from pool_env.game.games.wpa import rack_row
from pool_env.game.geometry import (
    ANGLE,
    CLEAR_PATH,
    TOLERANCE,
    VALID,
    PocketMouths,
    cue_speeds,
    ghost_shots,
)

#: Aim points across the pocket's mouth, in fractions of its half-width seen along the path.
OFFSETS = (-0.8, -0.4, 0.0, 0.4, 0.8)
#: The object ball's speed (m/s) as it reaches the pocket: a soft pot to a firm one.
ARRIVALS = (0.3, 0.9, 1.8)
#: Cue tip offsets ``(side, vertical)`` in fractions of R: stun, follow, draw.
TIPS = ((0.0, 0.0), (0.0, 0.4), (0.0, -0.4))
#: The pockets tried per layout, most forgiving first.
POCKETS_KEPT = 2


class NextShots(NamedTuple):
    """The candidates of ``L`` layouts (:func:`next_shot_table`), ``M`` per layout.

    Candidate ``m`` runs over :data:`OFFSETS` x the kept pockets (ball x pocket pairs) x
    :data:`ARRIVALS` x :data:`TIPS`, in that order (C order over ``(O, P, S, T)``).

    Attributes:
        actions: ``(L, M, A)`` full env actions.
        ok: ``(L, M)`` which are playable (a clear, valid ghost-ball shot the aim mode can
            play within the speed range).
        rows: ``(L, M, NG)`` each candidate's ghost-ball row
            (:func:`~pool_env.game.geometry.ghost_shots`: cut, distances, tolerance, ...).
        speeds: ``(L, M)`` the cue ball's speed (m/s).
        tips: ``(L, M, 2)`` the tip ``(side, vertical)`` in fractions of R.
        offsets: ``(M,)`` the aim's place across the mouth (:data:`OFFSETS`).
        arrivals: ``(M,)`` the object ball's speed at the pocket (:data:`ARRIVALS`).
        ranks: ``(M,)`` the pocket's rank among the kept ones (0: the most forgiving).
        balls: ``(L, M)`` the object ball each candidate pots (-1: none playable).
        pockets: ``(L, M)`` its pocket.
    """

    actions: NDArray[np.float64]
    ok: NDArray[np.bool_]
    rows: NDArray[np.float64]
    speeds: NDArray[np.float64]
    tips: NDArray[np.float64]
    offsets: NDArray[np.float64]
    arrivals: NDArray[np.float64]
    ranks: NDArray[np.int64]
    balls: NDArray[np.int64]
    pockets: NDArray[np.int64]


def next_shot_actions(
    config: GameConfig,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    targets: NDArray[np.int64] | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Candidate env actions on the legal balls of ``L`` layouts (module doc).

    Args:
        config: The env's config (a rotation game on a spin table).
        mouths: Its pockets.
        positions: ``(L, N, 2)`` ball centres, the cue ball where it lies.
        on_table: ``(L, N)`` which balls are on the table (an object ball at least).
        targets: ``(L, T)`` the shooter's legal first balls padded with -1
            (:func:`~agents.learned.legal_sets.target_sets`); ``None``: the ball on.

    Returns:
        ``(actions, ok)``: ``(L, M, A)`` full env actions and ``(L, M)`` which are playable
        (a clear, valid ghost-ball shot the aim mode can play within the speed range).
    """
    shots = next_shot_table(config, mouths, positions, on_table, targets)
    return shots.actions, shots.ok


def next_shot_table(
    config: GameConfig,
    mouths: PocketMouths,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    targets: NDArray[np.int64] | None = None,
) -> NextShots:
    """:func:`next_shot_actions` with what describes each candidate (:class:`NextShots`)."""
    table = config.table
    pos = np.ascontiguousarray(positions, dtype=np.float64)
    on = np.ascontiguousarray(on_table, dtype=np.bool_)
    n_layouts = on.shape[0]
    chosen = ball_on(on)[:, None] if targets is None else np.asarray(targets, dtype=np.int64)
    chosen = chosen.reshape(n_layouts, -1)
    k_pockets = table.n_pockets
    shots = [ghost_shots(table, mouths, pos, on, chosen, offset=o) for o in OFFSETS]
    # (L, O, T K, NG): ball slot t's pocket k at column t K + k
    rows = np.stack([g.reshape(n_layouts, -1, g.shape[-1]) for g in shots], axis=1)
    centre = rows[:, OFFSETS.index(0.0)]
    usable = (centre[..., VALID] > 0.5) & (centre[..., CLEAR_PATH] > 0.5)
    rank = np.argsort(-np.where(usable, centre[..., TOLERANCE], -1.0), axis=1)
    kept = rank[:, :POCKETS_KEPT]  # (L, P): ball x pocket pairs, most forgiving first
    picked = np.take_along_axis(rows, kept[:, None, :, None], axis=2)  # (L, O, P, NG)
    pocket_ok = np.take_along_axis(usable, kept, axis=1)  # (L, P)
    ok_rows = (picked[..., VALID] > 0.5) & pocket_ok[:, None, :]
    speeds = np.stack([cue_speeds(table, picked, a) for a in ARRIVALS], axis=-1)  # (L,O,P,S)
    shape = (*speeds.shape, len(TIPS))  # (L, O, P, S, T)
    angles = np.broadcast_to(picked[..., ANGLE][..., None, None], shape)
    speed = np.broadcast_to(speeds[..., None], shape)
    tips = np.broadcast_to(np.asarray(TIPS, dtype=np.float64), (*shape, 2))
    ok = np.broadcast_to(ok_rows[..., None, None], shape)
    m = int(np.prod(shape[1:]))
    # The aim refers to the balls the rules let the shooter hit first, as the env decodes it.
    refer = np.zeros_like(on)
    refer[:, 0] = True
    for slot in range(chosen.shape[1]):
        refer[np.arange(n_layouts), np.maximum(chosen[:, slot], 0)] |= chosen[:, slot] >= 0
    kept_balls = np.take_along_axis(chosen, kept // k_pockets, axis=1)  # (L, P)
    kept_pockets = kept % k_pockets
    parts, playable = encode_shots(
        config, pos, refer, angles.reshape(n_layouts, m), speed.reshape(n_layouts, m),
        tips.reshape(n_layouts, m, 2),
    )  # fmt: skip
    lo, top = config.speed_range
    flat_speed = speed.reshape(n_layouts, m)
    in_range = (flat_speed >= lo) & (flat_speed <= top)
    template = rule_action(config, np.zeros(4), ball=1)  # 10-ball's ball: set below
    actions = np.broadcast_to(template, (n_layouts, m, template.shape[0])).copy()
    actions[..., 0:2] = parts[..., 0:2]
    actions[..., list(config.tip_columns)] = parts[..., 2:4]  # type: ignore[arg-type]
    grid = np.meshgrid(
        np.asarray(OFFSETS), np.arange(POCKETS_KEPT), np.asarray(ARRIVALS),
        np.arange(len(TIPS)), indexing="ij",
    )  # fmt: skip
    ranks = grid[1].ravel()
    balls = np.where(ok_rows.any(axis=1), kept_balls, -1)[:, ranks]  # (L, M)
    pockets = kept_pockets[:, ranks]
    _write_calls(config, actions, balls, pockets)
    full_rows = np.broadcast_to(picked[:, :, :, None, None], (*shape, picked.shape[-1]))
    return NextShots(
        actions=actions,
        ok=ok.reshape(n_layouts, m) & playable & in_range,
        rows=full_rows.reshape(n_layouts, m, -1),
        speeds=flat_speed,
        tips=tips.reshape(n_layouts, m, 2),
        offsets=grid[0].ravel(),
        arrivals=grid[2].ravel(),
        ranks=ranks,
        balls=balls,
        pockets=pockets,
    )


def _write_calls(
    config: GameConfig,
    actions: NDArray[np.float64],
    balls: NDArray[np.int64],
    pockets: NDArray[np.int64],
) -> None:
    """Each candidate's calls in ``actions`` (module doc).

    10-ball's ball and pocket, 8-ball's pocket (the 8's call), none in 9-ball; a candidate
    of no ball keeps the template's.
    """
    ruleset = config.ruleset
    if not ruleset.calls_ball and config.game != "eight":
        return
    real = balls >= 0
    codes = np.array([encode_pocket(config, k) for k in range(config.table.n_pockets)])
    actions[..., 4] = np.where(real, codes[pockets], actions[..., 4])
    if ruleset.calls_ball:
        named = np.array([encode_ball(config, b) for b in range(1, ruleset.n_objects + 1)])
        column = actions[..., ruleset.ball_column]
        actions[..., ruleset.ball_column] = np.where(real, named[np.maximum(balls, 1) - 1], column)


def best_next_values(
    model: GameModel,
    mouths: PocketMouths,
    leaf: LeafValue,
    runout: bool,
    positions: NDArray[np.float64],
    on_table: NDArray[np.bool_],
    fouls: tuple[int, int],
    samples: int,
    racks: NDArray[np.int64] | None = None,
) -> NDArray[np.float64]:
    """``(L,)`` each layout's value to the shooter with its next shot searched (module doc).

    Args:
        model: The game model (the env's config, noise included).
        mouths: The table's pockets.
        leaf: The leaf value of what the next shot leaves.
        runout: Run-out mode (a miss or a foul is worth 0).
        positions: ``(L, N, 2)`` layouts, the shooter to play with the cue ball where it lies.
        on_table: ``(L, N)`` the balls on the table.
        fouls: The shooter's and the opponent's successive fouls (0..2).
        samples: Noisy plays of each candidate.
        racks: ``(L, N_RACK)`` each layout's rack row, the shooter in seat 0 (8-ball: its
            group); ``None``: a row with ``fouls`` alone (an open table). Off 9-ball the
            candidates go on the legal balls these rows give and the leaves are told the
            next shooter's (:func:`~agents.learned.leaf_value.outcome_values`).

    Returns:
        The best candidate's mean outcome value per layout; a layout with no candidate
        (no clear pot on a legal ball) keeps its own leaf value.
    """
    config = model.config
    n_layouts = positions.shape[0]
    hand = np.zeros(n_layouts, dtype=np.bool_)
    leaf_fouls = np.tile(np.asarray(fouls, dtype=np.int64), (n_layouts, 1))
    if racks is None:
        rows = np.tile(rack_row({"fouls": fouls}), (n_layouts, 1))
    else:
        rows = np.asarray(racks, dtype=np.int64).reshape(n_layouts, -1)
    targets = None
    ruleset = None
    if config.game != "nine":  # 9-ball: the ball on, as its values were fitted
        ruleset = config.ruleset
        targets = target_sets(ruleset.legal_first_balls(rows, on_table, np.zeros(n_layouts, int)))
        own = leaf(positions, on_table, hand, leaf_fouls, targets)
    else:
        own = leaf(positions, on_table, hand, leaf_fouls)
    if not n_layouts:
        return own
    actions, ok = next_shot_actions(config, mouths, positions, on_table, targets)
    layout, cand = np.nonzero(ok)
    if not layout.size:
        return own
    result, after, left, racks_after = model.play_racks(
        positions[layout], on_table[layout], rows[layout], actions[layout, cand], samples,
        common_noise=False,
    )  # fmt: skip
    value = outcome_values(
        leaf, runout, result, after, left, fouls, racks_after if ruleset else None, ruleset
    )
    means = value.reshape(-1, samples).mean(axis=1)
    best = np.full(n_layouts, -np.inf)
    np.maximum.at(best, layout, means)
    return np.where(np.isfinite(best), best, own)
