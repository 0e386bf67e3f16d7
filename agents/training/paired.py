"""A candidate-action model against its trivial policy (row 0 exactly), layout by layout.

Run: ``python -m agents.training.paired models/ppo_oneball.zip --episodes 3000 --seed 50000``.

Both play the same layouts (episode ``k`` reset with ``seed + k``), so the difference of
their clean-pot rates is estimated from the discordant layouts (one pots clean, the other
does not), with a 95% normal interval on the paired difference: much tighter than two
independent intervals would say.
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

import numpy as np

from agents.evaluation.episodes import run_episodes
from agents.learned.candidates import FirstRowAgent
from agents.learned.envs import make_env
from agents.learned.pretrained import load


def paired_clean(model_path: str, episodes: int, seed: int) -> dict[str, Any]:
    """Clean pots of the model and of row 0 on the same layouts, and their difference.

    Returns:
        ``model``, ``first_row`` (clean-pot rates), ``diff`` with its 95% interval
        ``(low, high)``, and the discordant counts ``model_only`` and ``first_row_only``.

    Raises:
        ValueError: If the model was not trained on candidate actions, or ``episodes < 2``.
    """
    if episodes < 2:
        raise ValueError(f"episodes must be >= 2, got {episodes}")
    policy = load(model_path)
    if policy.wrapper != "ghost_candidates":
        raise ValueError(f"{model_path} acts on {policy.wrapper!r}, not candidate actions")
    env = policy.make_env()
    ours = np.asarray(run_episodes(policy, env, episodes, seed).clean, dtype=float)
    env.close()
    cand = make_env(policy.env_id, policy.env_kwargs, "ghost_candidates")
    first = run_episodes(FirstRowAgent(cand.n_rows), cand, episodes, seed).clean
    cand.close()
    d = ours - np.asarray(first, dtype=float)
    half = 1.96 * float(np.std(d, ddof=1)) / math.sqrt(episodes)
    return {
        "model": float(ours.mean()),
        "first_row": float(np.mean(first)),
        "diff": (float(d.mean()), float(d.mean()) - half, float(d.mean()) + half),
        "model_only": int(np.sum(d > 0)),
        "first_row_only": int(np.sum(d < 0)),
    }


def main(argv: list[str] | None = None) -> int:
    """Print the paired comparison."""
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("model", help="a model .zip trained with wrapper ghost_candidates")
    p.add_argument("--episodes", type=int, default=3000)
    p.add_argument("--seed", type=int, default=50000)
    args = p.parse_args(argv)
    try:
        out = paired_clean(args.model, args.episodes, args.seed)
    except ValueError as exc:
        p.error(str(exc))
    value, low, high = out["diff"]
    print(
        f"{args.episodes} layouts from seed {args.seed}: clean pots {out['model']:.1%} (model) "
        f"vs {out['first_row']:.1%} (row 0 exactly); difference {100 * value:+.1f} points "
        f"[{100 * low:+.1f}, {100 * high:+.1f}]; clean for the model only on "
        f"{out['model_only']} layouts, for row 0 only on {out['first_row_only']}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
