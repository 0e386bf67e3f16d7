"""The figures of results/oneball_scratches.md: where a learner scratches, and why PPO stalls.

Three diagnoses, each small (under a minute of CPU):

* ``scratches MODEL``: an SB3 model on ``pool_env/OneBall-v1`` (``observation="shots"``),
  1000 layouts from seed 10000: each scratch with or without a pot, the cut of row 0, the
  tip and speed played, the spin-aware ghost-ball agent on the same layout, and the
  model's own aim and speed replayed with each vertical tip of :data:`TIPS` (side 0).
* ``windows``: how wide the pot window is in aim action units, around row 0 on the roll
  table (at row 0's speed and at fixed speeds) and around the ghost-ball agent's action
  on the spin table (layouts from seed 30000 with a valid row 0).
* ``aims MODEL``: a roll-table model's deterministic aim against the valid rows' aims:
  the policy's std, how far its aim is from row 0's, and whether a miss aims near a row
  (an imprecise aim) or between two rows' aims (the mean of a one-mode Gaussian pulled
  between two pockets).

    python -m tools.oneball_diagnosis scratches models/sac_oneball_spin.zip
    python -m tools.oneball_diagnosis windows
    python -m tools.oneball_diagnosis aims runs/OneBallRoll-v1/<run>/model.zip
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

import gymnasium as gym
import numpy as np
from numpy.typing import NDArray

from agents.baselines.ghost_ball import GhostBallAgent
from agents.evaluation.evaluate import load_model
from pool_env import obs_layout
from pool_env.game.shot_features import SHOT_FEATURES

#: Vertical tips (action units: - draw, + follow) the model's aim and speed are replayed with.
TIPS = (-1.0, -0.5, 0.0, 0.5, 1.0)
#: Cut bins (degrees) of the scratch table.
CUT_BINS = ((0, 15), (15, 30), (30, 45), (45, 60), (60, 90))
#: Aim offsets (action units) scanned for the pot windows, and the layouts scanned.
WINDOW_STEP = 0.0025
WINDOW_OFFSETS = np.arange(-0.1, 0.1 + WINDOW_STEP / 2, WINDOW_STEP)
WINDOW_LAYOUTS = 200
#: A miss "near a row" aims within this of a valid row's aim (half a median pot window).
NEAR = 0.04

_VALID, _AIM, _COS, _SPEED = (SHOT_FEATURES.index(n) for n in ("valid", "aim", "cos_cut", "speed"))


def _rows(env: gym.Env, obs: NDArray[Any]) -> NDArray[np.float32]:
    """The ``"shots"`` rows of one observation, ``(pockets, len(SHOT_FEATURES))``."""
    return obs[obs_layout(env.unwrapped.config)["shots"]].reshape(-1, len(SHOT_FEATURES))


def _play(env: gym.Env, seed: int, action: NDArray[Any]) -> tuple[bool, bool, float]:
    """``(potted, scratched, reward)`` of ``action`` on layout ``seed``."""
    env.reset(seed=seed)
    _, reward, *_, info = env.step(np.asarray(action, dtype=np.float32))
    return len(info["potted"]) > 0, bool(info["scratch"]), float(reward)


def scratches(model_path: str, episodes: int, seed: int) -> None:
    """Classify a spin-table model's scratches (module docstring)."""
    env = gym.make("pool_env/OneBall-v1", observation="shots")
    model, ghost = load_model(model_path), GhostBallAgent(env)
    log = []
    for k in range(episodes):
        obs, _ = env.reset(seed=seed + k)
        row = _rows(env, obs)[0]
        action, _ = model.predict(obs, deterministic=True)
        g_action, _ = ghost.predict(obs)
        pot, scratch, reward = _play(env, seed + k, action)
        g_pot, g_scratch, _ = _play(env, seed + k, g_action)
        tips = []
        for tip in TIPS:
            replay = np.array(action, dtype=np.float32)
            replay[2], replay[3] = 0.0, tip
            tips.append(_play(env, seed + k, replay)[:2])
        cut = math.degrees(math.acos(min(max(float(row[_COS]), 0.0), 1.0)))
        log.append(
            (
                pot,
                scratch,
                reward,
                g_pot,
                g_scratch,
                cut if row[_VALID] else math.nan,
                float(action[1]),
                float(action[3]),
                float(g_action[3]),
                tips,
            )
        )
    env.close()
    on_scratch = [e for e in log if e[1]]
    pots = np.array([e[0] for e in log])
    scr = np.array([e[1] for e in log])
    rewards = np.array([e[2] for e in log])
    cuts = np.array([e[5] for e in log])
    height = np.array([e[7] for e in log])
    print(
        f"{episodes} layouts from seed {seed}: pots {pots.sum()}, scratches {scr.sum()} "
        f"(with a pot {(scr & pots).sum()}, with a miss {(scr & ~pots).sum()}); ghost-ball: "
        f"pots {sum(e[3] for e in log)}, scratches {sum(e[4] for e in log)}, on the model's "
        f"scratch layouts pots {sum(e[3] for e in on_scratch)} and scratches "
        f"{sum(e[4] for e in on_scratch)}"
    )
    for name, mask in (
        ("clean pot", pots & ~scr),
        ("pot and scratch", pots & scr),
        ("clean miss", ~pots & ~scr),
        ("miss and scratch", ~pots & scr),
    ):
        print(f"  reward of a {name}: {sorted(set(rewards[mask].round(3)))}")
    for lo, hi in CUT_BINS:
        m = (cuts >= lo) & (cuts < hi)
        g = sum(e[4] for e, inside in zip(log, m, strict=True) if inside)
        print(
            f"  row 0 cut {lo}-{hi} deg: {m.sum()} layouts, model scratches {scr[m].sum()} "
            f"({scr[m].mean():.1%}), ghost-ball scratches {g}"
        )
    for name, m in (
        ("draw (< -0.2)", height < -0.2),
        ("stun", np.abs(height) <= 0.2),
        ("follow (> 0.2)", height > 0.2),
    ):
        print(
            f"  model's tip {name}: {m.sum()} shots, scratches {scr[m].sum()} ({scr[m].mean():.1%})"
        )
    g_height = np.array([e[8] for e in log])
    print(
        f"  ghost-ball's tip: follow {np.mean(g_height > 0.05):.0%}, stun "
        f"{np.mean(np.abs(g_height) <= 0.05):.0%}, draw {np.mean(g_height < -0.05):.0%}"
    )
    speed = np.array([e[6] for e in log])
    print(
        f"  speed action median: all {np.median(speed):+.2f}, "
        f"scratches {np.median(speed[scr]):+.2f}"
    )
    saved = sum(any(p and not s for p, s in e[9]) for e, s in zip(log, scr, strict=True) if s)
    print(f"  scratches a vertical tip (side 0) at the model's aim and speed pots clean: {saved}")
    for i, tip in enumerate(TIPS):
        clean = sum(e[9][i][0] and not e[9][i][1] for e, s in zip(log, scr, strict=True) if s)
        print(
            f"    tip {tip:+.1f}: clean on the scratch layouts {clean}; over all layouts pots "
            f"{sum(e[9][i][0] for e in log)}, scratches {sum(e[9][i][1] for e in log)}"
        )


