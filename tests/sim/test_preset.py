"""``Table.preset("pooltool-0.6")``: pooltool 0.6.0's values, to the last digit.

Checked against the literals of pooltool 0.6.0's source (``BallParams``, ``PocketTableSpecs``,
``CueSpecs``, ``default_resolver``) and, where the bench's pooltool virtualenv exists
(``bash bench/setup_pooltool.sh``), against pooltool itself, run in that virtualenv.
"""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

from bench.engines.pooltool_engine import pooltool_python
from pool_env import Table
from pool_env.interop.pooltool import POOLTOOL_MODELS

POOLTOOL = {  # the literals of pooltool 0.6.0's source
    "length": 1.9812,
    "width": 1.9812 / 2,
    "ball_radius": 0.028575,
    "ball_mass": 0.170097,
    "mu_roll": 0.01,
    "mu_slide": 0.2,
    "g": 9.81,
    "e_ball": 0.95,
    "e_cushion": 0.85,
    "e_jaw": 0.85,
    "cushion_friction": 0.2,
    "cushion_height": 0.64 * 2 * 0.028575,
    "cue_tip_radius": 0.0106045,
    "cue_end_mass": 0.170097 / 30,
    "spin_decel": 2.5 * (10 * 2 / 5 / 9) * 9.81,
    "cushion_omega_ratio": 1.8,
}


def test_the_preset_holds_pooltools_values_and_models():
    table = Table.preset("pooltool-0.6")
    for name, value in POOLTOOL.items():
        assert getattr(table, name) == value, name
    assert table.spin_decel == pytest.approx(10.9, abs=2e-15)  # not 10.889 (0.444 rounded)
    assert (table.model, table.cushion_model, table.ball_model) == ("spin", "stronge", "frictional")
    assert table.ball_friction == "pooltool"  # its FrictionalInelastic impulse, Alciatore's fit


def test_interops_models_are_the_presets():
    """``POOLTOOL_MODELS`` (for ``from_system``) turns a table's models into pooltool's."""
    table = Table(model="spin", **POOLTOOL_MODELS)
    preset = Table.preset("pooltool-0.6")
    for name in ("ball_friction", "cushion_model", "cushion_omega_ratio", "ball_model"):
        assert getattr(table, name) == getattr(preset, name), name
    assert Table(model="spin").cushion_model == "han"  # the package's own default differs


def test_overrides_and_unknown_names():
    table = Table.preset("pooltool-0.6", pockets="none", e_cushion=0.9)
    assert (table.pocket_model, table.e_cushion, table.ball_mass) == ("none", 0.9, 0.170097)
    with pytest.raises(ValueError, match=r"unknown preset 'pooltool-0\.5'.*pooltool-0\.6"):
        Table.preset("pooltool-0.5")
    with pytest.raises(ValueError, match=r"unknown Table keyword\(s\) \['foo'\].*'pockets'"):
        Table.preset("pooltool-0.6", foo=1)


def test_the_preset_is_a_spin_table_only():
    """Its cushion model, friction rule and other spin values mean nothing on the roll level."""
    with pytest.raises(ValueError, match=r"ball_friction='pooltool'.*model='spin' only"):
        Table.preset("pooltool-0.6", model="roll")


_PROBE = """
import json
import pooltool as pt
from pooltool.physics.resolve.resolver import default_resolver
b, t = pt.BallParams.default(), pt.objects.PocketTableSpecs()
c, r = pt.objects.CueSpecs.default(), default_resolver()
print(json.dumps({
    "version": pt.__version__,
    "length": t.l, "width": t.w, "cushion_height": t.cushion_height, "ball_radius": b.R,
    "ball_mass": b.m, "mu_roll": b.u_r, "mu_slide": b.u_s, "g": b.g, "e_ball": b.e_b,
    "e_cushion": b.e_c, "e_jaw": b.e_c, "cushion_friction": b.f_c,
    "cue_tip_radius": c.tip_radius, "cue_end_mass": c.end_mass,
    "spin_decel": 2.5 * b.u_sp_proportionality * b.g,
    "cushion_omega_ratio": r.ball_linear_cushion.omega_ratio,
    "models": [type(r.ball_linear_cushion).__name__, type(r.ball_circular_cushion).__name__,
               type(r.ball_ball).__name__, type(r.ball_ball.friction).__name__,
               [r.ball_ball.friction.a, r.ball_ball.friction.b, r.ball_ball.friction.c]],
}))
"""


def test_the_preset_against_pooltool_itself(tmp_path):
    python = pooltool_python()
    if python is None:
        pytest.skip(
            "no pooltool virtualenv at .bench-venvs/pooltool (bash bench/setup_pooltool.sh)"
        )
    run = subprocess.run(
        [str(python), "-c", _PROBE], capture_output=True, text=True, timeout=300,
        env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},  # pooltool writes ~/.config
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-2000:]
    theirs = json.loads(run.stdout.strip().splitlines()[-1])
    assert theirs.pop("version") == "0.6.0"
    models = theirs.pop("models")
    assert models[:4] == [
        "StrongeCompliantLinear",
        "StrongeCompliantCircular",
        "FrictionalInelastic",
        "AlciatoreBallBallFriction",
    ]
    assert models[4] == [0.009951, 0.108, 1.088]  # the fit this package's "pooltool" mode uses
    table = Table.preset("pooltool-0.6")
    for name, value in theirs.items():
        assert getattr(table, name) == value, name


def test_a_pooltool_shot_at_its_defaults_plays_the_same_through_the_preset(monkeypatch):
    """A System at pooltool's defaults, ported with ``POOLTOOL_MODELS``, plays the same.

    pooltool's default engine on a cut with english that meets the cushions; ``from_system``
    gives the preset's table, and the final positions agree.
    """
    pt = pytest.importorskip("pooltool", reason="pooltool 0.6.0 is not installed here")
    from pooltool.physics.engine import PhysicsEngine
    from pooltool.physics.resolve.resolver import default_resolver

    from pool_env.interop.pooltool import from_system, xy_from_pooltool

    specs = pt.objects.BilliardTableSpecs(l=1.9812, w=0.9906, cushion_height=0.64 * 2 * 0.028575)
    balls = {b: pt.Ball.create(b, xy=xy) for b, xy in (("cue", (0.5, 0.6)), ("1", (0.62, 1.3)))}
    cue = pt.Cue(cue_ball_id="cue", V0=2.5, phi=78.0, a=-0.2, b=0.3)
    system = pt.System(cue=cue, table=pt.Table.from_table_specs(specs), balls=balls)
    scene = from_system(system, pockets="none", table_options=POOLTOOL_MODELS)
    preset = Table.preset("pooltool-0.6", pockets="none")
    for name in (*POOLTOOL, "cushion_model", "ball_friction", "ball_model"):
        assert getattr(scene.table, name) == getattr(preset, name), name
    ours = scene.shoot()
    monkeypatch.setattr(pt.constants, "MIN_DIST", 1e-12)  # the spacer, shrunk as the bench does
    pt.simulate(system, engine=PhysicsEngine(resolver=default_resolver()), inplace=True)
    final = np.array([system.balls[i].state.rvw[0][:2] for i in scene.ids])
    assert sum(e.kind == "cushion" for e in ours.events) >= 2
    assert np.abs(ours.positions - xy_from_pooltool(final, scene.table.width)).max() < 1e-9
