"""Snooker's rules in plain Python, written from the WPBSA rule text: a test oracle.

It shares no code with :mod:`pool_env.game.games.snooker` (it imports nothing of it, nor
of the game layer's kernels): a table's frame state is a :class:`Frame` of named fields,
the balls a dict of positions, and every rule is restated here from the WPBSA's *Official
Rules of the Games of Snooker and English Billiards* (November 2019), section and rule
numbers as "S3 R7". What it decides, for one stroke whose outcome is given (the first ball
the cue ball hit, the balls potted, the colour nominated, the balls the cue ball touched
before the stroke, where the balls stopped):

- what is on (S2 R11, S3 R3), the fouls and their penalty (S3 R10, R11), the score;
- the colours put back (S3 R7: own spot, else the highest free spot, else as near the own
  spot as possible towards the top cushion, for any colour then below it on its line);
- the cue ball in hand in the D after an in-off (S3 R5): the requested point (the middle
  of the D's rear half) when free, else the nearest free point of a grid of step R/4;
- the free ball (S2 R13, S3 R12): whether the incoming striker is snookered (S2 R17),
  tested with the cue ball's path to both extreme edges of each ball on;
- the touching ball (S3 R8), the end of frame and the re-spotted black (S3 R4).

The conventions the product documents where the rule text leaves a number open are the
same (they are choices, not code): a spot is occupied when a ball centre is within
``2R + 1e-7`` m (the placement clearance) or the point lies outside the cushions' reach or
within a pocket's capture circle plus the clearance; a ball touches the cue ball within
``1e-6`` m of ``2R``; an unnamed colour on a colour-on stroke is the colour touched, else
the colour first hit, and with neither its value is 7; with the cue ball in hand the
snookered test is made from the D's points at radii ``k/4`` and angles
``90 + 22.5 j`` degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

REDS = frozenset(range(1, 16))
YELLOW, GREEN, BROWN, BLUE, PINK, BLACK = 16, 17, 18, 19, 20, 21
COLOURS = (YELLOW, GREEN, BROWN, BLUE, PINK, BLACK)
CLEARANCE = 1e-7
TOUCH = 1e-6


def value(ball: int) -> int:
    """Section 3 Rule 1: a red 1, yellow 2, green 3, brown 4, blue 5, pink 6, black 7."""
    return 1 if ball in REDS else {YELLOW: 2, GREEN: 3, BROWN: 4, BLUE: 5, PINK: 6, BLACK: 7}[ball]


@dataclass(frozen=True)
class Frame:
    """A frame between two strokes (the names a referee would use)."""

    striker: int = 0
    scores: tuple[int, int] = (0, 0)
    on: str = "red"  # "red", "colour" (after a red), "in_order"
    in_hand: bool = False
    free_ball: bool = False
    current_break: int = 0
    respotted_black: bool = False
    winner: int | None = None


@dataclass(frozen=True)
class TableSpec:
    """What the rules need of the table: its size, the ball radius, the capture circles."""

    length: float
    width: float
    radius: float
    pockets: tuple[tuple[float, float, float], ...]

    @property
    def scale(self) -> float:
        """The markings' scale: the table's length over the WPBSA table's 3.569 m."""
        return self.length / 3.569

    def spot(self, colour: int) -> tuple[float, float]:
        """Section 1 Rule 1(c)'s spots (scaled), x from the baulk cushion."""
        baulk, d = 0.737 * self.scale, 0.292 * self.scale
        mid = self.width / 2
        return {
            YELLOW: (baulk, mid - d),
            GREEN: (baulk, mid + d),
            BROWN: (baulk, mid),
            BLUE: (self.length / 2, mid),
            PINK: (0.75 * self.length, mid),
            BLACK: (self.length - 0.324 * self.scale, mid),
        }[colour]

    def free(self, point: tuple[float, float], balls: dict[int, tuple[float, float]]) -> bool:
        """A ball may stand at ``point``: on the bed, out of the pockets, touching no ball."""
        x, y = point
        r = self.radius
        if not (r <= x <= self.length - r and r <= y <= self.width - r):
            return False
        if any(math.dist(point, (px, py)) <= pr + CLEARANCE for px, py, pr in self.pockets):
            return False
        return all(math.dist(point, q) >= 2 * r + CLEARANCE for q in balls.values())


def put_back(table: TableSpec, balls: dict[int, tuple[float, float]], colours: list[int]) -> None:
    """Section 3 Rule 7: spot ``colours`` (into ``balls``)."""
    waiting = []
    for colour in sorted(colours, reverse=True):
        if table.free(table.spot(colour), balls):
            balls[colour] = table.spot(colour)
        else:
            waiting.append(colour)
    for colour in waiting:  # highest value first (R7(d))
        for spot in sorted(COLOURS, reverse=True):  # the highest-valued spot available
            if table.free(table.spot(spot), balls):
                balls[colour] = table.spot(spot)
                break
        else:
            balls[colour] = _along_line(table, balls, table.spot(colour))


