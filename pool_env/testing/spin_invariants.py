"""Invariant checks of the spin level (``Table(model="spin")``), on a recorded shot.

:mod:`pool_env.testing.invariants` dispatches here for a
:class:`~pool_env.sim.result.SpinShotResult`. The kinematics are written out again from the
equations of motion (``docs/sources.md``, pooltool 0.6.0), not imported from the kernels: a
check must not follow the code it checks when that code changes.

* Each segment row ``(x, y, vx, vy, wx, wy, wz, ax, ay)`` anchors a ball in one motion state.
  A *rolling* row has the rolling spin ``wx = -vy / R``, ``wy = vx / R`` exactly (the anchor
  writes it so); a *sliding* row has a slip ``u = (vx - R wy, vy + R wx) != 0``; a still or
  spinning row has no velocity and no surface spin.
* Between its rows a ball moves with the row's constant acceleration: sliding
  ``|acc| = mu_slide g`` against the slip, whose spin changes by ``(5 / 2R) tau (ay, -ax)``;
  rolling ``|acc| = mu_roll g`` against the velocity; ``wz`` falls at ``spin_decel``.
* Energy: translational plus rotational, ``m |v|^2 / 2 + I |w|^2 / 2`` with
  ``I = (2/5) m R^2``.

The motion check **M** asks of every row: the acceleration its state prescribes; that the
ball's next row comes no later than the row's own transition (slip, speed or spin used up);
that each transition event (``slide_roll``, ``stop``, ``roll_spin``, ``spin_stop``) happens
where the previous row's slip, speed or spin reached zero and writes the state it names;
and that a shot that ends under the cap ends with every ball still or potted, without spin.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from pool_env.sim.kernels.spin.collide import ALCIATORE_A, ALCIATORE_B
from pool_env.sim.result import KIND_NAMES, SpinShotResult
from pool_env.sim.table import Table

# Motion states of the contract (pool_env.sim.kernels.spin.state), written here on purpose.
STATIONARY, POTTED = 0, 4
SLIDE_ROLL, STOP, ROLL_SPIN, SPIN_STOP = (
    KIND_NAMES.index(k) for k in ("slide_roll", "stop", "roll_spin", "spin_stop")
)
ACC_RTOL = 1e-9  # relative: an acceleration's magnitude and direction
# A transition's quantity (slip, speed, spin) at its event: rounding of the event time only.
TRANSITION_RTOL = 1e-9
# A row lasts at most its own transition time, up to the rounding of event times.
DURATION_RTOL = 1e-9
REST_SPEED = 1e-9  # m/s: slower (also at the surface, R |w|) is at rest (the documented rule)


def is_spin(result: object) -> bool:
    """Whether ``result`` is a spin-level result (nine-column segment states)."""
    return isinstance(result, SpinShotResult)


def _rolling_rows(state: NDArray, radius: float) -> NDArray[np.bool_]:
    """Rows anchored rolling: the exact rolling spin and a non-zero velocity."""
    moving = (state[:, 2] != 0.0) | (state[:, 3] != 0.0)
    return moving & (state[:, 4] == -state[:, 3] / radius) & (state[:, 5] == state[:, 2] / radius)


def motion_at(
    table: Table, state: NDArray, tau: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Velocities ``(K, 2)`` and angular velocities ``(K, 3)`` of rows ``state`` after ``tau``.

    ``tau`` (``(K,)``, seconds since each row's anchor) must not pass the row's transition.
    """
    r = table.ball_radius
    v = state[:, 2:4] + state[:, 7:9] * tau[:, None]
    w = np.empty((state.shape[0], 3))
    rolling = _rolling_rows(state, r)
    k = 2.5 / r * tau
    w[:, 0] = np.where(rolling, -v[:, 1] / r, state[:, 4] + k * state[:, 8])
    w[:, 1] = np.where(rolling, v[:, 0] / r, state[:, 5] - k * state[:, 7])
    left = np.clip(np.abs(state[:, 6]) - table.spin_decel * tau, 0.0, None)
    w[:, 2] = np.sign(state[:, 6]) * left
    return v, w


def rows_energy(table: Table, state: NDArray, tau: NDArray, masses: NDArray) -> float:
    """Translational plus rotational kinetic energy of rows ``state`` after ``tau`` (J)."""
    v, w = motion_at(table, state, tau)
    r = table.ball_radius
    return float(
        (0.5 * masses * (v * v).sum(axis=1)).sum()
        + (0.2 * masses * r * r * (w * w).sum(axis=1)).sum()
    )


def velocity_at(state_row: NDArray, t0: float, t: float) -> NDArray[np.float64]:
    """In-plane velocity at ``t`` of a spin row anchored at ``t0``."""
    return state_row[2:4] + state_row[7:9] * (t - t0)


