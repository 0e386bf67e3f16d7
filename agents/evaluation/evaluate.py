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
``noise`` keyword (:func:`parse_noise`).
``--ends`` also counts how the racks of a rules id end (:func:`rack_ends`).
"""

from __future__ import annotations

import argparse
import difflib
import time
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pool_env
from agents.baselines.game_agents import GameGhostBallAgent, GameSearchAgent
from agents.baselines.ghost_ball import GhostBallAgent
from agents.baselines.random_agent import ConstantAgent, RandomAgent
from agents.baselines.search import SearchAgent
from agents.baselines.shot_row import ShotRowAgent
from agents.evaluation.constant_scan import best_constant_agent
from agents.evaluation.episodes import run_episodes
from agents.evaluation.metrics import Estimate
from agents.learned.envs import make_env
from agents.learned.lookahead import load_lookahead_agent
from agents.learned.player_file import load_search_player
from agents.learned.pretrained import load_model, model_config
from agents.learned.rack_play import RackAgent, load_rack_agent, rack_model_config
from agents.policy import Policy, last_plan
from pool_env import Table
from pool_env.extras import require
from pool_env.game.checks import parse_noise as parse_env_noise
from pool_env.game.noise import NOISE_MODELS, NoiseSpec

__all__ = [
    "BASELINES",
    "FILE_KINDS",
    "agent_kind",
    "check_agents",
    "evaluate_agent",
    "format_table",
    "load_model",
    "main",
    "make_agent",
    "model_config",
    "one_line",
    "run_episodes",
]

#: The baselines by name (``const`` also takes ``const:a0,a1``).
BASELINES = (
    "random", "const", "best-const", "ghost", "ghost-centre", "search", "rack-planner",
    "first-row",
)  # fmt: skip

#: The files an agent may be, by suffix (any case): what each holds.
FILE_KINDS = {
    ".zip": "an SB3 model",
    ".npz": "a rack or lookahead model",
    ".yaml": "a search player file",
    ".yml": "a search player file",
}


def agent_kind(name: str) -> str | None:
    """What ``name`` names: a baseline (``"baseline"``), a file's suffix, or ``None``.

    A file's suffix is read in any case (``X.YAML`` is a player file); a baseline is one of
    :data:`BASELINES` or ``const:a0,a1[,...]``.
    """
    if name in BASELINES or name.startswith("const:"):
        return "baseline"
    suffix = Path(name).suffix.lower()
    return suffix if suffix in FILE_KINDS else None


#: Statistics printed, with their labels; rates are shown as percentages.
COLUMNS: tuple[tuple[str, str, bool], ...] = (
    ("pots_per_shot", "pots/shot", True),
    ("clean_pot_rate", "clean pots/shot", True),
    ("scratch_rate", "scratch/shot", True),
    ("clear_rate", "clear rate", True),
    ("run_out_rate", "run-out rate", True),
    ("pots_per_turn", "pots/turn", False),
    ("shots_per_episode", "shots/episode", False),
    ("episode_reward", "episode reward", False),
)

#: The statistics of the game ids (rules): a won rack is a "clear", a run-out a rack won
#: in the first turn (every shot legal and keeping the table).
GAME_COLUMNS: tuple[tuple[str, str, bool], ...] = (
    ("fouls_per_shot", "fouls/shot", True),
    ("pots_per_shot", "pots/shot", False),
    ("scratch_rate", "scratch/shot", True),
    ("clear_rate", "racks won", True),
    ("run_out_rate", "run-outs", True),
    ("shots_per_episode", "shots/rack", False),
    ("episode_reward", "rack reward", False),
)


def make_agent(name: str, env: Any, seed: int = 0, players: int | None = None) -> Policy:
    """An agent by name: a baseline, an SB3 ``.zip``, a rack ``.npz`` or a search ``.yaml``.

    The names are :data:`BASELINES` (``"const:a0,a1"`` too); a ``.yaml`` is a search
    player's config (``models/search_player.yaml``).

    A ``.npz`` is a :class:`~agents.learned.rack_play.RackAgent` value, or a
    :class:`~agents.learned.lookahead.LookaheadAgent` layout value when its config says
    ``kind: lookahead``. ``players``: the rules agents' (2: they play against an opponent,
    built on the one-player id by the duels; ``None``: the env's).
    """
    if name == "random":
        return RandomAgent(env, seed=seed)
    config = getattr(env.unwrapped, "config", None)
    rules = config is not None and config.ruleset.has_rack
    if name in ("ghost", "ghost-centre"):
        spin = name == "ghost"
        if rules:
            return GameGhostBallAgent(env, spin=spin, players=players)
        return GhostBallAgent(env, spin=spin)
    if name == "search":
        if rules:
            return GameSearchAgent(env, seed=seed, players=players)
        return SearchAgent(env, seed=seed)
    if name == "best-const":
        return best_constant_agent(env)
    if name == "const" or name.startswith("const:"):  # full hit, hardest; or "const:a0,a1"
        _, _, values = name.partition(":")
        width = int(env.action_space.shape[0])
        default = (0.0, 1.0) + (0.0,) * (width - 2)  # a spin env: centre ball
        try:
            action = tuple(float(v) for v in values.split(",")) if values else default
        except ValueError:
            action = ()
        if len(action) != width or not all(-1.0 <= a <= 1.0 for a in action):  # NaN too
            raise ValueError(
                f"agent {name!r}: const:a0,a1[,...] takes the env's {width} action numbers, "
                "each in [-1, 1]"
            )
        return ConstantAgent(env, action)
    if name == "first-row":  # row 0 of the env's "shots" observation, played exactly
        return ShotRowAgent(env)
    if name == "rack-planner":  # the rack agent's candidates ranked by the planner's score
        return RackAgent(env, players=players)
    kind = agent_kind(name)
    if kind == ".zip":
        return load_model(name)
    if kind in (".yaml", ".yml"):  # a search player's config (learned.search_player)
        return load_search_player(name, env, players=players)
    if kind == ".npz":  # a learned rack value (learned.rack_play, learned.lookahead)
        config = rack_model_config(name)
        if config.get("kind") == "lookahead":
            return load_lookahead_agent(name, env, config, players=players)
        return load_rack_agent(name, env, players=players)
    raise _unknown_agent(name)


def _unknown_agent(name: str) -> ValueError:
    """The error for a name that is no agent: the names and the file kinds listed."""
    close = difflib.get_close_matches(name, BASELINES, n=1)
    hint = f" (did you mean {close[0]}?)" if close else ""
    suffixes: dict[str, list[str]] = {}
    for suffix, what in FILE_KINDS.items():
        suffixes.setdefault(what, []).append(suffix)
    files = ", ".join(f"{what} {'/'.join(ends)}" for what, ends in suffixes.items())
    return ValueError(
        f"unknown agent {name!r}{hint}: an agent is one of {', '.join(BASELINES)}, "
        f"const:a0,a1[,...], or a file (any case): {files}"
    )


def check_agents(
    parser: argparse.ArgumentParser,
    names: list[str],
    env_id: str,
    env_kwargs: dict[str, Any] | None,
    players: int | None = None,
) -> None:
    """Check the env and every agent among ``names`` before anything is played.

    The env must be made with ``env_kwargs`` (a known id, keys and values the env takes:
    :func:`~agents.learned.envs.make_env`); a name must be a baseline (:func:`agent_kind`)
    or a file of a known kind (:data:`FILE_KINDS`) that exists, and every agent is built
    on that env, so that it can refuse a game it cannot play (the search player off
    9-ball, the rack planner off the game ids, a model trained on other observations);
    ``best-const`` is checked without its scan. A command so exits at once with one line
    naming the value as written (``parser.error``, status 2) rather than a traceback later.
    """
    try:
        env = make_env(env_id, env_kwargs)
    except ValueError as err:
        parser.error(str(err))
    try:
        for name in names:
            try:
                _check_agent(name, env, env_id, env_kwargs, players)
            except ValueError as err:
                parser.error(str(err))
    finally:
        env.close()


def check_game_id(parser: argparse.ArgumentParser, env_id: str, command: str) -> None:
    """A command that plays racks by the rules refuses another id (a usage error, status 2)."""
    try:
        env = make_env(env_id)
    except ValueError as err:
        parser.error(str(err))
    game = is_game(env)
    env.close()
    if not game:
        ids = ", ".join(k for k in pool_env.ENV_IDS if "Game" in k)
        parser.error(f"{command} plays the game ids ({ids}), not {env_id}")


def _check_agent(
    name: str, env: Any, env_id: str, env_kwargs: dict[str, Any] | None, players: int | None
) -> None:
    """:func:`check_agents` for one name on its ``env``. Raises ``ValueError`` naming it."""
    kind, path = agent_kind(name), Path(name)
    if kind != "baseline" and path.is_dir():
        raise ValueError(f"agent {name!r} is a directory, not a file ({path.absolute()})")
    if kind is None:
        raise _unknown_agent(name)
    if kind != "baseline" and not path.is_file():
        raise ValueError(f"agent {name!r}: {FILE_KINDS[kind]} not found ({path.absolute()})")
    if kind == ".zip":
        _check_model(name, env_id, env_kwargs)
        return
    try:
        if name == "best-const":  # its scan is the evaluation's work: a constant agent only
            ConstantAgent(env, (0.0,) * int(env.action_space.shape[0]))
        else:
            make_agent(name, env, players=players)
    except ValueError as err:
        message = str(err)
        if name not in message:  # the agent's own words, with the name as written
            message = f"agent {name!r} cannot play {env_id}: {message}"
        raise ValueError(message) from None


def _check_model(name: str, env_id: str, env_kwargs: dict[str, Any] | None) -> None:
    """An SB3 model must read the observations and make the actions of ``env_id``.

    Its env is built as :func:`evaluate_agent` builds it (the saved config's settings
    under the command's); the shapes are compared before any episode is played.
    """
    config = model_config(name)
    kwargs = {**(config.get("env_kwargs") or {}), **(env_kwargs or {})}
    env = make_env(env_id, kwargs, config.get("wrapper"))
    try:
        model = load_model(name)
        for what in ("observation", "action"):
            want = getattr(model, f"{what}_space").shape
            got = getattr(env, f"{what}_space").shape
            if want != got:
                trained = config.get("env_id", "another env")
                raise ValueError(
                    f"agent {name!r} was trained on {trained} ({what}s of shape {want}) and "
                    f"cannot play {env_id} ({what}s of shape {got})"
                )
    finally:
        env.close()


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


#: What a row is, printed under the table when the row is in it.
ROW_NOTES = {
    "first-row": "first-row: the observation's easiest ghost-ball shot (row 0 of its shot "
    "features: aim and speed, the tip at the centre) played exactly, learning nothing: the "
    "geometry alone, which a learner on that observation must beat.",
}


#: On a one-shot task, the columns that are others by construction: a cleared episode is
#: a pot, a run-out a clean pot, and each turn one shot.
ONE_SHOT_TWINS = {
    "clear_rate": "pots_per_shot",
    "run_out_rate": "clean_pot_rate",
    "pots_per_turn": "pots_per_shot",
}


def one_shot(rows: dict[str, dict[str, Estimate]]) -> bool:
    """Whether every episode of every row was one shot (a one-shot task: OneBall, ...)."""
    return all(
        (stats["shots_per_episode"].low, stats["shots_per_episode"].high) == (1.0, 1.0)
        for stats in rows.values()
    )


def format_table(rows: dict[str, dict[str, Estimate]], episodes: int) -> str:
    """A markdown table: one row per agent, each statistic with its 95% interval.

    On a one-shot task (:func:`one_shot`) a column that repeats its twin in every row
    (:data:`ONE_SHOT_TWINS`: clears and pots per turn are pots per shot, run-outs clean
    pots) is left out, and so is shots per episode (1); the note under the table says so. A row of
    :data:`ROW_NOTES` gets its note.
    """
    # Pots per shot is a rate only while no shot pots two balls (a break can pot several).
    multi = any(stats["pots_per_shot"].high > 1.0 for stats in rows.values())
    game = any("fouls_per_shot" in stats for stats in rows.values())
    columns = GAME_COLUMNS if game else COLUMNS
    dropped: list[str] = []
    if rows and one_shot(rows):
        labels = {key: label for key, label, _ in columns}
        kept: list[tuple[str, str, bool]] = []
        for key, label, pct in columns:
            twin = ONE_SHOT_TWINS.get(key)
            if key == "shots_per_episode":
                dropped.append(f"{label} (1)")
            elif twin and all(_same(stats[key], stats[twin]) for stats in rows.values()):
                dropped.append(f"{label} (= {labels[twin]})")
            else:
                kept.append((key, label, pct))
        columns = tuple(kept)
    head = "| agent | " + " | ".join(label for _, label, _ in columns) + " |"
    lines = [head, "|" + "---|" * (len(columns) + 1)]
    for agent, stats in rows.items():
        cells = [
            stats[key].as_percent()
            if pct and not (multi and key == "pots_per_shot")
            else str(stats[key])
            for key, _, pct in columns
        ]
        lines.append(f"| {agent} | " + " | ".join(cells) + " |")
    lines.append("")
    if game:
        lines.append(
            f"{episodes} racks each, same seeds; 95% confidence intervals in brackets. Racks "
            "won: the rack ended with the agent's win (the 9, the 10 or the 8 legally potted). "
            "Run-out: won without a foul or a missed turn."
        )
    else:
        lines.append(
            f"{episodes} episodes each, same seeds; 95% confidence intervals in brackets. Clean "
            "pot: a shot that pots without scratching. Run-out: cleared in the first turn."
        )
    if dropped:
        lines.append(f"One shot per episode, so these columns repeat others: {', '.join(dropped)}.")
    lines += [note for name, note in ROW_NOTES.items() if any(_base(r) == name for r in rows)]
    return "\n".join(lines)


def _same(a: Estimate, b: Estimate) -> bool:
    """Two statistics equal in value and interval (one column repeating another)."""
    return (a.value, a.low, a.high) == (b.value, b.low, b.high)


def _base(row: str) -> str:
    """A row's agent name without its label (``"best-const (+0.50, ...)"``: ``"best-const"``)."""
    return row.split(" ")[0]


def one_line(rows: dict[str, dict[str, Estimate]]) -> str:
    """``pots per shot: ppo 74.0% (clean 65.6%, scratch 17.1%) | random ... | ...``."""
    parts = [
        f"{name.split(' ')[0]} {stats['pots_per_shot'].value:.1%} "
        f"(clean {stats['clean_pot_rate'].value:.1%}, scratch {stats['scratch_rate'].value:.1%})"
        for name, stats in rows.items()
    ]
    return "pots per shot: " + " | ".join(parts)


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


#: ``--noise`` spellings of no noise at all (exact shots).
NO_NOISE = ("none", "0")

#: The noise the game ids play at unless told otherwise: the field's, FastFiz's model x1
#: (the computer billiards championships' "low noise", :mod:`pool_env.game.noise`).
FIELD_NOISE = "fastfiz"


def parse_noise(text: str) -> NoiseSpec | None:
    """``--noise``'s text as the env's ``noise`` value, checked by the env's own check.

    ``"0.003,0.05[,0.05]"``: the sigmas (aim rad, speed m/s[, tip in fractions of R]);
    ``"fastfiz"``: FastFiz's model, the computer billiards championships' (x1);
    ``"fastfiz:K"``: that model times ``K >= 0`` (``fastfiz:5``: the championships' "high"
    noise; :mod:`pool_env.game.noise`); ``"none"`` or ``"0"``: exact shots (``None``).

    Raises:
        ValueError: Naming ``--noise`` and what is wrong with the text.
    """
    if text.strip().lower() in NO_NOISE:
        return None
    name, colon, multiple = text.partition(":")
    value: NoiseSpec
    try:
        if name in NOISE_MODELS:
            value = (name, float(multiple)) if colon else name
        else:
            value = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(
            f"--noise takes 2 or 3 comma-separated sigmas, {' or '.join(NOISE_MODELS)}"
            f"[:K] with a number K, or none; got {text!r}"
        ) from None
    try:  # a spin table takes every spelling: a roll env refuses a tip sigma itself
        parse_env_noise(value, Table(model="spin"))
    except ValueError as err:
        raise ValueError(f"--noise {text!r}: {err}") from None
    return value


def noise_label(noise: object) -> str:
    """The noise in force, in words: ``"none (exact shots)"``, ``"fastfiz (FastFiz x1)"``."""
    if noise is None:
        return "none (exact shots)"
    if isinstance(noise, str) and noise in NOISE_MODELS:  # a list (YAML sigmas) is no name
        return f"{noise} (FastFiz x1, the field's)"
    if isinstance(noise, tuple | list) and noise and noise[0] in NOISE_MODELS:
        return f"{noise[0]}:{noise[1]:g} (FastFiz x{noise[1]:g})"
    return "sigmas " + ", ".join(f"{float(v):g}" for v in noise)  # type: ignore[union-attr]


def is_game(env: Any) -> bool:
    """Whether ``env`` plays a rack by the rules (a game id: 9-ball, 10-ball, 8-ball)."""
    config = getattr(env.unwrapped, "config", None)
    return config is not None and config.ruleset.has_rack


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
    "models/ppo_oneball.zip), a rack or lookahead model .npz (models/runout_value.npz), or a "
    "search player file .yaml/.yml (models/search_player.yaml: 9-ball only)"
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
