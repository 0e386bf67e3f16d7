"""Smoke tests of the benchmark's engines: they integrate the same model as the simulator.

Physics assertions, not shape checks: as the step shrinks, the fixed-step integrator (and
pymunk, set up with the same model) must converge to the exact event-based result, at
first order in ``dt``.
"""

import itertools
import math

import numpy as np
import pytest

from bench.engines.fixed_step import simulate_fixed_step
from pool_env import Table, simulate

TABLE = Table(pockets="none")
# A 30-degree cut at 0.8 m/s on a pocketless table: one ball-ball impact, then cushions.
R = TABLE.ball_radius
OBJ = np.array([1.6, 0.7])
CUT = math.radians(30.0)
GHOST = OBJ - 2.0 * R * np.array([1.0, 0.0])
AIM = np.array([math.cos(CUT), math.sin(CUT)])
POSITIONS = np.array([GHOST - 0.8 * AIM, OBJ])
VELOCITIES = np.array([0.8 * AIM, [0.0, 0.0]])


def _exact():
    res = simulate(TABLE, POSITIONS, VELOCITIES)
    assert [(e.kind, e.i, e.j) for e in res.events if e.kind == "ball"] == [("ball", 0, 1)]
    return res.positions


def _fixed_error(dt: float) -> float:
    pos, _pocketed, _, capped, obj_vel, hits, _, _ = simulate_fixed_step(
        TABLE.params, TABLE.pockets, POSITIONS, VELOCITIES, np.full(2, TABLE.ball_mass), dt, 1
    )
    assert not capped
    assert hits[0, 1]
    # The object ball leaves along the line of centres at impact: +x for this cut.
    assert abs(math.degrees(math.atan2(obj_vel[1], obj_vel[0]))) < 2000.0 * dt + 1e-9
    return float(np.max(np.hypot(*(pos - _exact()).T)))


def test_fixed_step_converges_to_the_event_simulator_at_first_order():
    errors = [_fixed_error(dt) for dt in (1e-3, 1e-4, 1e-5)]
    # First order: each 10x smaller step cuts the error by roughly 10x (allow 4x-40x).
    for coarse, fine in itertools.pairwise(errors):
        assert 4.0 < coarse / fine < 40.0
    assert errors[2] < 1e-4


def test_fixed_step_conserves_momentum_and_restitution_in_a_head_on_impact():
    table = Table(pockets="none", e_ball=0.9)
    pos = np.array([[0.5, 0.6], [0.8, 0.6]])
    vel = np.array([[2.0, 0.0], [0.0, 0.0]])
    dt = 1e-5
    # Stop just after the impact: momentum 0.34 kg m/s split by restitution 0.9.
    out = simulate_fixed_step(
        table.params, table.pockets, pos, vel, np.full(2, 0.17), dt, 1, max_time=0.2
    )
    v_obj = out[4][0]
    v_at_impact = math.sqrt(2.0**2 - 2.0 * table.deceleration * (0.3 - 2.0 * R))
    assert v_obj == pytest.approx(v_at_impact * (1.0 + 0.9) / 2.0, rel=1e-3)


def test_pymunk_engine_converges_to_the_event_simulator():
    pytest.importorskip("pymunk")
    from bench.engines.pymunk_engine import simulate_pymunk

    exact = _exact()
    errors = []
    for dt in (1e-3, 1e-4):
        res = simulate_pymunk(TABLE, POSITIONS, VELOCITIES, dt=dt, obj=1)
        assert not res.capped
        assert (0, 1) in res.hits
        errors.append(float(np.max(np.hypot(*(res.positions - exact).T))))
    assert errors[1] < errors[0] / 4.0
    assert errors[1] < 2e-3


def test_the_reference_cache_is_keyed_by_every_module_of_the_reference(tmp_path) -> None:
    """The on-disk cache names its file by the reference package's sources, all of them."""
    import shutil

    from bench.errors import REFERENCE_SOURCE, ReferenceCache, reference_fingerprint

    modules = sorted(REFERENCE_SOURCE.glob("*.py"))
    assert len(modules) > 1  # a package, not the old single module
    copy = tmp_path / "reference"
    shutil.copytree(REFERENCE_SOURCE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    assert reference_fingerprint(copy) == reference_fingerprint()
    for module in sorted(copy.glob("*.py")):  # an edit to any one module changes the key
        before = reference_fingerprint(copy)
        module.write_bytes(module.read_bytes() + b"\n# edited\n")
        assert reference_fingerprint(copy) != before
    ReferenceCache(tmp_path / "cache")  # builds on the package as it is
    assert [p.name for p in (tmp_path / "cache").iterdir()] == []  # written on first use
