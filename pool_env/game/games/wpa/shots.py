"""The WPA games' shots, compiled: the cue ball in hand placed, then the calls and the strike.

Over the shared decoding (:mod:`pool_env.game.kernels.actions`): the action is ``(aim,
speed, cue x, cue y, pocket)``, then the game's own columns (10-ball's called ball, 9-ball
and 10-ball's option), then a spin table's tip.
"""

from __future__ import annotations

import numpy as np

from pool_env.game.games.wpa.params import (
    BALL_COLUMN,
    BREAK_HIGH,
    BREAK_LOW,
    HEAD_X,
    OPTION_COLUMN,
    VARIANT,
)
from pool_env.game.games.wpa.rack_state import (
    BEHIND,
    BREAKING,
    IN_HAND,
    OPTION,
    PUSH_OUT,
    SHOOTER,
    legal_targets,
)
from pool_env.game.kernels.actions import decode_actions, decoded_tips, shot_arrays, strike, unit
from pool_env.game.kernels.layout import point_free
from pool_env.game.kernels.params import (
    AIM_HIGH,
    AIM_LOW,
    REACH,
    SPEED_HIGH,
    SPEED_LOW,
    TIP_COLUMN,
    X_HIGH,
    X_LOW,
    Y_HIGH,
    Y_LOW,
)
from pool_env.sim.jit import kernel

#: Columns of the calls :func:`executed_rule_shots` returns: the called pocket, the called
#: ball (10-ball; -1 none), a push-out declared where the rules allow one, the option used
#: to hand the table back (no shot is played).
CALL_POCKET, CALL_BALL, CALL_PUSH_OUT, CALL_HAND_BACK, N_CALLS = range(5)


