"""The spin level's resolution kernels beside pooltool 0.6.0's own, on seeded random inputs.

Compares, impact by impact (no simulation): ``ball_ball_spin`` with pooltool's
``FrictionalInelastic`` (Alciatore friction), ``ball_ball_mathavan`` with its
``FrictionalMathavan``, ``cushion_han`` with its ``han2005``, ``cushion_spin`` in Stronge's
mode with its ``StrongeCompliantLinear`` (``omega_ratio`` 1.8, ``e_c`` 0.85) and
``cue_strike`` (through :func:`pool_env.sim.cue.from_pooltool`) with its
``InstantaneousPoint``. pooltool runs in its own virtualenv (``bash bench/setup_pooltool.sh``)
as a subprocess of this script, which writes the inputs and reads its outputs as JSON.

Usage: ``python -m bench.spin_kernels_pooltool [--venv .bench-venvs/pooltool] [--n 200]``.
Prints, per model, the largest absolute difference of the velocities (m/s) and spins
(rad/s, times R to compare with velocities), and for the ball-ball model the split by
restitution (pooltool's friction impulse is ``mu e_b c`` where this model has Coulomb's
``mu (1 + e_b) c / 2``: they agree at ``e_b = 1``, see ``spin_collide``'s docstring; the
line "friction mode 3" runs this kernel with pooltool's impulse, to show that this is the
only difference).

Measured (seed 19, n 200): ball-ball at ``e_b = 1`` 4.0e-15 m/s, at 0.95 5.0e-3 m/s (3.4e-15
in mode 3), cushion 2.7e-15, strike 5.7e-15; Mathavan 5.4e-14, Stronge 8.4e-14.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

R, M = 0.028575, 0.170097
H = 0.64 * 2 * R  # pooltool's default cushion height
TIP = 0.0106045


def _pooltool_side(cases: dict) -> dict:
    """Run pooltool's resolvers on ``cases`` (executed inside pooltool's venv)."""
    import pooltool as pt
    from pooltool.objects.ball.datatypes import Ball, BallState
    from pooltool.objects.table.components import LinearCushionSegment
    from pooltool.physics.resolve.ball_ball.frictional_inelastic import FrictionalInelastic
    from pooltool.physics.resolve.ball_ball.frictional_mathavan import FrictionalMathavan
    from pooltool.physics.resolve.ball_cushion.han_2005.model import han2005
    from pooltool.physics.resolve.ball_cushion.stronge_compliant.model import (
        StrongeCompliantLinear,
    )
    from pooltool.physics.resolve.stick_ball.instantaneous_point import InstantaneousPoint

    out: dict = {"ball_ball": [], "mathavan": [], "cushion": [], "stronge": [], "strike": []}
    for key, model in (("ball_ball", FrictionalInelastic()), ("mathavan", FrictionalMathavan())):
        for v1, w1, v2, w2, n, e in cases["ball_ball"]:
            b1 = Ball.create("1", xy=(0.5, 0.5))
            b2 = Ball.create("2", xy=(0.5 + 2 * R * n[0], 0.5 + 2 * R * n[1]))
            for ball, v, w in ((b1, v1, w1), (b2, v2, w2)):
                ball.params = ball.params.__class__(e_b=e)
                rvw = ball.state.rvw.copy()
                rvw[1] = [v[0], v[1], 0.0]
                rvw[2] = w
                ball.state = BallState(rvw, pt.constants.sliding)
            b1, b2 = model.solve(b1, b2)
            out[key].append(
                [*b1.state.rvw[1, :2], *b1.state.rvw[2], *b2.state.rvw[1, :2], *b2.state.rvw[2]]
            )
    stronge = StrongeCompliantLinear(omega_ratio=1.8)
    for v, w, n, h, e, f in cases["cushion"]:
        ball = Ball.create("1", xy=(0.5, 0.5))
        ball.params = ball.params.__class__(e_c=e, f_c=max(f, 1e-300))  # pooltool: f_c > 0
        ball.state = BallState(np.array([[0.5, 0.5, R], [v[0], v[1], 0.0], w]), 1)
        # the nose line R from the centre, across n, at the height h
        c = np.array([0.5 - R * n[0], 0.5 - R * n[1], h])
        along = np.array([-n[1], n[0], 0.0])
        segment = LinearCushionSegment("c", p1=c - along, p2=c + along)
        ball, _ = stronge.solve(ball, segment)
        out["stronge"].append([*ball.state.rvw[1, :2], *ball.state.rvw[2]])
    for v, w, n, h, e, f in cases["cushion"]:
        rvw = np.array([[0.5, 0.5, R], [v[0], v[1], 0.0], w], dtype=float)
        into = np.array([-n[0], -n[1], 0.0])  # pooltool's normal points along the velocity
        res = han2005(rvw, into, R, M, h, e, f)
        out["cushion"].append([*res[1, :2], *res[2]])
    strike = InstantaneousPoint()
    for v0, phi, theta, a, b in cases["strike"]:
        ball = Ball.create("cue", xy=(0.5, 0.5))
        cue = pt.Cue(V0=v0, phi=phi, theta=theta, a=a, b=b)
        _, ball = strike.solve(cue, ball)
        out["strike"].append([*ball.state.rvw[1, :2], *ball.state.rvw[2]])
    return out


def _cases(n: int, seed: int) -> dict:
    rng = np.random.default_rng(seed)

    def vec(k, scale):
        return (rng.uniform(-1, 1, k) * scale).tolist()

    ball_ball = []
    for i in range(n):
        angle = rng.uniform(-math.pi, math.pi)
        normal = [math.cos(angle), math.sin(angle)]
        v1, v2 = vec(2, 3.0), vec(2, 0.5)
        approach = (v1[0] - v2[0]) * normal[0] + (v1[1] - v2[1]) * normal[1]
        if approach <= 0.0:  # the loop resolves approaching pairs only
            v1 = [v1[0] + (0.1 - approach) * normal[0], v1[1] + (0.1 - approach) * normal[1]]
        e = 1.0 if i % 2 == 0 else 0.95
        ball_ball.append([v1, vec(3, 80.0), v2, vec(3, 40.0), normal, e])
    cushion = []
    for _ in range(n):
        angle = rng.uniform(-math.pi, math.pi)
        normal = [math.cos(angle), math.sin(angle)]
        v = vec(2, 2.0)
        v = [v[0] - 3.0 * normal[0], v[1] - 3.0 * normal[1]]  # into the cushion
        h = float(rng.choice([R, H, 1.4 * R]))
        cushion.append([v, vec(3, 100.0), normal, h, 0.85, float(rng.choice([0.0, 0.2, 0.6]))])
    strike = []
    for _ in range(n):
        radius = rng.uniform(0.0, 0.7)
        turn = rng.uniform(0, 2 * math.pi)
        strike.append(
            [
                rng.uniform(0.2, 8.0),
                rng.uniform(0, 360),
                rng.uniform(0, 80),
                radius * math.cos(turn),
                radius * math.sin(turn),
            ]
        )
    return {"ball_ball": ball_ball, "cushion": cushion, "strike": strike}


def _ours(cases: dict) -> dict:
    from types import SimpleNamespace

    from pool_env.sim.cue import from_pooltool
    from pool_env.sim.formulas import (
        ALCIATORE_FRICTION,
        POOLTOOL_FRICTION,
        STRONGE_CUSHION,
        ball_ball_mathavan,
        ball_ball_spin,
        cue_strike,
        cushion_han,
        cushion_spin,
    )

    out: dict = {"ball_ball": [], "ball_ball_pt_mu": [], "mathavan": [], "cushion": []}
    out |= {"stronge": [], "strike": []}
    buf = np.zeros(10)
    for v1, w1, v2, w2, n, e in cases["ball_ball"]:
        ball_ball_spin(*v1, *w1, *v2, *w2, *n, M, M, R, e, ALCIATORE_FRICTION, 0.0, buf)
        out["ball_ball"].append(buf.tolist())
        ball_ball_spin(*v1, *w1, *v2, *w2, *n, M, M, R, e, POOLTOOL_FRICTION, 0.0, buf)
        out["ball_ball_pt_mu"].append(buf.tolist())
        # pooltool's BallParams.u_s = 0.2 is Mathavan's table friction; 1000 steps
        ball_ball_mathavan(*v1, *w1, *v2, *w2, *n, M, M, R, e, ALCIATORE_FRICTION, 0.0, 0.2,
                           1000, buf)  # fmt: skip
        out["mathavan"].append(buf.tolist())
    for v, w, n, h, e, f in cases["cushion"]:
        cushion_han(*v, *w, *n, R, h, e, f, buf)
        out["cushion"].append(buf[:5].tolist())
        cushion_spin(*v, *w, *n, R, h, e, f, STRONGE_CUSHION, 1.8, buf)
        out["stronge"].append(buf[:5].tolist())
    table = SimpleNamespace(ball_radius=R, ball_mass=M, cue_tip_radius=TIP)
    for shot in cases["strike"]:
        angle, speed, tip, elevation = from_pooltool(*shot, table=table)
        cue_strike(speed, angle, tip[0], tip[1], elevation, R, M, M / 30, TIP, buf)
        out["strike"].append(buf[:5].tolist())
    return out


def _report(name: str, ours: list, theirs: list, width: int) -> None:
    a, b = np.array(ours)[:, :width], np.array(theirs)[:, :width]
    scale = np.ones(width)
    for k in range(width):  # spins compared as surface speeds w R
        if (width == 10 and k in (2, 3, 4, 7, 8, 9)) or (width == 5 and k >= 2):
            scale[k] = R
    diff = np.abs(a - b) * scale
    worst = diff.max(1)
    print(
        f"{name:26s} n={len(a):4d}  max |diff| {worst.max():.3e} m/s  median {np.median(worst):.3e}"
    )


def main() -> None:
    """Run both sides and print the differences."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--venv", default=".bench-venvs/pooltool")
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--seed", type=int, default=19)
    parser.add_argument("--pooltool-side", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.pooltool_side:
        json.dump(_pooltool_side(json.load(sys.stdin)), sys.stdout)
        return
    cases = _cases(args.n, args.seed)
    with tempfile.TemporaryDirectory() as scratch:
        env = {**os.environ, "HOME": scratch, "PYTHONDONTWRITEBYTECODE": "1"}
        env["NUMBA_CACHE_DIR"] = str(Path(scratch) / "numba")
        done = subprocess.run(
            [str(Path(args.venv) / "bin" / "python"), __file__, "--pooltool-side"],
            input=json.dumps(cases),
            capture_output=True,
            text=True,
            env=env,
            check=False,
        )
    if done.returncode:
        sys.exit(f"pooltool side failed:\n{done.stderr}")
    theirs = json.loads(done.stdout)
    ours = _ours(cases)
    bb_o, bb_t = np.array(ours["ball_ball"]), np.array(theirs["ball_ball"])
    elastic = np.array([c[5] == 1.0 for c in cases["ball_ball"]])
    _report("ball-ball, e_b = 1", bb_o[elastic], bb_t[elastic], 10)
    _report("ball-ball, e_b = 0.95", bb_o[~elastic], bb_t[~elastic], 10)
    bb_p = np.array(ours["ball_ball_pt_mu"])
    _report("  friction mode 3", bb_p[~elastic], bb_t[~elastic], 10)
    _report("ball-ball, Mathavan", ours["mathavan"], theirs["mathavan"], 10)
    _report("cushion (Han 2005)", ours["cushion"], theirs["cushion"], 5)
    _report("cushion (Stronge)", ours["stronge"], theirs["stronge"], 5)
    _report("strike (from_pooltool)", ours["strike"], theirs["strike"], 5)


if __name__ == "__main__":
    main()