def _transition_time(table: Table, s: NDArray) -> tuple[float, float]:
    """A row's own transition time and the quantity that runs out then (slip, speed, spin)."""
    r = table.ball_radius
    v = float(np.hypot(s[2], s[3]))
    if v == 0.0 and s[4] == 0.0 and s[5] == 0.0:
        if s[6] == 0.0:
            return np.inf, 0.0  # at rest for good
        return abs(s[6]) / table.spin_decel, abs(s[6])
    if s[4] == -s[3] / r and s[5] == s[2] / r:
        return v / (table.mu_roll * table.g), v
    slip = float(np.hypot(s[2] - r * s[5], s[3] + r * s[4]))
    return slip / (3.5 * table.mu_slide * table.g), slip


def _row_problems(table: Table, s: NDArray, potted: bool) -> list[str]:
    """The acceleration a row's state prescribes, or a still potted row."""
    r = table.ball_radius
    acc = np.asarray(s[7:9], dtype=np.float64)
    if potted:
        return [] if not np.any(s[2:9]) else ["a potted ball moves"]
    v = np.asarray(s[2:4], dtype=np.float64)
    if not np.any(v) and s[4] == 0.0 and s[5] == 0.0:
        return [] if not np.any(acc) else ["a still ball accelerates"]
    if s[4] == -s[3] / r and s[5] == s[2] / r:
        want, against, name = table.mu_roll * table.g, v, "rolling"
    else:
        want, name = table.mu_slide * table.g, "sliding"
        against = np.array([s[2] - r * s[5], s[3] + r * s[4]])
    unit = against / np.hypot(*against)
    if np.hypot(*(acc + want * unit)) > ACC_RTOL * want:
        return [f"a {name} row accelerates at {acc.tolist()}, expected {(-want * unit).tolist()}"]
    return []


def check_motion(table: Table, result: SpinShotResult) -> list[str]:
    """M: motion states, their accelerations, transitions and the final state (see above)."""
    ball, seg_t, state, potted = result.segments
    problems: list[str] = []
    # The next row of the same ball, or the shot's end.
    following = np.full(ball.shape[0], result.duration)
    seen: dict[int, int] = {}
    for row in range(ball.shape[0] - 1, -1, -1):
        b = int(ball[row])
        if b in seen:
            following[row] = seg_t[seen[b]]
        seen[b] = row
    for row in range(ball.shape[0]):
        s = state[row]
        for p in _row_problems(table, s, bool(potted[row])):
            problems.append(f"M: row {row} (ball {ball[row]}, t={seg_t[row]}): {p}")
        if potted[row]:
            continue
        span = following[row] - seg_t[row]
        limit, _ = _transition_time(table, s)
        if span > limit * (1.0 + DURATION_RTOL) + 4.0 * np.spacing(following[row]):
            problems.append(
                f"M: ball {ball[row]} keeps the row of t={seg_t[row]} for {span} s, past its "
                f"transition after {limit} s"
            )
    problems += _transition_problems(table, result)
    if not result.hit_event_cap:
        states = result.motion_states
        if np.any((states != STATIONARY) & (states != POTTED)) or np.any(result.angular_velocities):
            problems.append(f"M: the shot ends with motion states {states.tolist()} or spin")
    return problems[:10]


