"""Exact event roots: polynomial real-root isolation and the closed-form circle entry.

Coefficient lists are in ascending powers. Nothing here divides by a leading coefficient,
so the degree drops of the ideal model (equal directions, equal velocities) need no special
case (see the package docstring, "Numerics").
"""

from __future__ import annotations

from collections.abc import Sequence

from mpmath import mp, mpf

from pool_env.testing.reference.model import ReferenceSimulationError, Vec, dot, sub


def horner(c: Sequence[mpf], x: mpf) -> mpf:
    """Value of the polynomial ``c`` at ``x``."""
    acc = mpf(0)
    for coef in reversed(c):
        acc = acc * x + coef
    return acc


def deriv(c: Sequence[mpf]) -> list[mpf]:
    """Coefficients of the derivative of ``c``."""
    return [k * c[k] for k in range(1, len(c))]


def trim(c: Sequence[mpf]) -> list[mpf]:
    """Drop exactly-zero leading coefficients: the only degree drops that are real."""
    out = list(c)
    while out and out[-1] == 0:
        out.pop()
    return out


def refine(c: Sequence[mpf], lo: mpf, hi: mpf, flo: mpf, fhi: mpf) -> tuple[mpf, mpf]:
    """Shrink a sign-change bracket of a polynomial to ~50 digits.

    Safeguarded Newton: a Newton step is taken only when it stays inside the bracket and is
    shorter than half of it, and the bracket is bisected whenever four iterations have not
    halved it, so convergence is guaranteed and usually quadratic. Newton approaches a root
    from one side; once its step is below the tolerance, the next iterate is placed just
    past the root so that the bracket closes from both sides (callers rely on the bracket,
    not on the last iterate).

    Args:
        c: Polynomial coefficients, ascending powers.
        lo: Left end of the bracket.
        hi: Right end of the bracket, ``hi > lo``.
        flo: ``c(lo)``, non-zero.
        fhi: ``c(hi)``, non-zero and of the opposite sign to ``flo``.

    Returns:
        ``(x_lo, x_hi)``: the final bracket, ``x_lo`` on the side with the sign of ``flo``
        and ``x_hi`` on the side with the sign of ``fhi`` (equal if an exact zero was hit).
    """
    dc = deriv(c)
    neg_left = flo < 0
    x = (lo + hi) / 2
    checkpoint = hi - lo
    for it in range(1, 4000):
        fx = horner(c, x)
        if fx == 0:
            return x, x
        if (fx < 0) == neg_left:
            lo = x
        else:
            hi = x
        width = hi - lo
        tol = mp.eps * 64 * (abs(lo) + abs(hi)) + mpf("1e-80")
        if width <= tol:
            break
        dfx = horner(dc, x)
        step = fx / dfx if dfx != 0 else None
        if it % 4 == 0:
            stalled = width > checkpoint / 2
            checkpoint = width
        else:
            stalled = False
        if step is None or stalled or not (abs(step) < width / 2 and lo < x - step < hi):
            x = lo + width / 2
        elif abs(step) <= tol:
            # Converged from one side: probe just beyond the root to close the bracket.
            probe = x - step - (tol if step > 0 else -tol)
            x = probe if lo < probe < hi else lo + width / 2
        else:
            x = x - step
    return lo, hi


def sign_changes(c: Sequence[mpf], lo: mpf, hi: mpf) -> list[mpf]:
    """Points in ``(lo, hi)`` where a polynomial changes sign (or is exactly zero).

    Recursive real-root isolation: the sign changes of ``c'`` split ``[lo, hi]`` into pieces
    on which ``c`` is monotone, and each piece holds at most one root, which is bracketed and
    refined. Extra points (exact zeros without a sign change) are harmless to the callers,
    who only use the result to cut the window into monotone pieces.

    Args:
        c: Polynomial coefficients, ascending powers.
        lo: Left end of the window.
        hi: Right end of the window.

    Returns:
        The points, sorted ascending.
    """
    c = trim(c)
    if len(c) <= 1:
        return []
    if len(c) == 2:
        r = -c[0] / c[1]
        return [r] if lo < r < hi else []
    pts = [lo, *sign_changes(deriv(c), lo, hi), hi]
    vals = [horner(c, x) for x in pts]
    out: list[mpf] = []
    for k in range(len(pts) - 1):
        if k > 0 and vals[k] == 0:
            out.append(pts[k])
        f0, f1 = vals[k], vals[k + 1]
        if f0 != 0 and f1 != 0 and (f0 < 0) != (f1 < 0):
            a, b = refine(c, pts[k], pts[k + 1], f0, f1)
            out.append((a + b) / 2)
    return out


