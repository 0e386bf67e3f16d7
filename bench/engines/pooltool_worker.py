"""Run scenes through pooltool; meant for pooltool's own virtualenv (a subprocess).

Reads one JSON document on stdin, prints one on stdout. Imports nothing from this project.

Input::

    {"repeats": 3, "max_events": 5000, "timeout": 60.0,
     "scenes": [{"table": {"length", "width", "ball_radius", "ball_mass", "mu_roll", "g",
                           "e_ball", "e_cushion", "pockets": true|false},
                 "positions": [[x, y], ...], "velocities": [[vx, vy], ...], "obj": 1,
                 "masses": null | [m, ...]}]}

Spin scenes (the spin level's equal-model comparison, ``bench/spin_vs_pooltool.py``) add
``"model": "spin"`` and ``mu_slide``, ``spin_decel``, ``ball_friction`` (``"alciatore"``
or a constant), ``alciatore`` (``[a, b, c]`` of the fit), ``cushion_friction``,
``cushion_height`` to the table, and ``angular_velocities`` (``[[wx, wy, wz], ...]``, our
frame) and optionally ``strike`` (``{"V0", "phi", "theta", "a", "b", "M", "end_mass"}`` in
pooltool's own terms and frame; every ball then starts at rest) to the scene. They run on a
pocketless ``BilliardTableSpecs`` table with a ``Resolver`` of Han 2005 cushions, the
frictional inelastic ball-ball model and the instantaneous-point strike; the balls start in
the motion state their velocities and spins give, and the result adds the final
velocities, angular velocities and the event list (``[time, type, [ball indices]]``).
Options of a spin table: ``"cushion_model": "stronge"`` (with ``"cushion_omega_ratio"``)
for Stronge's compliant cushions, ``"ball_model": "mathavan"`` (with ``"mathavan_steps"``)
for ``FrictionalMathavan``. A spin table with ``"defaults": "pocketless"`` runs pooltool at
its own defaults but for the pockets: its default resolver (``default_resolver()``, not the
user's YAML), default ``BallParams`` and ``CueSpecs``, on a ``BilliardTableSpecs`` table
of the given size and cushion height (the strike's ``M`` and ``end_mass`` are ignored).
A spin scene whose table has ``"defaults": true`` runs pooltool as it ships instead: its
default pocket table (``PocketTableSpecs`` of the given size), its default physics engine
and its default ball parameters (the speed comparison "each simulator at its defaults").

Output: versions, import and warm-up (numba compile) seconds, and per scene the wall times
of ``pooltool.simulate`` (system construction is not timed), final positions, pocketed
balls (pocket centres in our frame, for matching), the object ball's velocity after its
first ball-ball event, the colliding pairs, the event count, and any error.

Frame: pooltool puts x across the width and y along the length. We rotate by +90 degrees:
ours ``(x, y)`` is pooltool's ``(W - y, x)``. Every ball starts *rolling* (angular velocity
matched to its velocity, no side spin), the closest pooltool state to our model; pooltool's
default resolver then adds sliding, spin and throw at each collision.
"""

from __future__ import annotations

import json
import signal
import sys
import time
import traceback
from typing import Any

import numpy as np

_T0 = time.perf_counter()
import pooltool as pt  # noqa: E402

_IMPORT_S = time.perf_counter() - _T0


class _TimeoutError(Exception):
    pass


def _on_alarm(signum: int, frame: Any) -> None:
    raise _TimeoutError


def read_job() -> dict:
    """The job on stdin, with the alarm that times a shot out armed and MIN_DIST applied."""
    signal.signal(signal.SIGALRM, _on_alarm)
    job = json.load(sys.stdin)
    if job.get("min_dist") is not None:
        # pooltool moves colliding balls apart to a gap of MIN_DIST (1e-6 m) before it
        # resolves an impact ("make_kiss"); a smaller gap shows what that spacer costs.
        pt.constants.MIN_DIST = float(job["min_dist"])
    return job


