"""Event kinds of both levels: the one enumeration every loop, kernel and result reads.

The codes are the tie-breaking order of simultaneous events (the loops' total order is
time, kind, first id, second id), so their values are part of the physics: a pocket
capture goes before an impact at the same instant, an impact before a cushion, and so
on. The roll level uses the first six; the spin level adds its three transitions.
"""

from __future__ import annotations

from typing import Literal

#: Ball ``i`` is captured by pocket ``j`` (capture circle entered or fall line reached).
POCKET = 0
#: Balls ``i < j`` meet.
BALL = 1
#: Ball ``i`` meets rail ``j`` (on a jaw table, the straight part between two pockets).
CUSHION = 2
#: Ball ``i`` comes to rest (on the spin level: rolling into rest without spin).
STOP = 3
#: Ball ``i`` meets jaw facing ``j = 2 k + side`` of pocket ``k``.
JAW = 4
#: Ball ``i`` meets the point (round tip) ``j = 2 k + side`` of pocket ``k``.
POINT = 5
#: Spin level: ball ``i`` stops sliding and rolls.
SLIDE_ROLL = 6
#: Spin level: rolling ball ``i`` comes to rest spinning in place about the vertical.
ROLL_SPIN = 7
#: Spin level: ball ``i`` stops spinning in place.
SPIN_STOP = 8
#: Columns of a ball's own-event row (``own[i]``): time, kind, argument (rail, pocket,
#: jaw); ``EV_END`` columns in all.
EV_T, EV_KIND, EV_ARG, EV_END = 0, 1, 2, 3
#: Greater than every kind: the loops' "no event found yet".
NO_EVENT = 99

EventKind = Literal[
    "pocket", "ball", "cushion", "stop", "jaw", "point", "slide_roll", "roll_spin", "spin_stop"
]

#: The name of each kind code (``KIND_NAMES[code]``), in tie-breaking order.
KIND_NAMES: tuple[EventKind, ...] = (
    "pocket", "ball", "cushion", "stop", "jaw", "point", "slide_roll", "roll_spin", "spin_stop"
)  # fmt: skip
#: Kinds that are cushion contacts for the rules (a rail, a jaw facing, a jaw point).
CUSHION_KINDS: tuple[EventKind, ...] = ("cushion", "jaw", "point")
#: The spin level's transitions of one ball's motion state (``j = -1``), and ``"stop"``.
TRANSITION_KINDS: tuple[EventKind, ...] = ("slide_roll", "stop", "roll_spin", "spin_stop")
