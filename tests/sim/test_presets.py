"""``Table.preset("snooker")`` and ``Table.preset("carom")``: values, sizes, pockets.

The values are the sourced ones of :mod:`pool_env.sim.presets` (WPBSA, UMB, Mathavan et al.
2010, pooltool 0.6.0); the snooker pockets are measured from the built ``Table.jaws`` and,
where the bench's pooltool virtualenv exists, held against the cushion segments pooltool
0.6.0 builds from its ``SnookerTableSpecs``.
"""

from __future__ import annotations

import json
import math
import subprocess

import numpy as np
import pytest

from bench.engines.pooltool_engine import pooltool_python
from pool_env import Table
from pool_env.interop.pooltool import xy_from_pooltool
from pool_env.sim.table import SPIN_ONLY

INCH = 0.0254
SNOOKER = {  # WPBSA sizes; pooltool's ball mass; Mathavan et al. 2010 (spin level)
    "length": 3.569,
    "width": 1.778,
    "ball_radius": 0.02625,
    "ball_mass": 0.140,
    "mu_roll": 0.01,
    "mu_slide": 0.212,
    "cushion_friction": 0.14,
    "cushion_height": 0.03675,
    "e_ball": 0.95,
    "e_cushion": 0.65,
}
CAROM = {  # UMB sizes; pooltool's BILLIARD_GENERIC mass and cushion friction
    "length": 2.84,
    "width": 1.42,
    "ball_radius": 0.03075,
    "ball_mass": 0.210,
    "cushion_height": 0.037,
    "cushion_friction": 0.15,
}


def test_the_snooker_preset_holds_its_values():
    table = Table.preset("snooker")
    for name, value in SNOOKER.items():
        assert getattr(table, name) == pytest.approx(value, rel=1e-15, abs=0), name
    assert (table.pocket_model, table.model) == ("jaws", "spin")


def test_the_carom_preset_holds_its_values():
    table = Table.preset("carom")
    for name, value in CAROM.items():
        assert getattr(table, name) == pytest.approx(value, rel=1e-15, abs=0), name
    assert table.model == "spin"


def test_the_sizes_are_inside_the_wpbsa_and_umb_rules():
    snooker, carom = Table.preset("snooker"), Table.preset("carom")
    # WPBSA 1(a): 11 ft 8.5 in x 5 ft 10 in, +/- 0.5 in; 2: balls of 52.5 mm (+0.05 mm).
    assert abs(snooker.length - 140.5 * INCH) <= 0.5 * INCH
    assert abs(snooker.width - 70.0 * INCH) <= 0.5 * INCH
    assert 0.0525 <= 2 * snooker.ball_radius <= 0.05255
    # UMB: 2.84 x 1.42 m, balls of 61-61.5 mm and 205-220 g, nose 37 +/- 1 mm.
    assert (carom.length, carom.width) == (2.84, 1.42)
    assert 0.061 <= 2 * carom.ball_radius <= 0.0615
    assert 0.205 <= carom.ball_mass <= 0.220
    assert abs(carom.cushion_height - 0.037) <= 0.001
    # The snooker cushion's contact at 7R/5, between the centre and the top of the ball.
    assert snooker.cushion_height == pytest.approx(1.4 * snooker.ball_radius, rel=1e-15)


def _line_distance(point, a, b) -> float:
    """Distance from ``point`` to the infinite line through ``a`` and ``b``."""
    d = (b - a) / np.hypot(*(b - a))
    q = point - a
    return abs(q[0] * d[1] - q[1] * d[0])


@pytest.mark.parametrize(
    ("k", "mouth", "tip"),
    [(0, 0.083, 4 * INCH), (1, 0.087, 2.5 * INCH), (2, 0.083, 4 * INCH),
     (3, 0.083, 4 * INCH), (4, 0.087, 2.5 * INCH), (5, 0.083, 4 * INCH)],
)  # fmt: skip
def test_snooker_pockets_measured_from_the_built_jaws(k: int, mouth: float, tip: float):
    """Mouth between the points, facings parallel to the axis, tips tangent to rail and facing."""
    table = Table.preset("snooker")
    jaw = table.jaws[k]
    assert np.hypot(*(jaw.points[1] - jaw.points[0])) == pytest.approx(mouth, abs=1e-15)
    assert jaw.tip_radius == pytest.approx(tip, abs=1e-15)
    (s0, e0), (s1, e1) = jaw.facings
    d0, d1 = (e0 - s0) / np.hypot(*(e0 - s0)), (e1 - s1) / np.hypot(*(e1 - s1))
    # Pocket angle 0: both facings run the same way, and the throat is the mouth wide.
    assert d0 @ d1 == pytest.approx(1.0, abs=1e-15)
    assert _line_distance(s1, s0, e0) == pytest.approx(mouth, abs=1e-14)
    for side in range(2):
        point, centre, start, end = jaw.points[side], jaw.tip_centres[side], *jaw.facings[side]
        rail_end = jaw.rail_ends[side]
        # Each point lies on its facing's line; the tip is tangent to that line and to the
        # rail's nose line (its tangent point on the rail is the rail's end).
        assert _line_distance(point, start, end) == pytest.approx(0.0, abs=1e-15)
        assert _line_distance(centre, start, end) == pytest.approx(tip, abs=1e-14)
        assert _line_distance(centre, point, rail_end) == pytest.approx(tip, abs=1e-14)
        assert np.hypot(*(rail_end - centre)) == pytest.approx(tip, abs=1e-14)
        assert np.hypot(*(start - centre)) == pytest.approx(tip, abs=1e-14)
        # The tip sits behind the nose: outside the playing rectangle.
        x, y = centre
        assert not (0.0 < x < table.length and 0.0 < y < table.width)


