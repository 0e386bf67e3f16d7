"""Run scenes through pooltool; meant for pooltool's own virtualenv (a subprocess).

Reads one JSON document on stdin, prints one on stdout. Imports nothing from this project.

Input::

    {"repeats": 3, "max_events": 5000, "timeout": 60.0,
     "scenes": [{"table": {"length", "width", "ball_radius", "ball_mass", "mu_roll", "g",
                           "e_ball", "e_cushion", "pockets": true|false},
                 "positions": [[x, y], ...], "velocities": [[vx, vy], ...], "obj": 1,
                 "masses": null | [m, ...]}]}

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


def _to_pt(x: float, y: float, width: float) -> tuple[float, float]:
    return width - y, x


def _from_pt(px: float, py: float, width: float) -> tuple[float, float]:
    return py, width - px


def _table(spec: dict) -> pt.Table:
    if spec["pockets"]:
        specs = pt.objects.PocketTableSpecs(l=spec["length"], w=spec["width"])
    else:
        specs = pt.objects.BilliardTableSpecs(l=spec["length"], w=spec["width"])
    return pt.Table.from_table_specs(specs)


def _system(scene: dict) -> pt.System:
    spec = scene["table"]
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
    return {
        "positions": positions,
        "pocket_xy": pocket_xy,
        "obj_vel": obj_vel,
        "hits": sorted(list(h) for h in hits),
        "n_events": len(system.events),
    }


def _run(scene: dict, repeats: int, max_events: int, timeout: float) -> dict:
    times = []
    cpu_times = []  # this thread's CPU time: what the load of other processes leaves alone
    out: dict = {}
    try:
        for _ in range(repeats):
            system = _system(scene)
            signal.setitimer(signal.ITIMER_REAL, timeout)
            t0, c0 = time.perf_counter(), time.thread_time()
            try:
                pt.simulate(system, inplace=True, max_events=max_events)
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
    signal.signal(signal.SIGALRM, _on_alarm)
    job = json.load(sys.stdin)
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
