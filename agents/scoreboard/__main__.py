"""``python -m agents.scoreboard``: the command's entry (:mod:`agents.scoreboard.command`)."""

import sys

from agents.scoreboard.command import main

if __name__ == "__main__":
    sys.exit(main())
