"""The WPA games' observation, compiled: the balls, then who may hit which, then the rack.

After the shared ball entries (:func:`pool_env.game.kernels.observe.encode_observations`):
the legal-ball flags and the rule features, from the viewer's seat.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from pool_env.game.games.wpa.params import OPTION_COLUMN, VARIANT
from pool_env.game.games.wpa.rack_state import (
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
)
from pool_env.game.kernels.observe import encode_observations
from pool_env.sim.jit import kernel

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
def n_rule_features(has_option):
    """The rule features: :data:`RULE_FEATURES`, and the option's where the game has it."""
    return N_RULE_FEATURES + (len(OPTION_FEATURES) if has_option else 0)


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
        params: The config's numbers (``params[VARIANT]``).
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
    game = int(params[VARIANT])
    has_option = params[OPTION_COLUMN] >= 0  # 9-ball and 10-ball, unless push_out=False
    out = np.zeros((b, 3 * n + n - 1 + n_rule_features(has_option)), dtype=np.float32)
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
        if has_option:
            to_shoot = row[SHOOTER] == viewer
            out[k, base + 7] = 1.0 if to_shoot and row[PUSH_OUT] != 0 else 0.0
            out[k, base + 8] = 1.0 if to_shoot and row[OPTION] != 0 else 0.0
    return out


@kernel
def legal_balls(game, on_table, rack, viewers):
    """``(B, N)``: which balls each table's viewer may hit first (the aim's reference set).

    Args:
        game: The game's code (:mod:`pool_env.game.games.wpa.rack_state`).
        on_table: ``(B, N)`` which balls are on the table.
        rack: ``(B, N_RACK)`` rack states.
        viewers: ``(B,)`` whose perspective (player 0 or 1).
    """
    out = np.zeros(on_table.shape, dtype=np.bool_)
    for k in range(on_table.shape[0]):
        legal_targets(game, rack[k], on_table[k], viewers[k], out[k])
    return out


#: The values each rule feature takes (:func:`encode_rule_observations`): the successive
#: fouls / 2, capped at 1; every other feature is a flag.
FEATURE_VALUES: dict[str, tuple[float, ...]] = {"fouls": (0.0, 0.5, 1.0),
                                                "opponent_fouls": (0.0, 0.5, 1.0)}  # fmt: skip


def check_rule_observation(
    name: str, game: int, obs: NDArray[Any], layout: dict[str, slice]
) -> None:
    """Refuse an observation whose rule part :func:`encode_rule_observations` never gives.

    The legal-ball flags 0 or 1, each set only for a ball on the table; each feature one of
    its values (:data:`FEATURE_VALUES`, else 0 or 1); the open table only in 8-ball; with
    one player the agent always to shoot and no opponent's fouls; the push-out and the
    option only for the viewer to shoot. ``obs``'s ball part is checked already.

    Args:
        name: The game's name, for the message.
        game: Its code.
        obs: One observation of the right size.
        layout: The game's observation layout.

    Raises:
        ValueError: Naming the first entry that no observation of the game holds.
    """

    def refuse(index: int, what: str) -> None:
        raise ValueError(
            f"observation[{index}] = {float(obs[index])!r} ({what}) is not what game={name!r} "
            "observes: not an observation of this env"
        )

    legal, start = obs[layout["legal"]], layout["legal"].start
    on = obs[layout["balls"]][5::3]  # balls 1..N-1
    for j in np.flatnonzero(~((legal == 0.0) | ((legal == 1.0) & (on == 1.0)))).tolist():
        refuse(start + j, f"ball {j + 1} may be hit first: a flag, set only for a ball on")
    feature = {key: float(obs[where][0]) for key, where in layout.items()
               if key not in ("balls", "legal", "shots")}  # fmt: skip
    for key, value in feature.items():
        if value not in FEATURE_VALUES.get(key, (0.0, 1.0)):
            refuse(layout[key].start, f"{key}: one of {FEATURE_VALUES.get(key, (0.0, 1.0))}")
    if game != EIGHT and feature["open_table"] != 0.0:
        refuse(layout["open_table"].start, "open_table: 8-ball's")
    for key in ("push_out", "option"):
        if feature.get(key, 0.0) == 1.0 and feature["to_shoot"] != 1.0:
            refuse(layout[key].start, f"{key}: only for the viewer to shoot")
