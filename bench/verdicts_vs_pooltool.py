"""Our snooker and three-cushion verdicts beside pooltool 0.6's rulesets, on the same shots.

Run (pooltool from ``bash bench/setup_pooltool.sh``; over a minute of CPU: under the lock)::

    flock /tmp/pool_cpu.lock python -m bench.verdicts_vs_pooltool  # writes the results file
    python -m bench.verdicts_vs_pooltool --shots 20                # smoke run (prints only)

Per game, :func:`bench.verdict_shots.make_cases` draws seeded shots (layouts, rule states,
strokes; the tables made equal to pooltool's where they can be: see that module). Each
shot is played twice:

* by pooltool, in its own virtualenv (``bench/engines/pooltool_verdicts.py``), which
  judges it by its own ruleset (``three_cushion.is_point``; ``_Snooker.build_shot_info``
  under the state's ``ShotConstraints``) and returns its outcome summary;
* by our simulator (:func:`bench.verdict_outcomes.ours`).

Both outcomes are read into one :class:`~bench.verdict_outcomes.Summary`. Then three
verdicts of each shot (:mod:`bench.verdict_rules`): pooltool's; ours, by our game's own
rules through its env (:mod:`bench.verdict_games`), once on our physics and once on
pooltool's outcome (the simulator's answer replaced by pooltool's, so that the rules are
compared on identical outcomes); and the rule text's (a third opinion, to say which engine
a disagreement proves wrong). The agreement rates:

(a) our verdict on our physics against pooltool's, over the shots whose outcome summaries
    agree (the fields a verdict reads: first and second contact and the cue ball's cushions
    before its second for three-cushion; first contact and the balls potted for snooker);
(b) our verdict on pooltool's outcome against pooltool's, over every shot pooltool plays
    to an end (no crash, no hang): identical outcomes.

Every disagreement is listed with its class and explanation.
"""

from __future__ import annotations

import argparse
import datetime
import hashlib
import json
import os
import time
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from bench.engines.pooltool_engine import run_worker
from bench.report import machine
from bench.verdict_outcomes import Summary, from_pooltool, ours
from bench.verdict_rules import pooltool_verdict, rule_text
from bench.verdict_shots import (
    SNOOKER_IDS,
    THREE_CUSHION_IDS,
    Case,
    make_cases,
    pooltool_job,
    table_of,
)
from pool_env.sim.table import Table

ROOT = Path(__file__).resolve().parents[1]
WORKER = Path(__file__).resolve().parent / "engines" / "pooltool_verdicts.py"
GAMES = ("three_cushion", "snooker")
#: The pooltool the worker runs (checked against its answer).
POOLTOOL_VERSION = "0.6.0"
#: pooltool's collision spacer for the comparison (its ``MIN_DIST``, 1e-6 m as it ships).
SPACER = 1e-12


def run_pooltool(game: str, cases: list[Case], cache: Path | None) -> list[dict[str, Any]]:
    """Pooltool's results for ``cases`` (read from ``cache`` if this very job ran before)."""
    job = pooltool_job(game, cases, min_dist=SPACER)
    digest = hashlib.sha256(json.dumps(job, sort_keys=True).encode()).hexdigest()[:16]
    path = None if cache is None else cache / f"{game}-{len(cases)}-{digest}.json"
    if path is not None and path.exists():
        kept = json.loads(path.read_text())
        if isinstance(kept, dict):
            return kept["results"], kept["seconds"]
    t0 = time.perf_counter()
    out = run_worker(WORKER, job, total_timeout=7200.0)
    seconds = time.perf_counter() - t0
    if not out["available"]:
        raise SystemExit(f"pooltool unavailable: {out['reason']}")
    if out["pooltool"] != POOLTOOL_VERSION:
        raise SystemExit(
            f"pooltool {out['pooltool']} found, the comparison is of {POOLTOOL_VERSION}"
        )
    results = out["results"]
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(json.dumps({"results": results, "seconds": seconds}))
    return results, seconds


def _name(game: str, ball: int) -> str:
    if ball < 0:
        return "-"
    return (THREE_CUSHION_IDS if game == "three_cushion" else SNOOKER_IDS)[ball]


def describe(game: str, s: Summary) -> str:
    """An outcome in a few words."""
    if game == "three_cushion":
        return f"{_name(game, s.first)}, {_name(game, s.second)}, {s.cushions_second} cushions"
    pots = " ".join(f"{_name(game, b)}@{p}" for b, p in s.potted) or "no pot"
    return f"first {_name(game, s.first)}; {pots}"


