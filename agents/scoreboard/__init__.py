"""The scoreboard: any policy on one fixed suite of tasks, scored between random and the best.

``python -m agents.scoreboard POLICY --suite short`` (:mod:`agents.scoreboard.command`)
plays each task of :mod:`agents.scoreboard.suite` with the policy
(:mod:`agents.scoreboard.policies`: a committed player, an SB3 model, a ``module:attr``
factory) through the evaluation's own runners (:mod:`agents.scoreboard.play`), keeps each
task's record episode by episode (:mod:`agents.scoreboard.results`), and reports each
figure with its 95% interval and a normalized score (:mod:`agents.scoreboard.figures`);
``--leaderboard`` writes ``docs/leaderboard.md`` from the committed results files
(:mod:`agents.scoreboard.leaderboard`).
"""

from agents.scoreboard.command import main

__all__ = ["main"]
