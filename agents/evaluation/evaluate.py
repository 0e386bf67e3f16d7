"""Evaluate agents on a pool environment: pots per shot, clean pots, scratches, clears, reward.

Usage::

    python -m agents.evaluate --env pool_env/OneBallRoll-v1 --agent random best-const ghost search
    python -m agents.evaluate --env pool_env/OneBallRoll-v1 --agent models/ppo_oneball.zip

Episode ``k`` is reset with seed ``seed + k``, so every agent sees the same layouts. A model
``.zip`` is loaded with the SB3 algorithm its name or saved config names; its environment
settings (``env_kwargs``, ``wrapper``) come from a ``config.yaml`` next to it, or from a
sidecar ``<name>_config.yaml``.

Agents by name: ``random`` (uniform actions), ``const[:a0,a1,...]`` (one action, default
the full hit ``0,1``, centre ball on a spin env), ``best-const`` (the best action of a grid
scan, see :mod:`agents.evaluation.constant_scan`), ``ghost`` (the geometric ghost-ball
heuristic, no simulation, :mod:`agents.baselines.ghost_ball`; on a spin env it plays
position with the tip), ``ghost-centre`` (the same on a spin env with a centre-ball tip
only: position by speed alone), ``search`` (candidate shots checked on the simulator:
the oracle upper bound, :mod:`agents.baselines.search`) and, on the spin 9-ball and 10-ball ids,
``rack-planner`` (:class:`agents.learned.rack_play.RackAgent`'s candidates ranked by the planner's
own score: the trivial policy of the learned rack agent's action space). A rack model
``.npz`` (:mod:`agents.learned.rack_play`, with its ``<name>_config.yaml``) plays its learned value.

Execution noise: ``--noise 0.003,0.05`` (aim rad, speed m/s) or ``--noise 0.003,0.05,0.05``
(and the tip's offset, fractions of R, on a spin env), or ``--noise fastfiz`` (FastFiz's model,
the computer billiards championships') and ``--noise fastfiz:5`` (five times it): the env's
``noise`` keyword (:func:`agents.evaluation.noise_flag.parse_noise`).
``--ends`` also counts how the racks of a rules id end (:func:`rack_ends`).
"""

from __future__ import annotations

import argparse
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

from agents.evaluation.constant_scan import best_constant_agent
from agents.evaluation.episodes import run_episodes
from agents.evaluation.metrics import Estimate
from agents.evaluation.noise_flag import FIELD_NOISE, noise_label, parse_noise
from agents.evaluation.players import agent_kind, check_agents, is_game, make_agent
from agents.evaluation.table import format_table
from agents.learned.envs import make_env
from agents.learned.pretrained import load_model, model_config
from agents.policy import Policy, last_plan
from pool_env.extras import require

__all__ = [
    "evaluate_agent",
    "load_model",
    "main",
    "model_config",
    "rack_ends",
    "run_episodes",
]


def evaluate_agent(
    name: str,
    env_id: str,
    episodes: int,
    seed: int,
    env_kwargs: dict[str, Any] | None = None,
    wrapper: str | None = None,
    agent: Policy | None = None,
    progress: Callable[[int], object] | None = None,
) -> dict[str, Estimate]:
    """Evaluate one agent (by name, or ``agent`` given) and return its summary.

    ``progress`` is called with 1 after each episode (:func:`run_episodes`).

    For a model path, the env is made with the model's saved ``wrapper`` and
    ``env_kwargs``, with ``env_kwargs`` given (a noise, say) over them.

    Examples:
        >>> from agents import evaluate_agent
        >>> summary = evaluate_agent("ghost", "pool_env/OneBallRoll-v1", episodes=20, seed=10000)
        >>> print(summary["pots_per_shot"], summary["scratch_rate"])
        1.000 [0.839, 1.000] 0.100 [0.028, 0.301]
    """
    if agent is None and agent_kind(name) == ".zip" and wrapper is None:
        config = model_config(name)  # the command's settings over the saved ones
        env_kwargs = {**(config.get("env_kwargs") or {}), **(env_kwargs or {})}
        wrapper = config.get("wrapper")
    env = make_env(env_id, env_kwargs, wrapper)
    try:
        agent = agent if agent is not None else make_agent(name, env, seed)
        return run_episodes(agent, env, episodes, seed, progress=progress).summary()
    finally:
        env.close()


def rack_ends(agent: Policy, env: Any, episodes: int, seed: int) -> Counter[tuple[str, str]]:
    """How each rack of a rules id ends: ``(shot, outcome)`` counts.

    ``shot`` is ``"break"``, ``"1st after break"``, ``"2nd after break"`` or ``"later"``;
    the outcome is ``"won"``, the foul's name, ``"missed"`` (a legal shot that potted
    nothing) or ``"missed call"`` (10-ball: a legal shot that potted, but not its call).
    With a :class:`~agents.baselines.game_agents.GameGhostBallAgent`, a shot it had no clear
    pot for is tagged ``"(fallback)"``: what limits a run-out.
    """
    names = ("break", "1st after break", "2nd after break")
    ends: Counter[tuple[str, str]] = Counter()
    for k in range(episodes):
        obs, _ = env.reset(seed=seed + k)
        for shot in range(10_000):
            action, _ = agent.predict(obs)
            obs, _, terminated, truncated, info = env.step(action)
            if not (terminated or truncated):
                continue
            missed = "missed call" if info.get("potted") else "missed"
            outcome = "won" if info.get("winner") == 0 else (info.get("foul") or missed)
            if last_plan(agent).get("kind") == "fallback":
                outcome += " (fallback)"
            ends[(names[shot] if shot < len(names) else "later", outcome)] += 1
            break
    return ends


