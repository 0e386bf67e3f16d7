"""Invariant checks on a recorded shot, shared by the tests and the fuzz benchmark.

The named invariants of ``docs/physics.md`` ("The hard cases"):

* **G** (geometry): no two balls on the table overlap by more than ``tol`` at any event, at
  rest, or at sampled instants between events; every ball on the table stays inside the
  playing region: the rails' rectangle and, on a jaw table, the pocket throats (clear of
  every facing and point, in front of the fall line).
* **P** (momentum): each ball-ball impact conserves the pair's momentum (a sticking lump
  touching a rail: up to the rail's impulse out of it; touching jaws and rails: up to
  impulses out of the contacts it touches).
* **E** (energy): kinetic energy never increases, across impacts or in between.
* **T** (termination): the shot ends at rest without reaching the event cap.
* **O** (order): event times never decrease, nor do the trajectory rows' times.

On the spin level (``Table(model="spin")``) the same checks take the spin into account
(energy is translational plus rotational, velocities follow each state's acceleration), and
:func:`~pool_env.testing.spin_invariants.check_motion` adds **M** (motion states,
transitions and the final state); see :mod:`pool_env.testing.spin_invariants`.

Each check returns a list of human-readable violations (empty when it holds).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from pool_env.sim.kernels.contact import CONTACT_TOL
from pool_env.sim.kernels.jaw_geometry import LOC_CIRCLE, LOC_FREE, locate_many
from pool_env.sim.result import ShotResult, SpinShotResult
from pool_env.sim.table import Table
from pool_env.testing import spin_invariants

GEOMETRY_TOL = 1e-9  # m
MOMENTUM_RTOL = 1e-12

# The documented rules' speeds (``docs/physics.md``, "Zeno rules"), written here rather than
# imported from the kernels: a check must not loosen when the code it checks is loosened.
# A ball slower than REST_SPEED after an impact is at rest; a sticking lump gives up a
# normal speed below ZENO_SPEED into a rail it touches.
REST_SPEED = 1e-9  # m/s
ZENO_SPEED = 1e-6  # m/s

ENERGY_RTOL = 1e-12


def _velocity(state: NDArray[np.float64], t0: float, t: float, decel: float) -> NDArray:
    """Velocity at ``t`` of a ball anchored at ``t0`` with ``state = (x, y, vx, vy)``."""
    v = state[2:4]
    speed = float(np.hypot(v[0], v[1]))
    if speed == 0.0:
        return np.zeros(2)
    remaining = max(speed - decel * (t - t0), 0.0)
    return v * (remaining / speed)


def impacts(result: ShotResult) -> list[tuple[int, float, list[int], NDArray, NDArray]]:
    """Each ball-ball impact with the velocities of the balls it changed, before and after.

    An impact usually changes its two balls; a sticking impact changes its whole cluster.

    Returns:
        Tuples ``(event_index, time, balls, before (B, 2), after (B, 2))``.
    """
    return [(k, t, balls, before, after) for k, t, balls, before, after, _ in _impacts(result)]


def _impacts(result: ShotResult) -> list[tuple[int, float, list[int], NDArray, NDArray, list]]:
    """:func:`impacts`, each with the segment rows the balls moved on before the impact."""
    ball, seg_t, state, _ = result.segments
    latest = {int(b): r for r, b in enumerate(ball[: result.n_balls])}
    bounds = np.append(result.event_first_segment, ball.shape[0])
    n_checked = result.n_events - 1 if result.hit_event_cap else result.n_events
    out = []
    decel = result._deceleration
    spin = spin_invariants.is_spin(result)
    # At the cap, the rows after the last event's are the balls stopped by the cap.
    for k, (t, kind) in enumerate(zip(result.event_times, result.event_kinds, strict=True)):
        if k >= n_checked:
            break
        rows = range(bounds[k], bounds[k + 1])
        if kind == 1:
            balls = [int(ball[r]) for r in rows]
            before = np.array(
                [
                    spin_invariants.velocity_at(state[latest[b]], seg_t[latest[b]], t)
                    if spin
                    else _velocity(state[latest[b]], seg_t[latest[b]], t, decel)
                    for b in balls
                ]
            )
            after = np.array([state[r, 2:4] for r in rows])
            out.append((k, float(t), balls, before, after, [latest[b] for b in balls]))
        for r in rows:
            latest[int(ball[r])] = r
    return out


def _rail_impulse_allowed(
    table: Table, positions: NDArray, p0: NDArray, dp: NDArray, slack: float
) -> bool:
    """Whether ``dp`` is an impulse the rails touched by a lump at ``positions`` can give.

    Each touched rail pushes only out of itself, by at most ``(1 + e_cushion)`` times the
    lump's momentum into it: per axis, the change must point away from a touched rail and
    not exceed that bound (``slack`` absorbs rounding).
    """
    r, tol = table.ball_radius, CONTACT_TOL
    x, y = positions[:, 0], positions[:, 1]
    bound = (1.0 + table.e_cushion) * np.abs(p0) + slack
    low = (x <= r + tol).any(), (y <= r + tol).any()  # rails x = R, y = R push to +
    high = (x >= table.length - r - tol).any(), (y >= table.width - r - tol).any()
    for axis in range(2):
        push = dp[axis]
        if abs(push) <= slack:
            continue
        if (push > 0.0 and not low[axis]) or (push < 0.0 and not high[axis]):
            return False
        if abs(push) > bound[axis]:
            return False
    return True


def _contact_normals(table: Table, positions: NDArray) -> list[NDArray]:
    """Unit normals, out of each contact, of the rails, facings and points a lump touches.

    Derived from the table's own geometry (``Table.jaws``), not from the kernels' rows: a
    rail at its line, a facing or a point at ``R`` (up to ``CONTACT_TOL``) from the ball's
    centre.
    """
    r, tol = table.ball_radius, CONTACT_TOL
    normals = []
    for p in positions:
        for coord, line, n in (
            (p[0], r, (1.0, 0.0)),
            (p[0], table.length - r, (-1.0, 0.0)),
            (p[1], r, (0.0, 1.0)),
            (p[1], table.width - r, (0.0, -1.0)),
        ):
            if abs(coord - line) <= tol:
                normals.append(np.array(n))
        for jaw in table.jaws:
            for side in range(2):
                c = jaw.tip_centres[side]
                d = float(np.hypot(*(p - c)))
                if 0.0 < d <= jaw.tip_radius + r + tol:
                    normals.append((p - c) / d)
                a, b = jaw.facings[side]
                u = b - a
                q = a + np.clip((p - a) @ u / (u @ u), 0.0, 1.0) * u  # nearest facing point
                d = float(np.hypot(*(p - q)))
                if 0.0 < d <= r + tol:
                    normals.append((p - q) / d)
    return normals


def _contact_impulse_allowed(
    table: Table, positions: NDArray, p0: NDArray, dp: NDArray, slack: float
) -> bool:
    """Whether ``dp`` is an impulse the contacts a lump at ``positions`` touches can give.

    Contacts only push out of themselves: ``dp`` must be a non-negative combination of one
    or two of their normals (in the plane, any vector of a cone of normals is one of two),
    and no larger than twice the lump's momentum (the lump's kinetic energy cannot rise).
    """
    if float(np.hypot(*dp)) > 2.0 * float(np.hypot(*p0)) + slack:
        return False
    normals = _contact_normals(table, positions)
    for n in normals:
        if abs(n[0] * dp[1] - n[1] * dp[0]) <= slack and n @ dp >= -slack:
            return True
    for a in range(len(normals)):
        for b in range(a + 1, len(normals)):
            basis = np.column_stack([normals[a], normals[b]])
            if abs(np.linalg.det(basis)) < 1e-12:
                continue
            lam = np.linalg.solve(basis, dp)
            if lam.min() >= -slack:
                return True
    return False


def _cone_distance(d: NDArray, normals: list[NDArray]) -> float:
    """Distance from ``d`` to the cone of non-negative combinations of ``normals`` (2D)."""
    best = float(np.hypot(*d))
    for n in normals:
        best = min(best, float(np.hypot(*(d - max(0.0, float(n @ d)) * n))))
    for a in range(len(normals)):
        for b in range(a + 1, len(normals)):
            basis = np.column_stack([normals[a], normals[b]])
            if abs(np.linalg.det(basis)) >= 1e-12 and np.linalg.solve(basis, d).min() >= 0.0:
                return 0.0  # inside the cone of the pair
    return best


def check_momentum(result: ShotResult, masses: ArrayLike, table: Table | None = None) -> list[str]:
    """P: every ball-ball impact conserves the momentum of the balls it changed.

    Up to rounding, and up to the documented rules: a ball that an impact leaves slower than
    ``REST_SPEED`` is at rest, which may happen twice to a ball of a sticking impact (once for
    the pair, once for its cluster), so at most ``2 * mass * REST_SPEED`` per ball; a sticking
    lump that touches a rail meets it as one body, so the rail may change the lump's
    momentum by an impulse out of the rail, at most ``(1 + e_cushion)`` times the lump's
    momentum into it (any direction if ``table`` is not given, within ``ZENO_SPEED * mass``); a
    sticking lump against a jaw loses its velocity into it if below ``ZENO_SPEED``; and a lump
    wedged between jaws and rails, pressing slowly into all of them, stops (see
    :func:`pool_env.sim.kernels.roll.jaw_impacts.unpress_lump`). On the spin level a sticking
    lump ends its balls' slides at once and rolls on together, so the cloth's friction changes its
    momentum (by at most :func:`~pool_env.testing.spin_invariants.lump_cloth_impulse`), and
    then meets the cushions it touches as one body (impulses out of them). With Mathavan's
    ball-ball model the cloth's friction acts within a pair impact (by at most
    :func:`~pool_env.testing.spin_invariants.mathavan_cloth_impulse`).
    """
    m = np.asarray(masses, dtype=np.float64)
    problems = []
    ball, _, state, _ = result.segments
    bounds = np.append(result.event_first_segment, ball.shape[0])
    spin = spin_invariants.is_spin(result)
    for k, t, balls, before, after, rows in _impacts(result):
        mb = m[balls][:, None]
        p0 = (mb * before).sum(axis=0)
        p1 = (mb * after).sum(axis=0)
        scale = float((mb * np.abs(before)).sum()) + 1e-300
        allowed = MOMENTUM_RTOL * scale + 2.0 * REST_SPEED * float(mb.sum())
        if np.abs(p1 - p0).max() <= allowed:
            continue
        if spin and table is not None and table.ball_model == "mathavan" and len(balls) == 2:
            bound = spin_invariants.mathavan_cloth_impulse(table, mb, before, after)
            if np.abs(p1 - p0).max() <= allowed + bound:  # the cloth's friction in the impact
                continue
        if len(balls) > 1 and np.all(after == after[0]):  # a sticking lump at a rail or jaw
            change = float(np.abs(p1 - p0).max())
            if change <= allowed + ZENO_SPEED * float(mb.sum()):  # a slow normal speed taken
                continue
            if np.all(after == 0.0) and change <= allowed + float(np.abs(p0).max()):
                continue  # wedged between jaws and rails, the lump stops
            if spin and table is not None:
                # The slides' cloth friction, taken at once, then the contacts the lump
                # touches, met as one body (impulses out of them).
                bound = spin_invariants.lump_cloth_impulse(table, result, rows, t, m[balls])
                normals = _contact_normals(table, state[bounds[k] : bounds[k + 1], 0:2])
                if _cone_distance(p1 - p0, normals) <= allowed + bound:
                    continue
            at = state[bounds[k] : bounds[k + 1], 0:2]
            if table is not None and _rail_impulse_allowed(table, at, p0, p1 - p0, allowed):
                continue
            if (
                table is not None
                and table.jaws
                and _contact_impulse_allowed(table, at, p0, p1 - p0, allowed)
            ):
                continue
        problems.append(f"P: impact {k} (t={t}, balls {balls}) momentum {p0} -> {p1}")
    return problems


def _energy_after_each_event(result: ShotResult, masses: NDArray) -> NDArray:
    """Kinetic energy at t = 0 and just after each event (one pass over the log)."""
    ball, seg_t, state, _ = result.segments
    n = result.n_balls
    decel = result._deceleration
    rows = np.arange(n)  # each ball's current anchor row
    bounds = np.append(result.event_first_segment, ball.shape[0])
    energy = np.empty(result.n_events + 1)

    def total(t: float) -> float:
        v = state[rows, 2:4]
        speed = np.hypot(v[:, 0], v[:, 1])
        left = np.clip(speed - decel * (t - seg_t[rows]), 0.0, None)
        scale = np.divide(left, speed, out=np.zeros_like(speed), where=speed > 0)
        return float(0.5 * (masses * (speed * scale) ** 2).sum())

    energy[0] = total(0.0)
    for k, t in enumerate(result.event_times):
        for r in range(bounds[k], bounds[k + 1]):
            rows[ball[r]] = r
        energy[k + 1] = total(float(t))
    return energy


def check_energy(result: ShotResult, masses: ArrayLike, table: Table | None = None) -> list[str]:
    """E: kinetic energy, taken just after each event, never increases.

    On the spin level the energy includes the spin's (``table`` is then required).
    """
    m = np.asarray(masses, dtype=np.float64)
    if spin_invariants.is_spin(result):
        if table is None:
            raise ValueError("check_energy needs the table of a spin-level result")
        energy = spin_invariants.energy_after_each_event(table, result, m)
    else:
        energy = _energy_after_each_event(result, m)
    times = np.concatenate([[0.0], result.event_times])
    rises = np.flatnonzero(np.diff(energy) > ENERGY_RTOL * max(energy[0], 1e-300))
    return [
        f"E: kinetic energy rises from {energy[k]} to {energy[k + 1]} at t={times[k + 1]}"
        for k in rises
    ]


def check_geometry(
    table: Table, result: ShotResult, samples: int = 2000, tol: float = GEOMETRY_TOL
) -> list[str]:
    """G: no overlap beyond ``tol`` and nothing outside the playing region.

    Checked at every event time, at rest, and at ``samples`` evenly spaced instants.
    """
    times = np.unique(
        np.concatenate(
            [[0.0, result.duration], result.event_times, np.linspace(0, result.duration, samples)]
        )
    )
    pos, potted = result.positions_at_many(times)
    r = table.ball_radius
    on = ~potted
    flat = pos.reshape(-1, 2)
    codes, _ = locate_many(
        np.ascontiguousarray(flat[:, 0]),
        np.ascontiguousarray(flat[:, 1]),
        table.params,
        table.pocket_geometry,
        tol,
    )
    # Entering a capture circle pots a ball, so only leaving the region is a violation.
    codes = codes.reshape(potted.shape)
    outside = on & (codes != LOC_FREE) & (codes != LOC_CIRCLE)
    escapes = [
        f"G: ball {b} outside the playing region at t={times[k]}: {pos[k, b].tolist()}"
        for k, b in zip(*np.nonzero(outside), strict=True)
    ]
    overlaps = []
    n = result.n_balls
    if n > 1:
        iu, ju = np.triu_indices(n, 1)
        dist = np.hypot(*(pos[:, ju] - pos[:, iu]).transpose(2, 0, 1))
        bad = on[:, iu] & on[:, ju] & (dist < 2 * r - tol)
        overlaps = [
            f"G: balls {iu[p]},{ju[p]} overlap by {2 * r - dist[k, p]:.3g} m at t={times[k]}"
            for k, p in zip(*np.nonzero(bad), strict=True)
        ]
    return escapes[:10] + overlaps[:10]


def check_termination(result: ShotResult) -> list[str]:
    """T: the shot came to rest without hitting the event cap."""
    return ["T: the shot hit the event cap"] if result.hit_event_cap else []


def check_order(result: ShotResult) -> list[str]:
    """O: event times and trajectory rows come in chronological order."""
    problems = []
    for name, times in (("event", result.event_times), ("segment", result.segments[1])):
        back = np.flatnonzero(np.diff(times) < 0.0)
        problems += [f"O: {name} {k + 1} at t={times[k + 1]} before t={times[k]}" for k in back]
    return problems[:10]


def check_shot(
    table: Table, result: ShotResult, masses: ArrayLike | None = None, samples: int = 2000
) -> list[str]:
    """All of G, P, E, T and O for one recorded shot, and M on the spin level."""
    m = np.full(result.n_balls, table.ball_mass) if masses is None else np.asarray(masses)
    problems = (
        check_termination(result)
        + check_order(result)
        + check_geometry(table, result, samples)
        + check_momentum(result, m, table)
        + check_energy(result, m, table)
    )
    if spin_invariants.is_spin(result):
        problems += spin_invariants.check_motion(table, result)
    return problems


def check_spin_energy(
    table: Table, result: SpinShotResult, masses: ArrayLike | None = None
) -> list[str]:
    """E on the spin level alone: :func:`check_energy` with the table's ball mass by default."""
    m = np.full(result.n_balls, table.ball_mass) if masses is None else masses
    return check_energy(result, m, table)
