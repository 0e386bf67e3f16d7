"""Head-to-head rule games (9-ball by default): two agents, alternating breaks, a 95% interval.

Usage::

    python -m agents.duels --agent models/rack_value.npz --opponent ghost --racks 400
    python -m agents.duels --env pool_env/TenBallGame-v1 --agent ghost --opponent search
    python -m agents.duels --agent ghost --opponent random --noise fastfiz:5

Rack ``k`` is :class:`pool_env.envs.multiagent.PoolDuelEnv` of the id's game and table reset
with seed ``seed + k``; the agent breaks the even racks (``player_0``) and the opponent the odd
ones, so each side breaks half of the same racks. Each agent is built as
:func:`agents.evaluation.players.make_agent` builds it on the single-player id with the same
settings (the planners read the table, the ranges and the noise from it), told that it
plays an opponent (``players=2``: it may push out), and plays from its seat's observation.
The win rate is won racks over all racks with its Wilson interval; a rack that reaches the
shot limit is a draw. Per side it also counts shots, pots, fouls and scratches, and how the
breaks went; ``--shots`` prints each side's shots by the plan its player chose
(``last_plan``: a pot, a safety or grid shot, a break, a push-out, a hand-back, ...) and the
outcome by the rules. ``--out`` writes every opponent's counts and each rack's winner as
JSON (what a paired comparison of two players on the same racks reads).
"""

from __future__ import annotations

import argparse
import json
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from agents.evaluation.metrics import wilson
from agents.evaluation.noise_flag import noise_label, parse_noise
from agents.evaluation.players import check_agents, check_game_id, make_agent
from agents.learned.envs import make_env
from agents.policy import Policy, last_plan
from pool_env.envs.multiagent import AGENTS, PoolDuelEnv
from pool_env.game.noise import NoiseSpec

ENV_ID = "pool_env/NineBallGame-v2"
#: The evaluation's execution noise (aim rad, speed m/s, tip fraction of R).
NOISE = (0.003, 0.05, 0.05)


def play_rack(
    duel: PoolDuelEnv,
    players: dict[str, Policy],
    seed: int,
    agent_breaks: bool,
    on_shot: Callable[[str, dict[str, Any]], None] | None = None,
) -> str | None:
    """Play one rack of ``players["agent"]`` against ``players["opponent"]`` to its end.

    Args:
        duel: The two-player env (reset here with ``seed``).
        players: ``"agent"`` and ``"opponent"``, each with ``predict(obs)``.
        seed: The rack's seed.
        agent_breaks: Whether the agent takes ``player_0``'s seat (the break).
        on_shot: Called after every shot with the shooter's side and its info.

    Returns:
        The side that won the rack, ``None`` for a draw (the shot limit).
    """
    duel.reset(seed=seed)
    seats = ("agent", "opponent") if agent_breaks else ("opponent", "agent")
    while not (duel.terminations[AGENTS[0]] or duel.truncations[AGENTS[0]]):
        seat = duel.agent_selection
        side = seats[AGENTS.index(seat)]
        action, _ = players[side].predict(duel.observe(seat))
        duel.step(np.asarray(action, dtype=np.float32))
        if on_shot is not None:
            on_shot(side, duel.infos[seat])
    winner = duel.infos[AGENTS[0]].get("winner")
    return None if winner is None else seats[AGENTS.index(winner)]


def plan_kind(player: Policy) -> str:
    """What kind of shot a planner just chose (its ``last_plan``; ``"-"`` for a policy)."""
    plan = last_plan(player)
    kind = str(plan.get("kind", "-"))
    shot = plan.get("shot")
    return f"{kind} {shot}" if isinstance(shot, str) else kind


def shot_outcome(info: dict[str, Any]) -> str:
    """A shot's outcome by the rules: ``"won"``, ``"pot"``, ``"miss"`` or the foul's name.

    9-ball and 10-ball also: ``"handed back"`` (the option used: no shot) and ``"push-out"``.
    """
    if info.get("handed_back"):
        return "handed back"
    if info.get("push_out") and info["foul"] is None:
        return "push-out"
    if info["foul"] is not None:
        return str(info["foul"])
    if info.get("winner") is not None:  # a legal shot that ends the rack wins it
        return "won"
    return "miss" if info["turn_over"] else "pot"