def _yaml_mapping(text: str) -> Any:
    """``--env-kwargs`` parsed as YAML.

    Raises:
        ValueError: On text that is not YAML (PyYAML's message on one line).
    """
    # pyyaml: an extra (train), not the core install; needed for --env-kwargs only
    yaml = require("yaml", "train", "--env-kwargs")
    try:
        return yaml.safe_load(text)
    except yaml.YAMLError as err:
        raise ValueError(" ".join(str(err).split())) from None


#: ``--help``'s list of the players ``--agent`` takes.
PLAYERS_HELP = (
    "agents by name (module doc): random, const (the full hit) or const:a0,a1[,...] (one "
    "action), best-const (a grid scan's best), ghost, ghost-centre, search, rack-planner (the "
    "game ids), first-row (observation=shots); or a file: an SB3 model .zip (e.g. "
    "models/ppo_oneball.zip), a rack, lookahead or rack-network model .npz "
    "(models/runout_value.npz, models/rack_net.npz), or a "
    "search player file .yaml/.yml (models/search_player.yaml: 9-ball; _ten, _eight)"
)


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(
        description=__doc__.split("\n")[0],
        epilog="Agents: " + PLAYERS_HELP + ".",
    )
    parser.add_argument("--env", default="pool_env/OneBallRoll-v1", help="registered env id")
    parser.add_argument(
        "--agent", nargs="+", default=["random", "ghost"], metavar="AGENT", help=PLAYERS_HELP
    )
    parser.add_argument("--episodes", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=10_000)
    parser.add_argument("--aim", default=None, help="override the env's aim mode")
    parser.add_argument(
        "--env-kwargs",
        default=None,
        help='gymnasium.make kwargs as YAML, e.g. "{noise: [0.003, 0.05]}"',
    )
    parser.add_argument(
        "--noise",
        default=None,
        help="execution noise: sigmas aim (rad), speed (m/s)[, tip (fraction of R)], e.g. "
        "0.003,0.05,0.05; fastfiz (FastFiz's model, the computer billiards championships') "
        "or fastfiz:K (K times it, e.g. fastfiz:5); none (exact shots). Default: fastfiz on "
        "the game ids (NineBallGame-*, TenBallGame-*, EightBallGame-*: the field's noise), "
        "the env's own (none) elsewhere",
    )
    parser.add_argument(
        "--scan-episodes",
        type=int,
        default=1000,
        help="episodes per action of the best-const grid scan",
    )
    parser.add_argument(
        "--ends",
        action="store_true",
        help="also count how the racks of a rules id end (rack_ends)",
    )
    parser.add_argument("--out", default=None, help="also write the table to this file")
    args = parser.parse_args(argv)
    if args.episodes < 1 or args.scan_episodes < 1:
        parser.error("--episodes and --scan-episodes must be >= 1")
    try:
        kwargs = _yaml_mapping(args.env_kwargs) if args.env_kwargs else {}
    except ValueError as err:
        parser.error(f"--env-kwargs {args.env_kwargs!r} is not YAML: {err}")
    if not isinstance(kwargs, dict):
        parser.error("--env-kwargs must be a YAML mapping")
    if args.noise is not None:
        try:
            kwargs["noise"] = parse_noise(args.noise)
        except ValueError as err:
            parser.error(str(err))
    if args.aim:
        kwargs["aim"] = args.aim
    try:
        probe = make_env(args.env, kwargs or None)
    except ValueError as err:
        parser.error(str(err))
    if "noise" not in kwargs and is_game(probe):  # the field's noise, unless told otherwise
        kwargs["noise"] = FIELD_NOISE
    noise = kwargs.get("noise", probe.unwrapped.config.noise)
    probe.close()
    check_agents(parser, args.agent, args.env, kwargs or None)
    rows, times = {}, {}
    for name in args.agent:
        agent, label = None, name
        if name == "best-const":  # scanned once, then labelled with the action it found
            scan_env = make_env(args.env, kwargs or None)
            agent = best_constant_agent(scan_env, episodes=args.scan_episodes)
            scan_env.close()
            label = "best-const (" + ", ".join(f"{a:+.2f}" for a in agent.action) + ")"
        start = time.perf_counter()
        rows[label] = evaluate_agent(
            name, args.env, args.episodes, args.seed, kwargs or None, agent=agent
        )
        times[label] = time.perf_counter() - start
    table = format_table(rows, args.episodes)
    others = {k: v for k, v in kwargs.items() if k != "noise"}
    settings = f" {others}" if others else ""
    print(
        f"{args.env}{settings}, noise {noise_label(noise)}, seeds "
        f"{args.seed}..{args.seed + args.episodes - 1}"
    )
    print(table)
    # Wall time of each row's evaluation (its agent and the env, one process) per shot played.
    for label, seconds in times.items():
        shots = rows[label]["shots_per_episode"].value * args.episodes
        print(f"- {label}: {seconds:.0f} s, {1000.0 * seconds / max(shots, 1.0):.1f} ms per shot")
    if args.ends:
        for name in args.agent:
            env = make_env(args.env, kwargs or None)
            ends = rack_ends(make_agent(name, env), env, args.episodes, args.seed)
            env.close()
            print(f"\nHow the racks end, {name}:")
            for (shot, outcome), count in sorted(ends.items(), key=lambda kv: -kv[1]):
                print(f"- {shot}: {outcome}: {count}")
    if args.out:
        Path(args.out).write_text(f"# Evaluation on {args.env}\n\n{table}\n")
    return 0
