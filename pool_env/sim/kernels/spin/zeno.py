"""The spin level's rules for contacts that would repeat without end (compiled).

The pressed-cushion rule (:func:`pressed_roll`): a ball left at a cushion with a normal
speed below ``V_ZENO``, or held there (:func:`held`), whose slip drives it back into the
cushion rolls at once (its slide's end state, the part into the cushion dropped): the
model has no constrained slide along a cushion.

Zeno rules (as the roll level): an impact repeating within ``ZENO_WINDOW`` slower than
``V_ZENO`` is perfectly inelastic along the normal; a pair repeating ``ZENO_REPEATS`` times
that closely sticks: it and every ball touching it roll on together (:func:`stick`: each
ball's slide ends at once, and all take the mean rolling velocity; energy only lost). So
does a pair that an impact leaves pressed together (:func:`pressed_pair`: its own
accelerations bring it back before it has parted by more than ``CONTACT_TOL``,
:func:`held`), whatever the restitution: with ``e = 1`` its bounces neither shrink nor end.
The lump then meets the cushions it touches as one body (the roll level's
``lump_off_contacts``) and, on a jaw table, with the roll level's jam rule for lumps
wedged between contacts (``jaw_impacts.unpress_lump``). A single ball meeting a cushion slowly
while wedged between contacts (:func:`wedged_ball`: a narrowing throat, its slip driving it
in) is held there too: without the rule it re-hit both facings thousands of times at one
instant and ended at the event cap.
"""

from __future__ import annotations

import math

import numpy as np

from pool_env.sim.jit import kernel
from pool_env.sim.kernels.contact import (
    CONTACT_TOL,
    V_REST,
    V_ZENO,
    ZENO_REPEATS,
    lump_off_contacts,
    slide,
    wedged,
)
from pool_env.sim.kernels.jaw_geometry import (
    J_FACING0,
    J_TIP0,
    JAW_COLS,
    jaw_normal,
    opening_of,
    throat_of,
)
from pool_env.sim.kernels.kinds import JAW, POINT
from pool_env.sim.kernels.params import P_E_CUSHION, P_E_JAW, P_LENGTH, P_RADIUS, P_WIDTH
from pool_env.sim.kernels.roots import APPROACH_RTOL, INF
from pool_env.sim.kernels.spin.state import (
    AX,
    AY,
    FORCE_ROLL,
    POTTED,
    TEND,
    VX,
    VY,
    set_anchor,
    state_at,
)

#: Rails' unit normals into the table, by rail index (0: x = R, 1: x = L - R, 2, 3: y).
RAIL_NX = (1.0, -1.0, 0.0, 0.0)
RAIL_NY = (0.0, 0.0, 1.0, -1.0)


@kernel
def _gather_contacts(x, y, prm, pockets, normals, es, count):
    """Append the unit normals (and restitutions) of every cushion a centre touches.

    A rail, jaw facing or jaw point is touched when the centre lies within
    ``CONTACT_TOL`` of it; a rail only outside the pocket openings. Returns the new count.
    """
    radius, length, width = prm[P_RADIUS], prm[P_LENGTH], prm[P_WIDTH]
    jaws = pockets.shape[1] == JAW_COLS
    for rail in range(4):
        coord = y if rail < 2 else x
        line = (radius, length - radius, radius, width - radius)[rail]
        here = x if rail < 2 else y
        if abs(here - line) <= CONTACT_TOL and not (jaws and opening_of(pockets, rail, coord) >= 0):
            normals[count, 0], normals[count, 1] = RAIL_NX[rail], RAIL_NY[rail]
            es[count] = prm[P_E_CUSHION]
            count += 1
    if jaws:
        k = throat_of(x, y, prm, pockets)
        for side in range(2 if k >= 0 else 0):
            for kind in (JAW, POINT):
                nx, ny = jaw_normal(pockets, kind, 2 * k + side, x, y)
                gap = _jaw_gap(pockets, kind, 2 * k + side, x, y)
                if gap <= CONTACT_TOL:
                    normals[count, 0], normals[count, 1] = nx, ny
                    es[count] = prm[P_E_JAW]
                    count += 1
    return count


@kernel
def _lump_off_cushions(snap, changed, size, vx, vy, prm, pockets):
    """A lump's common velocity after it meets the cushions its balls touch, as one body.

    The roll level's rules for a stuck lump (``resolve.lump_off_contacts`` and, on a jaw
    table, ``jaw_impacts.unpress_lump``): a lump wedged between contacts (pressing into them so
    that it cannot slide along any one of them without pressing into another) stops, the
    cushions taking its momentum; otherwise each touched rail, jaw facing or jaw point
    reflects the lump's normal velocity into it with its restitution (0 below ``V_ZENO``),
    and on a jaw table a component slower than ``V_ZENO`` still pressing into a contact
    is removed. Energy only drops; a ball wedged between a ball and a cushion would
    otherwise re-collide endlessly at one instant.
    """
    normals = np.zeros((8 * size, 2))
    es = np.zeros(8 * size)
    count = 0
    for c in range(size):
        x, y = snap[changed[c], 0], snap[changed[c], 1]
        count = _gather_contacts(x, y, prm, pockets, normals, es, count)
    if pockets.shape[1] != JAW_COLS:
        return lump_off_contacts(vx, vy, normals, es, count)
    if wedged(normals, count, vx, vy, INF, V_REST) or wedged(
        normals, count, vx, vy, V_ZENO, V_REST
    ):
        return 0.0, 0.0
    vx, vy = lump_off_contacts(vx, vy, normals, es, count)
    return slide(normals, count, vx, vy, V_ZENO, V_REST)


