"""9-ball, 10-ball and 8-ball (WPA world standardized rules), compiled: one shot judged.

The rules read a shot's outcome by ball number (ball ``k`` is numbered ``k``, the cue ball
0, as in :func:`pool_env.sim.layouts.break_scene`) and the table's *rack state*, one int64
row of :data:`N_RACK` columns (``GameState.rack``): who shoots, ball in hand (behind the
head string or anywhere), the break pending, each player's 8-ball group and successive
fouls, the winner, whether the next shot may be a push-out and whether the shooter may
hand the table back. :func:`judge_rack` updates that row in place.

9-ball (WPA rules 1-2): the cue ball must first contact the lowest-numbered ball on the
table; then a ball must be potted or some ball (the cue ball included) must touch a
cushion; a scratch and a shot that touches no ball are fouls. Legal break: the 1 first
(the lowest ball: a break set up without the 1 needs its lowest ball first),
and a ball potted or at least four object balls driven to a cushion. The 9 potted on a
legal shot wins (the break and combinations included); potted on a foul it is re-spotted.
A player who fouls on three successive shots loses the rack. After a foul the incoming
player has the cue ball in hand anywhere on the table.

The push-out (9-ball and 10-ball, WPA 9-ball rule 1.7, 10-ball rule 4): on the shot right
after a legal break, whoever shoots it may declare a push-out. The wrong-ball-first,
no-rail and no-contact fouls do not apply to it (a scratch still fouls); balls it pots stay
down and do not count, except the money ball (9 or 10), which is re-spotted. After a
legal push-out the opponent chooses: take the table as it lies, or hand it back to the
player who pushed (:data:`OPTION`: the incoming shooter's action says which).

10-ball (WPA 10-ball rules): the rack of ten, played as 9-ball (the lowest ball first, a
ball potted or a rail after contact, the 1 first and four balls to a rail on the break,
three fouls lose) with called shots: each shot after the break calls a ball and a pocket.
A legal shot that pots the called ball in the called pocket keeps the table (other balls
it pots stay down too); the 10 wins only when it is that called ball. A legal shot that
misses its call passes the turn: balls it potted stay down (the 10 re-spotted) and, if it
potted any, the incoming player has the option to shoot or hand the table back. The 10
potted on the break, on a foul, on a push-out or without its call is re-spotted; a legal
break that pots a ball keeps the table.

Both games: with the cue ball in hand behind the head string (the break, and after a
scratch on an 8-ball break), the cue ball may not first contact a ball whose base lies
behind the head string (``x < L / 4``; a ball on the line is playable) unless it crossed
the head string first (``kitchen_ball_first``, :func:`kitchen_foul`). When the cue ball
meets several balls at its first contact's instant (within
:data:`pool_env.game.games.wpa.first_contact.SIMULTANEOUS`), the shooter gets the
benefit: the contact is legal if any of them is a legal first ball
(:func:`pool_env.game.games.wpa.first_contact.read_first`), whatever their numbers.

8-ball (WPA rules 1, 3): the break is legal if a ball is potted or at least four object
balls touch a cushion (any first contact). The table is open after the break; the first
legal shot after the break that pots an object ball other than the 8 assigns that ball's
group (solids 1-7 or stripes 9-15; the first to drop) to the shooter, the other group to
the opponent. The shooter must first contact a ball of their group (open table: any ball
but the 8; group cleared: the 8), then pot a ball or make a ball touch a cushion. A
shooter who has cleared their group wins by potting the 8 in the called pocket on a legal
shot; potting the 8 before the group is cleared (not on the break), into another pocket,
or on a foul (a scratch included) loses. A scratch on the break gives the incoming player
ball in hand behind the head string; every other foul, ball in hand anywhere. The shooter
keeps the table after a legal shot that pots a ball of their group (open table: any ball
but the 8; the break: any ball, the 8 included, which is re-spotted).

Simplifications, all deliberate:

* No push-out in 8-ball (WPA has none), no called shots in 9-ball and none in 8-ball but
  the 8's pocket (so "pot a ball" means any object ball there), no safeties called (a
  10-ball shot that misses its call is one), no warning before the third foul, no
  jump, masse or "bad cue ball" fouls (the simulator has none of them), no stalemate rule,
  no three-foul rule in 8-ball (WPA has none either).
* An illegal break is a foul (``illegal_break``): the incoming player takes ball in hand on
  the table as it lies, rather than choosing to re-rack or to have the breaker break again.
  A scratch on a break is reported as ``scratch`` even if the break also failed otherwise.
* The 8 potted on the break is re-spotted and the break judged as any other (WPA 8-ball
  3.3(e) lets the breaker choose: re-spot the 8 and continue, or re-break; the breaker
  always takes the first: on a legal break the 8 counts as a potted ball, so the breaker
  keeps the table; on a scratch the turn passes with ball in hand behind the head string).
  Groups are never assigned on the break (the table is open after it).
* Balls potted on a foul stay down, except the 9 (re-spotted) and the 8 (the rack is lost,
  or re-spotted on the break). A re-spotted ball goes on the foot spot, or on the free
  point nearest to it (WPA: on the long string behind it).
* A pocket jaw counts as a cushion: every cushion impact the simulator reports after the
  first contact satisfies "a ball touched a rail".
* One foul reason is reported per shot, the first that applies in the order scratch,
  kitchen_ball_first, no_contact, wrong_ball_first, no_rail (on a break: scratch,
  kitchen_ball_first, then illegal_break).
* With one player (practice and run-out), the shooter never changes: after a foul the
  agent itself is the incoming player, with ball in hand; a lost rack (three fouls, the 8
  lost) is a win of the absent opponent, player 1. The agent may push out, and then shoots
  on: the opponent's option needs an opponent, so one player never has it, and a legal
  push-out does not end a run-out (:mod:`pool_env.game.games.wpa.judge`).
* The option is decided by the incoming player's next action, in its option component
  (``> 0``: hand the table back); the push-out is declared in the same component of the
  shot right after a legal break. Either declaration where the rules offer none is
  ignored (the shot is played as a shot).
"""

