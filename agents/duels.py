"""``python -m agents.duels``: head-to-head 9-ball racks of two agents, a 95% interval.

The command's entry; the duels are :mod:`agents.evaluation.duels` (its docstring gives the
usage).
"""

import sys

from agents.evaluation.duels import main

if __name__ == "__main__":
    sys.exit(main())
