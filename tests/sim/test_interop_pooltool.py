"""pool_env.interop.pooltool: the frame, aim, cue and parameter mappings, and round trips.

The mappings are plain functions, tested here without pooltool against closed forms and
their inverses (hypothesis). Where pooltool 0.6.0 is importable (``bash
bench/setup_pooltool.sh VENV`` then ``VENV/bin/python -m pip install -e .``), the
``System`` round trips run too, and a pooltool-native shot at pooltool's own defaults is
played by both simulators; elsewhere those tests skip, saying why.
"""

from __future__ import annotations

import importlib
import math
import os
import subprocess
import sys
from pathlib import Path
from types import ModuleType, SimpleNamespace
from typing import Any

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from pool_env import Table, shoot
from pool_env.extras import require
from pool_env.interop import pooltool as ip

ROOT = Path(__file__).resolve().parents[2]
ULP = 2.0**-52
M_CUE = ip.POOLTOOL_CUE_MASS

# pooltool 0.6.0's defaults (BallParams, CueSpecs), written out: the values a System
# carries when a pooltool user builds one without arguments.
PT_BALL = {
    "R": 0.028575,
    "m": 0.170097,
    "u_s": 0.2,
    "u_r": 0.01,
    "u_sp_proportionality": 10 * 2 / 5 / 9,
    "e_b": 0.95,
    "e_c": 0.85,
    "f_c": 0.2,
    "g": 9.81,
}
PT_TIP_RADIUS = 0.0106045
PT_END_MASS = 0.170097 / 30

finite = st.floats(-10.0, 10.0, allow_nan=False)
angles = st.floats(-4 * math.pi, 4 * math.pi, allow_nan=False)


def strike_table(radius: float, mass: float, tip_radius: float) -> SimpleNamespace:
    return SimpleNamespace(ball_radius=radius, ball_mass=mass, cue_tip_radius=tip_radius)


# --- the frame ---------------------------------------------------------------------------------


def test_frame_closed_form_and_corners() -> None:
    width, length = 1.27, 2.54
    points = np.array([[0.0, 0.0], [length, width], [0.3, 0.2]])
    np.testing.assert_array_equal(
        ip.xy_to_pooltool(points, width), [[width, 0.0], [0.0, length], [width - 0.2, 0.3]]
    )
    # our corner (0, 0) is pooltool's (W, 0); its head rail py = 0 is our x = 0
    np.testing.assert_array_equal(ip.xy_from_pooltool([[width, 0.0]], width), [[0.0, 0.0]])
    np.testing.assert_array_equal(ip.xy_from_pooltool([[0.5, 0.0]], width)[:, 0], [0.0])


@given(
    st.lists(st.tuples(st.floats(0.0, 3.0), st.floats(0.0, 1.5)), min_size=1, max_size=8),
    st.floats(0.1, 2.0),
)
def test_frame_round_trips(points: list[tuple[float, float]], width: float) -> None:
    there = ip.xy_to_pooltool(points, width)
    back = ip.xy_from_pooltool(there, width)
    np.testing.assert_allclose(back, points, rtol=0.0, atol=2 * ULP * 3.0)
    again = ip.xy_to_pooltool(ip.xy_from_pooltool(there, width), width)
    np.testing.assert_allclose(again, there, rtol=0.0, atol=4 * ULP * 3.0)


@given(
    st.lists(st.tuples(st.floats(0.0, 3.0), st.floats(0.0, 1.5)), min_size=1, max_size=4),
    st.floats(-1.0, 1.0),
    st.floats(-1.0, 1.0),
)
def test_a_shifted_pooltool_origin_is_subtracted(
    points: list[tuple[float, float]], x0: float, y0: float
) -> None:
    pts = np.array(points)
    shifted = ip.xy_from_pooltool(pts + [x0, y0], 1.27, origin=(x0, y0))
    np.testing.assert_allclose(shifted, ip.xy_from_pooltool(pts, 1.27), rtol=0, atol=1e-15)


@given(angles, st.floats(0.01, 2.0), st.floats(0.0, 2.5), st.floats(0.0, 1.2))
def test_an_aim_points_the_same_way_in_both_frames(
    angle: float, distance: float, x: float, y: float
) -> None:
    """A point moved ``d`` along ``angle`` here is moved ``d`` along ``phi`` in pooltool's frame."""
    start = np.array([[x, y]])
    end = start + distance * np.array([[math.cos(angle), math.sin(angle)]])
    phi = math.radians(ip.phi_from_angle(angle))
    moved = ip.xy_to_pooltool(end, 1.27) - ip.xy_to_pooltool(start, 1.27)
    np.testing.assert_allclose(
        moved[0], distance * np.array([math.cos(phi), math.sin(phi)]), rtol=0, atol=1e-13
    )


