"""What the agent sees (the observation) and the optional shaping potential."""

from __future__ import annotations

import math

import numpy as np

from pool_env.game.kernels.params import GAME
from pool_env.game.kernels.wpa import (
    BEHIND,
    BREAKING,
    EIGHT,
    FOULS_0,
    GROUP_0,
    IN_HAND,
    OPEN,
    OPTION,
    PUSH_OUT,
    SHOOTER,
    legal_targets,
    rotation,
)
from pool_env.sim.jit import kernel


@kernel
def encode_observations(positions, on_table, length, width):
    """Observation: per ball ``(x, y, on_table)``, ``x`` and ``y`` scaled to ``[-1, 1]``.

    A potted ball reads ``(0, 0, 0)``.

    Args:
        positions: ``(B, N, 2)`` centres (m).
        on_table: ``(B, N)`` which balls are on the table.
        length: Table length (m).
        width: Table width (m).

    Returns:
        ``(B, 3 N)`` float32.
    """
    b, n = on_table.shape
    out = np.zeros((b, 3 * n), dtype=np.float32)
    for k in range(b):
        for j in range(n):
            if on_table[k, j]:
                # Clamp: a ball on a rail may sit 1e-9 m outside it after rounding.
                x = (2.0 * positions[k, j, 0] - length) / length  # exact 0 on the centre line
                out[k, 3 * j] = min(max(x, -1.0), 1.0)
                y = (2.0 * positions[k, j, 1] - width) / width
                out[k, 3 * j + 1] = min(max(y, -1.0), 1.0)
                out[k, 3 * j + 2] = 1.0
    return out


@kernel
def potential(positions, on_table, pockets, scale):
    """Shaping potential: minus the summed distance of object balls to their nearest pocket.

    Ball 0 (the cue) is left out and potted balls count 0, so a cleared table has potential
    0; a table without pockets has potential 0 everywhere.

    Args:
        positions: ``(N, 2)`` centres of one table.
        on_table: ``(N,)`` which balls are on the table.
        pockets: ``(P, 3)`` capture circles.
        scale: Length to divide by (the table diagonal in the environment).

    Returns:
        The potential (<= 0).
    """
    if pockets.shape[0] == 0:
        return 0.0
    total = 0.0
    for j in range(1, on_table.shape[0]):
        if on_table[j]:
            best = np.inf
            for p in range(pockets.shape[0]):
                # sqrt of a sum is correctly rounded everywhere; libm's hypot is not (it
                # differs from CPython's in the last bits), and rewards must be reproducible.
                dx = positions[j, 0] - pockets[p, 0]
                dy = positions[j, 1] - pockets[p, 1]
                best = min(best, math.sqrt(dx * dx + dy * dy))
            total += best
    return -total / scale


@kernel
def pocket_potentials(positions, on_table, pockets, scale):
    """:func:`potential` of each of ``B`` tables: ``(B, N, 2)``, ``(B, N)`` in, ``(B,)`` out."""
    out = np.zeros(on_table.shape[0])
    for k in range(on_table.shape[0]):
        out[k] = potential(positions[k], on_table[k], pockets, scale)
    return out


#: Rule features after the balls' and the legal-ball flags, in this order.
RULE_FEATURES: tuple[str, ...] = (
    "ball_in_hand", "behind_head_string", "break", "open_table", "fouls", "opponent_fouls",
    "to_shoot",
)  # fmt: skip
N_RULE_FEATURES = 7

#: The rotation games' features after :data:`RULE_FEATURES` (9-ball, 10-ball): the viewer
#: may push out on this shot, the viewer may hand the table back instead of shooting.
OPTION_FEATURES: tuple[str, ...] = ("push_out", "option")


@kernel
def n_rule_features(game):
    """The rule features of ``game``: :data:`RULE_FEATURES`, and the rotation games' options."""
    return N_RULE_FEATURES + (len(OPTION_FEATURES) if rotation(game) else 0)


@kernel
def encode_rule_observations(params, positions, on_table, rack, viewers, length, width):
    """Observation under rules: the balls, the balls the viewer may hit first, the rack.

    Per table: :func:`encode_observations`' ``3 N`` entries; then for each object ball
    ``1..N-1`` whether the viewer may hit it first (9-ball: the ball on, one-hot; 8-ball:
    the viewer's group, every ball but the 8 on an open table, the 8 once the group is
    cleared, any ball on the break); then :data:`RULE_FEATURES`: the cue ball in hand,
    only behind the head string, the next shot is a break, the 8-ball table is open, the
    viewer's and the opponent's successive fouls / 2 (at most 1), and whether the viewer
    shoots next (always 1 with one player); in 9-ball and 10-ball also
    :data:`OPTION_FEATURES`: the viewer shoots next and may push out, or may hand the
    table back.

    Args:
        params: The config's numbers (``params[GAME]``).
        positions: ``(B, N, 2)`` centres (m).
        on_table: ``(B, N)`` which balls are on the table.
        rack: ``(B, N_RACK)`` rack states.
        viewers: ``(B,)`` whose perspective (player 0 or 1).
        length: Table length (m).
        width: Table width (m).

    Returns:
        ``(B, 3 N + N - 1 + F)`` float32, ``F`` the game's :func:`n_rule_features`.
    """
    b, n = on_table.shape
    balls = encode_observations(positions, on_table, length, width)
    game = int(params[GAME])
    out = np.zeros((b, 3 * n + n - 1 + n_rule_features(game)), dtype=np.float32)
    out[:, : 3 * n] = balls
    legal = np.empty(n, dtype=np.bool_)
    for k in range(b):
        viewer = viewers[k]
        row = rack[k]
        legal_targets(game, row, on_table[k], viewer, legal)
        for j in range(1, n):
            out[k, 3 * n + j - 1] = 1.0 if legal[j] else 0.0
        base = 4 * n - 1
        out[k, base] = 1.0 if row[IN_HAND] != 0 else 0.0
        out[k, base + 1] = 1.0 if row[BEHIND] != 0 else 0.0
        out[k, base + 2] = 1.0 if row[BREAKING] != 0 else 0.0
        out[k, base + 3] = 1.0 if game == EIGHT and row[GROUP_0 + viewer] == OPEN else 0.0
        out[k, base + 4] = min(row[FOULS_0 + viewer], 2) * 0.5
        out[k, base + 5] = min(row[FOULS_0 + 1 - viewer], 2) * 0.5
        out[k, base + 6] = 1.0 if row[SHOOTER] == viewer else 0.0
        if rotation(game):
            to_shoot = row[SHOOTER] == viewer
            out[k, base + 7] = 1.0 if to_shoot and row[PUSH_OUT] != 0 else 0.0
            out[k, base + 8] = 1.0 if to_shoot and row[OPTION] != 0 else 0.0
    return out


@kernel
def legal_balls(game, on_table, rack, viewers):
    """``(B, N)``: which balls each table's viewer may hit first (the aim's reference set).

    Args:
        game: The game's code (:mod:`pool_env.game.kernels.wpa`).
        on_table: ``(B, N)`` which balls are on the table.
        rack: ``(B, N_RACK)`` rack states.
        viewers: ``(B,)`` whose perspective (player 0 or 1).
    """
    out = np.zeros(on_table.shape, dtype=np.bool_)
    for k in range(on_table.shape[0]):
        legal_targets(game, rack[k], on_table[k], viewers[k], out[k])
    return out
