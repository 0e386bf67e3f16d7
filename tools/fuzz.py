"""Robustness fuzz: many random scenes and shots, every invariant checked on each.

Run: ``python -m tools.fuzz --shots 100000`` (the long run; CI runs a small sample through
``tests/sim/test_properties.py``). Prints the violation count and writes
``results/fuzz.md``. Scenes mix: random layouts of 2-16 balls (some touching), 9- and 15-ball
breaks with jittered aim, random speeds from 1e-6 to 15 m/s, random restitutions and
rolling resistances; jaw tables (half of them; random jaw restitution including 0),
capture-circle and pocketless tables, with shots aimed at a pocket's mouth one time in four
so that jaws are hit often; and what issue 11 found: masses spread over ratios up to 1e6,
lumps of light balls pressed into a rail by a heavy one, and tables, radii and speeds
scaled to the edges of the numeric limits.

``python -m tools.fuzz --model spin`` (from the repository's root) runs the same scene
kinds on spin tables (``Table(model="spin")``) with random spin parameters, cue strikes
with random tips and elevations, and random initial angular velocities
(:mod:`tools.fuzz_spin`); every invariant then includes the spin (energy with the
rotational part, and M, the motion states and transitions).

``--table snooker`` (or ``carom``) plays every shot on that preset's table
(``Table.preset``) instead of a random one: half the shots on the preset as it is, half
with random restitutions, rolling resistance and (spin) spin parameters over its
geometry. The snooker table's big round jaws are then hit one shot in four. ``carom`` is
a spin table only (``--model spin``).

Every invariant is checked on every shot, and a shot the simulator refuses (a ``ValueError``
from a table and a draw it accepted) is a violation (R): every draw is meant to be a real
shot. The termination target is no event-cap hit on a
damped table (``mu_roll >= 1e-3``, both restitutions below 1); an undamped table (elastic,
or nearly frictionless) can legitimately need any number of events, and its cap hits are
listed.
"""

from __future__ import annotations

import argparse
import time
from collections import Counter
from collections.abc import Iterator
from functools import partial
from itertools import islice
from pathlib import Path

import numpy as np

from pool_env import Table, simulate
from pool_env.sim.constants import MAX_LENGTH, MIN_LENGTH
from pool_env.sim.inputs import max_speed
from pool_env.sim.layouts import break_scene
from pool_env.sim.result import ShotResult
from pool_env.testing.invariants import check_shot
from pool_env.testing.scenes_random import (
    log_uniform_masses,
    lump_at_rail,
    random_layout,
    within_limits,
)
from tools import fuzz_spin

DEFAULT = Table()
MASS_RATIO = 1e6


def is_damped(table: Table) -> bool:
    """Whether every motion on ``table`` loses energy: the target's tables."""
    return table.mu_roll >= 1e-3 and table.e_ball < 1.0 and table.e_cushion < 1.0


def preset_table(
    rng: np.random.Generator, preset: str, spin: dict[str, object]
) -> tuple[Table, float]:
    """The ``preset``'s table, as it is or with random damping and ``spin`` parameters.

    ``spin`` is :func:`fuzz_spin.random_spin_parameters`'s draw on the spin level, else
    empty. Half the tables are the preset as it is (on ``spin``'s level); the other half
    draw restitutions and rolling resistance as :func:`random_table` does, over the
    preset's geometry.
    """
    level = {"model": "spin"} if spin else {"model": "roll"}
    if rng.random() < 0.5:
        return Table.preset(preset, **level), 1.0
    radius = float(Table.preset(preset, **level).ball_radius)
    e_cushion = float(rng.choice([1.0, 0.85, 0.65, rng.uniform(0, 1)]))
    e_jaw = float(rng.choice([e_cushion, rng.uniform(0, 1), 0.0]))
    kwargs: dict[str, object] = dict(level)
    if spin:
        kwargs = fuzz_spin.spin_table_kwargs(spin, radius)
        e_cushion = fuzz_spin.model_restitution(spin, e_cushion)
        e_jaw = fuzz_spin.model_restitution(spin, e_jaw)
    table = Table.preset(
        preset,
        mu_roll=0.01 if rng.random() < 0.5 else float(10 ** rng.uniform(-3, -1)),
        e_ball=float(rng.choice([1.0, 0.95, rng.uniform(0, 1), 0.0])),
        e_cushion=e_cushion,
        e_jaw=e_jaw,
        **kwargs,
    )
    return table, 1.0


