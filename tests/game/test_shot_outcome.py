"""What the rules read from a shot: first contact, rails after contact, pockets and their order.

Closed-form scenes on a carom table (no pocket to end a path early) and on the standard
table, each on the recorded, the unrecorded and the batched path; and, on random shots, the
kernel's tallies against a replay of the event log in Python.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, shoot, simulate
from pool_env.sim.batch import simulate_batch
from pool_env.sim.layouts import break_scene
from pool_env.sim.result import CUSHION_KINDS
from pool_env.testing.scenes_random import random_layout
from tests.helpers_sim import speed_after

R = Table().ball_radius


def _all_paths(table: Table, positions, angle: float, speed: float):
    """The recorded result, then the unrecorded one and the batched one as the same fields."""
    recorded = shoot(table, positions, angle, speed)
    unrecorded = shoot(table, positions, angle, speed, record=False)
    pos = np.asarray(positions, dtype=float)[None]
    vel = np.zeros_like(pos)
    vel[0, 0] = speed * math.cos(angle), speed * math.sin(angle)
    batch = simulate_batch(table, pos, vel)
    batched = {
        "first_hit": batch.first_hit[0],
        "cushions_after_contact": batch.cushions_after_contact[0],
        "pocketed": batch.pocketed[0],
        "pocket_order": batch.pocket_order[0],
    }
    return recorded, [recorded, unrecorded, batched]


def _field(result, name: str) -> list[int]:
    value = result[name] if isinstance(result, dict) else getattr(result, name)
    return np.asarray(value).tolist()


def _assert_fields(results, **expected) -> None:
    for result in results:
        for name, want in expected.items():
            assert _field(result, name) == want, name


def test_cue_drives_the_object_ball_to_one_rail(carom: Table) -> None:
    """A full hit sends ball 1 to the far rail once; the nearly stopped cue ball to none.

    Closed form: equal masses, so ball 1 leaves at ``(1 + e) / 2`` of the cue's impact
    speed and the cue keeps ``(1 - e) / 2``; the speed is chosen so that ball 1 reaches the
    rail at ``x = L - R`` and, slowed by ``e_cushion``, stops before travelling back to it.
    """
    y = carom.width / 2
    cue, obj = (0.6, y), (1.6, y)
    speed = 0.7
    v_hit = speed_after(carom, speed, obj[0] - cue[0] - 2 * R)
    u1 = (1 + carom.e_ball) / 2 * v_hit
    to_rail = carom.length - R - obj[0]
    assert u1**2 > 2 * carom.deceleration * to_rail  # reaches the rail
    back = (carom.e_cushion**2) * (u1**2 - 2 * carom.deceleration * to_rail)
    assert back / (2 * carom.deceleration) < to_rail  # and stops before its start point
    cue_left = (1 - carom.e_ball) / 2 * v_hit
    assert cue_left**2 / (2 * carom.deceleration) < to_rail  # the cue never meets it again

    recorded, results = _all_paths(carom, [cue, obj], 0.0, speed)
    assert recorded.first_contact == (0, 1)
    _assert_fields(
        results,
        first_hit=[1, 0],
        cushions_after_contact=[0, 1],
        pocketed=[-1, -1],
        pocket_order=[-1, -1],
    )


def test_cue_hits_nothing(carom: Table) -> None:
    """The cue ball misses ball 1 and bounces off rails: no contact, so no rail counts."""
    y = carom.width / 2
    recorded, results = _all_paths(carom, [(0.6, y), (1.6, y + 4 * R)], 0.0, 3.0)
    assert recorded.first_contact is None
    assert sum(e.kind == "cushion" and e.i == 0 for e in recorded.events) >= 2
    _assert_fields(results, first_hit=[-1, -1], cushions_after_contact=[0, 0])


def test_rail_before_first_contact_is_not_counted(carom: Table) -> None:
    """Cue ball straight down into the rail, back up through its start, full on ball 1.

    The cue's rail impact comes before the contact and is not counted; ball 1 is then
    driven up into the top rail: one rail after contact.
    """
    x = 1.0
    cue, obj = (x, 0.3), (x, 0.75)
    speed = 2.5
    recorded, results = _all_paths(carom, [cue, obj], -math.pi / 2, speed)
    kinds = [(e.kind, e.i, e.j) for e in recorded.events if e.kind != "stop"]
    assert kinds[0] == ("cushion", 0, 2)  # the bottom rail, y = R
    assert kinds[1] == ("ball", 0, 1)
    assert kinds[2] == ("cushion", 1, 3)  # ball 1 into the top rail, y = W - R
    # Closed form of the setup: the cue reaches ball 1 and ball 1 reaches the top rail.
    a = carom.deceleration
    v_rail = speed_after(carom, speed, cue[1] - R)
    v_hit = math.sqrt((carom.e_cushion * v_rail) ** 2 - 2 * a * (obj[1] - 2 * R - R))
    u1 = (1 + carom.e_ball) / 2 * v_hit
    assert u1**2 > 2 * a * (carom.width - R - obj[1])
    want_cushions = [sum(1 for k, i, _ in kinds[2:] if k == "cushion" and i == b) for b in range(2)]
    assert want_cushions[1] >= 1
    _assert_fields(results, first_hit=[1, 0], cushions_after_contact=want_cushions)


def test_pockets_and_their_order(table: Table) -> None:
    """Two balls rolled along the bottom rail line into the two bottom corners.

    Ball 0 starts 0.3 m from the left corner's mouth, ball 1 0.6 m from the right one at
    the same speed, so ball 0 drops first (closed form: less distance, same speed).
    """
    y = R
    positions = [(0.35, y), (table.length - 0.65, y), (table.length / 2 + 0.2, 0.6)]
    velocities = [(-2.0, 0.0), (2.0, 0.0), (0.0, 0.0)]
    for record in (True, False):
        result = simulate(table, positions, velocities, record=record)
        assert result.pocketed.tolist() == [0, 2, -1]
        assert result.pocket_order.tolist() == [0, 1, -1]
        assert result.first_hit.tolist() == [-1, -1, -1]


def _replay(result, n: int) -> tuple[list[int], list[int], list[int]]:
    """The tallies from the recorded event log, in plain Python (the reference)."""
    first_hit, cushions, order = [-1] * n, [0] * n, [-1] * n
    contact, dropped = False, 0
    for event in result.events:
        if event.kind == "ball":
            contact = True
            for a, b in ((event.i, event.j), (event.j, event.i)):
                if first_hit[a] < 0:
                    first_hit[a] = b
        elif event.kind in CUSHION_KINDS and contact:  # rails, jaw facings and points
            cushions[event.i] += 1
        elif event.kind == "pocket":
            order[event.i] = dropped
            dropped += 1
    return first_hit, cushions, order


@pytest.mark.parametrize("n_balls", [2, 5, 10])
def test_tallies_match_a_replay_of_the_event_log(table: Table, n_balls: int) -> None:
    rng = np.random.default_rng(n_balls)
    shots = []
    for _ in range(30):
        pos = random_layout(table, n_balls, rng)
        d = pos[1] - pos[0]
        angle = float(np.arctan2(d[1], d[0]) + rng.uniform(-0.1, 0.1))
        shots.append((pos, angle, float(rng.uniform(0.5, 8.0))))
    if n_balls == 10:
        shots.append((break_scene(table, "nine"), 0.0, 8.0))
    for pos, angle, speed in shots:
        recorded = shoot(table, pos, angle, speed)
        unrecorded = shoot(table, pos, angle, speed, record=False)
        first_hit, cushions, order = _replay(recorded, len(pos))
        for result in (recorded, unrecorded):
            assert result.first_hit.tolist() == first_hit
            assert result.cushions_after_contact.tolist() == cushions
            assert result.pocket_order.tolist() == order
            assert result.first_contact == recorded.first_contact
        if recorded.first_contact is not None:
            i, j = recorded.first_contact
            assert first_hit[i] == j and first_hit[j] == i


def test_batch_maps_tallies_to_table_indices(table: Table) -> None:
    """With inactive balls, the batch reports ball numbers of the full table."""
    rng = np.random.default_rng(5)
    n_tables, n_balls = 30, 7
    pos = np.array([random_layout(table, n_balls, rng) for _ in range(n_tables)])
    active = rng.random((n_tables, n_balls)) < 0.7
    active[:, 0] = True
    angle = rng.uniform(-np.pi, np.pi, n_tables)
    speed = rng.uniform(1.0, 8.0, n_tables)
    vel = np.zeros_like(pos)
    vel[:, 0] = np.stack([speed * np.cos(angle), speed * np.sin(angle)], axis=1)
    for parallel in (False, True):
        batch = simulate_batch(table, pos, vel, active=active, parallel=parallel)
        for b in range(n_tables):
            idx = np.flatnonzero(active[b])
            single = shoot(table, pos[b][idx], angle[b], speed[b], record=False)
            hits = [int(idx[h]) if h >= 0 else -1 for h in single.first_hit]
            assert batch.first_hit[b][idx].tolist() == hits
            assert batch.cushions_after_contact[b][idx].tolist() == (
                single.cushions_after_contact.tolist()
            )
            assert batch.pocket_order[b][idx].tolist() == single.pocket_order.tolist()
            off = ~active[b]
            assert np.all(batch.first_hit[b][off] == -1)
            assert np.all(batch.pocket_order[b][off] == -1)
            assert np.all(batch.cushions_after_contact[b][off] == 0)
