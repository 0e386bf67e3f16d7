"""``python -m agents.evaluate``: agents by name on the same seeds, one table of statistics.

The command's entry; the evaluation is :mod:`agents.evaluation.evaluate` (its docstring
gives the usage).
"""

import sys

from agents.evaluation.evaluate import main

if __name__ == "__main__":
    sys.exit(main())