def random_table(rng: np.random.Generator, **spin: object) -> tuple[Table, float]:
    """A random table and its length scale relative to the default table.

    One in ten is scaled (sizes, radius, pockets) by a log-uniform factor that reaches the
    numeric limits on both sides; rolling resistance spans 1e-4 to 0.1 (below 1e-3 for one
    table in ten). ``spin`` holds further keyword arguments of :class:`Table` (a spin
    table's model and parameters); they draw nothing from ``rng``.
    """
    scale = 1.0
    if rng.random() < 0.1:
        low = np.log10(MIN_LENGTH / DEFAULT.ball_radius)
        high = np.log10(MAX_LENGTH / DEFAULT.length)
        scale = float(10 ** rng.uniform(low, high))
    pockets = str(rng.choice(["jaws", "jaws", "circles", "none"]))
    if pockets == "jaws" and scale != 1.0:  # regulation jaws are sized in inches
        pockets = "circles"
    e_cushion = float(rng.choice([1.0, 0.85, 0.65, rng.uniform(0, 1)]))
    u = rng.random()  # mostly damped; one in ten nearly frictionless
    mu_roll = (
        0.01
        if u < 0.45
        else float(10 ** rng.uniform(-3, -1) if u < 0.9 else 10 ** rng.uniform(-4, -3))
    )
    if spin:
        spin = fuzz_spin.spin_table_kwargs(spin, DEFAULT.ball_radius * scale)
    e_ball = float(rng.choice([1.0, 0.95, rng.uniform(0, 1), 0.0]))
    e_jaw = float(rng.choice([e_cushion, rng.uniform(0, 1), 0.0]))
    if spin:
        e_cushion = fuzz_spin.model_restitution(spin, e_cushion)
        e_jaw = fuzz_spin.model_restitution(spin, e_jaw)
    table = Table(
        length=DEFAULT.length * scale,
        width=DEFAULT.width * scale,
        ball_radius=DEFAULT.ball_radius * scale,
        mu_roll=mu_roll,
        e_ball=e_ball,
        e_cushion=e_cushion,
        pockets=DEFAULT.pockets * scale if pockets == "circles" else pockets,
        e_jaw=e_jaw,
        **spin,  # type: ignore[arg-type]
    )
    return table, scale


def _is_valid(table: Table, positions: np.ndarray) -> bool:
    try:
        simulate(table, positions, np.zeros_like(positions), record=False)
    except ValueError:
        return False
    return True