from __future__ import annotations

from pool_env.game.games.wpa.rack_state import (
    BEHIND,
    BREAKING,
    EIGHT,
    EIGHT_EARLY,
    EIGHT_ON_FOUL,
    EIGHT_WRONG_POCKET,
    FOUL_BREAK,
    FOUL_KITCHEN,
    FOUL_NO_CONTACT,
    FOUL_NO_RAIL,
    FOUL_SCRATCH,
    FOUL_WRONG_BALL,
    FOULS_0,
    GROUP_0,
    IN_HAND,
    NINE,
    NO_FOUL,
    NO_LOSS,
    OPEN,
    OPTION,
    PUSH_OUT,
    SHOOTER,
    SOLIDS,
    STRIPES,
    TEN,
    THREE_FOULS,
    WINNER,
    ball_on,
    group_of,
    legal_first,
    money_ball,
    rotation,
)  # fmt: skip
from pool_env.sim.jit import kernel

#: Object balls driven to a cushion that make a break legal without a pot.
BREAK_RAILS = 4


@kernel
def foul_of(game, rack, on_table, first, scratch, n_potted, rail, to_rail, kitchen, push_out):
    """The first foul that applies to a shot (:data:`NO_FOUL` for a legal one).

    Args:
        game: :data:`NINE`, :data:`EIGHT` or :data:`TEN`.
        rack: The rack-state row before the shot.
        on_table: ``(N,)`` the balls on the table before the shot.
        first: The ball the cue ball hit first, -1 for none.
        scratch: The cue ball dropped.
        n_potted: Object balls potted.
        rail: Some ball touched a cushion after the first contact.
        to_rail: Object balls that touched a cushion after the first contact.
        kitchen: The cue ball, in hand behind the head string, first met a ball whose base
            lies behind it without crossing it first (:func:`kitchen_foul`).
        push_out: The shot is a push-out the rules allow: only the scratch (and the
            kitchen) fouls apply.
    """
    if scratch:
        return FOUL_SCRATCH
    if kitchen:
        return FOUL_KITCHEN
    if rack[BREAKING] != 0:  # rotation: the lowest ball first (the 1 of a rack)
        lowest = ball_on(game, rack, on_table, rack[SHOOTER])
        first_ok = first >= 0 and (game == EIGHT or first == lowest)
        spread = n_potted > 0 or to_rail >= BREAK_RAILS
        return NO_FOUL if first_ok and spread else FOUL_BREAK
    if push_out:
        return NO_FOUL
    if first < 0:
        return FOUL_NO_CONTACT
    player = rack[SHOOTER]
    on = ball_on(game, rack, on_table, player)
    if not legal_first(game, rack, on_table, player, on, first):
        return FOUL_WRONG_BALL
    if n_potted == 0 and not rail:
        return FOUL_NO_RAIL
    return NO_FOUL