@given(st.lists(st.tuples(st.floats(0, 2.5), st.floats(0, 1.2)), min_size=3, max_size=3))
def test_the_frame_turn_keeps_handedness(points: list[tuple[float, float]]) -> None:
    """A rotation, not a mirror: the signed area of a triangle keeps its sign and size."""

    def area(p: np.ndarray) -> float:
        (ux, uy), (vx, vy) = p[1] - p[0], p[2] - p[0]
        return float(ux * vy - uy * vx)

    ours = np.array(points)
    assert area(ip.xy_to_pooltool(ours, 1.27)) == pytest.approx(area(ours), abs=1e-12)


@given(angles)
def test_phi_is_the_angle_plus_90_degrees(angle: float) -> None:
    phi = ip.phi_from_angle(angle)
    assert phi == pytest.approx(math.degrees(angle) + 90.0, rel=1e-15, abs=1e-13)
    assert ip.angle_from_phi(phi) == pytest.approx(angle, rel=1e-14, abs=1e-14)


def test_phi_of_the_axes() -> None:
    assert ip.phi_from_angle(0.0) == 90.0  # our +x (up the table) is pooltool's +y
    assert ip.angle_from_phi(90.0) == 0.0
    assert ip.angle_from_phi(180.0) == pytest.approx(math.pi / 2)  # pooltool's -x: our +y


# --- the cue -----------------------------------------------------------------------------------

tables = st.builds(strike_table, st.floats(0.02, 0.04), st.floats(0.1, 0.3), st.floats(0.0, 0.015))


@st.composite
def shots(draw: Any) -> tuple[Any, float, float, tuple[float, float], float, float]:
    table = draw(tables)
    reach = 1.0 + table.cue_tip_radius / table.ball_radius
    # a tip in the box [-1, 1]^2 whose contact point lies on the ball
    radius = draw(st.floats(0.0, 0.999)) * min(reach, math.sqrt(2.0))
    turn = draw(st.floats(0.0, 2 * math.pi))
    side = max(-1.0, min(1.0, radius * math.cos(turn)))
    vertical = max(-1.0, min(1.0, radius * math.sin(turn)))
    return (
        table,
        draw(angles),
        draw(st.floats(0.01, 8.0)),
        (side, vertical),
        draw(st.floats(0.0, 1.4)),
        draw(st.floats(0.1, 2.0)),
    )


@given(shots())
def test_the_cue_round_trips(shot: tuple) -> None:
    table, angle, speed, tip, elevation, cue_mass = shot
    cue = ip.cue_to_pooltool(table, angle, speed, tip, elevation, cue_mass=cue_mass)
    back = ip.cue_from_pooltool(table, *cue, cue_mass=cue_mass)
    assert back[0] == pytest.approx(angle, rel=1e-14, abs=1e-14)
    assert back[1] == pytest.approx(speed, rel=1e-14)
    np.testing.assert_allclose(back[2], tip, rtol=1e-14, atol=1e-15)
    assert back[3] == pytest.approx(elevation, rel=1e-14, abs=1e-16)


@given(shots())
def test_the_cue_mapping_is_pooltools_strike(shot: tuple) -> None:
    """Closed forms: pooltool's ball speed (TP A-30) is ours, its contact point our tip's."""
    table, angle, speed, tip, elevation, cue_mass = shot
    v0, phi, theta, a, b = ip.cue_to_pooltool(table, angle, speed, tip, elevation,
                                              cue_mass=cue_mass)  # fmt: skip
    m = table.ball_mass
    ball_speed = 2.0 * v0 / (1.0 + m / cue_mass + 2.5 * (a * a + b * b))
    assert ball_speed * math.cos(math.radians(theta)) == pytest.approx(speed, rel=1e-14)
    reach = 1.0 + table.cue_tip_radius / table.ball_radius
    assert (-a * reach, b * reach) == pytest.approx(tip, rel=1e-14, abs=1e-15)
    assert a * a + b * b <= 1.0
    assert theta == pytest.approx(math.degrees(elevation), rel=1e-15)
    assert phi == ip.phi_from_angle(angle)


