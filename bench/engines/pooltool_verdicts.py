"""pooltool 0.6 plays shots and judges them by its own rulesets (``verdicts_vs_pooltool``).

Meant for pooltool's own virtualenv (run as a subprocess by
:func:`bench.engines.pooltool_engine.run_worker`); imports nothing from this project and
works in pooltool's frame and names throughout (the caller maps its layouts and shots with
``pool_env.interop.pooltool``). Reads one JSON document on stdin, prints one on stdout.

Input::

    {"timeout": 60.0, "min_dist": 1e-12 | null,
     "table": {"kind": "billiard" | "snooker", "l": ..., "w": ..., "cushion_height": ...},
     "ball": {BallParams keywords: "m", "R", "u_s", "u_r", "u_sp_proportionality", "e_b",
              "e_c", "f_c", "g"},
     "cue": {"M": ..., "tip_radius": ..., "end_mass": ...},
     "shots": [{"game": "three_cushion" | "snooker",
                "balls": {id: [x, y], ...},   # pooltool ids and frame
                "cue_ball": "white",           # three-cushion: "white" or "yellow"
                "stroke": {"V0", "phi", "theta", "a", "b"},
                # snooker only: pooltool's ShotConstraints of the shot
                "hittable": [ids], "call_shot": bool, "ball_call": id | null}]}

A ``"snooker"`` table is ``SnookerTableSpecs()`` with the given ``l``, ``w`` and
``cushion_height`` (its pockets as pooltool ships them), a ``"billiard"`` table
``BilliardTableSpecs``. Every shot runs on pooltool's default physics engine (its
``default_resolver()``, not a user's YAML), every ball with the given ``BallParams``.
``min_dist`` replaces pooltool's collision spacer ``constants.MIN_DIST`` (1e-6 m as it
ships; ``null`` keeps it), as ``bench/models_vs_pooltool.py`` does: the spacer backs the
balls apart before each impact, which later impacts amplify to millimetres.

Per shot the output has pooltool's verdict, from its ruleset's own ``build_shot_info``
on a two-player game (``"A"`` to shoot, ``"B"`` the opponent; scores start at zero):

* three-cushion (``_ThreeCushion``, the cue ball cueable): ``point`` (``is_point``),
  ``turn_over``, ``points`` (A's score after the shot);
* snooker (``_Snooker`` with the given constraints, phase from the constraints):
  ``legal``, ``reason``, ``turn_over``, ``points`` (A's score: the points of a legal
  pot), ``penalty`` (B's: the foul's points);

and the outcome summary the comparison reads: ``first`` (the first ball the cue ball
hit, ``None`` if none), ``second`` (the second distinct ball it hit), ``cushions_second``
(its linear-cushion events at or before that contact, as ``is_point`` counts them;
``None`` without a second ball), ``circular_second`` (its circular-cushion events then:
jaws), ``potted`` (``[id, pocket id]`` in the order they dropped), ``final`` (each ball's
final ``[x, y]``), ``pockets`` (each pocket id's centre), ``events`` (``[time, type,
ids]`` of every ball-ball, cushion and pocket event) and ``error`` (a crash or hang,
``None`` if none).
"""

from __future__ import annotations

import json
import signal
import sys
import traceback

import pooltool as pt
from pooltool.events.datatypes import EventType
from pooltool.physics.engine import PhysicsEngine
from pooltool.physics.resolve.resolver import default_resolver
from pooltool.ruleset.datatypes import BallInHandOptions, Player, ShotConstraints
from pooltool.ruleset.snooker import _Snooker
from pooltool.ruleset.three_cushion import _ThreeCushion, is_point
from pooltool.ruleset.utils import get_id_of_first_ball_hit

# A script beside pooltool_worker.py (its folder is on sys.path): the job's reading and
# the shot's timeout are that worker's.
from pooltool_worker import _TimeoutError, read_job

_KEPT = {
    EventType.BALL_BALL: "ball",
    EventType.BALL_LINEAR_CUSHION: "cushion",
    EventType.BALL_CIRCULAR_CUSHION: "jaw",
    EventType.BALL_POCKET: "pocket",
}


def _table(spec: dict) -> pt.Table:
    size = {"l": spec["l"], "w": spec["w"], "cushion_height": spec["cushion_height"]}
    if spec["kind"] == "snooker":
        return pt.Table.from_table_specs(pt.objects.SnookerTableSpecs(**size))
    return pt.Table.from_table_specs(pt.objects.BilliardTableSpecs(**size))


