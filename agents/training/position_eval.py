r"""Clear rates on the same episodes, and each agent's paired difference from the first.

``python -m agents.evaluate`` gives each agent's table row; a learner that beats a baseline
by a few points needs the *paired* difference on the same layouts and noise seeds, which
is much tighter than two independent intervals. This plays each agent as
``agents.evaluate`` does (:func:`~agents.evaluation.players.make_agent` on
:func:`~agents.learned.envs.make_env`, a model with its saved wrapper and kwargs;
:func:`~agents.evaluation.episodes.run_episodes`), keeps every episode's outcome, and
prints the table, the wall milliseconds per shot and the paired clear-rate differences
(:func:`agents.evaluation.runouts.paired_difference`). ``--save`` writes each agent's
episodes to JSON, ``--with`` pairs against saved ones (one evaluation of a baseline
serves every model played on its seeds)::

    python -m agents.training.position_eval --agent ghost --episodes 400 --seed 10000 \
        --env-kwargs "{n_balls: 3, end_on_miss: true, noise: [0.003, 0.05, 0.05]}" \
        --save runs/eval/ghost3.json
    python -m agents.training.position_eval --agent models/ppo_position.zip \
        --episodes 400 --seed 10000 --env-kwargs "{...}" --with runs/eval/ghost3.json
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path
from typing import Any

from agents.evaluation.episodes import run_episodes
from agents.evaluation.evaluate import _yaml_mapping
from agents.evaluation.metrics import Estimate
from agents.evaluation.players import agent_kind, make_agent
from agents.evaluation.runouts import paired_difference
from agents.evaluation.table import format_table
from agents.learned.envs import make_env
from agents.learned.pretrained import model_config


def play(
    name: str, env_id: str, episodes: int, seed: int, env_kwargs: dict[str, Any]
) -> dict[str, Any]:
    """One agent's episodes: summary, per-episode clears and wall seconds.

    A model ``.zip`` plays behind its saved wrapper, with its saved ``env_kwargs`` under
    the given ones (as :func:`agents.evaluation.evaluate.evaluate_agent`).
    """
    kwargs, wrapper = dict(env_kwargs), None
    if agent_kind(name) == ".zip":
        config = model_config(name)
        kwargs = {**(config.get("env_kwargs") or {}), **kwargs}
        wrapper = config.get("wrapper")
    env = make_env(env_id, kwargs, wrapper)
    try:
        agent = make_agent(name, env, seed)
        start = time.perf_counter()
        log = run_episodes(agent, env, episodes, seed)
        seconds = time.perf_counter() - start
    finally:
        env.close()
    summary = log.summary()
    shots = summary["shots_per_episode"].value * episodes
    return {
        "agent": name,
        "env_id": env_id,
        "env_kwargs": kwargs,
        "seed": seed,
        "episodes": episodes,
        "summary": {k: [v.value, v.low, v.high] for k, v in summary.items()},
        "cleared": [bool(c) for c in log.cleared],
        "seconds": seconds,
        "ms_per_shot": 1000.0 * seconds / max(shots, 1.0),
    }


def report(results: list[dict[str, Any]]) -> str:
    """The table, ms per shot, and every agent's clear-rate difference from the first."""
    rows = {r["agent"]: {k: Estimate(*v) for k, v in r["summary"].items()} for r in results}
    lines = [format_table(rows, results[0]["episodes"]), ""]
    lines += [f"- {r['agent']}: {r['ms_per_shot']:.1f} ms per shot" for r in results]
    base = results[0]
    ends = ["run-out" if c else "no" for c in base["cleared"]]
    for r in results[1:]:
        if (r["seed"], r["episodes"], r["env_kwargs"]) != (
            base["seed"],
            base["episodes"],
            base["env_kwargs"],
        ):
            raise ValueError(f"{r['agent']} was not played on {base['agent']}'s episodes")
        diff, low, high = paired_difference(["run-out" if c else "no" for c in r["cleared"]], ends)
        lines.append(
            f"- clear rate, {r['agent']} minus {base['agent']} (paired, same episodes): "
            f"{100 * diff:+.1f} points [{100 * low:+.1f}, {100 * high:+.1f}]"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--env", default="pool_env/Pool-v1")
    parser.add_argument("--agent", nargs="*", default=[], help="as agents.evaluate takes")
    parser.add_argument("--episodes", type=int, default=400)
    parser.add_argument("--seed", type=int, default=10_000)
    parser.add_argument("--env-kwargs", default="{}", help="gymnasium.make kwargs as YAML")
    parser.add_argument("--with", dest="saved", nargs="*", default=[], help="saved JSON first")
    parser.add_argument("--save", default=None, help="write the new agents' episodes here")
    args = parser.parse_args(argv)
    kwargs = _yaml_mapping(args.env_kwargs) or {}
    if not isinstance(kwargs, dict):
        parser.error("--env-kwargs must be a YAML mapping")
    results = [r for path in args.saved for r in json.loads(Path(path).read_text())]
    fresh = [play(a, args.env, args.episodes, args.seed, kwargs) for a in args.agent]
    if not results + fresh:
        parser.error("no agent: name one with --agent or a saved JSON with --with")
    if args.save:
        Path(args.save).parent.mkdir(parents=True, exist_ok=True)
        Path(args.save).write_text(json.dumps(fresh))
    print(f"{args.env} {kwargs}, seeds {args.seed}..{args.seed + args.episodes - 1}")
    print(report(results + fresh))
    return 0


if __name__ == "__main__":
    sys.exit(main())