@given(st.floats(0.05, 10.0), st.floats(-720, 720), st.floats(0, 85),
       st.floats(0.0, 0.72), st.floats(0, 2 * math.pi))  # fmt: skip
def test_the_cue_round_trips_from_pooltools_side(
    v0: float, phi: float, theta: float, radius: float, turn: float
) -> None:
    table = strike_table(PT_BALL["R"], PT_BALL["m"], PT_TIP_RADIUS)
    a, b = radius * math.cos(turn), radius * math.sin(turn)
    ours = ip.cue_from_pooltool(table, v0, phi, theta, a, b)
    back = ip.cue_to_pooltool(table, *ours)
    np.testing.assert_allclose(back, (v0, phi, theta, a, b), rtol=1e-13, atol=1e-13)


def test_a_centre_hit_and_english_have_their_closed_forms() -> None:
    table = strike_table(PT_BALL["R"], PT_BALL["m"], PT_TIP_RADIUS)
    cue = ip.cue_to_pooltool(table, 0.0, 1.0)
    assert cue == (pytest.approx((1.0 + PT_BALL["m"] / M_CUE) / 2.0, rel=1e-15), 90.0, 0.0,
                   0.0, 0.0)  # fmt: skip
    assert math.copysign(1.0, cue.a) == 1.0  # no -0.0 for a centre hit
    right = ip.cue_to_pooltool(table, 0.0, 1.0, tip=(0.3, 0.0))
    assert right.a == pytest.approx(-0.3 / (1.0 + PT_TIP_RADIUS / PT_BALL["R"]), rel=1e-15)
    assert right.a < 0.0  # right english is pooltool's a < 0 (its +1 is the ball's left)


