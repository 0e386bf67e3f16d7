"""The players ``--agent`` names, built on an env, and checked before anything is played.

A player is a baseline by name (:data:`BASELINES`, ``const:a0,a1[,...]``) or a file
(:data:`FILE_KINDS`: an SB3 ``.zip``, a rack, lookahead or rack-network ``.npz``, a search
player ``.yaml``). :func:`make_agent` builds one; :func:`check_agents` builds every one a
command names on its env first, so that a name, a file or a game the player cannot play is
a usage error (status 2, one line) and not a traceback after minutes of play.
"""

from __future__ import annotations

import argparse
import difflib
from pathlib import Path
from typing import Any

import pool_env
from agents.baselines.game_agents import GameGhostBallAgent, GameSearchAgent
from agents.baselines.ghost_ball import GhostBallAgent
from agents.baselines.random_agent import ConstantAgent, RandomAgent
from agents.baselines.search import SearchAgent
from agents.baselines.shot_row import ShotRowAgent
from agents.evaluation.constant_scan import best_constant_agent
from agents.learned.envs import make_env
from agents.learned.player_file import load_lookahead_agent, load_search_player
from agents.learned.pretrained import load_model, model_config
from agents.learned.rack_net import load_rack_net
from agents.learned.rack_play import RackAgent, load_rack_agent, rack_model_config
from agents.policy import Policy

__all__ = [
    "BASELINES",
    "FILE_KINDS",
    "agent_kind",
    "check_agents",
    "check_game_id",
    "is_game",
    "make_agent",
]

#: The baselines by name (``const`` also takes ``const:a0,a1``).
BASELINES = (
    "random", "const", "best-const", "ghost", "ghost-centre", "search", "rack-planner",
    "first-row",
)  # fmt: skip


#: The files an agent may be, by suffix (any case): what each holds.
FILE_KINDS = {
    ".zip": "an SB3 model",
    ".npz": "a rack, lookahead or rack-network model",
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


def make_agent(name: str, env: Any, seed: int = 0, players: int | None = None) -> Policy:
    """An agent by name: a baseline, an SB3 ``.zip``, a rack ``.npz`` or a search ``.yaml``.

    The names are :data:`BASELINES` (``"const:a0,a1"`` too); a ``.yaml`` is a search
    player's config (``models/search_player.yaml``).

    A ``.npz`` is a :class:`~agents.learned.rack_play.RackAgent` value, a lookahead's
    layout value when its config says ``kind: lookahead`` (the search player at depth 1:
    :func:`~agents.learned.player_file.load_lookahead_agent`), or a
    :class:`~agents.learned.rack_net.RackNetPlayer` network when it says
    ``kind: rack_net``. ``players``: the rules agents' (2: they play against an
    opponent, built on the one-player id by the duels; ``None``: the env's).
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
    if kind == ".npz":  # a rack value (learned.rack_play, .lookahead) or network (.rack_net)
        config = rack_model_config(name)
        if config.get("kind") == "lookahead":
            return load_lookahead_agent(name, env, config, players=players)
        if config.get("kind") == "rack_net":
            return load_rack_net(name, env, players=players)
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


def is_game(env: Any) -> bool:
    """Whether ``env`` plays a rack by the rules (a game id: 9-ball, 10-ball, 8-ball)."""
    config = getattr(env.unwrapped, "config", None)
    return config is not None and config.ruleset.has_rack