@kernel
def kitchen_foul(rack, first, first_x, head_x, crossed):
    """Whether the first contact breaks the kitchen rule.

    With the cue ball in hand behind the head string (``rack[BEHIND]``: the break, and
    after a scratch on an 8-ball break), the cue ball may not first meet a ball whose base
    (the point under its centre) lies behind the head string, ``first_x < head_x``, unless
    the cue ball crossed the head string before that contact (a ball on the line is
    playable).

    Args:
        rack: The rack-state row before the shot.
        first: The ball the cue ball met first, -1 for none.
        first_x: That ball's centre x before the shot (it rests until the cue ball meets it).
        head_x: The head string's x (``L / 4``).
        crossed: The cue ball's centre passed ``head_x`` before the contact.
    """
    return rack[BEHIND] != 0 and first >= 0 and first_x < head_x and not crossed


@kernel
def judge_rack(game, players, rack, on_table, first, scratch, potted, first_dropped,
               eight_pocket, called, rail, to_rail, kitchen, push_out, called_ball,
               call_made, offers_push_out):  # fmt: skip
    """Judge one shot and move the rack state on (``rack`` is updated in place).

    Args:
        game: :data:`NINE`, :data:`EIGHT` or :data:`TEN`.
        players: 1 (the shooter never changes) or 2.
        rack: The table's rack-state row, updated in place.
        on_table: ``(N,)`` balls on the table *before* the shot (not changed).
        first: The ball the cue ball hit first, -1 for none.
        scratch: The cue ball dropped.
        potted: ``(N,)`` booleans: the object balls the shot potted (index 0 ignored).
        first_dropped: The first object ball other than the 8 to drop, -1 for none.
        eight_pocket: The pocket the 8 dropped in, -1 if it did not (or not 8-ball).
        called: The pocket called for the 8 (-1: none).
        rail: Some ball touched a cushion after the first contact.
        to_rail: Object balls that touched a cushion after the first contact.
        kitchen: The first contact breaks the kitchen rule (:func:`kitchen_foul`).
        push_out: The shot was declared a push-out (read only where ``rack[PUSH_OUT]``).
        called_ball: 10-ball: the ball called (-1: none).
        call_made: 10-ball: the called ball dropped in the called pocket.
        offers_push_out: The game is played with the push-out (the rules option
            ``push_out``; False: 9-ball as ``NineBallGame-v1``, no push-out after the break).

    Returns:
        ``(foul, ball_on, respot, loss, keeps, counts)``: the foul code, the ball on before
        the shot (-1: none single), the ball to re-spot (-1: none), why the shooter lost
        (:data:`NO_LOSS`...), whether the shooter's turn goes on (a legal shot that pots a
        ball that keeps the table, counted as if two players played), and whether the
        balls it potted count as pots (a legal shot, not a push-out, a 10-ball call made).
        The winner is ``rack[WINNER]`` (-1 while undecided).
    """
    shooter = rack[SHOOTER]
    other = 1 - shooter
    n = on_table.shape[0]
    n_potted = 0
    for j in range(1, n):
        if potted[j]:
            n_potted += 1
    pushed = push_out and rack[PUSH_OUT] != 0
    on = ball_on(game, rack, on_table, shooter)
    foul = foul_of(game, rack, on_table, first, scratch, n_potted, rail, to_rail, kitchen,
                   pushed)  # fmt: skip
    breaking = rack[BREAKING] != 0
    respot, loss, winner = -1, NO_LOSS, -1
    option = False  # the incoming player may hand the table back
    if rotation(game):
        money = money_ball(game)
        # Counted pots: a legal shot, not a push-out; in 10-ball the break or a call made.
        counts = foul == NO_FOUL and not pushed
        if game == TEN and not breaking:
            counts = counts and call_made
        if n > money and potted[money]:
            # 9-ball: the 9 wins on any counted shot; 10-ball: only the called 10 (the
            # break's is re-spotted).
            if counts and (game == NINE or (called_ball == money and not breaking)):
                winner = shooter
            else:
                respot = money
        if foul != NO_FOUL and rack[FOULS_0 + shooter] + 1 >= 3:
            winner, loss = other, THREE_FOULS
        keeps = foul == NO_FOUL and n_potted > 0
        if pushed or (game == TEN and not breaking):
            keeps = counts and not pushed
        option = foul == NO_FOUL and (pushed or (game == TEN and not counts and n_potted > 0))
    else:
        counts = foul == NO_FOUL
        if eight_pocket >= 0:
            if breaking:
                respot = 8
            elif foul != NO_FOUL:
                loss = EIGHT_ON_FOUL
            elif on != 8:
                loss = EIGHT_EARLY
            elif called != eight_pocket:
                loss = EIGHT_WRONG_POCKET
            else:
                winner = shooter
            if loss != NO_LOSS:
                winner = other
        objects = n_potted - (1 if eight_pocket >= 0 else 0)
        group = rack[GROUP_0 + shooter]
        if foul == NO_FOUL and not breaking and group == OPEN and first_dropped > 0:
            group = group_of(first_dropped)
            rack[GROUP_0 + shooter] = group
            rack[GROUP_0 + other] = SOLIDS + STRIPES - group
        if breaking:  # a ball potted on a legal break keeps the table, the 8 included
            keeps = n_potted > 0 and foul == NO_FOUL
        elif group == OPEN:
            keeps = foul == NO_FOUL and objects > 0
        else:
            keeps = False
            if foul == NO_FOUL:
                for j in range(1, n):
                    if potted[j] and group_of(j) == group:
                        keeps = True
    rack[FOULS_0 + shooter] = rack[FOULS_0 + shooter] + 1 if foul != NO_FOUL else 0
    rack[BEHIND] = 1 if foul == FOUL_SCRATCH and breaking and game == EIGHT else 0
    rack[IN_HAND] = 1 if foul != NO_FOUL else 0
    rack[PUSH_OUT] = 1 if breaking and foul == NO_FOUL and rotation(game) and offers_push_out else 0
    rack[BREAKING] = 0
    rack[WINNER] = winner
    rack[OPTION] = 1 if option and players == 2 and winner < 0 else 0
    if players == 2 and not keeps:
        rack[SHOOTER] = other
    return foul, on, respot, loss, keeps, counts


@kernel
def hand_back(players, rack):
    """The incoming player uses the option: the table goes back, as it lies, to the other.

    Returns:
        Whether the rack had the option (else nothing changes and a shot is played).
    """
    if rack[OPTION] == 0 or players != 2:
        return False
    rack[OPTION] = 0
    rack[SHOOTER] = 1 - rack[SHOOTER]
    return True