@kernel
def place_in_hand(params, pockets, actions, tables, positions, on_table, rack):
    """Put the cue ball of each table in hand where ``actions[:, 2:4]`` ask.

    The two components map linearly onto the allowed centres: inside the cushions by a
    ball radius (``[R, L - R] x [R, W - R]``), and only behind the head string
    (``x <= L / 4``) when the rack state says so (after a scratch on an 8-ball break, and
    on every break). The cue ball is moved to that point, free or not.

    Args:
        params: The config's numbers.
        pockets: ``(P, 3)`` capture circles.
        actions: ``(K, 5)`` actions.
        tables: ``(K,)`` the tables that shoot.
        positions: ``(B, N, 2)`` ball centres, the cue balls in hand moved in place.
        on_table: ``(B, N)`` which balls are on each table.
        rack: ``(B, N_RACK)`` rack states.

    Returns:
        ``(K,)`` booleans: the requested point is not free (on or next to a ball, in a
        pocket): the caller moves the cue ball to the free point nearest to it
        (:func:`pool_env.game.spots.free_spot`).
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    unplaced = np.zeros(n_shots, dtype=np.bool_)
    others = np.empty((n_balls, 2))
    reach = params[REACH]
    for k in range(n_shots):
        b = tables[k]
        if rack[b, IN_HAND] == 0:
            continue
        x_high = params[HEAD_X] if rack[b, BEHIND] != 0 else params[X_HIGH]
        x = params[X_LOW] + unit(actions[k, 2]) * (x_high - params[X_LOW])
        y = params[Y_LOW] + unit(actions[k, 3]) * (params[Y_HIGH] - params[Y_LOW])
        count = 0
        for j in range(1, n_balls):
            if on_table[b, j]:
                others[count] = positions[b, j]
                count += 1
        positions[b, 0, 0], positions[b, 0, 1] = x, y
        free = point_free(x, y, params, pockets, others, count, reach * reach)
        unplaced[k] = not (free and x <= x_high)
    return unplaced


@kernel
def placed_rule_shots(params, pockets, actions, tables, positions, on_table, ptrs, rack):
    """A step's one compiled call: each cue ball in hand placed, then the shots struck.

    :func:`place_in_hand`, then :func:`executed_rule_shots` for every row whose placement
    is free. A row whose requested point is covered (rare) is left undecoded, its shot
    zero: the caller moves its cue ball to the free point nearest the requested one and
    decodes it with :func:`executed_rule_shots` (each table draws its noise from its own
    generator, so the order of the two calls changes no draw).

    Returns:
        ``(shots, velocities, calls, unplaced)``: as :func:`executed_rule_shots`, and the
        ``(K,)`` rows left to the caller.
    """
    unplaced = place_in_hand(params, pockets, actions, tables, positions, on_table, rack)
    shots, velocities, calls = executed_rule_shots(
        params, pockets, actions, tables, positions, on_table, ptrs, rack, unplaced
    )
    return shots, velocities, calls, unplaced


@kernel
def executed_rule_shots(params, pockets, actions, tables, positions, on_table, ptrs, rack, skip):
    """The shots of the rules' actions, the cue ball placed: the calls, aim, strike.

    The action is ``(aim, speed, cue x, cue y, pocket)``, then the game's own columns
    (``params[BALL_COLUMN]``: the called ball of 10-ball; ``params[OPTION_COLUMN]``: 9-ball
    and 10-ball's option), then on a spin table the tip (from ``params[TIP_COLUMN]``).

    ``actions[:, 4]`` calls pocket ``min(floor(P (a + 1) / 2), P - 1)`` (``P = 6``: six
    equal bins over ``[-1, 1]``, in ``table.pockets`` order; read by the rules when the
    shooter is on the 8, and on every 10-ball shot after the break); the ball column calls
    ball ``1 + min(floor(n (a + 1) / 2), n - 1)`` of the ``n`` object balls the same way.
    The option column, ``> 0``, declares a push-out on the shot right after a legal break
    (``rack[PUSH_OUT]``), and when the shooter has the option (``rack[OPTION]``) hands the
    table back instead of shooting: that row plays no shot (zero speed, no noise drawn).
    The speed maps onto the break range on a break. Relative and cut aim refer to the
    nearest ball the shooter may hit first (:func:`.rack_state.legal_targets`), not to
    the nearest ball.

    Args:
        params: The config's numbers.
        pockets: ``(P, 3)`` capture circles.
        actions: ``(K, A)`` actions.
        tables: ``(K,)`` the tables that shoot.
        positions: ``(B, N, 2)`` ball centres.
        on_table: ``(B, N)`` which balls are on each table.
        ptrs: ``(B, 3)`` generator addresses (noise as :func:`executed_shots`).
        rack: ``(B, N_RACK)`` rack states.
        skip: ``(K,)`` rows left as they are (zero shots, no noise drawn).

    Returns:
        ``(shots, velocities, calls)``: as :func:`executed_shots`, and ``(K, N_CALLS)``
        int64 calls (columns :data:`CALL_POCKET` ...).
    """
    n_shots, n_balls = tables.shape[0], on_table.shape[1]
    game = int(params[VARIANT])
    aims, speeds = decode_actions(
        actions, params[AIM_LOW], params[AIM_HIGH], params[SPEED_LOW], params[SPEED_HIGH]
    )
    tips = decoded_tips(params, actions, int(params[TIP_COLUMN]))
    shots, velocities = shot_arrays(params, n_shots, n_balls)
    calls = np.full((n_shots, N_CALLS), -1, dtype=np.int64)
    targets = np.empty(n_balls, dtype=np.bool_)
    n_pockets, n_objects = pockets.shape[0], n_balls - 1
    ball_column, option_column = int(params[BALL_COLUMN]), int(params[OPTION_COLUMN])
    for k in range(n_shots):
        if skip[k]:
            shots[k, :] = 0.0
            continue
        b = tables[k]
        row = rack[b]
        calls[k, CALL_POCKET] = min(int(unit(actions[k, 4]) * n_pockets), n_pockets - 1)
        if ball_column >= 0:
            calls[k, CALL_BALL] = 1 + min(int(unit(actions[k, ball_column]) * n_objects),
                                          n_objects - 1)  # fmt: skip
        declared = option_column >= 0 and actions[k, option_column] > 0.0
        calls[k, CALL_PUSH_OUT] = 1 if declared and row[PUSH_OUT] != 0 else 0
        calls[k, CALL_HAND_BACK] = 1 if declared and row[OPTION] != 0 else 0
        if calls[k, CALL_HAND_BACK] != 0:  # the table goes back: nothing is struck
            shots[k, :] = 0.0
            continue
        speed = speeds[k]
        if row[BREAKING] != 0:
            speed = params[BREAK_LOW] + unit(actions[k, 1]) * (
                params[BREAK_HIGH] - params[BREAK_LOW]
            )
        legal_targets(game, row, on_table[b], row[SHOOTER], targets)
        strike(params, aims[k], speed, tips[k], positions[b], targets, ptrs[b], shots[k],
                velocities[k])  # fmt: skip
    return shots, velocities, calls