@kernel
def wedged_ball(x, y, vx, vy, repeats, prm, pockets):
    """Whether a ball meeting a cushion is wedged there: the single ball's jam rule.

    The one-ball counterpart of the lump's (:func:`_lump_off_cushions`, after
    ``jaw_impacts.unpress_lump``), on jaw tables: a ball meeting a cushion while it presses into
    other contacts so that it cannot slide along any one of them without pressing into
    another (a ball in a narrowing throat, touching both facings) is held there. Without
    the rule its slip, turned by each facing's friction, drove it back in after every
    impact: the model's free slide re-hit the two facings in a sequence that shrank only
    geometrically, thousands of events at one instant, and ended at the event cap
    (``tests/sim/test_spin_hard_cases.py``). The caller stops it (velocity and rolling spin
    to zero; the spin about the vertical, which presses nowhere, kept): energy only drops.
    """
    if pockets.shape[1] != JAW_COLS:
        return False
    normals = np.zeros((8, 2))
    es = np.zeros(8)
    count = _gather_contacts(x, y, prm, pockets, normals, es, 0)
    if count < 2:
        return False
    if repeats >= ZENO_REPEATS:
        return True
    return wedged(normals, count, vx, vy, INF, V_REST) or wedged(
        normals, count, vx, vy, V_ZENO, V_REST
    )