def _system(job: dict, shot: dict) -> pt.System:
    balls = {
        bid: pt.Ball.create(bid, xy=(float(x), float(y)), **job["ball"])
        for bid, (x, y) in shot["balls"].items()
    }
    specs = pt.objects.CueSpecs(**job["cue"])
    cue = pt.Cue(cue_ball_id=shot["cue_ball"], specs=specs, **shot["stroke"])
    return pt.System(cue=cue, table=_table(job["table"]), balls=balls)


def _players() -> list[Player]:
    return [Player("A"), Player("B")]


def _three_cushion(system: pt.System, shot: dict) -> dict:
    game = _ThreeCushion(players=_players())
    game.shot_constraints = ShotConstraints(
        ball_in_hand=BallInHandOptions.NONE, movable=[], cueable=[shot["cue_ball"]],
        hittable=(), call_shot=False,
    )  # fmt: skip
    info = game.build_shot_info(system)
    return {
        "point": bool(is_point(system)),
        "legal": bool(info.legal),
        "turn_over": bool(info.turn_over),
        "points": int(info.score["A"]),
    }


def _snooker(system: pt.System, shot: dict) -> dict:
    game = _Snooker(players=_players())
    game.shot_constraints = ShotConstraints(
        ball_in_hand=BallInHandOptions.NONE, movable=[], cueable=["white"],
        hittable=tuple(shot["hittable"]), call_shot=bool(shot["call_shot"]),
        ball_call=shot["ball_call"], pocket_call="lb" if shot["call_shot"] else None,
    )  # fmt: skip
    info = game.build_shot_info(system)
    return {
        "legal": bool(info.legal),
        "reason": str(info.reason),
        "turn_over": bool(info.turn_over),
        "points": int(info.score["A"]),
        "penalty": int(info.score["B"]),
    }


def _summary(system: pt.System, cue_ball: str) -> dict:
    hit: list[str] = []
    second_time = None
    events = []
    for event in system.events:
        kind = _KEPT.get(event.event_type)
        if kind is None:
            continue
        ids = [a.id for a in event.agents if a.id in system.balls]
        if kind == "pocket":
            ids.append(event.agents[1].id)
        events.append([float(event.time), kind, ids])
        if kind == "ball" and cue_ball in ids:
            other = ids[0] if ids[1] == cue_ball else ids[1]
            if other not in hit:
                hit.append(other)
                if len(hit) == 2:
                    second_time = float(event.time)
    cushions = circular = None
    if second_time is not None:
        cushions = sum(
            1 for t, k, ids in events if k == "cushion" and ids[0] == cue_ball and t <= second_time
        )
        circular = sum(
            1 for t, k, ids in events if k == "jaw" and ids[0] == cue_ball and t <= second_time
        )
    return {
        "first": get_id_of_first_ball_hit(system, cue=cue_ball),
        "hit_order": hit,
        "second": hit[1] if len(hit) > 1 else None,
        "cushions_second": cushions,
        "circular_second": circular,
        "potted": [[ids[0], ids[1]] for _, k, ids in events if k == "pocket"],
        "final": {
            bid: [float(b.state.rvw[0][0]), float(b.state.rvw[0][1])]
            for bid, b in system.balls.items()
        },
        "pockets": {
            pid: [float(p.center[0]), float(p.center[1])] for pid, p in system.table.pockets.items()
        },
        "events": events,
    }


def _run(job: dict, shot: dict, engine: PhysicsEngine, timeout: float) -> dict:
    try:
        system = _system(job, shot)
        signal.setitimer(signal.ITIMER_REAL, timeout)
        try:
            pt.simulate(system, engine=engine, inplace=True)
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0.0)
        out = _summary(system, shot["cue_ball"])
        rules = _snooker if shot["game"] == "snooker" else _three_cushion
        out["verdict"] = rules(system, shot)
        out["error"] = None
    except _TimeoutError:
        out = {"error": f"hang: no result after {timeout} s"}
    except Exception as exc:  # a crash (or a ruleset's assertion) is a result, per shot
        where = traceback.format_exc(limit=4).strip().splitlines()[-3:]
        out = {"error": f"{type(exc).__name__}: {exc}"[:300], "where": where}
    return out


def main() -> None:
    """Read the job from stdin, play and judge its shots, print the results as JSON."""
    job = read_job()
    engine = PhysicsEngine(resolver=default_resolver())
    timeout = float(job.get("timeout", 60.0))
    results = [_run(job, shot, engine, timeout) for shot in job["shots"]]
    json.dump({"pooltool": pt.__version__, "results": results}, sys.stdout)


if __name__ == "__main__":
    main()