def play_duels(
    agent: str,
    opponent: str,
    racks: int,
    seed: int,
    noise: NoiseSpec | None = NOISE,
    env_id: str = ENV_ID,
    build: Callable[[Any], Policy] | None = None,
) -> dict[str, Any]:
    """Play ``racks`` racks of ``agent`` against ``opponent`` (names or model paths).

    The game and the table are ``env_id``'s (a rule game's id: 9-ball, 10-ball, 8-ball).
    ``build`` (``env -> agent``, called with the agent's single-player env) makes an agent
    that is no player name (the scoreboard's models and factories); ``agent`` then only
    labels it.

    Returns:
        ``wins``, ``losses``, ``draws``, ``win_rate`` (an
        :class:`~agents.evaluation.metrics.Estimate`) and per side (``"agent"``,
        ``"opponent"``) a :class:`~collections.Counter` of shots, pots, fouls, scratches,
        break scratches and breaks that kept the table, and ``"plan <kind>: <outcome>"``
        counts (:func:`plan_kind`, :func:`shot_outcome`); ``per_rack``: each rack's
        winner (``"agent"``, ``"opponent"`` or ``None``: a draw).

    Raises:
        ValueError: If ``racks < 1``.
    """
    if racks < 1:
        raise ValueError(f"racks must be >= 1, got {racks}")
    envs = [make_env(env_id, {"noise": noise}) for _ in range(2)]
    config = envs[0].unwrapped.config
    model = "spin" if config.spin else "roll"
    duel = PoolDuelEnv(game=config.game, model=model, noise=noise)
    players = {
        "agent": build(envs[0]) if build is not None else make_agent(agent, envs[0], players=2),
        "opponent": make_agent(opponent, envs[1], players=2),
    }
    counts = {side: Counter() for side in players}
    wins = losses = draws = 0
    per_rack: list[str | None] = []
    shot_of_rack = [0]

    def count(side: str, info: dict[str, Any]) -> None:
        c = counts[side]
        c[f"plan {plan_kind(players[side])}: {shot_outcome(info)}"] += 1
        c["shots"] += 1
        c["pots"] += len(info["potted"])
        c["fouls"] += info["foul"] is not None
        c["scratches"] += bool(info["scratch"])
        if shot_of_rack[0] == 0:  # the break
            c["breaks"] += 1
            c["break scratches"] += bool(info["scratch"])
            c["breaks kept"] += not info["turn_over"]
        shot_of_rack[0] += 1

    for k in range(racks):
        shot_of_rack[0] = 0
        winner = play_rack(duel, players, seed + k, k % 2 == 0, count)
        per_rack.append(winner)
        if winner is None:
            draws += 1
        elif winner == "agent":
            wins += 1
        else:
            losses += 1
    for env in envs:
        env.close()
    return {
        "wins": wins,
        "losses": losses,
        "draws": draws,
        "win_rate": wilson(float(wins), racks),
        "per_rack": per_rack,
        **counts,
    }


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--env", default=ENV_ID, help="the game's spin or roll id")
    parser.add_argument("--agent", required=True, help="a name of agents.evaluate or a model")
    parser.add_argument("--opponent", nargs="+", default=["ghost", "random"])
    parser.add_argument("--racks", type=int, default=400)
    parser.add_argument("--seed", type=int, default=20_000)
    parser.add_argument(
        "--noise",
        default="0.003,0.05,0.05",
        help="execution noise, as agents.evaluate takes it: sigmas (aim rad, speed m/s, tip "
        "in R), fastfiz / fastfiz:K (the computer billiards championships' model, K times) "
        "or none",
    )
    parser.add_argument("--shots", action="store_true", help="shots by plan and outcome")
    parser.add_argument("--out", default=None, help="write the results as JSON here")
    args = parser.parse_args(argv)
    if args.racks < 1:
        parser.error("--racks must be >= 1")
    try:
        noise = parse_noise(args.noise)
    except ValueError as err:
        parser.error(str(err))
    check_game_id(parser, args.env, "agents.duels")
    check_agents(parser, [args.agent, *args.opponent], args.env, {"noise": noise}, 2)
    print(f"{args.agent}, {args.env}, noise {noise_label(noise)}, racks seeds {args.seed}..")
    print("| opponent | won | lost | drawn | win rate [95%] | side: shots, pots/shot, fouls/shot, "
          "scratch/shot, break scratches, breaks kept |")  # fmt: skip
    print("|---|---|---|---|---|---|")
    record: dict[str, Any] = {
        "env": args.env, "agent": args.agent, "seed": args.seed, "racks": args.racks,
        "noise": args.noise, "opponents": {},
    }  # fmt: skip
    for opponent in args.opponent:
        start = time.perf_counter()
        out = play_duels(args.agent, opponent, args.racks, args.seed, noise, args.env)
        record["opponents"][opponent] = {
            **{k: out[k] for k in ("wins", "losses", "draws", "per_rack")},
            "win_rate": out["win_rate"].as_percent(),
            "sides": {side: dict(out[side]) for side in ("agent", "opponent")},
            "seconds": time.perf_counter() - start,
        }
        sides = []
        for side in ("agent", "opponent"):
            c = out[side]
            n = max(c["shots"], 1)
            sides.append(
                f"{side}: {c['shots']}, {c['pots'] / n:.3f}, {c['fouls'] / n:.3f}, "
                f"{c['scratches'] / n:.3f}, {c['break scratches']}/{c['breaks']}, "
                f"{c['breaks kept']}/{c['breaks']}"
            )
        print(
            f"| {opponent} | {out['wins']} | {out['losses']} | {out['draws']} | "
            f"{out['win_rate']} | {'; '.join(sides)} | ({time.perf_counter() - start:.0f} s)"
        )
        if args.shots:
            for side in ("agent", "opponent"):
                plans = sorted((k[5:], v) for k, v in out[side].items() if k.startswith("plan "))
                listed = ", ".join(f"{k} {v}" for k, v in plans)
                print(f"  {side} shots by plan: outcome: {listed}")
    if args.out:
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        Path(args.out).write_text(json.dumps(record, indent=1) + "\n")
        print(f"wrote {args.out}")
    return 0