def _to_pt(x: float, y: float, width: float) -> tuple[float, float]:
    return width - y, x


def _from_pt(px: float, py: float, width: float) -> tuple[float, float]:
    return py, width - px


def _table(spec: dict) -> pt.Table:
    if spec.get("defaults") == "pocketless":
        return pt.Table.from_table_specs(
            pt.objects.BilliardTableSpecs(
                l=spec["length"], w=spec["width"], cushion_height=spec["cushion_height"]
            )
        )
    if spec.get("defaults"):
        return pt.Table.from_table_specs(
            pt.objects.PocketTableSpecs(l=spec["length"], w=spec["width"])
        )
    if spec.get("model") == "spin":
        specs = pt.objects.BilliardTableSpecs(
            l=spec["length"], w=spec["width"], cushion_height=spec["cushion_height"]
        )
    elif spec["pockets"]:
        specs = pt.objects.PocketTableSpecs(l=spec["length"], w=spec["width"])
    else:
        specs = pt.objects.BilliardTableSpecs(l=spec["length"], w=spec["width"])
    return pt.Table.from_table_specs(specs)


def _engine(spec: dict) -> Any:
    """The pooltool physics engine configured to the spin level's models (or its default)."""
    from pooltool.physics.engine import PhysicsEngine
    from pooltool.physics.resolve.resolver import default_resolver

    if spec.get("defaults") == "pocketless":
        return PhysicsEngine(resolver=default_resolver())
    if spec.get("model") != "spin" or spec.get("defaults"):
        return None
    from pooltool.physics.resolve.ball_ball.friction import AlciatoreBallBallFriction
    from pooltool.physics.resolve.ball_ball.frictional_inelastic import FrictionalInelastic
    from pooltool.physics.resolve.ball_ball.frictional_mathavan import FrictionalMathavan
    from pooltool.physics.resolve.ball_cushion.han_2005.model import (
        Han2005Circular,
        Han2005Linear,
    )
    from pooltool.physics.resolve.ball_cushion.stronge_compliant.model import (
        StrongeCompliantCircular,
        StrongeCompliantLinear,
    )
    from pooltool.physics.resolve.resolver import Resolver

    default = Resolver.default()
    # A constant friction mu (0: frictionless, restitution kept) is the fit a + b e^(-c v)
    # with a = mu, b = 0.
    a, b, c = spec["alciatore"] if spec["ball_friction"] == "alciatore" else (
        float(spec["ball_friction"]), 0.0, 0.0)  # fmt: skip
    friction = AlciatoreBallBallFriction(a=a, b=b, c=c)
    ball_ball: Any = FrictionalInelastic(friction=friction)
    if spec.get("ball_model") == "mathavan":
        ball_ball = FrictionalMathavan(friction=friction, num_iterations=spec["mathavan_steps"])
    linear: Any = Han2005Linear()
    circular: Any = Han2005Circular()
    if spec.get("cushion_model") == "stronge":
        linear = StrongeCompliantLinear(omega_ratio=spec["cushion_omega_ratio"])
        circular = StrongeCompliantCircular(omega_ratio=spec["cushion_omega_ratio"])
    resolver = Resolver(
        ball_ball=ball_ball,
        ball_linear_cushion=linear,
        ball_circular_cushion=circular,
        ball_pocket=default.ball_pocket,
        stick_ball=default.stick_ball,  # InstantaneousPoint (with squirt)
        transition=default.transition,
        version=default.version,
    )
    return PhysicsEngine(resolver=resolver)


