"""Where a two-ball spin shot's time goes: a breakdown of ``shoot`` in microseconds.

Run (under the CPU lock, on a quiet machine)::

    python -m bench.spin_cost

On the two-ball shots of ``python -m bench.spin_vs_pooltool --time`` (the first 40 of
:func:`bench.spin_scenes.spin_shots` with two balls, pocketless spin table,
``record=False``), medians over the shots of the best of several repeats, thread CPU time.
Five figures per shot, each a different cut of the same call:

* ``shoot``: :func:`pool_env.shoot` end to end from Python;
* ``kernel from Python``: the one compiled call ``LEVELS["spin"].kernels.packed_strike`` from
  Python (:mod:`pool_env.sim.levels`) (what ``shoot`` makes after its argument checks);
* ``result``: building the :class:`~pool_env.sim.result.SpinShotResult` from its return;
* ``kernel compiled``: the same call from a compiled loop (no dispatcher, no boxing);
* ``kernel, no events``: that with ``max_events=0`` (the strike, the validation, the
  set-up, the first predictions and the packing: every fixed compiled cost).

So the Python entry is ``shoot - kernel from Python - result``; the dispatcher (argument
unboxing, the returned buffer and tuple) ``kernel from Python - kernel compiled``; the
physics ``kernel compiled - kernel, no events``, per event over the shot's events.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

import numba
import numpy as np

from bench.spin_scenes import spin_shots, spin_table
from pool_env import shoot
from pool_env.sim.levels import LEVELS
from pool_env.sim.result import SpinShotResult

_STRIKE = LEVELS["spin"].kernels.packed_strike


@numba.njit
def _compiled(pos, shot, masses, prm, pockets, cap, reps):
    """``reps`` calls of the compiled strike from a compiled loop; returns the event count."""
    n_ev = 0
    for _ in range(reps):
        out = _STRIKE(
            pos, 0, shot[0], shot[1], shot[2], shot[3], shot[4], masses, prm, pockets, cap,
            False,
        )  # fmt: skip
        n_ev = out[5]
    return n_ev


def _best(f: Callable[[], None], calls: int, repeats: int = 7) -> float:
    """Best thread-CPU microseconds per call of ``f`` (which makes ``calls`` calls)."""
    f()
    out = np.inf
    for _ in range(repeats):
        t0 = time.thread_time()
        f()
        out = min(out, (time.thread_time() - t0) / calls)
    return float(out * 1e6)


def breakdown(n_shots: int = 40, calls: int = 200) -> dict[str, float]:
    """Median microseconds per figure of the module docstring, and events per shot."""
    table = spin_table()
    shots = [s for s in spin_shots(4 * n_shots, table=table) if len(s.positions) == 2]
    prm, pockets, none = table.spin_params, table.pocket_geometry, np.empty(0)
    cap = 10_000  # the default event cap
    rows = []
    for s in shots[:n_shots]:
        pos = np.ascontiguousarray(s.positions, dtype=np.float64)
        arg = np.array([s.speed, s.angle, s.tip[0], s.tip[1], s.elevation])

        def run_shoot(s=s, pos=pos) -> None:
            for _ in range(calls):
                shoot(table, pos, s.angle, s.speed, 0, tip=s.tip, elevation=s.elevation,
                      record=False)  # fmt: skip

        floats = arg.tolist()  # Python floats, as shoot passes them

        def run_kernel(pos=pos, a=floats) -> None:
            for _ in range(calls):
                _STRIKE(pos, 0, a[0], a[1], a[2], a[3], a[4], none, prm, pockets, cap, False)

        raw = _STRIKE(pos, 0, *arg.tolist(), none, prm, pockets, cap, False)

        def run_result(raw=raw) -> None:
            for _ in range(calls):
                SpinShotResult(raw, 2, table.deceleration, False)

        rows.append(
            (
                _best(run_shoot, calls),
                _best(run_kernel, calls),
                _best(run_result, calls),
                _best(lambda p=pos, a=arg: _compiled(p, a, none, prm, pockets, cap, calls), calls),
                _best(lambda p=pos, a=arg: _compiled(p, a, none, prm, pockets, 0, calls), calls),
                float(raw[5]),
            )
        )
    med = np.median(np.array(rows), axis=0)
    keys = ("shoot", "kernel_from_python", "result", "kernel_compiled", "kernel_no_events")
    out = dict(zip(keys, med[:5].tolist(), strict=True))
    out["events"] = float(med[5])
    return out


def main() -> None:
    """Print the breakdown as a markdown table."""
    load = os.getloadavg()[0]
    b = breakdown()
    physics = b["kernel_compiled"] - b["kernel_no_events"]
    print(f"two-ball spin shots, record=False; load {load:.1f} -> {os.getloadavg()[0]:.1f}; "
          f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}")  # fmt: skip
    print("| part | us per shot |")
    print("|---|---:|")
    for label, value in (
        ("shoot, end to end", b["shoot"]),
        ("Python entry (argument checks)", b["shoot"] - b["kernel_from_python"] - b["result"]),
        ("result object", b["result"]),
        ("dispatcher (unboxing, the returned buffer and tuple)",
         b["kernel_from_python"] - b["kernel_compiled"]),
        ("fixed compiled cost (strike, validation, set-up, first predictions, packing)",
         b["kernel_no_events"]),
        (f"physics: {b['events']:.1f} events at {physics / b['events']:.2f} us", physics),
    ):  # fmt: skip
        print(f"| {label} | {value:.2f} |")


if __name__ == "__main__":
    main()