def test_the_bench_strike_is_the_mapping() -> None:
    """bench/spin_scenes.py hands pooltool the package's mapping (one copy of it)."""
    pytest.importorskip("mpmath", reason="bench/spin_scenes.py needs the bench extra")
    from bench.spin_scenes import POOLTOOL_CUE_MASS, SpinShot, pooltool_strike

    table = Table(model="spin", pockets="none")
    empty = np.zeros((1, 2))
    shot = SpinShot("s", empty, 0.4, 1.5, (-0.3, 0.2), 0.1, empty, np.zeros((1, 3)))
    out = pooltool_strike(table, shot)
    cue = ip.cue_to_pooltool(table, 0.4, 1.5, (-0.3, 0.2), 0.1, cue_mass=POOLTOOL_CUE_MASS)
    assert out == {**cue._asdict(), "M": POOLTOOL_CUE_MASS, "end_mass": table.cue_end_mass}
    assert out["phi"] == pytest.approx(math.degrees(0.4) + 90.0, rel=1e-15)
    assert out["a"] == pytest.approx(0.3 / (1 + table.cue_tip_radius / table.ball_radius))


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"speed": 0.0}, "speed"),
        ({"speed": -1.0}, "speed"),
        ({"angle": math.nan}, "angle"),
        ({"tip": (1.2, 0.0)}, r"\[-1, 1\]"),
        ({"tip": (0.99, 0.99)}, "off its surface"),
        ({"tip": (0.1,)}, "pair"),
        ({"tip": ("0.1", 0.0)}, "tip side"),
        ({"elevation": math.pi / 2}, "elevation"),
        ({"elevation": -0.1}, "elevation"),
        ({"cue_mass": 0.0}, "cue_mass"),
    ],
)
def test_bad_shots_are_refused(kwargs: dict, message: str) -> None:
    table = strike_table(PT_BALL["R"], PT_BALL["m"], PT_TIP_RADIUS)
    shot = {"angle": 0.0, "speed": 1.0, **kwargs}
    with pytest.raises(ValueError, match=message):
        ip.cue_to_pooltool(table, **shot)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: ip.xy_to_pooltool([[0.1, 0.2, 0.3]], 1.27), "shape"),
        (lambda: ip.xy_to_pooltool([[0.1, math.inf]], 1.27), "finite"),
        (lambda: ip.xy_to_pooltool([[0.1, 0.2]], 0.0), "width"),
        (lambda: ip.xy_from_pooltool([[0.1, 0.2]], 1.27, origin=(math.nan, 0.0)), "origin"),
        (lambda: ip.phi_from_angle("0"), "angle"),
        (lambda: ip.angle_from_phi(math.inf), "phi"),
        (lambda: ip.cue_from_pooltool(Table(model="spin"), 1.0, 90.0, 90.0, 0.0, 0.0), "theta"),
        (lambda: ip.cue_from_pooltool(Table(model="spin"), 0.0, 90.0, 0.0, 0.0, 0.0), "V0"),
    ],
)
def test_bad_points_and_angles_are_refused(call: Any, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        call()


# --- the parameters ------------------------------------------------------------------------


def test_pooltools_default_ball_is_a_table() -> None:
    options = ip.table_options_from_pooltool(PT_BALL, 2.54, 1.27, 0.0365, PT_TIP_RADIUS,
                                             PT_END_MASS)  # fmt: skip
    table = Table(model="spin", **options)
    assert table.spin_decel == pytest.approx(10.9, rel=1e-15)  # (5/2)(4/9) 9.81
    assert (table.ball_mass, table.e_cushion, table.cue_end_mass) == (0.170097, 0.85,
                                                                     PT_END_MASS)  # fmt: skip
    assert ip.ball_params_from_table(table) == pytest.approx(
        {k: v for k, v in PT_BALL.items()}, rel=1e-15
    )


@given(
    st.fixed_dictionaries(
        {
            "R": st.floats(0.02, 0.035),
            "m": st.floats(0.1, 0.3),
            "u_s": st.floats(0.05, 0.5),
            "u_r": st.floats(0.002, 0.05),
            "u_sp_proportionality": st.floats(0.1, 1.0),
            "e_b": st.floats(0.5, 1.0),
            "e_c": st.floats(0.3, 1.0),
            "f_c": st.floats(0.01, 0.5),
            "g": st.floats(9.7, 9.9),
        }
    )
)
def test_ball_parameters_round_trip(ball: dict[str, float]) -> None:
    options = ip.table_options_from_pooltool(ball, 2.54, 1.27, 1.28 * ball["R"], 0.0106,
                                             ball["m"] / 30)  # fmt: skip
    table = Table(model="spin", pockets="none", **options)
    for name, field in ip.BALL_FIELDS.items():
        assert getattr(table, field) == ball[name], name
    assert table.spin_decel == 2.5 * ball["u_sp_proportionality"] * ball["g"]
    back = ip.ball_params_from_table(table)
    assert back.keys() == ball.keys()
    assert back == pytest.approx(ball, rel=1e-15)


def test_parameters_pooltool_lacks_are_refused() -> None:
    with pytest.raises(ValueError, match="lack"):
        ip.table_options_from_pooltool({"R": 0.03}, 2.54, 1.27, 0.036, 0.01, 0.005)
    with pytest.raises(ValueError, match="cushion friction"):
        ip.ball_params_from_table(Table(model="spin", cushion_friction=0.0))
    with pytest.raises(ValueError, match="Table"):
        ip.ball_params_from_table(SimpleNamespace())  # type: ignore[arg-type]


# --- the scene (no pooltool) ----------------------------------------------------------------


def test_a_scene_plays_what_shoot_plays() -> None:
    table = Table(pockets="none")
    positions = [[0.5, 0.6], [1.2, 0.62]]
    scene = ip.Scene(table, positions, ("cue", "1"), 0, 0.02, 1.3)
    assert not scene.positions.flags.writeable
    ours = scene.shoot()
    direct = shoot(table, positions, 0.02, 1.3)
    np.testing.assert_array_equal(ours.positions, direct.positions)
    assert ours.first_hit.tolist() == [1, 0]  # and a collision happened


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"ids": ("cue",)}, "ids"),
        ({"ids": ("cue", "cue")}, "distinct"),
        ({"ids": "cue1"}, "ids"),
        ({"cue": 2}, "cue"),
        ({"positions": [[0.5, 0.6], [0.51, 0.6]]}, "overlap"),
        ({"positions": [[0.01, 0.6], [1.2, 0.6]]}, "off the table"),
        ({"tip": (0.3, 0.0)}, "model='spin'"),  # a roll table has no spin
        ({"speed": 0.0}, "speed"),
        ({"masses": [0.17, -1.0]}, "mass"),
    ],
)
def test_a_bad_scene_is_refused(changes: dict, message: str) -> None:
    args = {"table": Table(pockets="none"), "positions": [[0.5, 0.6], [1.2, 0.6]],
            "ids": ("cue", "1"), "cue": 0, "angle": 0.0, "speed": 1.0, **changes}  # fmt: skip
    with pytest.raises(ValueError, match=message):
        ip.Scene(**args)