def first_contact(g: Sequence[mpf], lo: mpf, hi: mpf) -> mpf | None:
    """First point in ``[lo, hi]`` where the gap ``g`` reaches zero while decreasing.

    Args:
        g: Gap polynomial ``|d|^2 - 4R^2`` (ascending powers); negative means overlap.
        lo: Start of the validity window.
        hi: End of the validity window.

    Returns:
        The contact time (on the ``g <= 0`` side of the root, within ~1e-50 relative), or
        ``None`` if the gap does not close while approaching inside the window.

    Raises:
        ReferenceSimulationError: If the balls overlap and start approaching with zero
            approach speed (sustained contact, which the event model cannot express).
    """
    if not hi > lo:
        return None
    dg = deriv(g)
    pts = [lo, *sign_changes(dg, lo, hi), hi]
    vals = [horner(g, x) for x in pts]
    for k in range(len(pts) - 1):
        x0, x1, f0, f1 = pts[k], pts[k + 1], vals[k], vals[k + 1]
        if not f1 < f0:
            continue  # separating (or constant) on this piece: no impact
        if f0 <= 0:
            # Touching or overlapping at the start of a closing piece. At the window start
            # this is the contact rule's "approaching means collide now".
            if k == 0 and horner(dg, x0) < 0:
                return x0
            raise ReferenceSimulationError(
                "balls in contact start closing with zero approach speed (sustained "
                "contact); the event model cannot resolve it"
            )
        if f1 == 0:
            root = x1
        elif f1 < 0:
            _, root = refine(g, x0, x1, f0, f1)
        else:
            continue
        if horner(dg, root) < 0:
            return root
        # A tangential touch (g' = 0 where g = 0) transfers no impulse: not an impact.
    return None


def gap_poly(p_i: Vec, v_i: Vec, acc_i: Vec, p_j: Vec, v_j: Vec, acc_j: Vec, r: mpf) -> list[mpf]:
    """Gap ``|p_j(tau) - p_i(tau)|^2 - (2r)^2`` for ``p(tau) = p + v tau + acc tau^2 / 2``.

    Args:
        p_i: Position of ball i at ``tau = 0``.
        v_i: Velocity of ball i at ``tau = 0``.
        acc_i: Constant acceleration of ball i (``-a u`` moving, zero resting).
        p_j: Position of ball j at ``tau = 0``.
        v_j: Velocity of ball j at ``tau = 0``.
        acc_j: Constant acceleration of ball j.
        r: Ball radius.

    Returns:
        Coefficients of the (at most) quartic, ascending powers of ``tau``.
    """
    d0 = sub(p_j, p_i)
    d1 = sub(v_j, v_i)
    d2 = ((acc_j[0] - acc_i[0]) / 2, (acc_j[1] - acc_i[1]) / 2)
    return [
        dot(d0, d0) - 4 * r * r,
        2 * dot(d0, d1),
        dot(d1, d1) + 2 * dot(d0, d2),
        2 * dot(d1, d2),
        dot(d2, d2),
    ]


def circle_entry(p: Vec, u: Vec, centre: Vec, radius_sq: mpf) -> mpf | None:
    """Arc length along ``p + s u`` (``u`` a unit vector) at which the path enters a circle.

    Used for a pocket's capture circle, a jaw point's contact circle and a resting ball's
    contact circle (``2R`` about its centre). Solved in the cancellation-free form
    ``s = c / (-b + sqrt(b^2 - c))``.

    Args:
        p: Start of the path.
        u: Unit direction of travel.
        centre: Centre of the circle.
        radius_sq: Square of its radius (each caller squares as it always has, so the
            50-digit results do not move by one rounding).

    Returns:
        ``0`` if ``p`` is on or inside the circle and moving inwards (contact now), the
        arc length of the entry otherwise, or ``None`` if the path moves away from (or
        tangentially past) the centre, misses the circle or only grazes it (no impulse).
    """
    q = sub(p, centre)
    b = dot(u, q)
    if b >= 0:
        return None  # moving away from (or tangentially past) the centre
    c = dot(q, q) - radius_sq
    if c <= 0:
        return mpf(0)  # on or inside the circle and moving inwards: contact now
    disc = b * b - c
    if disc <= 0:
        return None  # a miss, or an exact tangential graze without entering
    return c / (-b + mp.sqrt(disc))
