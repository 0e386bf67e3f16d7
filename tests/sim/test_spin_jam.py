"""A ball wedged between two jaw facings on the spin level (issue 19, what remained: item 3).

The hard case: a corner throat cut steeper than regulation (``corner_cut`` 145-147 degrees,
a 0.2 m shelf) narrows to one ball's width before its fall line. Driven in, ball 0 ends
touching both facings. Each Han reflection sent it off one facing straight into the
other, and its spin, turned by each facing's friction, drove it back in: before the single
ball's jam rule (``spin_zeno.wedged_ball``) both scenes ran into the event cap (3,000
events, 2,990 of them jaw impacts at one or two instants). Now the ball is held there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pool_env import Table, simulate
from pool_env.sim.kernels.jaw_geometry import J_FACING0
from pool_env.sim.pockets import JawSpec
from pool_env.testing.invariants import check_geometry
from pool_env.testing.spin_invariants import energy_after_each_event

R = 0.028575

# (corner_cut, mouth - 4R, e_jaw, e_ball, positions, velocities, angular velocities, masses):
# found by a random search over such throats; each hit the cap before the rule.
SCENES = {
    "dead-facings": (
        146.90583150373388, 0.012838221051232383, 0.0, 0.0,
        [[0.087467373590637, 0.04485933153387653], [0.04485933153387653, 0.087467373590637]],
        [[-1.777601536532929, -1.326380156940067], [-0.5575239786900809, -0.5575239786900809]],
        [[70.37438901422202, 79.92977802069923, -17.759035206007766],
         [7.857949457828267, -59.076435118497635, -22.691951425478216]],
        [1.0, 0.6929668100453075],
    ),
    "lively-facings": (
        146.83175846961353, 0.017268649973281664, 0.19677724150574566, 0.04208777458734828,
        [[0.09001403328129454, 0.04544545817756504], [0.04544545817756504, 0.09001403328129454]],
        [[-1.7862995884052981, -1.9492739127371481], [-1.035264775574454, -1.035264775574454]],
        [[29.73664732838735, 19.833194350251446, -16.195229406710112],
         [27.489062875320787, 25.71638580091448, -36.02912694854835]],
        None,
    ),
}  # fmt: skip


def _facing_gaps(table: Table, p: np.ndarray) -> list[float]:
    """Distances of a centre from the two facing lines of pocket 0, less R."""
    gaps = []
    for start, end in table.jaws[0].facings:
        d = (end - start) / np.hypot(*(end - start))
        rel = p - start
        gaps.append(abs(rel[0] * d[1] - rel[1] * d[0]) - table.ball_radius)
    return gaps


@pytest.mark.parametrize("name", sorted(SCENES))
def test_a_ball_wedged_between_two_facings_is_held_there(name: str) -> None:
    cut, extra, e_jaw, e_ball, pos, vel, ang, masses = SCENES[name]
    spec = JawSpec(corner_mouth=4 * R + extra, corner_cut=cut, corner_shelf=0.2)
    table = Table(model="spin", pockets=spec, e_jaw=e_jaw, e_ball=e_ball)
    result = simulate(table, pos, vel, masses, max_events=3000, angular_velocities=ang)
    assert not result.hit_event_cap and not result.stopped_by_cap.any()
    assert result.n_events < 100  # it had 3,000 (the cap) before the rule
    assert result.pocketed.tolist() == [-1, -1]
    assert check_geometry(table, result) == []
    mass = np.full(2, table.ball_mass) if masses is None else np.asarray(masses)
    energy = energy_after_each_event(table, result, mass)
    assert np.all(np.diff(energy) <= 1e-12 * energy[0]), "the jam added energy"
    # The jam: at one of its jaw impacts ball 0 is held (velocity and rolling spin zero),
    # touching both facings (wedged, neither through one nor potted).
    jaw_times = {e.time for e in result.events if e.kind == "jaw" and e.i == 0}
    ball, t, state, _ = result.segments
    still = (ball == 0) & (np.hypot(state[:, 2], state[:, 3]) == 0.0)
    held = [r for r in np.flatnonzero(still) if float(t[r]) in jaw_times]
    assert held, "no jam at a jaw impact"
    np.testing.assert_array_equal(state[held[0], 4:6], 0.0)
    gaps = _facing_gaps(table, state[held[0], :2])
    assert max(abs(g) for g in gaps) < 1e-9, gaps
    assert math.isfinite(result.duration)


def test_the_jam_rule_leaves_one_facing_alone() -> None:
    """A ball meeting one facing of a regulation throat, spinning, is reflected (Han).

    One contact is never a wedge: the regulation throat is wider than a ball all the way to
    its fall line.
    """
    table = Table(model="spin")
    row = table.pocket_geometry[0]
    start, along, normal = (
        row[J_FACING0 : J_FACING0 + 2],
        row[J_FACING0 + 2 : J_FACING0 + 4],
        (row[J_FACING0 + 4 : J_FACING0 + 6]),
    )
    centre = start + 0.2 * row[J_FACING0 + 6] * along + (R + 0.01) * normal
    result = simulate(table, [centre], [-1.0 * normal], angular_velocities=[[0.0, 0.0, 30.0]])
    assert result.events[0].kind == "jaw"
    _, _, state, _ = result.segments
    row0 = result.event_first_segment[0]
    assert float(np.dot(state[row0, 2:4], normal)) > 0.1  # rebounds off it, not held