def test_missing_pooltool_names_the_install_step() -> None:
    code = (
        "import sys; sys.modules['pooltool'] = None\n"
        "from pool_env.interop.pooltool import from_system\nfrom_system(None)"
    )
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert run.returncode != 0
    last = run.stderr.strip().splitlines()[-1]
    assert last.startswith("ModuleNotFoundError: pool_env.interop.pooltool needs pooltool")
    assert "bench/setup_pooltool.sh" in last and "pooltool-billiards 0.6.0" in last


def test_importing_the_module_does_not_import_pooltool() -> None:
    code = "import sys, pool_env.interop.pooltool; print('pooltool' in sys.modules)"
    run = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert run.stdout.strip() == "False", run.stderr


def test_require_needs_an_extra_or_an_install_step() -> None:
    with pytest.raises(ValueError, match="extra or the install step"):
        require("numpy", None, "this test")
    with pytest.raises(ModuleNotFoundError, match="this test needs no_such_mod: do this"):
        require("no_such_mod", None, "this test", install="do this")


# --- from_system on a pooltool-shaped stand-in (no pooltool needed) --------------------------


class _StandInSystem:
    """The parts of a ``pooltool.System`` that ``from_system`` reads (a 2.54 x 1.27 m table)."""

    def __init__(self, balls: dict[str, tuple[float, float, float]], b: float = 0.0) -> None:
        def segment(x: float, y: float) -> SimpleNamespace:
            return SimpleNamespace(p1=np.array([x, y, 0.0365]))

        linear = {"3": segment(0.0, 0.0), "18": segment(0.0, 0.0), "12": segment(1.27, 0.0),
                  "9": segment(0.0, 2.54)}  # fmt: skip
        self.table = SimpleNamespace(cushion_segments=SimpleNamespace(linear=linear),
                                     has_pockets=False)  # fmt: skip
        params = SimpleNamespace(**PT_BALL)
        self.balls = {
            name: SimpleNamespace(
                id=name, params=params,
                state=SimpleNamespace(s=0, rvw=np.array([xyz, [0.0] * 3, [0.0] * 3])),
            )
            for name, xyz in balls.items()
        }  # fmt: skip
        specs = SimpleNamespace(tip_radius=PT_TIP_RADIUS, end_mass=PT_END_MASS, M=0.567)
        self.cue = SimpleNamespace(cue_ball_id="cue", V0=1.0, phi=90.0, theta=0.0, a=0.0, b=b,
                                   specs=specs)  # fmt: skip


@pytest.fixture
def stand_in(monkeypatch: pytest.MonkeyPatch) -> None:
    """``from_system`` reads ``_StandInSystem`` as its ``pooltool.System``."""
    fake = SimpleNamespace(System=_StandInSystem)
    monkeypatch.setattr("pool_env.interop.pooltool.read_system.load_pooltool", lambda: fake)


R_PT = PT_BALL["R"]


@pytest.mark.usefixtures("stand_in")
def test_a_ball_off_the_cloth_is_refused_by_name_and_height() -> None:
    """A ball above (airborne) or below the cloth plane ``z = R`` is refused, not flattened."""
    on = {"cue": (0.6, 0.5, R_PT), "1": (0.6, 1.2, R_PT)}
    scene = ip.from_system(_StandInSystem(on))
    assert scene.ids == ("cue", "1")
    for z in (R_PT + 0.01, R_PT - 1e-6, 0.0):
        with pytest.raises(ValueError, match=rf"ball '1' is at height z={z!r} m, off the cloth"):
            ip.from_system(_StandInSystem({**on, "1": (0.6, 1.2, z)}))
    # Rounding of the plane is read as on it (HEIGHT_RTOL of R).
    ip.from_system(_StandInSystem({**on, "1": (0.6, 1.2, R_PT * (1 + 1e-12))}))
    system = _StandInSystem(on)
    system.balls["1"].state.rvw[1][2] = 0.3  # a vertical velocity alone: in motion
    with pytest.raises(ValueError, match="ball '1' is in motion"):
        ip.from_system(system)


