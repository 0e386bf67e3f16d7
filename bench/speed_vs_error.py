"""Speed against error: this simulator, a fixed-step integrator, pymunk and pooltool.

One command, one run, one machine::

    python -m bench.speed_vs_error                # full run (~15-25 min on 2 cores)
    python -m bench.speed_vs_error --quick        # smaller suites
    python -m bench.speed_vs_error --spin-only    # the spin level's section alone (~3 min)

writes ``results/speed_vs_error.md``, ``results/speed_vs_error.png`` (the roll level) and
``results/speed_vs_error_spin.png`` (the spin level beside pooltool on equal physics,
:mod:`bench.spin_rows`). ``--spin-only`` rewrites only the spin section of an existing
report (and its plot), saying so with its own command, date and load. pooltool runs in its
own virtualenv (``bash bench/setup_pooltool.sh``); without it the report says why.
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from bench import sections
from bench.engines.fixed_step import simulate_fixed_step
from bench.engines.pooltool_engine import run_pooltool
from bench.errors import ReferenceCache
from bench.report import Metrics, machine, metrics, notes, plot, shots_table, targets
from bench.runners import Run, run_fixed, run_ours, run_pooltool_suite, run_pymunk
from bench.scenes import break_suite, shot_suite
from bench.spin_rows import SpinSuite, run_spin_suite, spin_plot, spin_section

ROOT = Path(__file__).resolve().parents[1]
FIXED_DTS = (1e-2, 1e-3, 1e-4, 1e-5)


@dataclass(frozen=True)
class Config:
    """Suite sizes and repeats of a run."""

    shots: int
    breaks: int
    chaos_breaks: int
    repeats: int
    pymunk_subset: dict[float, int]  # dt -> number of shots (pymunk is slow at small dt)
    pymunk_break_subset: dict[float, int]
    spin_shots: int  # struck shots of the spin level (bench.spin_rows)


FULL = Config(
    500,
    40,
    10,
    7,
    {1 / 60: 500, 1e-3: 500, 1e-4: 100, 1e-5: 12},
    {1 / 60: 40, 1e-3: 40, 1e-4: 8, 1e-5: 2},
    200,
)
QUICK = Config(40, 4, 2, 3, {1 / 60: 40, 1e-3: 20, 1e-4: 3}, {1 / 60: 4, 1e-3: 2, 1e-4: 1}, 40)


def _log(msg: str) -> None:
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", flush=True)


def _fresh_process_first_shot() -> float:
    """Seconds from a new interpreter to the end of its first shot (cached kernels)."""
    code = (
        "import time; t=time.perf_counter(); import numpy as np; "
        "from pool_env import Table, shoot; shoot(Table(), np.array([[0.5,0.6],[1.5,0.6]]), "
        "0.0, 1.0); print(time.perf_counter()-t)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=False, cwd=ROOT
    )
    try:
        return float(out.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        return math.nan


def _warm_up() -> dict[str, float]:
    """First-call costs (numba compile or cache load), measured before anything is timed."""
    from pool_env import Table, shoot

    table = Table(pockets="circles")  # the pocket model the fixed-step engine shares
    pos = np.array([[0.5, 0.6], [1.5, 0.6]])
    t0 = time.perf_counter()
    shoot(table, pos, 0.0, 1.0)
    first_ours = time.perf_counter() - t0
    t0 = time.perf_counter()
    simulate_fixed_step(
        table.params,
        table.pockets,
        pos,
        np.array([[1.0, 0.0], [0.0, 0.0]]),
        np.full(2, table.ball_mass),
        1e-3,
        1,
    )
    first_fixed = time.perf_counter() - t0
    return {"ours": first_ours, "fixed": first_fixed, "fresh": _fresh_process_first_shot()}


def _subset(n_total: int, n: int) -> list[int]:
    return list(np.linspace(0, n_total - 1, min(n, n_total)).round().astype(int))


def _suite_runs(
    scenes: list, cfg: Config, subset: dict[float, int], use_pymunk: bool, repeats: int
) -> list[Run]:
    runs = [run_ours(scenes, repeats, record=False), run_ours(scenes, repeats, record=True)]
    _log("  ours done")
    for dt in FIXED_DTS:
        runs.append(run_fixed(scenes, dt, repeats if dt >= 1e-4 else 1))
        _log(f"  fixed-step dt={dt:g} done")
    if use_pymunk:
        for dt in subset:
            runs.append(run_pymunk(scenes, dt, _subset(len(scenes), subset[dt])))
            _log(f"  pymunk dt={dt:g} done")
    return runs


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark and write the report; returns the exit status."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small suites (~2 min)")
    ap.add_argument("--out", type=Path, default=ROOT / "results")
    ap.add_argument("--no-pooltool", action="store_true")
    ap.add_argument("--no-pymunk", action="store_true")
    ap.add_argument("--no-cache", action="store_true", help="no on-disk reference cache")
    ap.add_argument(
        "--spin-only", action="store_true", help="run the spin level only; rewrite its section"
    )
    args = ap.parse_args(argv)
    cfg = QUICK if args.quick else FULL
    t_start = time.perf_counter()
    args.out.mkdir(parents=True, exist_ok=True)
    info = machine()
    _log(f"machine: {info}")
    if args.spin_only:
        return _spin_only(cfg, args, info)
    warm = _warm_up()
    use_pymunk = not args.no_pymunk
    if use_pymunk:
        try:
            import pymunk  # noqa: F401
        except ImportError:
            use_pymunk = False
    shots, breaks = shot_suite(cfg.shots), break_suite(cfg.breaks)
    cache = ReferenceCache(None if args.no_cache else args.out / ".cache")
    _log(f"{len(shots)} shots, {len(breaks)} breaks; computing the reference")
    refs = [cache.get(s) for s in shots]
    brefs = [cache.get(s) for s in breaks]
    cache.save()
    _log(f"reference: {cache.computed} computed in {cache.seconds:.1f} s")

    _log("shots")
    runs = _suite_runs(shots, cfg, cfg.pymunk_subset, use_pymunk, cfg.repeats)
    _log("breaks")
    bruns = _suite_runs(breaks, cfg, cfg.pymunk_break_subset, use_pymunk, cfg.repeats)
    pt_info: dict = {"available": False, "reason": "disabled with --no-pooltool"}
    if not args.no_pooltool:
        _log("pooltool (subprocess)")
        pt_run, pt_info = run_pooltool_suite([*shots, *breaks], repeats=3)
        if pt_run is not None:
            n = len(shots)
            runs.append(_slice(pt_run, 0, n))
            bruns.append(_slice(pt_run, n, len(breaks)))
    base, bbase = float(np.median(runs[0].times)), float(np.median(bruns[0].times))
    rows = [metrics(r, refs, base) for r in runs]
    brows = [metrics(r, brefs, bbase) for r in bruns]
    _log("chaos")
    chaos = sections.chaos_rows(breaks[: cfg.chaos_breaks])
    _log("hard cases")
    pooltool_fn = (
        None
        if args.no_pooltool
        else (lambda scenes: run_pooltool(scenes, repeats=1, max_events=20000, timeout=120.0))
    )
    hard = sections.hard_section(cache, pooltool_fn, use_pymunk)
    cache.save()
    _log("spin level")
    spin = run_spin_suite(cfg.spin_shots, cfg.repeats, use_pooltool=not args.no_pooltool)
    spin_plot(spin, args.out / "speed_vs_error_spin.png")
    plot(rows, brows, args.out / "speed_vs_error.png")
    text = _render(
        cfg,
        args,
        info,
        warm,
        pt_info,
        rows,
        brows,
        bruns,
        brefs,
        chaos,
        hard,
        notes(runs, refs),
        time.perf_counter() - t_start,
        cache,
        spin,
    )
    (args.out / "speed_vs_error.md").write_text(text)
    _log(f"wrote {args.out / 'speed_vs_error.md'} in {time.perf_counter() - t_start:.0f} s")
    return 0


def _render(
    cfg: Config,
    args: argparse.Namespace,
    info: dict,
    warm: dict,
    pt_info: dict,
    rows: list[Metrics],
    brows: list[Metrics],
    bruns: list[Run],
    brefs: list,
    chaos: list[str],
    hard: list[str],
    note_lines: list[str],
    seconds: float,
    cache: ReferenceCache,
    spin: SpinSuite,
) -> str:
    cmd = _command(args)
    pt_ver = pt_info.get("pooltool", "not run")
    lines = [
        "# Speed against error",
        "",
        f"Generated by `{cmd}` in one run of {seconds / 60:.1f} min on "
        f"{time.strftime('%Y-%m-%d')} (commit {info['commit']}). Every number below comes "
        "from that run; times are wall-clock medians (and 95th percentiles) over scenes, each "
        f"scene's time the median of {cfg.repeats} repeats (1 for pymunk, fixed-step at "
        "dt=1e-5 and the reference), with numba kernels warmed up first. The machine is shared "
        "and noisy: compare ratios within this run (column `x ours`), not absolute times "
        "across runs.",
        "",
        "| machine | |",
        "|---|---|",
        f"| CPU | {info['cpu']}, {info['cores']} cores |",
        f"| OS | {info['os']} |",
        f"| python | {info['python']} |",
        f"| numpy / numba / llvmlite | {info['numpy']} / {info['numba']} / {info['llvmlite']} |",
        f"| pymunk | {info['pymunk']} |",
        f"| mpmath (reference) | {info['mpmath']} |",
        f"| pooltool | {pt_ver} (own venv: python {pt_info.get('python', '?')}, numpy "
        f"{pt_info.get('numpy', '?')}, numba {pt_info.get('numba', '?')}) |",
        "",
        "## Targets",
        "",
        *targets(rows, brows),
        "",
        "## Non-chaotic shots (1-3 collisions)",
        "",
        f"{cfg.shots} seeded shots (`bench/scenes.py`: straight and cut pot attempts, banks, "
        "two-ball combinations, cue-ball cushion shots; cue speed 0.3-2.5 m/s; kept when the "
        "shot has 1-3 ball-ball and cushion impacts). Errors are against the 50-digit mpmath "
        "reference (`pool_env/testing/reference/`): final-position error is the largest "
        "distance between a ball's final centre and the reference's (a potted ball keeps its "
        "capture point); direction error is the angle of the object ball's velocity right "
        "after its first impact; `same pots` is the share of shots with the same balls in the "
        "same pockets. pymunk at small dt ran on an evenly spread subset (column `scenes`).",
        "",
        *shots_table(rows),
        "",
        "`*` pooltool 0.6.0 runs with its default physics (the balls start rolling without "
        "side spin; collisions add sliding, spin and throw) and its own pocket geometry, so "
        "its differences from the reference measure the model difference, not integration "
        "error: its row is there for speed on the same layouts.",
        "",
        "![time per shot against error](speed_vs_error.png)",
        "",
        *note_lines,
        "",
        *spin_section(
            spin, cmd, time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), info["commit"]
        ),
        "",
        "## Breaks (chaotic)",
        "",
        f"{cfg.breaks} seeded breaks (touching 9-ball and 15-ball racks, cue ball on the head "
        "string up to 15 cm off centre, aimed at the apex with 0.5 degree scatter, 6-9 m/s). "
        "Every method diverges from the reference on a break, this simulator included, so "
        "these rows report speed and outcome statistics, not accuracy.",
        "",
        *sections.breaks_table(brows, bruns, brefs),
        "",
        "### How fast a 1e-12 m perturbation grows",
        "",
        f"The first {cfg.chaos_breaks} breaks, run again with the cue ball moved 1e-12 m "
        "sideways; divergence = largest position difference at each ball-ball collision time "
        "of the first run; growth per collision = 10^slope of log10(divergence) against the "
        "collision count, fitted up to 1 mm. The last column compares this simulator (float64) "
        "with the reference (50 digits) on the unperturbed break. In a touching rack, contacts "
        "a few 1e-18 s apart are below float64's time resolution, so their order (and the "
        "break) can jump at once; the spaced rack shows the smooth growth of chaos.",
        "",
        *chaos,
        "",
        "## Hard cases (docs/physics.md) on every engine",
        "",
        "Tags: `crash` raised; `hang` hit the step/event cap or time limit; `escape` a ball "
        "not potted ended off the playing surface; `overlap` at rest two balls overlap or a "
        "ball is past a rail line by more than 1e-9 m; `tunnel` a contact that must happen "
        "did not; `phantom` a contact that must not happen did. pooltool has its own pocket "
        "jaws and spin physics (marked `(spin)` in the error table).",
        "",
        *hard,
        "",
        "On the touching 16-ball rack every engine, this simulator included, ends metres from "
        "the reference: the rack's contacts follow each other a few 1e-18 s apart, below "
        "float64's time resolution at t ~ 0.5 s (1e-16 s), so float64 takes them in its fixed "
        "tie order while the reference resolves their true order (see the perturbation "
        "table). The invariants still hold; the break is a different, equally valid one.",
        "",
        "## Compile and start-up costs (not in the times above)",
        "",
        f"- this simulator: first call in this process {warm['ours']:.2f} s (numba on-disk "
        f"cache); a fresh interpreter to the end of its first shot {warm['fresh']:.2f} s.",
        f"- fixed-step integrator: first call {warm['fixed']:.2f} s.",
        f"- pooltool: import {pt_info.get('import_s', math.nan):.1f} s, first simulation "
        f"{pt_info.get('warmup_s', math.nan):.1f} s (compiles its numba kernels on first use; "
        "about 30-45 s without its cache).",
        f"- 50-digit reference: {cache.computed} scenes computed in {cache.seconds:.1f} s "
        "(the rest came from the on-disk cache).",
    ]
    if not pt_info.get("available"):
        lines.append(f"- pooltool did not run: {pt_info.get('reason', 'unknown reason')}.")
    return "\n".join(lines) + "\n"


def _command(args: argparse.Namespace) -> str:
    flags = [f for f in ("quick", "spin_only", "no_pooltool", "no_pymunk") if getattr(args, f)]
    return " ".join(
        ["python -m bench.speed_vs_error", *("--" + f.replace("_", "-") for f in flags)]
    )


def _spin_only(cfg: Config, args: argparse.Namespace, info: dict) -> int:
    """Run the spin level alone and put its section into the existing report."""
    spin = run_spin_suite(cfg.spin_shots, cfg.repeats, use_pooltool=not args.no_pooltool)
    spin_plot(spin, args.out / "speed_vs_error_spin.png")
    date = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    lines = spin_section(spin, _command(args), date, info["commit"])
    lines.insert(2, "This section alone was rerun with `--spin-only`; the rest of the report "
                    "comes from the run named at the top.\n")  # fmt: skip
    report = args.out / "speed_vs_error.md"
    old = report.read_text() if report.exists() else "# Speed against error\n"
    report.write_text(splice_section(old, lines))
    _log(f"wrote the spin section of {report}")
    return 0


def splice_section(text: str, section: list[str]) -> str:
    """``text`` with its ``## Spin level`` section replaced by ``section``.

    The section runs from its heading to the next ``## `` heading; without one it goes in
    before ``## Breaks``, or at the end.
    """
    lines = text.rstrip("\n").split("\n")
    heads = [k for k, line in enumerate(lines) if line.startswith("## ")]
    start = next((k for k in heads if lines[k].startswith("## Spin level")), None)
    if start is not None:
        end = next((k for k in heads if k > start), len(lines))
    else:
        start = end = next((k for k in heads if lines[k].startswith("## Breaks")), len(lines))
    head = "\n".join(lines[:start]).rstrip("\n")
    tail = "\n".join(lines[end:])
    parts = [head, "\n".join(section).strip("\n"), tail]
    return "\n\n".join(p for p in parts if p) + "\n"


def _slice(run: Run, start: int, n: int) -> Run:
    return Run(
        run.method,
        run.engine,
        run.dt,
        [k - start for k in run.index[start : start + n]],
        run.times[start : start + n],
        run.outcomes[start : start + n],
        run.note,
    )


if __name__ == "__main__":
    sys.exit(main())