def physics_reason(game: str, o: Summary, p: Summary, table: Table) -> str:
    """Why two outcomes differ, in words (which field, and the cause where it is plain)."""
    if o.first != p.first:
        return "first contact differs: " + parting(o, p)
    if game == "three_cushion":
        return "second contact or cushion count differs"
    ours_potted = {b for b, _ in o.potted}
    parts = []
    for b, pocket in p.potted:
        if b in ours_potted:
            continue
        gap = float(np.hypot(*(np.array(o.final[b]) - table.pockets[pocket, :2])))
        if gap < table.pockets[pocket, 2]:
            parts.append(
                f"{_name(game, b)} drops on pooltool (its centre entered pooltool's pocket "
                f"circle); on ours it stops in the jaws, {100 * gap:.1f} cm from the pocket's "
                "corner point, short of the fall line"
            )
        else:
            t_drop = next(e[0] for e in p.events if e[1] == "pocket" and e[2] == b)

            def jaw(events: list[list[Any]], b: int = b, t: float = t_drop) -> bool:
                return any(e[1] == "circular" and e[2] == b and abs(e[0] - t) < 0.3
                           for e in events)  # fmt: skip

            how = (
                "it meets a jaw's rounded point where pooltool's drops without one"
                if jaw(o.events) and not jaw(p.events)
                else "both meet a jaw's point, then part"
                if jaw(o.events)
                else "no jaw point on ours"
            )
            parts.append(
                f"{_name(game, b)} drops on pooltool; on ours the jaws turn it away ({how}; "
                f"it ends {gap:.2f} m from that pocket)"
            )
    for b, _ in o.potted:
        if b not in {x for x, _ in p.potted}:
            parts.append(f"{_name(game, b)} drops on ours only")
    return "; ".join(parts) + " (pocket models differ)"


_KIND_WORDS = {"circular": "a jaw's rounded point", "linear": "a cushion", "ball": "a ball",
               "pocket": "a pocket"}  # fmt: skip


def parting(o: Summary, p: Summary) -> str:
    """Where two event lists part: the last event they share, and each one's next."""
    k = 0
    for a, b in zip(o.events, p.events, strict=False):
        same_ball = a[1] != "ball" or {a[2], a[3]} == {b[2], b[3]}
        if a[1] != b[1] or a[2] != b[2] or not same_ball or abs(a[0] - b[0]) > 1e-6:
            break
        k += 1

    def next_of(events: list[list[Any]]) -> str:
        return _KIND_WORDS[events[k][1]] if k < len(events) else "nothing"

    where = "at once" if k == 0 else f"after {_KIND_WORDS[o.events[k - 1][1]]} at t = " \
        f"{o.events[k - 1][0]:.3f} s on both"  # fmt: skip
    return f"the paths part {where}; next, ours meets {next_of(o.events)}, pooltool's " \
        f"{next_of(p.events)}"  # fmt: skip


def compare(game: str, n: int, seed: int, cache: Path | None, judge: Any) -> dict[str, Any]:
    """Play and judge ``n`` shots of ``game``; the counts and the disagreements."""
    table = table_of(game)
    cases = make_cases(game, n, seed, lambda case: ours(case, table).point_made())
    results, t_pt = run_pooltool(game, cases, cache)
    rows = []
    counts: Counter[str] = Counter()
    t0 = time.perf_counter()
    for case, res in zip(cases, results, strict=True):
        if res.get("error"):
            counts["pooltool_error"] += 1
            rows.append({"case": case, "class": "undefined", "why": f"pooltool: {res['error']}"})
            continue
        p_out = from_pooltool(case, table, res)
        o_out = ours(case, table)
        v_pt = pooltool_verdict(game, res["verdict"])
        text_p = rule_text(case, p_out)
        same_outcome = o_out.key(game) == p_out.key(game)
        counts["defined"] += 1
        counts["same_outcome"] += same_outcome
        counts["text_equals_pooltool"] += text_p == v_pt
        row = {"case": case, "ours_out": o_out, "pt_out": p_out, "pooltool": v_pt,
               "text": text_p, "same_outcome": same_outcome}  # fmt: skip
        if game == "three_cushion":
            counts["points_pooltool"] += v_pt["point"]
            counts["both_hit"] += p_out.second >= 0
            counts["close_calls"] += p_out.cushions_second in (2, 3)
        else:
            counts["fouls_pooltool"] += v_pt["foul"]
            counts["pots_pooltool"] += bool(p_out.potted)
        if judge is not None:
            v_own = judge(case, None)
            v_on_pt = judge(case, p_out)
            row["ours_own"], row["ours_on_pt"] = v_own, v_on_pt
            counts["b_agree"] += v_on_pt == v_pt
            if same_outcome:
                counts["a_agree"] += v_own == v_pt
            counts["raw_agree"] += v_own == v_pt
        rows.append(row)
    counts_t = time.perf_counter() - t0
    return {"game": game, "cases": cases, "rows": rows, "counts": counts,
            "seconds": (t_pt, counts_t), "judged": judge is not None}  # fmt: skip