@pytest.mark.usefixtures("stand_in")
def test_a_roll_scene_ports_no_spin_parameter() -> None:
    """``model="roll"`` ports no spin parameter (the roll table refuses them), the rest.

    A spin scene keeps them.
    """
    on = {"cue": (0.6, 0.5, R_PT), "1": (0.6, 1.2, R_PT)}
    roll = ip.from_system(_StandInSystem(on), model="roll").table
    spin = ip.from_system(_StandInSystem(on)).table
    assert roll.model == "roll" and roll.mu_slide == Table().mu_slide
    assert roll.cue_tip_radius == Table().cue_tip_radius != spin.cue_tip_radius == PT_TIP_RADIUS
    assert roll.e_cushion == spin.e_cushion == PT_BALL["e_c"]
    with pytest.raises(ValueError, match="model='spin'"):  # b = 0.2: draw, the roll level has none
        ip.from_system(_StandInSystem(on, b=0.2), model="roll")


# --- with pooltool ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def pt(tmp_path_factory: pytest.TempPathFactory) -> ModuleType:
    """pooltool, imported with a scratch HOME (it writes its settings under ~/.config)."""
    if not ip.pooltool_available():
        pytest.skip(f"pooltool is not installed here ({ip.INSTALL})")
    old = os.environ.get("HOME")
    os.environ["HOME"] = str(tmp_path_factory.mktemp("pooltool-home"))
    try:
        module = importlib.import_module("pooltool")
    finally:
        if old is None:
            os.environ.pop("HOME")
        else:
            os.environ["HOME"] = old
    return module


def test_pooltool_available_is_whether_it_imports() -> None:
    assert ip.pooltool_available() == (importlib.util.find_spec("pooltool") is not None)


@pytest.mark.parametrize("pockets", ["none", "jaws"])
@pytest.mark.parametrize("cue", [0, 2])
def test_a_scene_round_trips_through_a_system(pt: ModuleType, pockets: str, cue: int) -> None:
    table = Table(model="spin", pockets=pockets, ball_mass=0.16, cushion_friction=0.15)
    positions = np.array([[0.4, 0.3], [1.3, 0.9], [2.0, 0.5]])
    system = ip.to_system(table, positions, 2.9, 1.7, cue=cue, tip=(-0.25, 0.4),
                          elevation=0.2)  # fmt: skip
    assert isinstance(system, pt.System)
    assert system.cue.cue_ball_id == "cue" and system.table.has_pockets == (pockets == "jaws")
    assert sorted(system.balls) == ["1", "2", "cue"]
    np.testing.assert_array_equal(
        system.balls["cue"].state.rvw[0][:2], [table.width - positions[cue, 1], positions[cue, 0]]
    )
    scene = ip.from_system(system)
    assert scene.ids[scene.cue] == "cue"
    order = [list(system.balls).index(i) for i in scene.ids]
    np.testing.assert_allclose(scene.positions, positions[order], rtol=0, atol=4 * ULP)
    assert (scene.angle, scene.speed, scene.elevation) == pytest.approx((2.9, 1.7, 0.2),
                                                                        rel=1e-14)  # fmt: skip
    assert scene.tip == pytest.approx((-0.25, 0.4), rel=1e-14)
    for name in ("length", "width", "ball_radius", "ball_mass", "mu_roll", "mu_slide", "g",
                 "e_ball", "e_cushion", "cushion_friction", "cushion_height", "cue_tip_radius",
                 "cue_end_mass"):  # fmt: skip
        assert getattr(scene.table, name) == pytest.approx(getattr(table, name), rel=1e-15), name
    assert scene.table.pocket_model == table.pocket_model
    assert scene.table.spin_decel == pytest.approx(table.spin_decel, rel=1e-15)
    assert scene.masses is None
    again = scene.to_system()
    for name in ("V0", "phi", "theta", "a", "b"):
        assert getattr(again.cue, name) == pytest.approx(getattr(system.cue, name), rel=1e-14)


def pooltool_native(pt: ModuleType, balls: dict[str, tuple[float, float]], *stroke: float) -> Any:
    """A System as a pooltool user builds one: pooltool's defaults, its frame, its cue."""
    table = pt.Table.from_table_specs(pt.objects.BilliardTableSpecs(l=2.54, w=1.27))
    made = {bid: pt.Ball.create(bid, xy=xy) for bid, xy in balls.items()}
    v0, phi, theta, a, b = stroke
    cue = pt.Cue(cue_ball_id="cue", V0=v0, phi=phi, theta=theta, a=a, b=b)
    return pt.System(cue=cue, table=table, balls=made)