def _along_line(table: TableSpec, balls: dict[int, tuple[float, float]],
                spot: tuple[float, float]) -> tuple[float, float]:  # fmt: skip
    """As near ``spot`` as possible towards the top cushion, else below it (R7(e), (f))."""
    x0, y = spot
    reach = 2 * table.radius + CLEARANCE
    blocks = [(qx, math.sqrt(reach**2 - (y - qy) ** 2)) for qx, qy in balls.values()
              if abs(y - qy) < reach]  # fmt: skip
    blocks += [(px, math.sqrt((pr + CLEARANCE) ** 2 - (y - py) ** 2))
               for px, py, pr in table.pockets if abs(y - py) <= pr + CLEARANCE]  # fmt: skip
    for direction in (1.0, -1.0):
        x = x0
        while True:
            # a block holds x within its half-width (and rounding); x leaves by its far end
            ends = [c + direction * (h * (1 + 1e-9) + 2e-11) for c, h in blocks
                    if abs(x - c) < h * (1 + 1e-9)]  # fmt: skip
            if not ends:
                break
            x = max(ends) if direction > 0 else min(ends)
        if table.radius <= x <= table.length - table.radius:
            return (x, y)
    return spot


def in_d(table: TableSpec, point: tuple[float, float]) -> bool:
    """Section 1 Rule 1(c): on or within the lines of the D."""
    baulk, d = 0.737 * table.scale, 0.292 * table.scale
    return point[0] <= baulk and math.dist(point, (baulk, table.width / 2)) <= d


def place_cue(table: TableSpec, balls: dict[int, tuple[float, float]]) -> tuple[float, float]:
    """Section 3 Rule 5: the cue ball in hand, in the D: its rear half's middle, or near it."""
    baulk, d = 0.737 * table.scale, 0.292 * table.scale
    mid = table.width / 2
    want = (baulk - d / 2, mid)
    if table.free(want, balls):
        return want
    step = table.radius / 4
    n = int(d / step)
    points = [(baulk - i * step, mid + k * step) for i in range(n + 1) for k in range(-n, n + 1)]
    points = [p for p in points if in_d(table, p) and table.free(p, balls)]
    return min(points, key=lambda p: math.dist(p, want))


def _path_blocked(table: TableSpec, cue: tuple[float, float], target: tuple[float, float],
                  side: int, others: list[tuple[float, float]]) -> bool:  # fmt: skip
    """Whether the stroke to the extreme edge ``side`` of the ball at ``target`` meets a ball.

    The cue ball grazing the target on that side ends where its centre is ``2R`` from the
    target's, on the tangent from its start: any other ball within ``2R`` of that path
    is met first.
    """
    two_r = 2 * table.radius
    d = math.dist(cue, target)
    if d <= two_r:
        return False
    toward = math.atan2(target[1] - cue[1], target[0] - cue[0]) + side * math.asin(two_r / d)
    length = math.sqrt(d * d - two_r * two_r)
    ux, uy = math.cos(toward), math.sin(toward)
    for q in others:
        along = max(0.0, min(length, (q[0] - cue[0]) * ux + (q[1] - cue[1]) * uy))
        closest = (cue[0] + along * ux, cue[1] + along * uy)
        if math.dist(q, closest) < two_r:
            return True
    return False


def is_snookered(table: TableSpec, cue: tuple[float, float],
                 balls: dict[int, tuple[float, float]], on: set[int]) -> bool:  # fmt: skip
    """Section 2 Rule 17: no ball on can be struck at both extreme edges."""
    others = [p for j, p in balls.items() if j not in on]
    return not any(
        not _path_blocked(table, cue, balls[j], s, others) and
        not _path_blocked(table, cue, balls[j], -s, others)
        for j in on for s in (1,)  # both sides: s and -s
    )  # fmt: skip


def snookered_from_d(table: TableSpec, balls: dict[int, tuple[float, float]], on: set[int]) -> bool:
    """The snookered test with the cue ball in hand: from every sample point of the D."""
    baulk, d = 0.737 * table.scale, 0.292 * table.scale
    mid = table.width / 2
    for k in range(5):
        for j in range(9):
            angle = math.pi / 2 + j * math.pi / 8
            p = (baulk + d * k / 4 * math.cos(angle), mid + d * k / 4 * math.sin(angle))
            if table.free(p, balls) and not is_snookered(table, p, balls, on):
                return False
    return True


@dataclass(frozen=True)
class Verdict:
    """What the referee calls: the foul (None or its name) and points."""

    foul: str | None
    penalty: int
    points: int
    free_ball_played: bool
    frame_over: bool
    tie: bool


Balls = dict[int, tuple[float, float]]