def windows() -> None:
    """Pot windows in aim units on both tables (module docstring)."""
    roll = gym.make("pool_env/OneBallRoll-v1", observation="shots")
    for speed in (None, -0.5, 0.0, 0.5, 1.0):
        _window(
            roll,
            "roll, row 0" + (" at its speed" if speed is None else f" at {speed:+.1f}"),
            lambda obs, row, s=speed: np.array([row[_AIM], row[_SPEED] if s is None else s]),
        )
    roll.close()
    spin = gym.make("pool_env/OneBall-v1", observation="shots")
    ghost = GhostBallAgent(spin)
    _window(spin, "spin, the ghost-ball agent's action", lambda obs, row: ghost.predict(obs)[0])
    spin.close()


def _window(env: gym.Env, name: str, centre: Any) -> None:
    """Print the pot windows of ``centre(obs, row 0)`` shifted in aim on ``env``."""
    widths = []
    for k in range(WINDOW_LAYOUTS):
        obs, _ = env.reset(seed=30_000 + k)
        row = _rows(env, obs)[0]
        if row[_VALID] != 1.0:
            continue
        base = np.asarray(centre(obs, row), dtype=np.float32)
        n = 0
        for offset in WINDOW_OFFSETS:
            shifted = base.copy()
            shifted[0] = np.clip(base[0] + offset, -1.0, 1.0)
            n += _play(env, 30_000 + k, shifted)[0]
        widths.append(n * WINDOW_STEP)
    w = np.array(widths)
    print(
        f"{name}: {len(w)} layouts, pot window median {np.median(w):.4f} (quartiles "
        f"{np.quantile(w, 0.25):.4f}-{np.quantile(w, 0.75):.4f}), none {np.mean(w == 0):.0%}"
    )


def aims(model_path: str, episodes: int, seed: int) -> None:
    """A roll-table model's aims against the rows' (module docstring)."""
    env = gym.make("pool_env/OneBallRoll-v1", observation="shots")
    model = load_model(model_path)
    std = np.exp(model.policy.log_std.detach().numpy())
    errors, pots, near, between = [], [], [], []
    for k in range(episodes):
        obs, _ = env.reset(seed=seed + k)
        rows = _rows(env, obs)
        action, _ = model.predict(obs, deterministic=True)
        pot = _play(env, seed + k, action)[0]
        valid = rows[rows[:, _VALID] == 1.0]
        if not len(valid):
            continue
        errors.append(abs(float(action[0] - valid[0, _AIM])))
        pots.append(pot)
        if not pot:
            gaps = np.abs(valid[:, _AIM] - action[0])
            near.append(gaps.min() < NEAR)
            inside = valid[:, _AIM].min() < action[0] < valid[:, _AIM].max()
            between.append(inside and gaps.min() >= NEAR)
    env.close()
    e, p = np.array(errors), np.array(pots)
    print(
        f"policy std (aim, speed): {np.round(std, 4)}; {len(e)} layouts with a valid row, "
        f"pots there {p.mean():.1%}"
    )
    print(
        f"|aim - row 0's aim|: median {np.median(e):.4f} (on pots {np.median(e[p]):.4f}, on "
        f"misses {np.median(e[~p]):.4f})"
    )
    print(
        f"misses {len(near)}: within {NEAR} of a valid row's aim {np.mean(near):.1%}, between "
        f"two valid rows' aims and {NEAR} from each {np.mean(between):.1%}"
    )


def main(argv: list[str] | None = None) -> int:
    """Run one diagnosis."""
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("what", choices=("scratches", "windows", "aims"))
    p.add_argument("model", nargs="?", help="an SB3 .zip (scratches, aims)")
    p.add_argument("--episodes", type=int, default=1000)
    p.add_argument("--seed", type=int, default=10_000)
    args = p.parse_args(argv)
    if args.what != "windows" and not args.model:
        p.error(f"{args.what} needs a model (.zip)")
    if args.what == "scratches":
        scratches(args.model, args.episodes, args.seed)
    elif args.what == "aims":
        aims(args.model, args.episodes, args.seed)
    else:
        windows()
    return 0


if __name__ == "__main__":
    sys.exit(main())