NATIVE_SHOTS = {
    "draw, left english": ({"cue": (0.6, 0.5)}, 0.35, 97.0, 0.0, 0.2, -0.3),
    "elevated cue, right english": ({"cue": (0.7, 0.9)}, 0.3, 60.0, 12.0, -0.25, 0.1),
    "cut with follow": ({"cue": (0.635, 0.6), "1": (0.70, 1.1)}, 0.4, 83.0, 0.0, 0.0, 0.3),
    "stun with side": ({"cue": (0.5, 0.5), "1": (0.52, 0.9)}, 0.35, 87.5, 0.0, 0.15, 0.0),
}


@pytest.mark.parametrize("name", list(NATIVE_SHOTS))
def test_a_pooltool_shot_ported_lands_where_pooltool_puts_it(pt: ModuleType, name: str) -> None:
    """The ported scene and pooltool's default engine agree on equal models.

    No cushion: pooltool's default cushion model is Stronge's, which this package lacks.
    """
    balls, *stroke = NATIVE_SHOTS[name]
    system = pooltool_native(pt, balls, *stroke)
    scene = ip.from_system(system, table_options={"ball_friction": "pooltool"})
    ours = scene.shoot()
    spacer = pt.constants.MIN_DIST
    pt.constants.MIN_DIST = 1e-12  # its collision spacer, shrunk as bench/spin_vs_pooltool does
    try:
        pt.simulate(system, inplace=True)
    finally:
        pt.constants.MIN_DIST = spacer
    kinds = {str(event.event_type) for event in system.events}
    assert not any("cushion" in kind for kind in kinds), kinds
    final = np.array([system.balls[i].state.rvw[0][:2] for i in scene.ids])
    theirs = ip.xy_from_pooltool(final, scene.table.width)
    assert np.abs(theirs - scene.positions).max() > 0.2  # the shot went somewhere
    np.testing.assert_allclose(ours.positions, theirs, rtol=0, atol=1e-9)


def test_a_system_is_read_as_it_is_refused_when_it_cannot_be(pt: ModuleType) -> None:
    balls = {"cue": (0.6, 0.5), "1": (0.7, 1.0), "2": (0.3, 1.5)}
    system = pooltool_native(pt, balls, 1.0, 90.0, 0.0, 0.0, 0.0)
    system.balls["2"].state.s = pt.constants.pocketed  # a pocketed ball is left out
    assert ip.from_system(system).ids == ("cue", "1")
    system.balls["1"].state.s = pt.constants.rolling
    with pytest.raises(ValueError, match="in motion"):
        ip.from_system(system)
    system = pooltool_native(pt, balls, 1.0, 90.0, 0.0, 0.0, 0.0)
    system.balls["cue"].state.s = pt.constants.pocketed
    with pytest.raises(ValueError, match="not on the table"):
        ip.from_system(system)
    system = pooltool_native(pt, balls, 1.0, 90.0, 0.0, 0.0, 0.0)
    system.balls["1"] = pt.Ball.create("1", xy=(0.7, 1.0), e_c=0.5)
    with pytest.raises(ValueError, match="e_c"):
        ip.from_system(system)
    system = pooltool_native(pt, {"cue": (0.6, 0.5), "1": (0.6, 0.51)}, 1.0, 90.0, 0, 0, 0)
    with pytest.raises(ValueError, match="overlap"):
        ip.from_system(system)
    with pytest.raises(ValueError, match=r"pooltool\.System"):
        ip.from_system(object())
    system = pooltool_native(pt, {"cue": (0.6, 0.5)}, 1.0, 90.0, 0.0, 0.0, 0.2)
    with pytest.raises(ValueError, match="model='spin'"):
        ip.from_system(system, model="roll")  # b = 0.2 is draw/follow: the roll level has none


def test_unequal_masses_have_no_system(pt: ModuleType) -> None:
    table = Table(model="spin", pockets="none")
    scene = ip.Scene(table, [[0.5, 0.6], [1.2, 0.6]], ("cue", "1"), 0, 0.0, 1.0,
                     masses=[0.17, 0.2])  # fmt: skip
    with pytest.raises(ValueError, match="one mass"):
        scene.to_system()
    same = ip.Scene(table, [[0.5, 0.6], [1.2, 0.6]], ("cue", "1"), 0, 0.0, 1.0,
                    masses=[table.ball_mass] * 2)  # fmt: skip
    assert {b.params.m for b in same.to_system().balls.values()} == {table.ball_mass}