def test_the_snooker_jaws_are_round_down_to_the_fall_line():
    """The big round jaws reach past the fall line: a ball drops before any straight facing.

    Each tip meets its facing ``r / tan(cut / 2)`` behind the mouth (42 mm at a corner,
    63.5 mm at the centre), deeper than the fall line (36 mm, 24 mm): every jaw contact on
    this table is a round-jaw contact (a ``"point"`` event).
    """
    table = Table.preset("snooker")
    for jaw in table.jaws:
        fall = jaw.fall_line.mean(axis=0)
        for start, _ in jaw.facings:
            assert (start - fall) @ jaw.fall_normal < -0.005  # 5 mm and more behind it


def test_a_jaw_tables_capture_circles_are_its_own_mouths():
    """``table.pockets`` on a JawSpec table summarises *its* mouths, not the WPA ones.

    The games keep spotted balls clear of these circles (``pool_env.game.spots``).
    """
    table = Table.preset("snooker")
    r = table.ball_radius
    corner, side = math.hypot(r, 0.083 / math.sqrt(2.0)), math.hypot(2 * r, 0.087 / 2)
    np.testing.assert_allclose(table.pockets[:, 2], [corner, side, corner] * 2, rtol=1e-15)
    assert Table().pockets[0, 2] == pytest.approx(math.hypot(0.028575, 4.5 * INCH / 2**0.5))


def test_the_snooker_preset_makes_a_roll_table_too():
    """``model="roll"`` is allowed on snooker: the same table less its spin-only values."""
    spin, roll = Table.preset("snooker"), Table.preset("snooker", model="roll")
    assert roll.model == "roll"
    default = Table(model="roll", ball_radius=roll.ball_radius, ball_mass=roll.ball_mass)
    for name in SPIN_ONLY:
        assert getattr(roll, name) == getattr(default, name), name
    for name in ("length", "width", "ball_radius", "ball_mass", "mu_roll", "e_cushion"):
        assert getattr(roll, name) == getattr(spin, name), name
    np.testing.assert_array_equal(roll.pocket_geometry, spin.pocket_geometry)
    # A spin value given by the caller still means nothing on the roll level.
    with pytest.raises(ValueError, match=r"mu_slide=0\.3.*model='spin' only"):
        Table.preset("snooker", model="roll", mu_slide=0.3)


def test_the_carom_preset_is_pocketless_and_spin_only():
    table = Table.preset("carom")
    assert (table.pocket_model, table.pockets.shape, table.jaws) == ("none", (0, 3), ())
    assert table.n_pockets == 0
    np.testing.assert_array_equal(
        table.rails, [[(0, 0), (2.84, 0)], [(2.84, 0), (2.84, 1.42)],
                      [(2.84, 1.42), (0, 1.42)], [(0, 1.42), (0, 0)]],
    )  # fmt: skip
    with pytest.raises(ValueError, match=r"cushion_friction=0\.15.*model='spin' only"):
        Table.preset("carom", model="roll")


_PROBE = """
import json
import pooltool as pt
specs = pt.objects.SnookerTableSpecs(l=3.569, w=1.778)
segments = pt.Table.from_table_specs(specs).cushion_segments
print(json.dumps({
    "tips": {k: [list(s.center[:2]), s.radius] for k, s in segments.circular.items()},
    "lines": {k: [list(s.p1[:2]), list(s.p2[:2])] for k, s in segments.linear.items()},
}))
"""


def test_the_snooker_pockets_are_pooltools_shape(tmp_path):
    """The tip circles and facings pooltool 0.6.0 builds from ``SnookerTableSpecs``.

    pooltool's specs at the WPBSA size (its own default size is 3.5445 x 1.7465 m); every
    one of its 12 jaw circles is one of ours (centre and radius), and each of its 12 jaw
    facings lies on the line of one of ours.
    """
    python = pooltool_python()
    if python is None:
        pytest.skip("no pooltool virtualenv at .bench-venvs/pooltool (bench/setup_pooltool.sh)")
    run = subprocess.run(
        [str(python), "-c", _PROBE], capture_output=True, text=True, timeout=300,
        env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},  # pooltool writes ~/.config
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-2000:]
    theirs = json.loads(run.stdout.strip().splitlines()[-1])
    table = Table.preset("snooker")
    ours = [(c, j.tip_radius) for j in table.jaws for c in j.tip_centres]
    assert len(theirs["tips"]) == len(ours) == 12
    for centre, radius in theirs["tips"].values():
        xy = xy_from_pooltool([centre], table.width)[0]
        gaps = [np.hypot(*(xy - c)) + abs(radius - r) for c, r in ours]
        assert min(gaps) < 1e-12, (centre, radius)
    facings = [tuple(f) for j in table.jaws for f in j.facings]
    jaw_lines = [k for k in theirs["lines"] if k not in ("3", "6", "9", "12", "15", "18")]
    assert len(jaw_lines) == 12
    for key in jaw_lines:
        p1, p2 = xy_from_pooltool(theirs["lines"][key], table.width)
        gaps = [_line_distance(p1, s, e) + _line_distance(p2, s, e) for s, e in facings]
        assert min(gaps) < 1e-12, key