def _spin_ball(bid: str, scene: dict, k: int, mass: float) -> pt.Ball:
    """A ball with the spin level's parameters and its initial state (pooltool frame)."""
    spec = scene["table"]
    width, radius, g = spec["width"], spec["ball_radius"], spec["g"]
    x, y = scene["positions"][k]
    vx, vy = scene["velocities"][k]
    wx, wy, wz = scene["angular_velocities"][k]
    if spec.get("defaults"):  # pooltool's own ball parameters
        ball = pt.Ball.create(bid, xy=_to_pt(x, y, width))
        ball.state.s = pt.constants.stationary
        return ball
    ball = pt.Ball.create(
        bid,
        xy=_to_pt(x, y, width),
        m=mass,
        R=radius,
        u_s=spec["mu_slide"],
        u_r=spec["mu_roll"],
        # spin deceleration = (5/2) (u_sp / R) g with u_sp = proportionality * R
        u_sp_proportionality=spec["spin_decel"] * 2.0 / (5.0 * g),
        e_b=spec["e_ball"],
        e_c=spec["e_cushion"],
        f_c=spec["cushion_friction"],
        g=g,
    )
    # Ours (x, y) is pooltool's (W - y, x): vectors (and the spin about z) turn by +90 deg.
    v, w = [-vy, vx, 0.0], [-wy, wx, wz]
    ball.state.rvw[1] = v
    ball.state.rvw[2] = w
    slip = (v[0] - radius * w[1], v[1] + radius * w[0])
    if v[0] == 0 and v[1] == 0 and w[0] == 0 and w[1] == 0:
        ball.state.s = pt.constants.spinning if wz != 0 else pt.constants.stationary
    elif slip == (0.0, 0.0):
        ball.state.s = pt.constants.rolling
    else:
        ball.state.s = pt.constants.sliding
    return ball


def _system(scene: dict) -> pt.System:
    spec = scene["table"]
    if spec.get("model") == "spin":
        n = len(scene["positions"])
        masses = scene.get("masses") or [spec["ball_mass"]] * n
        balls = {
            ("cue" if k == 0 else str(k)): _spin_ball("cue" if k == 0 else str(k), scene, k,
                                                      masses[k])
            for k in range(n)
        }  # fmt: skip
        strike = scene.get("strike")
        if strike is None:
            cue = pt.Cue(cue_ball_id="cue", V0=0.0)
        elif spec.get("defaults") == "pocketless":  # pooltool's own CueSpecs
            cue = pt.Cue(
                cue_ball_id="cue", V0=strike["V0"], phi=strike["phi"], theta=strike["theta"],
                a=strike["a"], b=strike["b"],
            )  # fmt: skip
        else:
            specs = pt.objects.CueSpecs(M=strike["M"], end_mass=strike["end_mass"])
            cue = pt.Cue(
                cue_ball_id="cue",
                V0=strike["V0"],
                phi=strike["phi"],
                theta=strike["theta"],
                a=strike["a"],
                b=strike["b"],
                specs=specs,
            )
        return pt.System(cue=cue, table=_table(spec), balls=balls)
    width, radius = spec["width"], spec["ball_radius"]
    balls = {}
    masses = scene.get("masses") or [spec["ball_mass"]] * len(scene["positions"])
    for k, ((x, y), (vx, vy)) in enumerate(
        zip(scene["positions"], scene["velocities"], strict=True)
    ):
        bid = "cue" if k == 0 else str(k)
        ball = pt.Ball.create(
            bid,
            xy=_to_pt(x, y, width),
            m=masses[k],
            R=radius,
            u_r=spec["mu_roll"],
            g=spec["g"],
            e_b=spec["e_ball"],
            e_c=spec["e_cushion"],
        )
        pvx, pvy = -vy, vx
        if pvx or pvy:
            ball.state.rvw[1] = [pvx, pvy, 0.0]
            ball.state.rvw[2] = [-pvy / radius, pvx / radius, 0.0]  # rolling: no slip
            ball.state.s = pt.constants.rolling
        balls[bid] = ball
    return pt.System(cue=pt.Cue(cue_ball_id="cue"), table=_table(spec), balls=balls)


def _index(bid: str) -> int:
    return 0 if bid == "cue" else int(bid)


