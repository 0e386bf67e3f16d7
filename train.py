"""``python train.py``: the training command of :mod:`agents.train`, run from a clone.

Installed, the same command is ``python -m agents.train`` or ``pool-env-train``.
"""

import sys

from agents.train import build_parser, main, parse_sets

__all__ = ["build_parser", "main", "parse_sets"]

if __name__ == "__main__":
    sys.exit(main())