def classify(game: str, row: dict[str, Any]) -> list[tuple[str, str]]:
    """The disagreements of one shot: ``(class, explanation)`` each."""
    if row.get("class") == "undefined":
        return [("undefined", row["why"])]
    out = []
    v_pt, text = row["pooltool"], row["text"]
    if text != v_pt:
        out.append(("pooltool vs rule text", f"pooltool {v_pt}, rule text {text}"))
    if "ours_on_pt" in row:
        mine = row["ours_on_pt"]
        if mine != v_pt:
            wrong = "ours" if mine != text else "pooltool"
            why = f"ours {mine}, pooltool {v_pt}, rule text {text}: {wrong} wrong"
            out.append(("rules (identical outcome)", why))
        if row["same_outcome"] and row["ours_own"] != v_pt:
            out.append(("rules (own physics, same outcome)",
                        f"ours {row['ours_own']}, pooltool {v_pt}"))  # fmt: skip
        if not row["same_outcome"] and row["ours_own"] != v_pt:
            why = physics_reason(game, row["ours_out"], row["pt_out"], table_of(game))
            out.append(("physics", f"{why}: ours {row['ours_own']}, pooltool {v_pt}"))
    elif not row["same_outcome"]:
        text_o = rule_text(row["case"], row["ours_out"])
        if text_o != v_pt:
            why = physics_reason(game, row["ours_out"], row["pt_out"], table_of(game))
            out.append(("physics", f"{why}: by the rule text, ours {text_o}, pooltool {v_pt}"))
    return out


def pct(a: int, b: int) -> str:
    """``a / b`` as a percentage."""
    return f"{100.0 * a / b:.1f}%" if b else "-"


#: The page's account of the set-up and of each class of disagreement.
NOTES = [
    "## How the two are made comparable",
    "",
    "- Same shots: each layout, rule state and stroke is played by both engines; the",
    "  stroke is mapped by `pool_env.interop.pooltool.cue_to_pooltool` (level cue).",
    "- Three-cushion: our table is pooltool's carom table (`BilliardTableSpecs()`, its",
    "  `BILLIARD_GENERIC` ball) under pooltool's default physics",
    "  (`Table.preset(\"pooltool-0.6\")`'s models), pocketless on both sides; pooltool's",
    "  collision spacer `MIN_DIST` is 1e-12 m as in `bench/models_vs_pooltool.py`. The",
    "  physics is then the same (final positions within about 1e-9 m), and so is every",
    "  outcome summary.",
    "- Snooker: pooltool's `SnookerTableSpecs()` size and cushion height and its",
    "  `SNOOKER_GENERIC` ball, the same physics models; the pockets cannot be equal:",
    "  pooltool's are circular jaw segments and a pocket circle whose entry is the drop,",
    "  ours the jaw model (`JawSpec`, `pool_env.sim.presets.SNOOKER_POCKETS`: pooltool's",
    "  mouths, cut, depths and jaw radii) with its fall line. A shot whose outcome summary",
    "  differs (first contact, or the balls potted) is a physics disagreement, kept out of",
    "  rate (a) and listed below; rate (b) judges pooltool's own outcome by our rules.",
    "- Common ground only: the states are ones both rulesets define (a red on, a",
    "  nominated colour after a red or after the last red, the colours in order); not",
    "  free ball, the touching ball or push stroke (layouts keep 2 mm between balls and",
    "  from the cushions), the miss, the re-spotted black, or three-cushion's break (the",
    "  red first), which pooltool's rulesets do not have.",
    "- The rule text (`bench/verdict_rules.py`, written from the UMB and WPBSA rules, no",
    "  code shared) is the third opinion that says which engine a disagreement proves",
    "  wrong.",
    "",
    "Classes of disagreement: `physics` (the engines' outcomes differ; each engine's",
    "verdict is its rules' on its own outcome: see rate (b)); `rules (identical outcome)`",
    "(our game and pooltool judge the same outcome differently; the rule text names the",
    "wrong one); `rules (own physics, same outcome)`; `pooltool vs rule text`; `undefined`",
    "(pooltool crashed or hung).",
    "",
]


#: The causes of a physics disagreement, as :func:`physics_reason` words them.
CAUSES = (
    "stops in the jaws",
    "it meets a jaw's rounded point where pooltool's drops without one",
    "both meet a jaw's point, then part",
    "no jaw point on ours",
    "drops on ours only",
    "first contact differs",
)