def _summary(system: pt.System, scene: dict) -> dict:
    width = scene["table"]["width"]
    n = len(scene["positions"])
    positions = [[0.0, 0.0]] * n
    pocket_xy: list[list[float] | None] = [None] * n
    for bid, ball in system.balls.items():
        k = _index(bid)
        px, py = float(ball.state.rvw[0][0]), float(ball.state.rvw[0][1])
        positions[k] = list(_from_pt(px, py, width))
    obj = scene.get("obj", -1)
    obj_vel = None
    hits = set()
    for event in system.events:
        if event.event_type == pt.EventType.BALL_BALL:
            ids = [_index(a.id) for a in event.agents]
            hits.add(tuple(sorted(ids)))
            if obj_vel is None and obj in ids:
                final = event.agents[ids.index(obj)].final
                v = final.state.rvw[1]
                obj_vel = [float(v[1]), float(-v[0])]
        elif event.event_type == pt.EventType.BALL_POCKET:
            k = _index(event.agents[0].id)
            centre = system.table.pockets[event.agents[1].id].center
            pocket_xy[k] = list(_from_pt(float(centre[0]), float(centre[1]), width))
    out = {
        "positions": positions,
        "pocket_xy": pocket_xy,
        "obj_vel": obj_vel,
        "hits": sorted(list(h) for h in hits),
        "n_events": len(system.events),
    }
    if scene["table"].get("model") == "spin":
        velocities, spins = [[0.0, 0.0]] * n, [[0.0, 0.0, 0.0]] * n
        for bid, ball in system.balls.items():
            _, (pvx, pvy, _), (pwx, pwy, pwz) = ball.state.rvw
            velocities[_index(bid)] = [float(pvy), float(-pvx)]
            spins[_index(bid)] = [float(pwy), float(-pwx), float(pwz)]
        out["velocities"], out["angular_velocities"] = velocities, spins
        out["events"] = [
            [float(e.time), str(e.event_type), [_index(a.id) for a in e.agents if a.id in
                                                system.balls]]
            for e in system.events
        ]  # fmt: skip
    return out


def _run(scene: dict, repeats: int, max_events: int, timeout: float) -> dict:
    times = []
    cpu_times = []  # this thread's CPU time: what the load of other processes leaves alone
    out: dict = {}
    engine = _engine(scene["table"])
    try:
        for _ in range(repeats):
            system = _system(scene)
            signal.setitimer(signal.ITIMER_REAL, timeout)
            t0, c0 = time.perf_counter(), time.thread_time()
            try:
                pt.simulate(system, engine=engine, inplace=True, max_events=max_events)
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0.0)
            times.append(time.perf_counter() - t0)
            cpu_times.append(time.thread_time() - c0)
        out = _summary(system, scene)
        out["capped"] = max_events > 0 and out["n_events"] >= max_events
        out["error"] = None
    except _TimeoutError:
        out = {"error": f"hang: no result after {timeout} s", "kind": "hang"}
    except Exception as exc:  # a crash is a result here, reported per scene
        tb = traceback.format_exc(limit=3).strip().splitlines()[-1]
        out = {"error": f"{type(exc).__name__}: {exc}"[:300], "kind": "crash", "where": tb}
    out["times"] = times
    out["cpu_times"] = cpu_times
    return out


def main() -> None:
    """Read the job from stdin, run it, print the results as JSON."""
    job = read_job()
    scenes = job["scenes"]
    t0 = time.perf_counter()
    if scenes:  # first use compiles pooltool's numba kernels (or loads them from its cache)
        _run(scenes[0], 1, job.get("max_events", 0), 600.0)
    warmup_s = time.perf_counter() - t0
    results = [
        _run(s, job.get("repeats", 1), job.get("max_events", 0), job.get("timeout", 60.0))
        for s in scenes
    ]
    import numba

    json.dump(
        {
            "pooltool": pt.__version__,
            "numpy": np.__version__,
            "numba": numba.__version__,
            "python": sys.version.split()[0],
            "import_s": _IMPORT_S,
            "warmup_s": warmup_s,
            "results": results,
        },
        sys.stdout,
    )


if __name__ == "__main__":
    main()