def random_case(
    rng: np.random.Generator, preset: str | None = None, **spin: object
) -> tuple[Table, np.ndarray, np.ndarray, np.ndarray]:
    """One random table, layout, initial velocities and masses (``spin``: as random_table).

    ``preset``: the table is that preset's (:func:`preset_table`), not a random one.
    """
    if preset is None:
        table, scale = random_table(rng, **spin)
    else:
        table, scale = preset_table(rng, preset, spin)
    kind = rng.integers(5)
    if kind == 4:  # a heavy ball drives a chain of light ones into a rail
        speed = min(float(rng.uniform(0.05, 5) * np.sqrt(scale)), 0.999 * max_speed(table))
        for _ in range(20):
            pos, vel = lump_at_rail(
                table, rng, int(rng.integers(1, 4)), float(rng.uniform(0, 0.5) * scale), speed
            )
            if _is_valid(table, pos):
                break
        else:
            kind = 1
        if kind == 4:
            n = pos.shape[0]
            ratio = float(10 ** rng.uniform(0, np.log10(MASS_RATIO)))
            masses = np.full(n, table.ball_mass)
            masses[0] *= np.sqrt(ratio)  # the driver heavy, the chain light
            masses[1:] /= np.sqrt(ratio)
            return table, pos, within_limits(table, vel, masses), masses
    if kind == 0:
        pos = break_scene(table, str(rng.choice(["nine", "eight"])))
        if not _is_valid(table, pos):  # a scaled table's pockets may cover the rack
            kind = 1
    if kind != 0:
        n = int(rng.integers(2, 17))
        gap = float(rng.choice([0.0, 1e-3, 0.05])) * scale
        pos = random_layout(table, n, rng, min_gap=gap)
        if kind == 1 and n > 1:  # push ball 1 to touch ball 0 exactly, in a random direction
            phi = rng.uniform(0, 2 * np.pi)
            cand = pos[0] + 2 * table.ball_radius * np.array([np.cos(phi), np.sin(phi)])
            trial = pos.copy()
            trial[1] = cand
            if _is_valid(table, trial):
                pos = trial
    n = pos.shape[0]
    vel = np.zeros((n, 2))
    movers = [0] if rng.random() < 0.8 else list(range(n))
    fastest = max_speed(table)
    for i in movers:
        # Mostly playing speeds (scaled with the table), a tail down to 1e-6 m/s, and a few
        # up to the fastest speed the limits allow on this table.
        u = rng.random()
        if u < 0.75:
            speed = float(rng.uniform(0.1, 15) * np.sqrt(scale))
        elif u < 0.95:
            speed = float(10 ** rng.uniform(-6, -1))
        else:
            speed = float(10 ** rng.uniform(-1, 0) * fastest)
        phi = rng.uniform(0, 2 * np.pi) if kind else rng.normal(0, 0.01)
        if kind and table.n_pockets and rng.random() < 0.25:  # at a pocket's mouth, jittered
            target = table.pockets[int(rng.integers(table.n_pockets)), :2]
            aim = target - pos[i] + rng.normal(0.0, 0.03 * scale, 2)
            phi = float(np.arctan2(aim[1], aim[0]))
        vel[i] = min(speed, 0.999 * fastest) * np.array([np.cos(phi), np.sin(phi)])
    u = rng.random()
    if u < 0.2:
        masses = rng.uniform(0.1, 0.3, n)
    elif u < 0.4:
        masses = log_uniform_masses(rng, n, table.ball_mass, MASS_RATIO)
    else:
        masses = np.full(n, table.ball_mass)
    return table, pos, within_limits(table, vel, masses), masses


def shot_problems(table: Table, result: ShotResult, masses: np.ndarray, samples: int) -> list[str]:
    """Every invariant of one shot; an event-cap hit counts only on a damped table.

    The target: a damped table always comes to rest under the cap. An undamped one
    (elastic, or nearly frictionless) can need any number of events: a light ball rattling
    between a rail and a heavy ball that it slowly pushes away.
    """
    problems = check_shot(table, result, masses, samples=samples)
    if result.hit_event_cap:
        problems = [p for p in problems if not p.startswith("T:")]
        if is_damped(table):
            problems.append("T: a damped table hit the event cap")
    return problems


def cases(seed: int, model: str = "roll", preset: str | None = None) -> Iterator[tuple]:
    """The fuzz's shots in order: ``(table, positions, velocities, masses, run)``.

    ``run()`` simulates the shot. Scenes are drawn without simulating, so shot ``k`` of a
    seed can be regenerated alone (``--only k``) to reproduce a violation. ``preset``: every
    shot on that preset's table (:func:`preset_table`).
    """
    rng = np.random.default_rng(seed)
    while True:
        if model == "spin":
            spin = fuzz_spin.random_spin_parameters(rng)
            table, pos, vel, masses = random_case(rng, preset, **spin)
            yield table, pos, vel, masses, fuzz_spin.spin_shot(rng, table, pos, vel, masses)
        else:
            table, pos, vel, masses = random_case(rng, preset)
            yield table, pos, vel, masses, partial(simulate, table, pos, vel, masses)


