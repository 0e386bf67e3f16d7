"""The WPA games' rack state: one int64 row per table, its columns, codes and names.

The rules (:mod:`pool_env.game.games.wpa.rules`) read a shot's outcome against this row and
move it on; the observation, the shot's decoding and the first-contact reading ask it who
may hit which ball first (:func:`legal_targets`). Ball ``k`` is numbered ``k``, the cue ball
0, as in :func:`pool_env.sim.layouts.break_scene`.
"""

from __future__ import annotations

from pool_env.sim.jit import kernel

#: The games' codes (``params[VARIANT]``, :mod:`pool_env.game.games.wpa.params`); 0 is none.
NINE, EIGHT, TEN = 1, 2, 3

#: Columns of a rack-state row: the shooter (0 or 1), ball in hand, ... behind the head
#: string, the next shot is a break, each player's group (:data:`OPEN`, :data:`SOLIDS`,
#: :data:`STRIPES`), each player's successive fouls, the winner (-1 while undecided), the
#: next shot may be a push-out, the shooter may hand the table back instead of shooting.
(
    SHOOTER, IN_HAND, BEHIND, BREAKING, GROUP_0, GROUP_1, FOULS_0, FOULS_1, WINNER, PUSH_OUT,
    OPTION, N_RACK,
) = range(12)  # fmt: skip

#: How a step was played (the rules' ``PLAY`` result column): a shot, a declared
#: push-out, or the option used to hand the table back (no shot played).
SHOT, PUSHED_OUT, HANDED_BACK = 0, 1, 2

#: 8-ball groups.
OPEN, SOLIDS, STRIPES = 0, 1, 2

#: Foul codes and their ``info["foul"]`` names.
NO_FOUL, FOUL_SCRATCH, FOUL_WRONG_BALL, FOUL_NO_RAIL, FOUL_NO_CONTACT, FOUL_BREAK = range(6)
FOUL_KITCHEN = 6
FOUL_NAMES: tuple[str | None, ...] = (
    None, "scratch", "wrong_ball_first", "no_rail", "no_contact", "illegal_break",
    "kitchen_ball_first",
)  # fmt: skip

#: Why a rack was lost, and the names.
NO_LOSS, EIGHT_EARLY, EIGHT_WRONG_POCKET, EIGHT_ON_FOUL, THREE_FOULS = range(5)
LOSS_NAMES: tuple[str | None, ...] = (
    None, "eight_early", "eight_wrong_pocket", "eight_on_foul", "three_fouls",
)  # fmt: skip


@kernel
def rotation(game):
    """Whether ``game`` is played in rotation (the lowest ball first): 9-ball and 10-ball."""
    return game in (NINE, TEN)


#: The ball that wins the rack, by game code (code 0 is none): read by Python without
#: compiling :func:`money_ball`.
MONEY_BALLS = (-1, 9, 8, 10)


@kernel
def money_ball(game):
    """The ball that wins the rack: 9, 8 or 10 (:data:`MONEY_BALLS`)."""
    return MONEY_BALLS[game]


@kernel
def group_of(ball):
    """The 8-ball group of ``ball``: :data:`SOLIDS` (1-7), :data:`STRIPES` (9-15), else OPEN."""
    if 1 <= ball <= 7:
        return SOLIDS
    if 9 <= ball <= 15:
        return STRIPES
    return OPEN


@kernel
def ball_on(game, rack, on_table, player):
    """The one ball ``player`` must hit first, or -1 when it is not a single one.

    9-ball and 10-ball: the lowest-numbered ball on the table; 8-ball: the 8 once the
    player's group is cleared, else -1 (any ball of the group, or of either on an open table).
    """
    n = on_table.shape[0]
    if rotation(game):
        for j in range(1, n):
            if on_table[j]:
                return j
        return -1
    group = rack[GROUP_0 + player]
    if group == OPEN:
        return -1
    for j in range(1, n):
        if on_table[j] and group_of(j) == group:
            return -1
    return 8


@kernel
def legal_first(game, rack, on_table, player, on, j):
    """Whether ``player`` may hit ball ``j`` first (``on`` is :func:`ball_on`'s answer)."""
    if j < 1 or j >= on_table.shape[0] or not on_table[j]:
        return False
    if rotation(game):
        return j == on
    if rack[BREAKING] != 0:
        return True
    if on == 8:
        return j == 8
    group = rack[GROUP_0 + player]
    if group == OPEN:
        return j != 8
    return group_of(j) == group


@kernel
def legal_targets(game, rack, on_table, player, out):
    """``out[j]``: ``player`` may hit ball ``j`` first (the break: any ball in 8-ball)."""
    on = ball_on(game, rack, on_table, player)
    for j in range(on_table.shape[0]):
        out[j] = legal_first(game, rack, on_table, player, on, j)


@kernel
def new_rack(rack, breaking):
    """Reset a rack-state row: player 0 to shoot, open table, no fouls, no winner.

    A break (``breaking``) is played with the cue ball in hand behind the head string.
    """
    rack[:] = 0
    rack[WINNER] = -1
    if breaking:
        rack[BREAKING] = 1
        rack[IN_HAND] = 1
        rack[BEHIND] = 1