def referee(table: TableSpec, frame: Frame, before: Balls, after: Balls, first: int | None,
            potted: set[int], nominated: int | None,
            touching: set[int]) -> tuple[Frame, Balls, Verdict]:  # fmt: skip
    """One stroke judged.

    Args:
        table: The table.
        frame: The frame before the stroke.
        before: The balls on the table before the stroke (ball -> centre), the cue ball 0.
        after: Where every ball of ``before`` stopped (potted ones: anywhere).
        first: The first ball the cue ball hit, or None.
        potted: The balls potted (0: the cue ball).
        nominated: The colour nominated, or None.
        touching: The balls the cue ball touched before the stroke.

    Returns:
        The frame after, the balls on the table after (cue ball placed), the verdict.
    """
    reds_before = [j for j in before if j in REDS]
    colours_before = sorted(j for j in before if j in COLOURS)
    nominee = nominated if nominated in before and nominated in COLOURS else None
    # S2 R11 / R13: which balls are on, the value of the ball on, the free ball
    free, colour = None, None
    if frame.on == "red":
        if frame.free_ball and nominee is not None:
            free = nominee
            may_hit = {free}
        else:
            may_hit = set(reds_before)
        on_value = 1
        may_pot = set(reds_before) | ({free} if free else set())
    elif frame.on == "colour":
        colour = nominee
        if colour is None:
            touched = [j for j in colours_before if j in touching]
            colour = touched[0] if touched else (first if first in COLOURS else None)
        may_hit = {colour} if colour else set()
        on_value = value(colour) if colour else 7
        may_pot = set(may_hit)
    else:
        lowest = colours_before[0]
        on_value = value(lowest)
        if frame.free_ball and nominee is not None and nominee != lowest:
            free = nominee
            may_hit = {free}
        else:
            may_hit = {lowest}
        may_pot = {lowest} | ({free} if free else set())
    # S3 R8: a touching ball on counts as hit when played away from, moving it is a push
    pushed = first is not None and first in touching
    touching_on = bool(touching & may_hit)
    deemed_hit = touching_on and not pushed
    objects_potted = potted - {0}
    foul = None
    if pushed:
        foul = "push"
    elif first is None and not deemed_hit:
        foul = "no_contact"
    elif not (first in may_hit or deemed_hit):
        foul = "wrong_ball_first"
    elif 0 in potted:
        foul = "in_off"
    elif not objects_potted <= may_pot:
        foul = "ball_not_on_potted"
    penalty, points = 0, 0
    respot: list[int] = []
    if foul:  # S3 R11: 4, or the value of the ball on or ball concerned
        involved = [4, on_value] + [value(j) for j in objects_potted]
        if free:
            involved.append(value(free))
        if first is not None and (first in may_hit or not deemed_hit):
            involved.append(value(first))
        penalty = max(involved)
        respot = [j for j in objects_potted if j in COLOURS]
    elif frame.on == "red":
        points = len(objects_potted)
        respot = [free] if free in objects_potted else []
    elif frame.on == "colour":
        if colour in objects_potted:
            points, respot = value(colour), [colour]
    else:
        if objects_potted:
            points = on_value
        respot = [free] if free in objects_potted else []
    scores = list(frame.scores)
    if foul:
        scores[1 - frame.striker] += penalty
    else:
        scores[frame.striker] += points
    turn_passes = bool(foul) or points == 0
    only_black = frame.on != "colour" and colours_before == [BLACK] and not reds_before
    frame_over = only_black and (bool(foul) or points > 0)
    balls = {j: after[j] for j in before if j not in potted}  # the cue ball too, unless potted
    cue_in_hand = 0 in potted
    cue = None if cue_in_hand else after[0]
    new = replace(frame, scores=(scores[0], scores[1]), free_ball=False, in_hand=cue_in_hand)
    tie = False
    if frame_over:
        new = replace(new, current_break=0 if turn_passes else frame.current_break + points)
        if scores[0] != scores[1]:
            new = replace(new, winner=0 if scores[0] > scores[1] else 1)
        else:  # S3 R4(b): the black re-spotted, from in hand, the next score or foul ends it
            tie = True
            balls.pop(BLACK, None)  # picked up (if still on the table) and spotted
            balls.pop(0, None)  # the cue ball is in hand, off the table: it covers no spot
            put_back(table, balls, [BLACK])
            cue_in_hand = True
            new = replace(new, striker=1 - frame.striker, current_break=0, on="in_order",
                          in_hand=True, respotted_black=True)  # fmt: skip
    else:
        put_back(table, balls, respot)
    if cue_in_hand:
        balls.pop(0, None)
        cue = place_cue(table, balls)
    balls[0] = cue
    verdict = Verdict(foul, penalty, points, free is not None, frame_over, tie)
    if frame_over:
        return new, balls, verdict
    reds_left = any(j in REDS for j in balls)
    if not turn_passes:
        on = {"red": "colour", "colour": "red" if reds_left else "in_order"}.get(
            frame.on, "in_order")  # fmt: skip
        return replace(new, on=on, current_break=frame.current_break + points), balls, verdict
    new = replace(new, striker=1 - frame.striker, current_break=0,
                  on="red" if reds_left else "in_order")  # fmt: skip
    if foul:  # S3 R12: free ball if the incoming striker is snookered
        on = {j for j in balls if j in REDS} if reds_left else {
            min(j for j in balls if j in COLOURS)}  # fmt: skip
        objects = {j: p for j, p in balls.items() if j != 0}
        hidden = (snookered_from_d(table, objects, on) if cue_in_hand
                  else is_snookered(table, cue, objects, on))  # fmt: skip
        new = replace(new, free_ball=hidden)
    return new, balls, verdict