def main() -> None:
    """Run the fuzz and write ``results/fuzz.md``."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--shots", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--samples", type=int, default=400, help="G samples between events")
    parser.add_argument(
        "--out", type=Path, default=None, help="default results/fuzz.md or results/fuzz_spin.md"
    )
    parser.add_argument("--model", choices=["roll", "spin"], default="roll")
    parser.add_argument("--progress", type=int, default=10000, help="shots per progress line")
    parser.add_argument("--only", type=int, default=None, help="rerun one shot and print it")
    parser.add_argument("--spin", action="store_true", help="the same as --model spin")
    parser.add_argument(
        "--table",
        choices=["random", "snooker", "carom"],
        default="random",
        help="random tables (default) or every shot on Table.preset(TABLE)",
    )
    args = parser.parse_args()
    if args.spin:
        args.model = "spin"
    if args.table == "carom" and args.model == "roll":
        parser.error("--table carom is a spin table only (three-cushion): add --model spin")
    preset = None if args.table == "random" else args.table
    if args.only is not None:
        shots = cases(args.seed, args.model, preset)
        table, pos, vel, masses, run = next(islice(shots, args.only, None))
        result = run()
        print(table, pos.tolist(), vel.tolist(), masses.tolist(), result, sep="\n")
        print(check_shot(table, result, masses, samples=args.samples))
        return
    if args.out is None:
        stem = "fuzz" if args.model == "roll" else "fuzz_spin"
        args.out = Path(f"results/{stem}{'' if preset is None else '_' + preset}.md")
    started = time.time()
    failures: list[str] = []
    long_shots: list[str] = []
    damped_caps = 0
    damped_shots = 0
    events = []
    kinds: Counter[str] = Counter()
    refused: list[str] = []
    for shot, (table, _pos, _vel, masses, run) in enumerate(cases(args.seed, args.model, preset)):
        if shot == args.shots:
            break
        try:
            result = run()
        except ValueError as exc:  # R: the table and the draw were accepted, the shot not
            refused.append(f"shot {shot}: {exc}")
            kinds.update("R")
            failures.append(f"shot {shot}: ['R: refused: {exc}']")
            print(failures[-1], flush=True)
            continue
        events.append(result.n_events)
        damped = is_damped(table)
        damped_shots += damped
        problems = shot_problems(table, result, masses, args.samples)
        if result.hit_event_cap:
            damped_caps += damped
            long_shots.append(f"shot {shot}: capped at {result.duration:.3g} s ({table!r})")
        if shot % 10 == 0:
            again = run()
            if not np.array_equal(again.positions, result.positions) or not np.array_equal(
                again.event_times, result.event_times
            ):
                problems.append("D: rerun differs")
        if problems:
            kinds.update({p[0] for p in problems})
            failures.append(f"shot {shot}: {problems[:3]}")
            print(failures[-1], flush=True)
        if (shot + 1) % args.progress == 0:
            print(
                f"{shot + 1} shots, {len(failures)} with violations {dict(sorted(kinds.items()))}"
                f", {damped_caps} damped caps, {len(refused)} refused, events median "
                f"{np.median(events):.0f}, {time.time() - started:.0f} s",
                flush=True,
            )
    ev = np.array(events)
    report = [
        "# Fuzz: invariants over random scenes and shots",
        "",
        f"Command: `python -m tools.fuzz --shots {args.shots} --seed {args.seed}"
        f"{' --model spin' if args.model == 'spin' else ''}"
        f"{'' if preset is None else ' --table ' + preset}`",
        "",
        f"- shots: {args.shots}; shots with any violation (G, P, E, T, O, M, D, R): "
        f"{len(failures)}",
        f"- shots with a violation, by kind: {dict(sorted(kinds.items()))}",
        f"- shots refused by a ValueError (R, not simulated): {len(refused)}",
        *[f"  - {s}" for s in refused[:5]],
        f"- damped tables (mu_roll >= 1e-3, e_ball < 1, e_cushion < 1): {damped_shots} "
        f"shots, {damped_caps} event-cap hits",
        f"- events per shot: median {np.median(ev):.0f}, p99 {np.percentile(ev, 99):.0f}, "
        f"max {ev.max()}",
        f"- wall time: {time.time() - started:.0f} s",
        "- shots on undamped tables that reached the default cap of 10,000 events (G, P, E",
        f"  and D checked over their events; no bound on their length): {len(long_shots)}",
        *[f"  - {s}" for s in long_shots[:20]],
        *([f"  - ... ({len(long_shots)} in all)"] if len(long_shots) > 20 else []),
        "",
    ]
    report += [f"- {f}" for f in failures[:50]]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text("\n".join(report) + "\n")
    print("\n".join(report))


if __name__ == "__main__":
    main()