def _transition_problems(table: Table, result: SpinShotResult) -> list[str]:
    """Each transition event happens where its quantity runs out and writes its state."""
    ball, seg_t, state, _ = result.segments
    r = table.ball_radius
    bounds = np.append(result.event_first_segment, ball.shape[0])
    latest = {int(b): row for row, b in enumerate(ball[: result.n_balls])}
    problems = []
    n_checked = result.n_events - 1 if result.hit_event_cap else result.n_events
    for k, (t, kind, i) in enumerate(
        zip(result.event_times, result.event_kinds, result.event_i, strict=True)
    ):
        if k >= n_checked:
            break  # at the cap, the last event's rows run on into the balls the cap stopped
        rows = range(bounds[k], bounds[k + 1])
        if kind in (SLIDE_ROLL, STOP, ROLL_SPIN, SPIN_STOP) and len(rows) == 1:
            before = state[latest[int(i)]]
            tau = np.array([t - seg_t[latest[int(i)]]])
            v, w = motion_at(table, before[None, :], tau)
            _, scale = _transition_time(table, before)
            after = state[rows[0]]
            if kind == SLIDE_ROLL:
                left = float(np.hypot(v[0, 0] - r * w[0, 1], v[0, 1] + r * w[0, 0]))
                # The slip is a difference of the ball's speeds: rounded relative to them,
                # at the anchor, at the event, and to the change in between.
                change = 3.5 * float(np.hypot(*before[7:9])) * float(tau[0])
                anchor = float(np.hypot(*before[2:4]) + r * np.hypot(*before[4:6]))
                scale += change + anchor + float(np.hypot(*v[0]) + r * np.hypot(*w[0, :2]))
                wrote = after[4] == -after[3] / r and after[5] == after[2] / r
            elif kind == SPIN_STOP:
                left, wrote = abs(w[0, 2]), not np.any(after[2:9])
            else:  # a rolling ball rests, still or spinning
                left = float(np.hypot(*v[0]))
                wrote = not np.any(after[2:6]) and not np.any(after[7:9])
                # A spin left slower than the rest speed at the surface rests as well.
                spins = abs(w[0, 2]) * r >= REST_SPEED
                wrote = wrote and (after[6] != 0.0) == (kind == ROLL_SPIN and spins)
            # The event time is rounded to ulp(t): the quantity runs on at its rate that long.
            rate = (
                table.spin_decel
                if kind == SPIN_STOP
                else float(np.hypot(*before[7:9])) * (3.5 if kind == SLIDE_ROLL else 1.0)
            )
            if left > TRANSITION_RTOL * scale + 8.0 * rate * np.spacing(t) or not wrote:
                problems.append(
                    f"M: {KIND_NAMES[kind]} of ball {i} at t={t}: {left} left of {scale}, "
                    f"state written {after.tolist()}"
                )
        for row in rows:
            latest[int(ball[row])] = row
    return problems


def energy_after_each_event(table: Table, result: SpinShotResult, masses: NDArray) -> NDArray:
    """Kinetic energy (translational and rotational) at t = 0 and just after each event."""
    ball, seg_t, state, _ = result.segments
    rows = np.arange(result.n_balls)
    bounds = np.append(result.event_first_segment, ball.shape[0])
    energy = np.empty(result.n_events + 1)
    energy[0] = rows_energy(table, state[rows], np.zeros(rows.shape[0]), masses)
    for k, t in enumerate(result.event_times):
        for r in range(bounds[k], bounds[k + 1]):
            rows[ball[r]] = r
        energy[k + 1] = rows_energy(table, state[rows], float(t) - seg_t[rows], masses)
    return energy


def lump_cloth_impulse(
    table: Table, result: SpinShotResult, rows: list[int], t: float, masses: NDArray
) -> float:
    """The largest cloth impulse a sticking lump may take when its slides end at once (N s).

    Each ball of the lump ends its slide at the natural-roll velocity ``v - (2/7) u``, so the
    cloth changes its momentum by ``(2/7) m |u|`` at most, with ``u`` the slip the impact left
    it (unseen in the log). The impact adds no energy, so with ``E`` the lump's kinetic
    energy before it and ``M`` its mass, ``sum m |u| <= sum m (|v| + R |w|) <=
    sqrt(M sum m (2 |v|^2 + 2 R^2 |w|^2)) <= sqrt(10 M E)``: the bound is
    ``(2/7) sqrt(10 M E)``.
    """
    _, seg_t, state, _ = result.segments
    idx = np.asarray(rows)
    energy = rows_energy(table, state[idx], t - seg_t[idx], masses)
    return 2.0 / 7.0 * float(np.sqrt(10.0 * masses.sum() * energy))


def mathavan_cloth_impulse(table: Table, masses: NDArray, before: NDArray, after: NDArray) -> float:
    """The largest cloth impulse a pair impact of Mathavan's model may take (N s).

    In Mathavan's model (:mod:`~pool_env.sim.kernels.spin.mathavan`) the pressed ball's
    cloth friction acts during the impact: at most ``k = mu_s mu_b`` times the normal impulse
    ``P`` (``mu_b`` the largest ball-ball friction). Each ball's momentum change along the line
    of centres is ``P`` less at most that friction, so ``P <= |dp_b| / (1 - k)`` for either
    ball ``b`` and the pair's momentum changes by at most ``k min_b |dp_b| / (1 - k)``.

    Args:
        table: A spin table with ``ball_model="mathavan"`` (``Table`` keeps ``k <= 1``).
        masses: The two balls' masses, shape ``(2,)`` or ``(2, 1)``.
        before: Their velocities before the impact, shape ``(2, 2)``.
        after: Their velocities after it.
    """
    friction = table.ball_friction
    mu_b = ALCIATORE_A + ALCIATORE_B if isinstance(friction, str) else float(friction)
    k = table.mu_slide * mu_b
    if k >= 1.0:
        return float("inf")
    change = np.linalg.norm(np.reshape(masses, (-1, 1)) * (after - before), axis=1)
    return k * float(change.min()) / (1.0 - k)