@kernel
def _jaw_gap(pockets, kind, arg, x, y):
    """Distance of a centre from facing or point ``arg`` (``inf`` beyond a facing's ends)."""
    row = pockets[arg // 2]
    side = arg % 2
    if kind == JAW:
        col = J_FACING0 + 7 * side
        along = (x - row[col]) * row[col + 2] + (y - row[col + 1]) * row[col + 3]
        if along < 0.0 or along > row[col + 6]:
            return INF
        return abs((x - row[col]) * row[col + 4] + (y - row[col + 1]) * row[col + 5])
    col = J_TIP0 + 3 * side
    return abs(math.sqrt((x - row[col]) ** 2 + (y - row[col + 1]) ** 2) - row[col + 2])


@kernel
def held(parting, closing, last):
    """Whether a contact that parts at ``parting`` is held: it comes back within tolerance.

    A ball pressed into a contact (another ball, a cushion) by its own acceleration, the
    cloth's friction on its slip, bounces off it and is brought back: leaving at ``s``
    with a closing acceleration ``a`` along the normal, it meets the contact again after
    ``2 s / a``, having parted by ``s^2 / (2 a)``. For ``e < 1`` the bounces shrink
    geometrically (a Zeno sequence, entering the window of the Zeno rules only once they
    come faster than it); for ``e = 1`` they repeat at one speed for as long as the slip
    lasts, tens of thousands of microsecond bounces (the event cap;
    ``tests/sim/test_spin_zeno.py``). Parting by no more than ``CONTACT_TOL``, the
    tolerance within which balls touch, the contact never opens: it is one contact under
    a compressive load, whose mean force the bounces only resolve into impulses. The rule
    holds only while the acceleration does: the contact must close again within ``last``.

    Args:
        parting: The normal speed away from the contact just after the impact.
        closing: The normal acceleration towards it.
        last: How long the acceleration lasts (to the next transition).
    """
    if not closing > 0.0 or parting < 0.0:
        return False
    return parting * parting <= 2.0 * closing * CONTACT_TOL and 2.0 * parting <= closing * last


@kernel
def pressed_pair(st, i, j, nx, ny, now):
    """Whether balls ``i`` and ``j``, just re-anchored by their impact, are pressed together.

    Two touching balls whose slips drive them into each other (spins pushing them
    together) are one contact under a load when :func:`held`; the caller sticks them
    (:func:`stick`), as it does a Zeno pair, whatever the restitution.

    Args:
        st: The anchors, ``i`` and ``j`` re-anchored at ``now`` by the impact.
        i, j: The balls.
        nx, ny: The unit normal from ``i``'s centre to ``j``'s.
        now: The impact's time.
    """
    parting = (st[j, VX] - st[i, VX]) * nx + (st[j, VY] - st[i, VY]) * ny
    closing = (st[i, AX] - st[j, AX]) * nx + (st[i, AY] - st[j, AY]) * ny
    return held(parting, closing, min(st[i, TEND], st[j, TEND]) - now)


@kernel
def stick(st, ms, masses, i, now, prm, pockets, changed):
    """Ball ``i`` and every ball touching it, transitively, roll on together.

    The lump ends its slide at once: each ball's natural-roll velocity ``v - (2/7) u``
    (angular momentum about its cloth contact conserved), and all roll at their
    momentum-weighted mean, side spins ``wz`` kept. Each step only loses energy (a slide's
    end; the mean of rolling velocities at fixed momentum); the momentum changes only by
    the cloth's friction impulse the slides would have applied. Rolling with one velocity,
    the lump's balls have one acceleration and no slip that presses them together.

    The lump then meets every cushion one of its balls touches as one body
    (:func:`_lump_off_cushions`).

    Returns how many balls changed (their indices in ``changed``).
    """
    n = st.shape[0]
    reach2 = (2.0 * prm[P_RADIUS] + CONTACT_TOL) ** 2
    snap = np.empty((n, 7))
    for k in range(n):
        snap[k, 0], snap[k, 1], snap[k, 2], snap[k, 3], snap[k, 4], snap[k, 5], snap[k, 6] = (
            state_at(st, ms, k, now, prm)
        )
    inside = np.zeros(n, dtype=np.bool_)
    inside[i] = True
    changed[0] = i
    size = 1
    head = 0
    while head < size:
        k = changed[head]
        head += 1
        for m in range(n):
            if not inside[m] and ms[m] != POTTED:
                dx, dy = snap[m, 0] - snap[k, 0], snap[m, 1] - snap[k, 1]
                if dx * dx + dy * dy <= reach2:
                    inside[m] = True
                    changed[size] = m
                    size += 1
    # Each ball's natural-roll velocity v - (2/7) u (its slide's end), then their
    # momentum-weighted mean: the lump rolls together, with no slip left to press it.
    radius = prm[P_RADIUS]
    px = py = total = 0.0
    for c in range(size):
        k = changed[c]
        ux = snap[k, 2] - radius * snap[k, 5]
        uy = snap[k, 3] + radius * snap[k, 4]
        px += masses[k] * (snap[k, 2] - 2.0 / 7.0 * ux)
        py += masses[k] * (snap[k, 3] - 2.0 / 7.0 * uy)
        total += masses[k]
    vx, vy = _lump_off_cushions(snap, changed, size, px / total, py / total, prm, pockets)
    for c in range(size):
        k = changed[c]
        s = snap[k]
        set_anchor(
            st, ms, k, now, s[0], s[1], vx, vy, -vy / radius, vx / radius, s[6], prm, FORCE_ROLL
        )
    return size


@kernel
def pressed_roll(out, nx, ny, radius, slide_decel):
    """The pressed-cushion rule: a ball held at a cushion by its own slip rolls at once.

    ``out`` holds a cushion impact's result ``(vx, vy, wx, wy, wz)``, ``n`` the cushion's
    normal into the table, ``slide_decel`` the sliding deceleration ``mu_s g``. If the ball
    leaves slower than ``V_ZENO`` along ``n``, or so slowly that it comes back within
    ``CONTACT_TOL`` (:func:`held`: an elastic cushion returns its speed whole, so the
    bounces would never shrink), while its slip drives it back into the cushion (the
    cloth's friction ``-mu g u / |u|`` has a component against ``n``), the model's free
    slide would re-hit the cushion endlessly (a Zeno sequence, or microsecond bounces at
    one speed) or, at rounding speed, pass it. The cushion's reaction would hold
    the ball at it while the slip dies; this rule ends that slide at once instead: the
    ball takes the rolling velocity its slide would end in, ``v - (2/7) u`` (angular
    momentum about the cloth contact conserved), loses any part of it into the cushion
    and rolls. Energy only drops. Returns whether the rule applied (``out`` rewritten).
    """
    vx, vy, wx, wy = out[0], out[1], out[2], out[3]
    ux, uy = vx - radius * wy, vy + radius * wx
    slip = math.sqrt(ux * ux + uy * uy)
    into = ux * nx + uy * ny
    if not into > APPROACH_RTOL * slip:
        return False  # the slip does not press the ball into the cushion
    parting = vx * nx + vy * ny
    # The slide lasts slip / (3.5 mu_s g); its friction presses in at mu_s g into / slip.
    pressed = held(parting, slide_decel * into / slip, slip / (3.5 * slide_decel))
    if not (abs(parting) < V_ZENO or pressed):
        return False
    vx -= 2.0 / 7.0 * ux
    vy -= 2.0 / 7.0 * uy
    vn = vx * nx + vy * ny
    if vn < 0.0:
        vx -= vn * nx
        vy -= vn * ny
    out[0], out[1] = vx, vy
    out[2], out[3] = -vy / radius, vx / radius
    return True
