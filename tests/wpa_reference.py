"""A plain-Python reference of the 9-ball, 10-ball and 8-ball rules (WPA): tests only.

The product's one copy of the rules is compiled, :mod:`pool_env.game.games.wpa.rules`; this
file shares no code with it and is what ``tests/game/test_wpa.py`` and ``tests/game/test_games.py``
check it against (on the rule-case table and on random outcomes).

Ball ``k`` is numbered ``k``: row 0 is the cue ball, rows 1-9 (9-ball), 1-10 (10-ball) or
1-15 (8-ball) the object balls, as in :func:`pool_env.sim.layouts.break_scene`. Players are
0 and 1 (a single-agent env plays both seats, or lets its own next shot be the "incoming
player").

:func:`judge` takes the rack's :class:`RackState` before a shot and the shot's
:class:`ShotOutcome` (built from a :class:`~pool_env.ShotResult` by :func:`outcome_of`,
from a batch row by :func:`batch_outcome`) and returns the :class:`Verdict` and the next state. It
never simulates, never draws random numbers and never mutates its inputs.

9-ball (WPA rules 1-2): the cue ball must first contact the lowest-numbered ball on the
table; then a ball must be potted or some ball (the cue ball included) must touch a
cushion; a scratch and a shot that touches no ball are fouls. Legal break: the 1 first,
and a ball potted or at least four object balls driven to a cushion. The 9 potted on a legal
shot wins (the break and combinations included); potted on a foul it is re-spotted,
other balls potted on a foul stay down. A player who fouls on three successive shots
loses the rack. After a foul the incoming player has the
cue ball in hand anywhere on the table. (Re-spotting and ball-in-hand placement are
:func:`pool_env.game.spots.free_spot`'s, not this file's.)

The push-out (WPA 9-ball 1.7, 10-ball 4): if the break was legal, the shot after it may be
declared a push-out by whoever plays it. Wrong ball first, no rail and no contact are then
no fouls (a scratch is); potted balls stay down and count for nothing, but the 9 (10) is
spotted. After a legal push-out the other player may take the table as it lies or give it
back to the one who pushed. One agent (run-out mode, :func:`run_out_ends`) shoots on.

10-ball (WPA 10-ball rules): 9-ball's rotation, break and three-foul rule on ten balls,
with every shot after the break called (a ball and a pocket). The shot continues the inning
only if it is legal and the called ball drops in the called pocket; the 10 wins when it is
that called ball, and is spotted whenever else it drops (the break included). A legal
shot that misses its call ends the inning, and if it potted any ball the other player may
take the table or hand it back. Balls potted stay down but the 10.

8-ball (WPA rules 1, 3): the break is legal if a ball is potted or at least four object
balls touch a cushion. The table is open after the break; the first legal shot after the
break that pots an object ball other than the 8 assigns its group (solids 1-7 or stripes
9-15) to the shooter, the other group to the opponent. The shooter must first contact a
ball of their group (open table: any ball but the 8; group cleared: the 8), then pot a ball
or make a ball touch a cushion. A shooter who has cleared their group wins by potting the 8
in the called pocket on a legal shot; potting the 8 before the group is cleared (not on the
break), into another pocket, or on a foul (a scratch included) loses. A scratch on the
break gives the incoming player ball in hand behind the head string; every other foul,
ball in hand anywhere. The shooter keeps the table after a legal shot that pots a ball of
their group (open table: any ball but the 8; the break: any ball, the re-spotted 8 too).

Simplifications, all deliberate:

* No called shots in 9-ball, none in 8-ball but the 8's pocket (so "pot a ball" means any
  object ball; on an open table the group goes to the ball that dropped first), no
  safeties called (a 10-ball shot that misses its call is one), no warning before the
  third foul, no jump, masse or "bad cue ball" fouls (the simulator has none of them), and
  no stalemate rule.
* An illegal break is a foul ("illegal_break"): the incoming player takes ball in hand on
  the table as it lies, rather than choosing to re-rack or to have the breaker break again.
  On an 8-ball break a scratch is reported as "scratch" (ball in hand behind the head
  string); a break that also fails the four-rails test is still reported as "scratch".
* The 8 potted on the break is re-spotted and the break judged as any other; of the
  breaker's two choices (WPA 8-ball 3.3(e): re-spot and continue, or re-break) the breaker
  always continues: after a legal break that pots the 8, the breaker keeps the table.
  Groups are never assigned on the break (the table is open after it).
* Balls potted on a foul stay down (WPA 9-ball 1.4 and 8-ball 3.3), except the 9 (re-spotted)
  and the 8 (the rack is lost, or re-spotted on the break).
* A pocket jaw counts as a cushion: every cushion impact the simulator reports after the
  first contact satisfies "a ball touched a rail".
* One foul reason is reported per shot, the first that applies in the order scratch,
  kitchen_ball_first, no_contact, wrong_ball_first, no_rail (on a break: scratch,
  kitchen_ball_first, then illegal_break).

Both games: with the cue ball in hand behind the head string, a first ball whose base lies
behind the head string (x < L / 4; on the line it is playable) is a foul
("kitchen_ball_first") unless the cue ball crossed the head string first. When the cue ball
meets several balls at its first contact's instant (within :data:`SIMULTANEOUS`), the
shooter gets the benefit: the contact is legal if any of them may be hit first
(:func:`first_read`), whatever their numbers.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from pool_env.sim.batch import BatchResult
from pool_env.sim.result import ShotResult

Game = Literal["nine", "ten", "eight"]
FoulReason = Literal[
    "scratch", "wrong_ball_first", "no_rail", "no_contact", "illegal_break", "kitchen_ball_first"
]

#: Group codes of 8-ball: the table is open, solids (1-7), stripes (9-15).
OPEN, SOLIDS, STRIPES = 0, 1, 2
#: The codes by the names ``PoolEnv.rack`` gives them.
GROUPS_BY_NAME = {"open": OPEN, "solids": SOLIDS, "stripes": STRIPES}
#: Balls per game, cue ball included.
N_BALLS: dict[str, int] = {"nine": 10, "ten": 11, "eight": 16}
#: The games with the push-out and the option, and the ball each is won with.
ROTATION: dict[str, int] = {"nine": 9, "ten": 10}
#: Object balls driven to a cushion that make a break legal without a pot.
BREAK_RAILS = 4
#: Impacts of the cue ball this close in time (s) to its first are simultaneous (the
#: tolerance the product documents, pool_env.game.games.wpa.first_contact.SIMULTANEOUS).
SIMULTANEOUS = 1e-9


def group_of(ball: int) -> int:
    """The 8-ball group of object ball ``ball`` (``SOLIDS``, ``STRIPES``; the 8 is neither)."""
    if 1 <= ball <= 7:
        return SOLIDS
    if 9 <= ball <= 15:
        return STRIPES
    return OPEN


@dataclass(frozen=True, slots=True)
class ShotOutcome:
    """What the rules read from one shot, by ball number.

    Attributes:
        first_hit: The ball the cue ball touched first, -1 if none.
        potted: Object balls potted, in the order they dropped.
        pockets: The pocket each of :attr:`potted` dropped into (same order).
        scratch: Whether the cue ball was potted.
        rail_after_contact: Whether any ball (the cue ball included) touched a cushion
            after the cue ball's first contact.
        object_balls_to_rail: How many object balls touched a cushion after that contact.
        simultaneous: Other balls the cue ball met at the instant of its first contact.
        kitchen: Of :attr:`first_hit` and :attr:`simultaneous`, the balls whose base lay
            behind the head string before the shot.
        crossed_head_string: Whether the cue ball's centre passed the head string before
            its first contact.
    """

    first_hit: int
    potted: tuple[int, ...]
    pockets: tuple[int, ...]
    scratch: bool
    rail_after_contact: bool
    object_balls_to_rail: int
    simultaneous: tuple[int, ...] = ()
    kitchen: tuple[int, ...] = ()
    crossed_head_string: bool = True

    @classmethod
    def from_arrays(
        cls,
        first_hit: ArrayLike,
        cushions_after_contact: ArrayLike,
        pocketed: ArrayLike,
        pocket_order: ArrayLike,
        balls: ArrayLike | None = None,
    ) -> ShotOutcome:
        """The outcome from a shot's per-ball tallies (a ``ShotResult`` or a batch row).

        Args:
            first_hit: The first ball each row touched (``ShotResult.first_hit``).
            cushions_after_contact: Each row's cushion impacts after the first contact.
            pocketed: Each row's pocket, -1 if none.
            pocket_order: The order in which the rows dropped, -1 if not.
            balls: The ball number of each simulated row, when only some balls were
                simulated (ball-number order, the cue ball first); default: row ``k`` is
                ball ``k``.

        Raises:
            ValueError: If the arrays disagree in length or ``balls`` does not start with
                the cue ball.
        """
        hit = np.asarray(first_hit, dtype=np.int64)
        rails = np.asarray(cushions_after_contact, dtype=np.int64)
        pocket = np.asarray(pocketed, dtype=np.int64)
        order = np.asarray(pocket_order, dtype=np.int64)
        number = np.arange(hit.shape[0]) if balls is None else np.asarray(balls, np.int64)
        if not (hit.shape == rails.shape == pocket.shape == order.shape == number.shape):
            raise ValueError("the per-ball arrays and balls must all have one entry per ball")
        if number.shape[0] == 0 or number[0] != 0:
            raise ValueError("row 0 must be the cue ball (ball number 0)")
        dropped = [k for k in np.argsort(order, kind="stable") if order[k] >= 0 and k != 0]
        cue_hit = int(hit[0])
        return cls(
            first_hit=int(number[cue_hit]) if cue_hit >= 0 else -1,
            potted=tuple(int(number[k]) for k in dropped),
            pockets=tuple(int(pocket[k]) for k in dropped),
            scratch=bool(pocket[0] >= 0),
            rail_after_contact=bool(np.any(rails > 0)),
            object_balls_to_rail=int(np.count_nonzero(rails[1:] > 0)),
        )


def outcome_of(
    result: ShotResult, balls: ArrayLike | None = None, head_x: float | None = None
) -> ShotOutcome:
    """The :class:`ShotOutcome` of a simulated shot (recorded or not).

    Args:
        result: The shot, the cue ball in row 0.
        balls: The ball number of each row (see :meth:`ShotOutcome.from_arrays`).
        head_x: The head string's x: with a recorded shot, the balls met at the first
            contact's instant, those behind the head string, and whether the cue ball
            crossed it first are read from the trajectory (events and exact positions).
    """
    out = ShotOutcome.from_arrays(
        result.first_hit,
        result.cushions_after_contact,
        result.pocketed,
        result.pocket_order,
        balls,
    )
    if head_x is None or not result.recorded or out.first_hit < 0:
        return out
    number = np.arange(result.n_balls) if balls is None else np.asarray(balls, np.int64)
    events = result.events
    hits = [e for e in events if e.kind == "ball" and 0 in (e.i, e.j)]
    t1 = hits[0].time
    met: list[int] = []
    for e in hits:
        if e.time <= t1 + SIMULTANEOUS and int(number[e.j if e.i == 0 else e.i]) not in met:
            met.append(int(number[e.j if e.i == 0 else e.i]))
    start = result.positions_at(0.0)
    row = {int(b): r for r, b in enumerate(number)}
    kitchen = tuple(b for b in met if start[row[b], 0] < head_x)
    # The cue ball moves straight between its events: its largest x before the contact is
    # at one of them (or the start).
    times = [0.0] + [e.time for e in events if e.time <= t1]
    crossed = any(result.positions_at(t)[0, 0] > head_x for t in times)
    return replace(out, simultaneous=tuple(met[1:]), kitchen=kitchen,
                   crossed_head_string=crossed)  # fmt: skip


def batch_outcome(batch: BatchResult, b: int) -> ShotOutcome:
    """The :class:`ShotOutcome` of table ``b`` of a batch whose rows are ball numbers."""
    return ShotOutcome.from_arrays(
        batch.first_hit[b],
        batch.cushions_after_contact[b],
        batch.pocketed[b],
        batch.pocket_order[b],
    )


@dataclass(frozen=True, slots=True)
class RackState:
    """Everything the rules need to judge the next shot (the Markov part of the game).

    Attributes:
        game: ``"nine"`` or ``"eight"``.
        on_table: Per ball number, whether the object ball is on the table (index 0, the
            cue ball, is always True: a scratched cue ball comes back in hand).
        shooter: The player at the table (0 or 1).
        breaking: The next shot is the break.
        fouls: Successive fouls of each player (9-ball's three-foul rule).
        groups: Each player's 8-ball group (``OPEN`` until assigned).
        ball_in_hand: The shooter places the cue ball before shooting.
        behind_head_string: ... and only behind the head string (after an 8-ball break
            scratch).
        winner: The player who won the rack, or None while it is being played.
        push_out: The shot may be declared a push-out (the one right after a legal break).
        option: The shooter may give the table back instead of shooting.
        offers_push_out: The game is played with the push-out (False: 9-ball under the
            rules option ``push_out=False``, as ``pool_env/NineBallGame-v1`` plays it).
    """

    game: Game
    on_table: tuple[bool, ...]
    shooter: int = 0
    breaking: bool = True
    fouls: tuple[int, int] = (0, 0)
    groups: tuple[int, int] = (OPEN, OPEN)
    ball_in_hand: bool = False
    behind_head_string: bool = False
    winner: int | None = None
    push_out: bool = False
    option: bool = False
    offers_push_out: bool = True

    def __post_init__(self) -> None:
        if self.game not in N_BALLS:
            raise ValueError(f"game must be one of {list(N_BALLS)}, got {self.game!r}")
        if (self.push_out or self.option) and (
            self.game not in ROTATION or self.breaking or self.ball_in_hand
            or (self.push_out and self.option)
        ):  # fmt: skip
            raise ValueError("a push-out or an option comes in 9-ball or 10-ball, after the break")
        if not self.offers_push_out and (self.game != "nine" or self.push_out or self.option):
            raise ValueError("only 9-ball is played without the push-out, and then has none")
        if len(self.on_table) != N_BALLS[self.game] or not self.on_table[0]:
            raise ValueError(
                f"on_table must have {N_BALLS[self.game]} flags for {self.game} (cue ball True)"
            )
        if self.shooter not in (0, 1) or self.winner not in (None, 0, 1):
            raise ValueError("shooter (and winner, if any) must be player 0 or 1")

    @classmethod
    def new_rack(cls, game: Game, shooter: int = 0) -> RackState:
        """A racked table: every ball on, ``shooter`` to break."""
        if game not in N_BALLS:
            raise ValueError(f"game must be one of {list(N_BALLS)}, got {game!r}")
        return cls(game=game, on_table=(True,) * N_BALLS[game], shooter=shooter)

    @property
    def ball_on(self) -> int | None:
        """The ball the shooter must hit first, if it is a single one.

        9-ball and 10-ball: the lowest-numbered ball on the table; 8-ball: the 8 once the
        shooter's group is cleared, else None (any ball of the group, or of either on an
        open table).
        """
        if self.game in ROTATION:
            return next((b for b in range(1, len(self.on_table)) if self.on_table[b]), None)
        group = self.groups[self.shooter]
        if group != OPEN and not any(self.on_table[b] for b in _members(group)):
            return 8
        return None

    def legal_first_balls(self) -> tuple[int, ...]:
        """The balls the cue ball may touch first on the next shot."""
        on = self.ball_on
        if self.game in ROTATION or on == 8:
            return () if on is None else (on,)
        group = self.groups[self.shooter]
        if group == OPEN:
            return tuple(b for b in range(1, 16) if b != 8 and self.on_table[b])
        return tuple(b for b in _members(group) if self.on_table[b])


def _members(group: int) -> range:
    return range(1, 8) if group == SOLIDS else range(9, 16)


@dataclass(frozen=True, slots=True)
class Verdict:
    """The rules' judgement of one shot.

    Attributes:
        foul: None, or the reason: ``"scratch"``, ``"wrong_ball_first"``, ``"no_rail"``,
            ``"no_contact"``, ``"illegal_break"``.
        legal: Whether the shot was legal (no foul).
        ball_on: The ball on before the shot (see :attr:`RackState.ball_on`).
        respot: Balls to put back on the table (the 9 potted on a foul, the 8 on a break).
        winner: The player who won the rack with this shot, or None.
        loss: Why the shooter lost, if they did: ``"eight_early"``,
            ``"eight_wrong_pocket"``, ``"eight_on_foul"``, ``"three_fouls"``.
        shooter_continues: Whether the same player shoots next.
        push_out: The shot was played as a push-out.
        handed_back: The shooter used the option to give the table back (no shot).
    """

    foul: FoulReason | None
    legal: bool
    ball_on: int | None
    respot: tuple[int, ...]
    winner: int | None
    loss: str | None
    shooter_continues: bool
    push_out: bool = False
    handed_back: bool = False


def _may_hit_first(state: RackState, ball: int) -> bool:
    if state.breaking:  # 8-ball: any ball; rotation: the lowest (the 1 of a full rack)
        return state.game == "eight" or ball == state.ball_on
    return ball in state.legal_first_balls()


def first_read(state: RackState, shot: ShotOutcome) -> int:
    """The first ball the rules read (the shooter gets the benefit of a simultaneous hit).

    Of the balls met at the first instant, the first that may be hit first, else the first.
    """
    if shot.first_hit < 0:
        return -1
    met = (shot.first_hit, *shot.simultaneous)
    return next((b for b in met if _may_hit_first(state, b)), shot.first_hit)


def _foul(state: RackState, shot: ShotOutcome, pushed: bool = False) -> FoulReason | None:
    """The first foul reason that applies to ``shot`` from ``state``, or None.

    A push-out (``pushed``) fouls only by the scratch (and the kitchen rule, which a
    push-out never meets: the cue ball is not in hand).
    """
    if shot.scratch:
        return "scratch"
    first = first_read(state, shot)
    if (state.ball_in_hand and state.behind_head_string and first in shot.kitchen
            and not shot.crossed_head_string):  # fmt: skip
        return "kitchen_ball_first"
    if state.breaking:
        spread = bool(shot.potted) or shot.object_balls_to_rail >= BREAK_RAILS
        ok = first >= 0 and _may_hit_first(state, first) and spread
        return None if ok else "illegal_break"
    if pushed:
        return None
    if first < 0:
        return "no_contact"
    if first not in state.legal_first_balls():
        return "wrong_ball_first"
    if not shot.potted and not shot.rail_after_contact:
        return "no_rail"
    return None


def judge(
    state: RackState,
    shot: ShotOutcome,
    called_pocket: int | None = None,
    called_ball: int | None = None,
    push_out: bool = False,
    hand_back: bool = False,
) -> tuple[Verdict, RackState]:
    """Judge one shot (or the option used) and move the rack on.

    Args:
        state: The rack before the shot (not finished: ``state.winner is None``).
        shot: What happened (read only when a shot is played).
        called_pocket: The called pocket: the 8's (read only when the shooter is on the 8;
            None there means no call, and the 8 then drops in an uncalled pocket), and the
            called ball's in 10-ball.
        called_ball: 10-ball: the called ball (None: no call, so no call is made).
        push_out: The shooter declares a push-out (it is one only if ``state.push_out``).
        hand_back: The shooter gives the table back (only if ``state.option``; else the
            shot is played).

    Returns:
        The :class:`Verdict` and the rack after the shot (re-spotted balls back on; the
        next shooter, ball in hand, groups and foul counts updated).

    Raises:
        ValueError: If the rack is already decided, or the shot pots a ball that is not
            on the table.
    """
    if state.winner is not None:
        raise ValueError(f"the rack is over: player {state.winner} won it")
    if hand_back and state.option:
        verdict = Verdict(None, True, state.ball_on, (), None, None, False, handed_back=True)
        return verdict, replace(state, shooter=1 - state.shooter, option=False)
    for ball in shot.potted:
        if not (0 < ball < len(state.on_table) and state.on_table[ball]):
            raise ValueError(f"ball {ball} was potted but is not on the table")
    if state.game in ROTATION:
        return _judge_rotation(state, shot, called_pocket, called_ball, push_out and state.push_out)
    return _judge_eight(state, shot, called_pocket)


def run_out_ends(verdict: Verdict) -> bool:
    """Whether the judged shot ends a one-agent run-out (``end_on_foul=True``).

    The rack decided, a foul, or a legal shot after which the shooter would not go on; but
    one agent shoots on after its legal push-out (the opponent's option needs an opponent).
    """
    if verdict.winner is not None or verdict.foul is not None:
        return True
    return not (verdict.shooter_continues or verdict.push_out)


def _next_turn(state: RackState, foul: FoulReason | None, keeps: bool, **changes) -> RackState:
    """The state after a shot: who shoots, with the cue ball in hand or not.

    The push-out is offered after a legal break of a rotation game; the option lapses
    unless ``changes`` grants it.
    """
    shooter = state.shooter if keeps else 1 - state.shooter
    fouls = list(state.fouls)
    fouls[state.shooter] = fouls[state.shooter] + 1 if foul else 0
    behind = foul == "scratch" and state.breaking and state.game == "eight"
    return replace(
        state,
        shooter=shooter,
        breaking=False,
        fouls=(fouls[0], fouls[1]),
        ball_in_hand=foul is not None,
        behind_head_string=behind,
        push_out=state.breaking
        and foul is None
        and state.game in ROTATION
        and state.offers_push_out,
        option=changes.pop("option", False),
        **changes,
    )


def _off(
    on_table: tuple[bool, ...], potted: tuple[int, ...], respot: tuple[int, ...]
) -> tuple[bool, ...]:
    down = set(potted) - set(respot)
    return tuple(on and b not in down for b, on in enumerate(on_table))


def _judge_rotation(
    state: RackState,
    shot: ShotOutcome,
    called_pocket: int | None,
    called_ball: int | None,
    pushed: bool,
) -> tuple[Verdict, RackState]:
    """9-ball and 10-ball: the push-out, 10-ball's calls, the money ball, three fouls."""
    money = ROTATION[state.game]
    foul = _foul(state, shot, pushed)
    made = (
        called_ball in shot.potted
        and called_pocket is not None
        and shot.pockets[shot.potted.index(called_ball)] == called_pocket
    )
    called_game = state.game == "ten" and not state.breaking
    # The shot's pots count (the inning goes on, the money ball can win) when it is legal,
    # not a push-out and, in 10-ball after the break, its call was made.
    counted = foul is None and not pushed and (made or not called_game)
    wins = money in shot.potted and counted and (not called_game or called_ball == money)
    if state.game == "ten" and state.breaking:
        wins = False  # the 10 on the break is spotted
    winner = state.shooter if wins else None
    respot = (money,) if money in shot.potted and not wins else ()
    loss = None
    if foul and state.fouls[state.shooter] + 1 >= 3:
        winner, loss = 1 - state.shooter, "three_fouls"
    keeps = counted and bool(shot.potted)
    option = (
        foul is None
        and winner is None
        and (pushed or (called_game and not made and bool(shot.potted)))
    )
    on_table = _off(state.on_table, shot.potted, respot)
    after = _next_turn(state, foul, keeps, on_table=on_table, winner=winner, option=option)
    verdict = Verdict(
        foul, foul is None, state.ball_on, respot, winner, loss, keeps and winner is None,
        push_out=pushed,
    )  # fmt: skip
    return verdict, after


def _judge_eight(
    state: RackState, shot: ShotOutcome, called: int | None
) -> tuple[Verdict, RackState]:
    ball_on = state.ball_on
    foul = _foul(state, shot)
    on_eight = ball_on == 8
    respot: tuple[int, ...] = ()
    winner = loss = None
    if 8 in shot.potted:
        if state.breaking:
            respot = (8,)
        elif foul:
            loss = "eight_on_foul"
        elif not on_eight:
            loss = "eight_early"
        elif called is None or shot.pockets[shot.potted.index(8)] != called:
            loss = "eight_wrong_pocket"
        else:
            winner = state.shooter
        if loss:
            winner = 1 - state.shooter
    groups = state.groups
    group = groups[state.shooter]
    objects = [b for b in shot.potted if b != 8]
    if foul is None and not state.breaking and group == OPEN and objects:
        group = group_of(objects[0])
        mine = [OPEN, OPEN]
        mine[state.shooter], mine[1 - state.shooter] = group, SOLIDS + STRIPES - group
        groups = (mine[0], mine[1])
    if state.breaking:  # the 8 re-spotted, the breaker continues (WPA 8-ball 3.3(e))
        keeps = foul is None and bool(shot.potted)
    elif group == OPEN:
        keeps = foul is None and bool(objects)
    else:
        keeps = foul is None and any(group_of(b) == group for b in objects)
    on_table = _off(state.on_table, shot.potted, respot)
    after = _next_turn(state, foul, keeps, on_table=on_table, winner=winner, groups=groups)
    verdict = Verdict(foul, foul is None, ball_on, respot, winner, loss, keeps and winner is None)
    return verdict, after