def report(runs: list[dict[str, Any]], command: str) -> str:
    """The results page."""
    today = datetime.date.today().isoformat()
    m = machine()
    lines = [
        "# Verdicts beside pooltool 0.6.0's rulesets",
        "",
        f"`{command}` ({today}); see the script's docstring for the set-up, and",
        "`bench/verdict_shots.py` for the tables, layouts, states and strokes.",
        "",
        f"Machine: {m['cpu']}, {m['cores']} cores shared (load {os.getloadavg()[0]:.1f}), "
        f"{m['os']}, Python {m['python']}, numba {m['numba']}, commit {m['commit']}; "
        f"pooltool {POOLTOOL_VERSION} in its own venv.",
        "",
        "| game | shots | defined | outcome summaries agree | pooltool = rule text "
        "| (a) ours = pooltool, own physics, same outcome | (b) ours = pooltool, identical "
        "outcome | ours = pooltool, all shots |",
        "|---|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for run in runs:
        c, judged = run["counts"], run["judged"]
        d, s = c["defined"], c["same_outcome"]
        a = f"{c['a_agree']} / {s} ({pct(c['a_agree'], s)})" if judged else "pending"
        b = f"{c['b_agree']} / {d} ({pct(c['b_agree'], d)})" if judged else "pending"
        raw = f"{c['raw_agree']} / {d} ({pct(c['raw_agree'], d)})" if judged else "pending"
        lines.append(
            f"| {run['game']} | {len(run['cases'])} | {d} | {s} ({pct(s, d)}) | "
            f"{c['text_equals_pooltool']} / {d} | {a} | {b} | {raw} |"
        )
    lines.append("")
    for run in runs:
        c, game = run["counts"], run["game"]
        if game == "three_cushion":
            lines.append(
                f"Three-cushion: pooltool scores {c['points_pooltool']} points; the cue ball "
                f"meets both object balls in {c['both_hit']} shots, {c['close_calls']} of them "
                "with 2 or 3 cushions before the second (the close calls)."
            )
        else:
            lines.append(
                f"Snooker: pooltool calls {c['fouls_pooltool']} fouls; "
                f"{c['pots_pooltool']} shots pot a ball."
            )
        lines.append(
            f"Seconds: pooltool's worker {run['seconds'][0]:.0f}, ours and the verdicts "
            f"{run['seconds'][1]:.0f}."
        )
        lines.append("")
    lines += NOTES
    lines += ["## Every disagreement", "",
              "| game | shot | state | outcome (ours / pooltool) | class | explanation |",
              "|---|---:|---|---|---|---|"]  # fmt: skip
    classes: Counter[tuple[str, str]] = Counter()
    physics: Counter[str] = Counter()
    for run in runs:
        game = run["game"]
        for row in run["rows"]:
            for cls, why in classify(game, row):
                classes[(game, cls)] += 1
                case = row["case"]
                state = case.state.get("phase", "") if game == "snooker" else ""
                if game == "snooker" and case.state["nominated"] >= 0:
                    state += f" ({_name(game, case.state['nominated'])} called)"
                elif game == "snooker":
                    state += f" (on {_name(game, case.state['on'][0])}..)"
                outcome = "-"
                if "pt_out" in row:
                    outcome = f"{describe(game, row['ours_out'])} / {describe(game, row['pt_out'])}"
                lines.append(f"| {game} | {case.index} | {state} | {outcome} | {cls} | {why} |")
                if cls == "physics":
                    physics.update(c for c in CAUSES if c in why)
    lines += ["", "## Disagreements by class", ""]
    lines += [f"- {game}, {cls}: {k}" for (game, cls), k in sorted(classes.items())]
    if physics:
        lines += ["", "Physics disagreements by cause (a row may name several balls):", ""]
        lines += [f"- {cause}: {k}" for cause, k in physics.most_common()]
    return "\n".join(lines) + "\n"


def main() -> None:
    """Run the comparison; write the results page (unless a smoke run)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--shots", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--games", nargs="+", choices=GAMES, default=list(GAMES))
    parser.add_argument(
        "--cache",
        type=Path,
        default=Path("/tmp/verdicts_vs_pooltool"),
        help="where pooltool's results are kept between runs ('' for none)",
    )
    parser.add_argument("--out", type=Path, default=ROOT / "results" / "verdicts_vs_pooltool.md")
    args = parser.parse_args()
    from bench.verdict_games import game_judge

    cache = args.cache if str(args.cache) else None
    runs = [compare(g, args.shots, args.seed, cache, game_judge(g)) for g in args.games]
    command = "python -m bench.verdicts_vs_pooltool"
    if args.shots != 1000 or args.seed != 0:
        command += f" --shots {args.shots} --seed {args.seed}"
    page = report(runs, command)
    print(page)
    if args.shots >= 1000 and set(args.games) == set(GAMES):
        args.out.write_text(page)
        print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
