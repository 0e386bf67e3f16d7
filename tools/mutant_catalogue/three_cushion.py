"""Mutants of three-cushion (game/games/three_cushion/ and the simulator's second-hit tally).

The rules are numpy (no kernel to recompile): killed by the reference comparison
(tests/game/three_cushion/test_reference.py: the rows the simulator's tally makes of random
event lists, judged against the plain-Python reference reading the events) and the played
rule cases (tests/game/three_cushion/test_rule_cases.py).
"""

from __future__ import annotations

from tools.mutant_catalogue.base import G, K, Mutant

TC = G + "games/three_cushion/"
REFERENCE = ("tests/game/three_cushion/test_reference.py",)
PLAYED = ("tests/game/three_cushion/test_rule_cases.py",)

MUTANTS: tuple[Mutant, ...] = (
    Mutant(
        "carom-two-cushions-score",
        "rules",
        TC + "rules.py",
        "CUSHIONS_NEEDED = 3",
        "CUSHIONS_NEEDED = 2",
        REFERENCE,
        "a carom off two cushions scored (UMB art. 83: three)",
        "three_cushion.rules.judge_rows: the point",
    ),
    Mutant(
        "carom-cushion-at-the-contact-not-counted",
        "rules",
        K + "sequence.py",
        "if now <= t_second[i]:",
        "if now < t_second[i]:",
        REFERENCE,
        "a cushion impact at the very instant of the second contact left out of the count",
        "sequence.tally: cushions_at_second, the tie rule",
    ),
    Mutant(
        "carom-second-hit-same-ball",
        "rules",
        K + "sequence.py",
        "elif first != j and balls[BALL_SECOND_HIT, i] < 0:",
        "elif balls[BALL_SECOND_HIT, i] < 0:",
        REFERENCE,
        "the cue ball meeting its first ball twice taken as its second ball",
        "sequence._touch: the second distinct ball",
    ),
    Mutant(
        "carom-inning-goes-on-after-a-miss",
        "rules",
        TC + "rules.py",
        "passes = (missed | to_equalize) & ~terminated",
        "passes = to_equalize & ~terminated",
        (*REFERENCE, *PLAYED),
        "a miss does not pass the table (UMB art. 24/25)",
        "three_cushion.rules.judge_rows: the inning's end",
    ),
    Mutant(
        "carom-one-inning-does-not-end",
        "rules",
        TC + "rules.py",
        "terminated = ~point | reached",
        "terminated = reached",
        (*REFERENCE, *PLAYED),
        "the one-inning task goes on after a miss",
        "three_cushion.rules.judge_rows, one player",
    ),
    Mutant(
        "carom-target-one-past",
        "rules",
        TC + "rules.py",
        "reached = point & (rack[rows, SCORE_0 + s] >= target)",
        "reached = point & (rack[rows, SCORE_0 + s] > target)",
        (*REFERENCE, *PLAYED),
        "the match ends one point after the target",
        "three_cushion.rules.judge_rows: the target",
    ),
    Mutant(
        "carom-no-equalizing-inning",
        "rules",
        TC + "rules.py",
        "first_wins = reached & (s == 0) & (not equalizing)",
        "first_wins = reached & (s == 0)",
        (*REFERENCE, *PLAYED),
        "white wins at the target without the yellow's equalizing inning",
        "three_cushion.rules.judge_rows: the equalizing inning",
    ),
    Mutant(
        "carom-equalized-is-a-win",
        "rules",
        TC + "rules.py",
        "np.where(in_equalizing, DRAW, 1)[second_reaches]",
        "np.where(in_equalizing, 1, 1)[second_reaches]",
        (*REFERENCE, *PLAYED),
        "the yellow reaching the target in its equalizing inning wins instead of drawing",
        "three_cushion.rules.judge_rows: the equalizing inning's draw",
    ),
    Mutant(
        "carom-inning-limit-one-late",
        "rules",
        TC + "rules.py",
        "at_limit &= rack[:, INNINGS_0 + 1] >= inning_limit",
        "at_limit &= rack[:, INNINGS_0 + 1] > inning_limit",
        (*REFERENCE, *PLAYED),
        "the match plays one inning past the limit",
        "three_cushion.rules.judge_rows: the inning limit",
    ),
    Mutant(
        "carom-limit-tie-to-white",
        "rules",
        TC + "rules.py",
        "scores[:, 0] > scores[:, 1], 0,",
        "scores[:, 0] >= scores[:, 1], 0,",
        (*REFERENCE, *PLAYED),
        "equal scores at the inning limit won by white (a draw)",
        "three_cushion.rules.judge_rows: on_points",
    ),
    Mutant(
        "carom-break-any-ball-first",
        "rules",
        TC + "rules.py",
        "foul = (rack[:, BREAKING] != 0) & (first != RED)",
        "foul = (rack[:, BREAKING] != 0) & (first < 0)",
        REFERENCE,
        "the opening shot legal on the opponent's ball (UMB art. 23: the red first)",
        "three_cushion.rules.judge_rows: the break",
    ),
    Mutant(
        "carom-respot-for-white-always",
        "rules",
        TC + "game.py",
        "starting_layout(config.table, int(shooter[k]))",
        "starting_layout(config.table)",
        PLAYED,
        "a frozen yellow re-spotted with white on the head string (UMB art. 27)",
        "ThreeCushion._respot_frozen",
    ),
    Mutant(
        "carom-frozen-reads-the-wrong-ball",
        "rules",
        TC + "game.py",
        "touching = frozen(state.positions[tables], shooter, config.table.ball_radius)",
        "touching = frozen(state.positions[tables], 0 * shooter, config.table.ball_radius)",
        PLAYED,
        "the white's contact checked whoever strikes next",
        "ThreeCushion._respot_frozen: the next striker's cue ball",
    ),
    Mutant(
        "carom-codec-aims-from-white",
        "actions",
        G + "codec.py",
        "cue = int(ruleset.cue_columns(state)[0])",
        "cue = 0",
        ("tests/game/three_cushion/test_played.py",),
        "encode_action's cut aim refers from ball 0 on the yellow's turn",
        "codec._aim",
    ),
)
