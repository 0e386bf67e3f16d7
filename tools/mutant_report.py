"""The mutation runner's report: the Markdown table of a run, with its command and load."""

from __future__ import annotations

import os
import subprocess
import time
from pathlib import Path

from tools.mutant_runner import ROOT, Outcome


def report(
    baselines: list[Outcome],
    outcomes: list[Outcome],
    command: str,
    wall: float,
    load_start: float | None = None,
    commit: str | None = None,
) -> str:
    """The Markdown table of a run.

    ``load_start`` is the load average when it began; ``commit`` the tree's commit when
    it began (default: the repository's now).
    """
    killed = sum(o.status == "killed" for o in outcomes)
    not_run = sum(o.status == "not run" for o in outcomes)
    total = len(outcomes) - not_run
    lines = [
        "# Mutation testing: planted bugs and the tests that catch them",
        "",
        f"Command: `{command}`",
        "",
        f"Made {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} at commit "
        f"`{commit or commit_label(ROOT)}`; load average "
        + (f"{load_start:.2f} at the start, " if load_start is not None else "")
        + f"{os.getloadavg()[0]:.2f} at the end; wall time "
        f"{wall / 60:.1f} min.",
        "",
        "Baselines (the unmutated tree, the union of the subsets of each mode): "
        + "; ".join(
            f"{'interpreted' if b.interpreted else 'compiled'} "
            + ("**passed**" if b.status == "survived" else f"**{b.status}** ({b.detail})")
            for b in baselines
        )
        + ".",
        "",
        f"**Killed {killed} of {total} run ({100.0 * killed / max(total, 1):.1f}%)**"
        + (
            f" ({not_run} of the {len(outcomes)} not run: the time budget ended first)"
            if not_run
            else ""
        )
        + "; "
        f"survived {sum(o.status == 'survived' for o in outcomes)}, "
        f"stale {sum(o.status == 'stale' for o in outcomes)}, "
        f"timeout {sum(o.status == 'timeout' for o in outcomes)}, "
        f"error {sum(o.status == 'error' for o in outcomes)}.",
        "",
        "Each mutant runs in a scratch copy of the tree with its own numba cache; the "
        "catalogue is `tools/mutant_catalogue/`, one module an area. Mode `interp.`: the "
        "subset ran with the kernels interpreted (`NUMBA_DISABLE_JIT=1`, no compile); "
        "`jit`: compiled afresh (`--compiled` forces it for all).",
        "",
        "| mutant | area | file | models | mode | result | killed by | s |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for o in outcomes:
        m = o.mutant
        assert m is not None
        lines.append(
            f"| `{m.name}` | {m.area} | `{m.file}` | {m.models} | "
            f"{'-' if o.status == 'not run' else 'interp.' if o.interpreted else 'jit'} | "
            f"{o.status} | "
            f"{o.detail.replace('|', '/') or '-'} | {o.seconds:.0f} |"
        )
    return "\n".join(lines) + "\n"


def commit_label(root: Path) -> str:
    """The short commit of the checkout at ``root``, marked if it has uncommitted changes."""
    out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True)
    dirty = subprocess.run(["git", "status", "--porcelain"], cwd=root, capture_output=True)
    return out.stdout.decode().strip() + (" + uncommitted changes" if dirty.stdout.strip() else "")
