"""Watch a player: one whole rack played by it, written as an animated GIF or an MP4.

Usage::

    python -m agents.evaluation.watch --agent models/search_player.yaml \
        --env pool_env/NineBallGame-v2 --seed 0 --run-out --out rack.gif

The player is any ``--agent`` the other commands take (a baseline by name or a file,
:func:`~agents.evaluation.players.make_agent`) on any id; it plays one episode from
``reset(seed=--seed)`` to its end: a rack won or lost, or with ``--run-out`` (the game's
``end_on_foul``, as ``agents.evaluation.runouts`` plays) the first miss or foul. Each shot
is drawn by the env itself (``PoolEnv.shot_frames``: the cue stick at its aim for 0.6 s,
then the balls sampled from their exact trajectories) and the rack is written with
:func:`pool_env.render.save_animation`, so the file shows what the env's recorder
(``RecordShots``, ``save_shot``) would, shot after shot. One line is printed per shot
(what was potted, a foul, the turn, the rack's end) and the file written.

Bad input (an agent, id, keyword, noise, player count, suffix or playback value) is a usage
error before anything is played (status 2, one line naming the value as written).
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from agents.evaluation.evaluate import _yaml_mapping
from agents.evaluation.noise_flag import noise_kwargs
from agents.evaluation.players import check_agents, make_agent
from agents.learned.envs import make_env
from agents.policy import Policy
from pool_env.render import Frame, animation_suffix, save_animation

__all__ = ["Playback", "ShotRecord", "describe_shot", "main", "play_rack", "watch"]

#: GIF frame delays are whole hundredths of a second, and browsers show a delay under 2 of
#: them as 10 (a GIF above 50 fps plays slower than asked): a GIF's fps is at most 50.
GIF_MAX_FPS = 50


def _is_number(value: object) -> bool:
    """A real number, not a bool (``True`` is no speed)."""
    return isinstance(value, int | float) and not isinstance(value, bool)


@dataclass(frozen=True)
class Playback:
    """How the rack is drawn and played back; checked when made.

    The defaults keep a 9-ball run-out GIF near 1 MB: 20 fps (a GIF delay of exactly
    5 hundredths: 15 fps would round to 6 and play 11% fast) at real speed, and a shot's
    balls shown for at most 3 s (a break rolls for ~10 s; it is sped up to fit), so a
    rack of ten shots is ~700 frames of which the GIF stores only what moved.

    Attributes:
        fps: Frames per second, of the drawing and of the file.
        speed: Playback speed (1 is real time).
        max_seconds: A shot's balls longer in motion are sped up to fit in this time.
        hold: Seconds the last frame stays before the file loops (0: none).
    """

    fps: int = 20
    speed: float = 1.0
    max_seconds: float = 3.0
    hold: float = 1.0

    def __post_init__(self) -> None:
        """Refuse a value no animation can take, naming its flag and the value."""
        if isinstance(self.fps, bool) or not isinstance(self.fps, int) or self.fps < 1:
            raise ValueError(f"--fps must be an integer >= 1, got {self.fps!r}")
        for flag, value in (("--speed", self.speed), ("--max-seconds-per-shot", self.max_seconds)):
            if not (_is_number(value) and math.isfinite(value) and value > 0):
                raise ValueError(f"{flag} must be a finite number > 0, got {value!r}")
        if not (_is_number(self.hold) and math.isfinite(self.hold) and self.hold >= 0):
            raise ValueError(f"--hold must be a finite number of seconds >= 0, got {self.hold!r}")

    def check_file(self, path: str | Path) -> str:
        """The suffix of ``path`` (``.gif``, ``.mp4``), checked with this playback.

        Raises:
            ValueError: On another suffix, or a GIF faster than :data:`GIF_MAX_FPS`.
        """
        try:
            suffix = animation_suffix(path)
        except ValueError as err:
            raise ValueError(f"--out: {err}") from None
        if suffix == ".gif" and self.fps > GIF_MAX_FPS:
            raise ValueError(
                f"--fps {self.fps} is too fast for a GIF: at most {GIF_MAX_FPS} (its delays "
                "are whole hundredths of a second, shorter ones are shown slower); use .mp4"
            )
        return suffix

    @property
    def hold_frames(self) -> int:
        """How many copies of the last frame make :attr:`hold`."""
        return round(self.hold * self.fps)


@dataclass(frozen=True)
class ShotRecord:
    """One shot of the rack as played.

    Attributes:
        number: 1 for the first (the break of a rack game).
        info: The step's ``info``, as the env returned it.
        frames: How many frames the shot was drawn in.
        line: What :func:`describe_shot` printed for it.
    """

    number: int
    info: dict[str, Any]
    frames: int
    line: str


def describe_shot(number: int, info: dict[str, Any]) -> str:
    """A shot in words, from the env's ``info``: the balls potted, a foul, how it ends.

    Reads the keys a game id reports (``potted``, ``foul``, ``push_out``, ``handed_back``,
    ``turn_over``, ``winner``, ``loss``) and, on an id without rules, ``scratch``.
    """
    potted = tuple(info.get("potted") or ())
    words = [f"potted {', '.join(str(b) for b in potted)}" if potted else "nothing potted"]
    if info.get("handed_back"):
        words = ["handed the table back"]
    elif info.get("push_out"):
        words.append("push-out")
    if info.get("foul") is not None:
        words.append(f"foul: {info['foul']}")
    elif info.get("scratch"):
        words.append("scratch")
    winner = info.get("winner", -1)
    if winner == 0:
        words.append("rack won")
    elif winner == 1:
        words.append(f"rack lost: {info['loss']}" if info.get("loss") else "rack lost")
    elif info.get("turn_over"):
        words.append("turn over")
    return f"shot {number}: " + "; ".join(words)


def play_rack(
    agent: Policy,
    env: Any,
    seed: int,
    playback: Playback,
    echo: Callable[[str], object] = print,
) -> tuple[list[Frame], list[ShotRecord]]:
    """Play one episode of ``agent`` on ``env`` from ``reset(seed=seed)``, drawing each shot.

    Args:
        agent: The player (``predict(obs, deterministic=True)``).
        env: An env made with ``render_mode`` ``"rgb_array"`` (the shots' trajectories are
            kept; no frame is drawn that is not used).
        seed: The reset's seed: the rack and the execution noise.
        playback: The frames' rate, speed and longest shot.
        echo: Called with each shot's line as it is played.

    Returns:
        Every shot's frames in order (the last held for ``playback.hold``), and the shots.
    """
    obs, _ = env.reset(seed=seed)
    frames: list[Frame] = []
    shots: list[ShotRecord] = []
    done = False
    while not done:
        action = agent.predict(obs, deterministic=True)[0]
        obs, _, terminated, truncated, info = env.step(action)
        done = terminated or truncated
        drawn = env.unwrapped.shot_frames(playback.fps, playback.speed, playback.max_seconds)
        frames += drawn
        line = describe_shot(len(shots) + 1, info)
        if truncated and not terminated:
            line += "; time limit"
        shots.append(ShotRecord(len(shots) + 1, info, len(drawn), line))
        echo(line)
    frames += [frames[-1]] * playback.hold_frames  # the same array: a GIF merges them
    return frames, shots


def watch(
    agent_name: str,
    env_id: str,
    seed: int,
    out: str | Path,
    env_kwargs: dict[str, Any] | None = None,
    playback: Playback | None = None,
    width: int = 480,
    players: int | None = None,
    echo: Callable[[str], object] = print,
) -> list[ShotRecord]:
    """Play one rack of ``agent_name`` on ``env_id`` and write it to ``out``.

    ``out``'s suffix is checked first (``.gif`` or ``.mp4``, :meth:`Playback.check_file`);
    its folder is made if missing.

    Returns:
        The shots as played.

    Raises:
        ValueError: On a bad suffix or playback, or what the env or agent refuses.
    """
    playback = playback or Playback()
    playback.check_file(out)
    kwargs = {**(env_kwargs or {}), "render_mode": "rgb_array", "render_width": width}
    env = make_env(env_id, kwargs)
    try:
        agent = make_agent(agent_name, env, seed, players=players)
        frames, shots = play_rack(agent, env, seed, playback, echo)
    finally:
        env.close()
    Path(out).parent.mkdir(parents=True, exist_ok=True)
    save_animation(frames, out, playback.fps)
    seconds = len(frames) / playback.fps
    size = Path(out).stat().st_size
    echo(f"wrote {out}: {len(shots)} shots, {len(frames)} frames, {seconds:.1f} s, {size} bytes")
    return shots


def main(argv: list[str] | None = None) -> int:
    """Command-line entry point."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--agent", required=True, help="the player, as agents.evaluate's")
    parser.add_argument("--env", default="pool_env/NineBallGame-v2", help="registered env id")
    parser.add_argument("--seed", type=int, default=0, help="the reset's seed: rack and noise")
    parser.add_argument(
        "--noise", default="fastfiz", help="as agents.evaluate's --noise (none: exact shots)"
    )
    parser.add_argument(
        "--env-kwargs", default=None, help='gymnasium.make kwargs as YAML, e.g. "{max_shots: 30}"'
    )
    parser.add_argument(
        "--run-out",
        action="store_true",
        help="end the rack at the first miss or foul (the game's end_on_foul)",
    )
    parser.add_argument(
        "--players",
        type=int,
        choices=(1, 2),
        default=None,
        help="the rules agents' (2: play as against an opponent; default: the env's)",
    )
    parser.add_argument("--out", required=True, help="the file to write: .gif or .mp4")
    parser.add_argument("--width", type=int, default=480, help="frame width in pixels")
    parser.add_argument("--fps", type=int, default=Playback.fps)
    parser.add_argument("--speed", type=float, default=Playback.speed, help="1: real time")
    parser.add_argument(
        "--max-seconds-per-shot",
        type=float,
        default=Playback.max_seconds,
        help="a longer shot is sped up to fit",
    )
    parser.add_argument(
        "--hold", type=float, default=Playback.hold, help="seconds on the last frame"
    )
    args = parser.parse_args(argv)
    try:
        playback = Playback(args.fps, args.speed, args.max_seconds_per_shot, args.hold)
        playback.check_file(args.out)
    except ValueError as err:
        parser.error(str(err))
    if Path(args.out).is_dir():
        parser.error(f"--out {args.out!r} is a directory, not a file")
    kwargs: dict[str, Any] = {}
    if args.env_kwargs:
        try:
            kwargs = _yaml_mapping(args.env_kwargs)
        except ValueError as err:
            parser.error(f"--env-kwargs {args.env_kwargs!r} is not YAML: {err}")
        if not isinstance(kwargs, dict):
            parser.error(f"--env-kwargs must be a YAML mapping, got {args.env_kwargs!r}")
    kwargs.update(noise_kwargs(parser, args.noise))
    if args.run_out:
        kwargs["end_on_foul"] = True
    render = {"render_mode": "rgb_array", "render_width": args.width}
    check_agents(parser, [args.agent], args.env, {**kwargs, **render}, args.players)
    print(f"{args.agent} on {args.env}, seed {args.seed}, noise {args.noise}", flush=True)
    watch(
        args.agent, args.env, args.seed, args.out, kwargs, playback, args.width, args.players,
        echo=lambda line: print(line, flush=True),
    )  # fmt: skip
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
