"""The catalogue of planted bugs for :mod:`bench.mutants`: data only.

Each entry is one realistic bug: the file, a short snippet of the current source that must
occur exactly once in it (``tests/test_mutant_catalogue.py`` checks that, so the catalogue
cannot rot silently), what replaces it, the focused test subset that should catch it, and
the real mistake it models. Snippets are kept short and stable so that unrelated edits of
the file do not move them.

Dropped as equivalent (each was run, survived every test, and no observable behaviour
tells it apart from the code):

* ``jaws._facing_entry`` without ``or along > extent``: an offset facing ends ``2R`` past
  the fall line (``R (n . fall_normal) - 2R < 0``: behind it), so a contact beyond its end
  lies behind the fall line, which a straight path from the throat reaches first, and a
  centre there is potted.
* ``pockets.kernel_rows`` anchoring the fall line at one end instead of its middle: any
  point of the line gives the same half-plane (up to rounding).
* ``predict.predict_own`` without ``or enter_b == enter_a``: folding one pocket twice into
  the earliest event changes nothing (same times, kinds and tie rules).
* ``rules._first_ball`` returning ``j`` for ``j if i == CUE else i``: a shot's first
  impact always involves the cue ball (only it moves at the start), which is column 0, so
  the ``else`` branch is dead.

Not equivalent, not killed, left out: ``jaws.unpress_lump`` without the facing's extent
check (a lump touching a facing's line beyond its ends); no scene of the suite puts a
sticking lump there.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Mutant:
    """One planted bug.

    Attributes:
        name: Short unique identifier (used on the command line and in the table).
        area: What it breaks: ``impacts``, ``cushions``, ``motion``, ``roots``, ``ties``,
            ``zeno``, ``pockets``, ``jaws``, ``loop``, ``rewards``, ``observations``, ``actions``,
            ``seeding``, ``env``, ``vector``, ``sb3``, ``ball in hand``.
        file: Path relative to the repository root.
        original: Exact source snippet; must occur exactly once in ``file``.
        mutated: What replaces it.
        tests: pytest arguments selecting the subset to run (files or node ids).
        models: The real bug it stands for.
        target: The function (and rule) the snippet sits in, for moving the mutant when
            the code moves (find the same rule in its new home and copy that line as
            ``original``). Empty when the file and ``models`` say enough.
    """

    name: str
    area: str
    file: str
    original: str
    mutated: str
    tests: tuple[str, ...]
    models: str
    target: str = ""


_K = "pool_env/sim/kernels/"
_G = "pool_env/game/"
_W = _G + "kernels/wpa.py"

# Focused subsets: each a few files that pin the physics or rules the mutant breaks.
SIM = (
    "tests/test_event_ties.py",
    "tests/test_zeno_rules.py",
    "tests/test_closed_forms.py",
    "tests/test_hard_cases.py",
    "tests/test_pinned_hard_cases.py",
)
SIM_AND_REFERENCE = (*SIM, "tests/test_reference_compare.py")
SIM_AND_PROPERTIES = (*SIM, "tests/test_properties.py")
OUTCOME = ("tests/test_shot_outcome.py", "tests/test_batch.py")
POCKETS = (
    "tests/test_pocket_geometry.py",
    "tests/test_closed_forms.py",
    "tests/test_reference_compare.py",
)
# The most focused files come first: with -x a killed mutant stops at its first failure.
DECISION = ("tests/test_env_expectations.py", "tests/test_game_actions.py", "tests/test_env.py")
VECTOR = ("tests/test_env_expectations.py", "tests/test_vector.py")
SB3 = ("tests/test_native_vec_expectations.py", "tests/test_native_vec.py")
REFERENCE = ("tests/test_game_reference.py",)
# The product's compiled rules: the rule cases through the env first (each a shot and its
# verdict, and the property test against the plain-Python reference), then the rule cases
# shot by the physics (tests/test_rule_cases.py judges only the reference: no use here).
GAMES = ("tests/test_games.py", "tests/test_wpa.py")
# The two-player front (PettingZoo), on the same compiled step as the env (so, like
# tests/test_games.py, it needs the compiled random-number intrinsics: never interpreted).
DUEL = ("tests/test_multiagent.py",)
# Jaw tables: the regulation numbers and closed forms first, then the hard cases and the
# reference scenes (facings, points and fall lines against the 50-digit reference).
JAWS = (
    "tests/test_jaw_closed_forms.py",
    "tests/test_jaws.py",
    "tests/test_reference_compare.py::test_jaw_scenes_match_reference",
)

#: Test files that never reach the vector env's compiled random-number intrinsics, so they
#: can run with the kernels interpreted (``NUMBA_DISABLE_JIT=1``): a mutant whose subset is
#: all such files skips the ~25 s of compiling a fresh kernel cache.
INTERPRETABLE = frozenset(
    {
        *SIM,
        "tests/test_reference_compare.py",
        "tests/test_properties.py",
        "tests/test_pocket_geometry.py",
        "tests/test_batch.py",
        "tests/test_shot_outcome.py",
        "tests/test_jaws.py",
        "tests/test_jaw_closed_forms.py",
        "tests/test_wpa.py",
        "tests/test_layout_rules.py",
    }
)

_ALL: tuple[Mutant, ...] = (
    # -- ball-ball impacts ---------------------------------------------------------------
    Mutant(
        "impact-seed-sign",
        "impacts",
        _K + "resolve.py",
        "ui_new = (mi * ui + mj * uj + mj * e_eff * (uj - ui)) / total",
        "ui_new = (mi * ui + mj * uj - mj * e_eff * (uj - ui)) / total",
        SIM,
        "the seed's printed restitution sign (striker passes through)",
    ),
    Mutant(
        "impact-elastic",
        "impacts",
        _K + "resolve.py",
        "e_eff = e if approach",
        "e_eff = 1.0 if approach",
        SIM,
        "e_ball ignored: every fast impact elastic",
    ),
    Mutant(
        "impact-normal-swapped",
        "impacts",
        _K + "resolve.py",
        "nx, ny = dx / dist, dy / dist",
        "nx, ny = dy / dist, dx / dist",
        SIM,
        "the seed's swapped sin/cos in the rotate-back step",
    ),
    Mutant(
        "impact-masses-swapped",
        "impacts",
        _K + "resolve.py",
        "mi, mj = masses[i], masses[j]",
        "mi, mj = masses[j], masses[i]",
        SIM_AND_REFERENCE,
        "per-ball masses read for the wrong ball",
    ),
    Mutant(
        "impact-tangential-loss",
        "impacts",
        _K + "resolve.py",
        "vxi += (ui_new - ui) * nx",
        "vxi = 0.99 * vxi + (ui_new - ui) * nx",
        SIM_AND_REFERENCE,
        "a 1% loss of the striker's x velocity at impact (friction leaking in)",
    ),
    # -- cushions ------------------------------------------------------------------------
    Mutant(
        "cushion-e-ball",
        "cushions",
        _K + "resolve.py",
        "a, e = params[P_DECEL], params[P_E_CUSHION]",
        "a, e = params[P_DECEL], params[P_E_BALL]",
        SIM,
        "cushion restitution taken from e_ball",
    ),
    Mutant(
        "cushion-tangential",
        "cushions",
        _K + "resolve.py",
        "            vx = -e * vx",
        "            vx = -vx\n            vy = e * vy",
        SIM,
        "restitution applied to the tangential component of a side-rail hit",
    ),
    Mutant(
        "cushion-far-rail-line",
        "cushions",
        _K + "predict.py",
        "line = length - radius if ux > 0.0 else radius",
        "line = length - 0.5 * radius if ux > 0.0 else radius",
        SIM,
        "the far rail's centre line offset by R/2 instead of R",
    ),
    # -- motion --------------------------------------------------------------------------
    Mutant(
        "motion-decel-1pct",
        "motion",
        "pool_env/sim/table.py",
        "params[P_DECEL] = self.mu_roll * self.g",
        "params[P_DECEL] = 1.01 * self.mu_roll * self.g",
        SIM,
        "rolling deceleration 1% off in the kernels' parameters",
    ),
    Mutant(
        "motion-rest-distance",
        "motion",
        _K + "motion.py",
        "s = spd * spd / (2.0 * a)",
        "s = spd * spd / a",
        SIM,
        "stopping distance v^2/a instead of v^2/(2a)",
    ),
    Mutant(
        "motion-arc-time",
        "motion",
        _K + "motion.py",
        "den = speed + math.sqrt(disc)",
        "den = 2.0 * speed",
        SIM,
        "event time from the constant-speed approximation t = s / v",
    ),
    Mutant(
        "timeline-positions-at",
        "motion",
        _K + "timeline.py",
        "s = tau * (spd - 0.5 * a * tau)",
        "s = tau * (spd - a * tau)",
        SIM,
        "positions_at between events with a doubled deceleration (final state still right)",
    ),
    # -- roots ---------------------------------------------------------------------------
    Mutant(
        "roots-polish-early",
        "roots",
        _K + "roots.py",
        "for _ in range(200):",
        "for _ in range(2):",
        SIM_AND_REFERENCE,
        "the contact-time polish stopped after two iterations",
    ),
    Mutant(
        "roots-ray-circle",
        "roots",
        _K + "roots.py",
        "return cc / (-b + math.sqrt(disc))",
        "return cc / (-b + math.sqrt(disc)) + 1e-7",
        SIM,
        "a ball-ball or pocket entry 0.1 um late along the path",
    ),
    Mutant(
        "roots-inflection-points",
        "roots",
        _K + "roots.py",
        "quadratic_roots(6.0 * c2, 6.0 * wc,",
        "quadratic_roots(6.0 * c2, 3.0 * wc,",
        SIM_AND_PROPERTIES,
        "a factor 2 lost in the derivative of D'': closest approaches bracketed wrongly",
    ),
    Mutant(
        "predict-cull-radius",
        "roots",
        _K + "predict.py",
        "capsules_may_meet(caps, i, j, 2.0 * radius + CULL_MARGIN)",
        "capsules_may_meet(caps, i, j, radius + CULL_MARGIN)",
        SIM_AND_PROPERTIES,
        "the capsule cull with R instead of 2R: grazing impacts culled",
    ),
    # -- tie order -----------------------------------------------------------------------
    Mutant(
        "tie-kind-order",
        "ties",
        _K + "loop.py",
        "        return kind < bkind",
        # Ball (1) and cushion (2) swap ranks in the total order; the codes stay.
        "        return (kind ^ 3 if 0 < kind < 3 else kind) < "
        "(bkind ^ 3 if 0 < bkind < 3 else bkind)",
        SIM,
        "event-kind tie order reversed: a cushion before a ball at the same instant",
    ),
    Mutant(
        "tie-jaw-before-ball",
        "ties",
        _K + "loop.py",
        "        return kind < bkind",
        # Jaw (4) and point (5) contacts rank before pocket (0) and ball (1) at a tie.
        "        return (kind - 6 if kind > 3 else kind) < (bkind - 6 if bkind > 3 else bkind)",
        JAWS,
        "facing and point contacts taken before a ball impact at the same instant",
    ),
    Mutant(
        "tie-id-order",
        "ties",
        _K + "loop.py",
        "        return i < bi",
        "        return i > bi",
        SIM,
        "simultaneous events of one kind taken highest ball first",
    ),
    # -- Zeno and sticking ---------------------------------------------------------------
    Mutant(
        "zeno-threshold-1e-3",
        "zeno",
        _K + "resolve.py",
        "V_ZENO = 1e-6  # m/s",
        "V_ZENO = 1e-3  # m/s",
        SIM,
        "the inelastic (Zeno) threshold raised from 1e-6 to 1e-3 m/s",
    ),
    Mutant(
        "zeno-isolated-inelastic",
        "zeno",
        _K + "resolve.py",
        "(approach > 0.0 and repeats < 2)",
        "(approach > 0.0 and repeats < 1)",
        SIM,
        "every slow impact inelastic, not only a repeating one",
    ),
    Mutant(
        "zeno-contact-tolerance",
        "zeno",
        _K + "resolve.py",
        "CONTACT_TOL = 1e-9  # m",
        "CONTACT_TOL = 1e-3  # m",
        SIM_AND_PROPERTIES,
        "a sticking lump that swallows balls a millimetre away",
    ),
    Mutant(
        "zeno-pressed-sign",
        "zeno",
        _K + "resolve.py",
        "+ 2.0 * (dx * cx + dy * cy) <= 0.0",
        "- 2.0 * (dx * cx + dy * cy) <= 0.0",
        SIM_AND_PROPERTIES,
        "the 'pressed together' test with the relative deceleration's sign flipped",
    ),
    # -- event loop ----------------------------------------------------------------------
    Mutant(
        "loop-cushion-no-repredict",
        "loop",
        _K + "loop.py",
        "            _repredict_pairs(st, status, bi, now, params, own, caps, pair)\n",
        "",
        SIM_AND_PROPERTIES,
        "pairs not re-predicted after a cushion (stale impact times)",
    ),
    Mutant(
        "tally-rail-before-contact",
        "rules",
        _K + "loop.py",
        "        if first_i >= 0:  # a jaw facing or point is a cushion for the rules\n",
        "        if True:\n",
        OUTCOME,
        "rails before the shot's first contact counted for the rules",
    ),
    Mutant(
        "tally-first-hit-overwritten",
        "rules",
        _K + "loop.py",
        "        if balls[BALL_FIRST_HIT, j] < 0:\n            balls[BALL_FIRST_HIT, j] = i",
        "        if True:\n            balls[BALL_FIRST_HIT, j] = i",
        OUTCOME,
        "a ball's first hit overwritten by every later hit",
    ),
    Mutant(
        "tally-pocket-order",
        "rules",
        _K + "loop.py",
        "            if balls[BALL_POCKET, k] >= 0:",
        "            if balls[BALL_POCKET, k] > 0:",
        OUTCOME,
        "the drop order misses balls in pocket 0",
    ),
    Mutant(
        "batch-first-contact-index",
        "loop",
        _K + "batch.py",
        "out.first_contact[b, 1] = index[shot.first_j]",
        "out.first_contact[b, 1] = shot.first_j",
        ("tests/test_batch.py", "tests/test_env_expectations.py"),
        "the batch's first contact in active-ball rows, not ball numbers",
    ),
    # -- pockets (capture circles) -------------------------------------------------------
    Mutant(
        "pocket-corner-mouth",
        "pockets",
        "pool_env/sim/table.py",
        "corner_r = math.hypot(r, CORNER_MOUTH / math.sqrt(2.0))",
        "corner_r = math.hypot(r, CORNER_MOUTH / 2.0)",
        POCKETS,
        "corner mouth measured along the rail, not across the 45-degree cut",
    ),
    Mutant(
        "pocket-side-centre",
        "pockets",
        "pool_env/sim/table.py",
        "(length / 2.0, -r, side_r)",
        "(length / 2.0, 0.0, side_r)",
        POCKETS,
        "side pocket circle centred on the cushion nose instead of R behind it",
    ),
    Mutant(
        "pocket-radius-squared",
        "pockets",
        _K + "predict.py",
        "pockets[k, 1], r * r, True)",
        "pockets[k, 1], r * (r - 1e-4), True)",
        POCKETS,
        "pocket capture radius 0.1 mm short in the predictor only",
    ),
    # -- pocket jaws (facings, points, fall lines) ------------------------------------------
    Mutant(
        "jaw-corner-cut-149",
        "jaws",
        "pool_env/sim/pockets.py",
        "CORNER_CUT_DEG = 142.0",
        "CORNER_CUT_DEG = 149.0",
        JAWS,
        "corner facing cut at 135 + 14 degrees (the side pocket's extra) instead of 135 + 7",
    ),
    Mutant(
        "jaw-side-cut-97",
        "jaws",
        "pool_env/sim/pockets.py",
        "SIDE_CUT_DEG = 104.0",
        "SIDE_CUT_DEG = 97.0",
        JAWS,
        "side facing cut at 90 + 7 degrees (the corner's extra) instead of 90 + 14",
    ),
    Mutant(
        "jaw-corner-mouth-along-rail",
        "jaws",
        "pool_env/sim/pockets.py",
        "c = spec.corner_mouth / math.sqrt(2.0)",
        "c = spec.corner_mouth / 2.0",
        JAWS,
        "corner points set half the mouth from the corner along each rail (mouth 3.18 in)",
    ),
    Mutant(
        "jaw-side-shelf-far-end",
        "jaws",
        "pool_env/sim/pockets.py",
        "SIDE_SHELF = 0.1875 * INCH",
        "SIDE_SHELF = 0.375 * INCH",
        JAWS,
        "side shelf at the deep end of the WPA range (3/8 in) instead of mid-range",
    ),
    Mutant(
        "jaw-shelf-in-front",
        "jaws",
        "pool_env/sim/pockets.py",
        "fall_point = 0.5 * (p[0] + p[1]) - shelf * mouth_n",
        "fall_point = 0.5 * (p[0] + p[1]) + shelf * mouth_n",
        JAWS,
        "the fall line set the shelf depth in front of the mouth (normal sign)",
    ),
    Mutant(
        "jaw-tip-centre-cos",
        "jaws",
        "pool_env/sim/pockets.py",
        "centres.append(p[k] + tip_radius / math.sin(half) * bisector)",
        "centres.append(p[k] + tip_radius / math.cos(half) * bisector)",
        JAWS,
        "round tip's centre r / cos(cut/2) along the bisector instead of r / sin(cut/2)",
    ),
    Mutant(
        "jaw-tip-tangent-tan",
        "jaws",
        "pool_env/sim/pockets.py",
        "tangent = tip_radius / math.tan(half)",
        "tangent = tip_radius * math.tan(half)",
        JAWS,
        "rail end and facing start r tan(cut/2) from the point instead of r / tan(cut/2)",
    ),
    Mutant(
        "jaw-corner-tip-radius-from-side",
        "jaws",
        "pool_env/sim/pockets.py",
        "corner = (spec.corner_cut, spec.corner_shelf, spec.corner_tip_radius, ball_radius)",
        "corner = (spec.corner_cut, spec.corner_shelf, spec.side_tip_radius, ball_radius)",
        JAWS,
        "corner points rounded with the side pockets' tip radius",
    ),
    Mutant(
        "jaw-facing-stops-at-fall-line",
        "jaws",
        "pool_env/sim/pockets.py",
        "(to_fall + 2.0 * ball_radius / depth_rate) * d",
        "to_fall * d",
        JAWS,
        "facings cut off at the fall line: the offset facing ends in front of it",
    ),
    Mutant(
        "jaw-tip-not-offset",
        "jaws",
        "pool_env/sim/pockets.py",
        "row[tip + 2] = jaw.tip_radius + ball_radius",
        "row[tip + 2] = jaw.tip_radius",
        JAWS,
        "point's contact radius without the ball radius (the centre touches the bare tip)",
    ),
    Mutant(
        "jaw-facing-offset-sign",
        "jaws",
        "pool_env/sim/pockets.py",
        "row[col : col + 2] = start + ball_radius * n",
        "row[col : col + 2] = start - ball_radius * n",
        JAWS,
        "facing offset by R into the cushion instead of towards the throat",
    ),
    Mutant(
        "jaw-fall-line-offset",
        "jaws",
        "pool_env/sim/pockets.py",
        "row[J_FX : J_FX + 2] = jaw.fall_line.mean(axis=0)",
        "row[J_FX : J_FX + 2] = jaw.fall_line.mean(axis=0) - ball_radius * jaw.fall_normal",
        JAWS,
        "fall line offset by R like a cushion (the ball must pass it whole to drop)",
    ),
    Mutant(
        "jaw-side-opening-at-points",
        "jaws",
        "pool_env/sim/pockets.py",
        "ends = sorted(float(jaw.rail_ends[f][axis]) for f in range(2))",
        "ends = sorted(float(jaw.points[f][axis]) for f in range(2))",
        JAWS,
        "side opening between the points: the rounded tips' stretch of rail line is a rail",
    ),
    Mutant(
        "jaw-corner-opening-at-points",
        "jaws",
        "pool_env/sim/pockets.py",
        "end = float(jaw.rail_ends[f][axis])",
        "end = float(jaw.points[f][axis])",
        JAWS,
        "corner opening from the point: the rounded tip's stretch of rail line is a rail",
    ),
    Mutant(
        "jaw-facing-before-start",
        "jaws",
        _K + "jaws.py",
        "if along < 0.0 or along > extent:",
        "if along > extent:",
        JAWS,
        "a facing contact accepted before the facing starts (on its extension past the tip)",
    ),
    Mutant(
        "jaw-point-normal-of-facing",
        "jaws",
        _K + "jaws.py",
        "if kind == JAW:",
        "if kind >= JAW:",
        JAWS,
        "a point impact reflected off its facing's normal, not the line from the tip centre",
    ),
    Mutant(
        "jaw-locate-either-point",
        "jaws",
        _K + "jaws.py",
        "if not (_free_of_point(row, 0, x, y, tol) and _free_of_point(row, 1, x, y, tol)):",
        "if not (_free_of_point(row, 0, x, y, tol) or _free_of_point(row, 1, x, y, tol)):",
        JAWS,
        "a centre clear of one facing counts as free (the region check and invariant G loosen)",
    ),
    Mutant(
        "jaw-locate-tip-unsquared",
        "jaws",
        _K + "jaws.py",
        "return (x - cx) ** 2 + (y - cy) ** 2 >= (rho - tol) ** 2",
        "return (x - cx) ** 2 + (y - cy) ** 2 >= rho - tol",
        JAWS,
        "the tip's squared distance compared with an unsquared radius (every tip cone refused)",
    ),
    Mutant(
        "jaw-restitution-of-cushion",
        "jaws",
        "pool_env/sim/table.py",
        "params[P_E_JAW] = self.e_jaw",
        "params[P_E_JAW] = self.e_cushion",
        JAWS,
        "jaw impacts with e_cushion: e_jaw never reaches the kernels",
    ),
    Mutant(
        "jaw-cull-own-throat",
        "jaws",
        _K + "predict.py",
        "for k in (here, enter_a, enter_b):",
        "for k in (enter_a, enter_b):",
        JAWS,
        "the jaw cull forgets the throat the ball is in (only openings crossed count)",
    ),
    # -- the 9/8-ball rules, compiled (game/kernels/wpa.py, the rule columns of rules.py) --
    # Killed through the env's rule cases (tests/test_games.py) and the physics-shot cases
    # of tests/test_wpa.py, both checked against the plain-Python reference
    # (tests/wpa_reference.py, never mutated: it is the test's oracle, not product code).
    Mutant(
        "rules-break-three-rails",
        "rules",
        _W,
        "BREAK_RAILS = 4",
        "BREAK_RAILS = 3",
        GAMES,
        "a break legal with three object balls to a cushion (WPA: four)",
        "wpa.foul_of, break: four object balls to a rail (BREAK_RAILS)",
    ),
    Mutant(
        "rules-nine-break-any-ball-first",
        "rules",
        _W,
        "first_ok = first >= 0 and (game == EIGHT or first == 1)",
        "first_ok = first >= 0",
        GAMES,
        "a 9-ball break that hits another ball before the 1 is legal",
        "wpa.foul_of, break: the 1 first in 9-ball",
    ),
    Mutant(
        "rules-pot-needs-a-rail",
        "rules",
        _W,
        "if n_potted == 0 and not rail:",
        "if not rail:",
        GAMES,
        "a pot without a rail after contact called a no-rail foul",
        "wpa.foul_of: no_rail only when nothing is potted",
    ),
    Mutant(
        "rules-wrong-ball-ignored",
        "rules",
        _W,
        "if not legal_first(game, rack, on_table, player, on, first):",
        "if not on_table[first]:",
        GAMES,
        "any object ball first is legal (the ball on / group ignored)",
        "wpa.foul_of: wrong_ball_first against legal_first",
    ),
    Mutant(
        "rules-three-fouls-at-two",
        "rules",
        _W,
        "rack[FOULS_0 + shooter] + 1 >= 3",
        "rack[FOULS_0 + shooter] + 1 >= 2",
        GAMES,
        "the three-foul loss on the second foul in a row",
        "wpa.judge_rack, 9-ball: three successive fouls lose",
    ),
    Mutant(
        "rules-three-fouls-of-the-opponent",
        "rules",
        _W,
        "and rack[FOULS_0 + shooter] + 1 >= 3",
        "and rack[FOULS_0 + other] + 1 >= 3",
        GAMES,
        "the three-foul rule reads the other player's successive fouls",
        "wpa.judge_rack, 9-ball: the shooter's own fouls in a row",
    ),
    Mutant(
        "rules-nine-respot-on-legal",
        "rules",
        _W,
        "if foul != NO_FOUL:\n                respot = 9\n            else:",
        "respot = 9\n            if foul == NO_FOUL:",
        GAMES,
        "the 9 re-spotted even when it wins the rack",
        "wpa.judge_rack, 9-ball: the 9 re-spotted only on a foul",
    ),
    Mutant(
        "rules-nine-keeps-after-foul",
        "rules",
        _W,
        "keeps = foul == NO_FOUL and n_potted > 0",
        "keeps = n_potted > 0",
        GAMES,
        "a shooter who pots on a foul keeps the table",
        "wpa.judge_rack, 9-ball: who shoots next",
    ),
    Mutant(
        "rules-foul-count-not-reset",
        "rules",
        _W,
        "+ 1 if foul != NO_FOUL else 0",
        "+ 1 if foul != NO_FOUL else rack[FOULS_0 + shooter]",
        GAMES,
        "a legal shot does not reset the successive-foul count",
        "wpa.judge_rack: foul counts",
    ),
    Mutant(
        "rules-fouls-counted-for-the-opponent",
        "rules",
        _W,
        "rack[FOULS_0 + shooter] = rack[FOULS_0 + shooter] + 1",
        "rack[FOULS_0 + other] = rack[FOULS_0 + other] + 1",
        GAMES,
        "the successive-foul count of the wrong player moved on",
        "wpa.judge_rack: the shooter's foul count",
    ),
    Mutant(
        "rules-kitchen-after-any-scratch",
        "rules",
        _W,
        "rack[BEHIND] = 1 if foul == FOUL_SCRATCH and breaking and game == EIGHT else 0",
        "rack[BEHIND] = 1 if foul == FOUL_SCRATCH and game == EIGHT else 0",
        GAMES,
        "ball in hand behind the head string after every 8-ball scratch, not only on the break",
        "wpa.judge_rack: ball in hand behind the head string",
    ),
    Mutant(
        "rules-ball-in-hand-on-every-miss",
        "rules",
        _W,
        "rack[IN_HAND] = 1 if foul != NO_FOUL else 0",
        "rack[IN_HAND] = 1 if foul != NO_FOUL or not keeps else 0",
        GAMES,
        "ball in hand whenever the turn passes, not only after a foul",
        "wpa.judge_rack: ball in hand after a foul",
    ),
    Mutant(
        "rules-break-pending-not-cleared",
        "rules",
        _W,
        "rack[BREAKING] = 0",
        "rack[BREAKING] = rack[BREAKING]",
        GAMES,
        "the break flag not cleared after the break: every shot judged as a break",
        "wpa.judge_rack: the break is one shot",
    ),
    Mutant(
        "rules-eight-uncalled-wins",
        "rules",
        _W,
        "elif called != eight_pocket:",
        "elif called >= 0 and called != eight_pocket:",
        GAMES,
        "the 8 potted without a call wins (any pocket counts)",
        "wpa.judge_rack, 8-ball: the 8 in the called pocket",
    ),
    Mutant(
        "rules-eight-foul-not-lost",
        "rules",
        _W,
        "elif foul != NO_FOUL:\n                loss = EIGHT_ON_FOUL",
        "elif foul == FOUL_SCRATCH:\n                loss = EIGHT_ON_FOUL",
        GAMES,
        "the 8 potted on a foul other than a scratch does not lose",
        "wpa.judge_rack, 8-ball: the 8 on a foul loses",
    ),
    Mutant(
        "rules-group-of-last-pot",
        "rules",
        _G + "rules.py",
        "elif order[k, c] < first_order:",
        "elif first_order > n_cols or order[k, c] > first_order:",
        GAMES,
        "an open table assigned the group of the last ball potted, not the first",
        "rules.judge_rules: the first object ball to drop (first_dropped)",
    ),
    Mutant(
        "rules-outcome-drop-order",
        "rules",
        _G + "rules.py",
        "elif order[k, c] < first_order:",
        "elif first_dropped < 0:",
        GAMES,
        "the first ball dropped taken by ball number, not by the order the balls dropped",
        "rules.judge_rules: first_dropped in drop order",
    ),
    Mutant(
        "rules-group-on-the-break",
        "rules",
        _W,
        "if foul == NO_FOUL and not breaking and group == OPEN and first_dropped > 0:",
        "if foul == NO_FOUL and group == OPEN and first_dropped > 0:",
        GAMES,
        "groups assigned by a ball potted on the break",
        "wpa.judge_rack, 8-ball: the table stays open after the break",
    ),
    Mutant(
        "rules-opponent-group-same",
        "rules",
        _W,
        "rack[GROUP_0 + other] = SOLIDS + STRIPES - group",
        "rack[GROUP_0 + other] = group",
        GAMES,
        "the opponent given the shooter's group when the table's groups are assigned",
        "wpa.judge_rack, 8-ball: group assignment",
    ),
    Mutant(
        "rules-eight-keeps-on-any-pot",
        "rules",
        _W,
        "if potted[j] and group_of(j) == group:",
        "if potted[j] and j != 8:",
        GAMES,
        "the shooter keeps the table after potting only an opponent's ball",
        "wpa.judge_rack, 8-ball: who shoots next",
    ),
    Mutant(
        "rules-on-the-eight-too-early",
        "rules",
        _W,
        "if on_table[j] and group_of(j) == group:\n            return -1\n    return 8",
        "if not on_table[j] and group_of(j) == group:\n            return 8\n    return -1",
        GAMES,
        "on the 8 as soon as one ball of the group is down",
        "wpa.ball_on: on the 8 once the group is cleared",
    ),
    Mutant(
        "rules-open-table-eight-legal",
        "rules",
        _W,
        "return j != 8",
        "return True",
        GAMES,
        "the 8 a legal first ball on an open table",
        "wpa.legal_first: open table",
    ),
    Mutant(
        "rules-stripes-include-eight",
        "rules",
        _W,
        "if 9 <= ball <= 15:",
        "if 8 <= ball <= 15:",
        GAMES,
        "the 8 counted among the stripes (a striped player is never on the 8)",
        "wpa.group_of: the balls of each group",
    ),
    Mutant(
        "rules-outcome-cue-rail-counted",
        "rules",
        _G + "rules.py",
        "if j != CUE:\n                    to_rail += 1",
        "to_rail += 1\n                if j != CUE:\n                    pass",
        GAMES,
        "the cue ball counted among the object balls driven to a rail on the break",
        "rules.judge_rules: object balls to a rail (to_rail)",
    ),
    Mutant(
        "rules-win-reward-sign",
        "rewards",
        _G + "rules.py",
        "reward += params[W_WIN] if winner == shooter else -params[W_WIN]",
        "reward += params[W_WIN] if winner != shooter else -params[W_WIN]",
        GAMES,
        "the rack's win reward given for a loss and the other way round",
        "rules.judge_rules: reward_win",
    ),
    Mutant(
        "info-first-ball-is-cue",
        "observations",
        _G + "rules.py",
        "return j if i == CUE else i",
        "return i if i == CUE else j",
        (*DECISION, *REFERENCE, *GAMES),
        "the first ball taken from the wrong side of the impact pair: the cue ball itself",
        "rules._first_ball",
    ),
    # -- ball in hand, the called pocket, re-spotting (actions.py, scenes.free_spot, step) --
    Mutant(
        "placement-kitchen-half-table",
        "ball in hand",
        _G + "config.py",
        "out[kp.HEAD_X] = table.length / 4.0",
        "out[kp.HEAD_X] = table.length / 2.0",
        GAMES,
        "ball in hand behind the head string allowed up to the centre line, not L/4",
        "config params HEAD_X: the head string at L/4 (place_in_hand's box)",
    ),
    Mutant(
        "placement-free-spot-kitchen-half-table",
        "ball in hand",
        _G + "scenes.py",
        "params[kp.X_HIGH] = table.length / 4.0",
        "params[kp.X_HIGH] = table.length / 2.0",
        GAMES,
        "the nearest-free-point search behind the head string goes up to the centre line",
        "scenes.free_spot: behind_head_string box",
    ),
    Mutant(
        "placement-ball-disc-radius",
        "ball in hand",
        _G + "scenes.py",
        "min_d2 = (reach - CLEARANCE / 2.0) ** 2",
        "min_d2 = (reach / 2.0) ** 2",
        GAMES,
        "a placed ball kept R from the others instead of 2R (overlap)",
        "scenes.free_spot: candidates 2R from every ball",
    ),
    Mutant(
        "placement-respot-in-front",
        "ball in hand",
        _G + "scenes.py",
        "return cand[ok][int(np.argmin(dist))].copy()",
        "return cand[ok][int(np.argmax(dist))].copy()",
        GAMES,
        "a placed or re-spotted ball goes to the farthest free candidate, not the nearest",
        "scenes.free_spot: as close to the target as possible",
    ),
    Mutant(
        "duel-ball-in-hand-anywhere",
        "ball in hand",
        _G + "kernels/actions.py",
        "x_high = params[HEAD_X] if rack[b, BEHIND] != 0 else params[X_HIGH]",
        "x_high = params[X_HIGH]",
        (*GAMES, *DUEL),
        "the cue ball in hand placed anywhere, not behind the head string (break, scratch)",
        "actions.place_in_hand: the kitchen",
    ),
    Mutant(
        "placement-nearest-free-leaves-kitchen",
        "ball in hand",
        _G + "step.py",
        "_place(config, state, b, CUE, target, bool(rack[b, wpa.BEHIND]))",
        "_place(config, state, b, CUE, target)",
        GAMES,
        "a cue ball in hand on a covered point moved to a free point past the head string",
        "step._step_rules: the nearest free point behind the head string",
    ),
    Mutant(
        "rack-in-hand-column",
        "ball in hand",
        _G + "kernels/actions.py",
        "if rack[b, IN_HAND] == 0:",
        "if rack[b, BEHIND] == 0:",
        (*GAMES, *DUEL),
        "the rack state's ball-in-hand column swapped with behind-the-head-string",
        "actions.place_in_hand: whom the action places",
    ),
    Mutant(
        "rack-break-speed-on-ball-in-hand",
        "actions",
        _G + "kernels/actions.py",
        "if row[BREAKING] != 0:",
        "if row[IN_HAND] != 0:",
        (*GAMES, *DUEL),
        "the break's speed range read from the ball-in-hand column (every ball in hand)",
        "actions.executed_rule_shots: the break speed range",
    ),
    Mutant(
        "duel-called-pocket-magnitude",
        "rules",
        _G + "kernels/actions.py",
        "called[k] = min(int(_unit(actions[k, 4]) * n_pockets), n_pockets - 1)",
        "called[k] = min(int(abs(actions[k, 4]) * n_pockets), n_pockets - 1)",
        (*GAMES, *DUEL),
        "the called-pocket action decoded from [0, 1] (its magnitude), not [-1, 1]",
        "actions.executed_rule_shots: action 4 -> the pocket called for the 8",
    ),
    Mutant(
        "called-pocket-rounded",
        "rules",
        _G + "kernels/actions.py",
        "int(_unit(actions[k, 4]) * n_pockets)",
        "int(_unit(actions[k, 4]) * n_pockets + 0.5)",
        (*GAMES, *DUEL),
        "the called-pocket bin rounded instead of floored: off by one in the upper half",
        "actions.executed_rule_shots: six equal bins over [-1, 1]",
    ),
    # -- the two-player front (pool_env/multiagent.py) ---------------------------------
    Mutant(
        "duel-winner-reward-sign",
        "rewards",
        "pool_env/multiagent.py",
        "self.rewards[name] = 1.0 if k == winner else -1.0",
        "self.rewards[name] = 1.0 if k != winner else -1.0",
        DUEL,
        "the rack's +1 / -1 given to the wrong player",
        "PoolDuelEnv.step: rewards at the end of the rack",
    ),
    Mutant(
        "duel-turn-kept",
        "rules",
        "pool_env/multiagent.py",
        "        self.agent_selection = AGENTS[int(self._state.rack[0, wpa.SHOOTER])]\n"
        "        self._accumulate_rewards()",
        "        self._accumulate_rewards()",
        DUEL,
        "the agent selection not moved to the rack's shooter after a shot",
        "PoolDuelEnv.step: who plays next",
    ),
    # -- the decision process ------------------------------------------------------------
    Mutant(
        "reward-shaping-sign",
        "rewards",
        _G + "rules.py",
        "+ params[W_SHAPING] * phi_change",
        "- params[W_SHAPING] * phi_change",
        (*DECISION, *REFERENCE),
        "the shaping term's sign flipped (rewards moving balls away from pockets)",
    ),
    Mutant(
        "reward-scratch-with-pot",
        "rewards",
        _G + "rules.py",
        "params[W_POT] * n_potted\n",
        "params[W_POT] * (0 if scratch else n_potted)\n",
        (*DECISION, *REFERENCE),
        "object balls potted on a scratch not counted",
    ),
    Mutant(
        "observation-y-scale",
        "observations",
        _G + "kernels/observe.py",
        "y = (2.0 * positions[k, j, 1] - width) / width",
        "y = (2.0 * positions[k, j, 1] - width) / length",
        (*DECISION, *SB3),
        "y scaled by the table length",
    ),
    Mutant(
        "observation-flag",
        "observations",
        _G + "kernels/observe.py",
        "out[k, 3 * j + 2] = 1.0",
        "out[k, 3 * j + 2] = 1.0 if j > 0 else 0.0",
        (*DECISION, *SB3),
        "the cue ball's on-table flag never set",
    ),
    Mutant(
        "action-speed-decode",
        "actions",
        _G + "kernels/actions.py",
        "v = (min(max(float(actions[k, 1]), -1.0), 1.0) + 1.0) * 0.5",
        "v = min(max(float(actions[k, 1]), 0.0), 1.0)",
        DECISION,
        "speed action read as [0, 1] instead of [-1, 1]",
    ),
    Mutant(
        "action-cut-radius",
        "actions",
        _G + "kernels/actions.py",
        "s = param * 2.0 * ball_radius / dist",
        "s = param * ball_radius / dist",
        DECISION,
        "cut offset in radii instead of diameters",
    ),
    Mutant(
        "action-relative-sign",
        "actions",
        _G + "kernels/actions.py",
        "return base + (param if mode == 1 else 0.0)",
        "return base - (param if mode == 1 else 0.0)",
        DECISION,
        "relative aim measured clockwise",
    ),
    Mutant(
        "env-end-on-scratch",
        "env",
        _G + "rules.py",
        "missed = n_potted == 0 or scratch",
        "missed = n_potted == 0",
        DECISION,
        "end_on_miss ignores a scratch that also pots",
    ),
    Mutant(
        "info-potted-bits-shift",
        "observations",
        _G + "rules.py",
        "bits |= np.int64(1) << (j - 1)",
        "bits |= np.int64(1) << j",
        (*DECISION, *REFERENCE),
        "potted-ball bit j instead of j - 1 (ball 1 reported as ball 2)",
    ),
    Mutant(
        "scratch-spot-unchecked",
        "ball in hand",
        _G + "rules.py",
        "if point_free(x, y, params, pockets, others, count, reach * reach):",
        "if True:",
        (*DECISION, *REFERENCE),
        "a scratched cue ball (or a re-spotted ball) put on its spot even when a ball covers it",
    ),
    Mutant(
        "layout-gap-one-radius",
        "seeding",
        _G + "kernels/layout.py",
        "if dx * dx + dy * dy < min_d2:",
        "if dx * dx + dy * dy < 0.25 * min_d2:",
        ("tests/test_layout_rules.py", *DECISION, *REFERENCE),
        "random layouts keep centres half the reach apart (balls overlap)",
    ),
    Mutant(
        "layout-same-uniform-for-y",
        "seeding",
        _G + "kernels/layout.py",
        "y = y0 + draws[2 * i + 1] * (y1 - y0)",
        "y = y0 + draws[2 * i] * (y1 - y0)",
        (*DECISION, *REFERENCE),
        "x and y of a drawn ball from the same uniform number (layouts on a diagonal)",
    ),
    Mutant(
        "layout-pocket-clearance",
        "seeding",
        _G + "kernels/layout.py",
        "r = pockets[p, 2] + params[CLEARANCE]",
        "r = pockets[p, 2]",
        ("tests/test_layout_rules.py", *DECISION, *REFERENCE),
        "drawn balls may touch a capture circle (no clearance)",
    ),
    Mutant(
        "potential-counts-cue",
        "rewards",
        _G + "kernels/observe.py",
        "for j in range(1, on_table.shape[0]):",
        "for j in range(0, on_table.shape[0]):",
        (*DECISION, *REFERENCE),
        "the shaping potential counts the cue ball's distance to a pocket",
    ),
    # -- the vector env and the SB3 adapter ----------------------------------------------
    Mutant(
        "seed-offset",
        "seeding",
        _G + "checks.py",
        "return [check_seed(seed) + i for i in range(n)]",
        "return [check_seed(seed) + i + 1 for i in range(n)]",
        (*VECTOR, *SB3),
        "table i seeded with seed + i + 1",
    ),
    Mutant(
        "vector-truncation",
        "vector",
        _G + "rules.py",
        "truncated = limit > 0.0 and shots >= limit",
        "truncated = limit > 0.0 and shots > limit",
        (*VECTOR, "tests/test_game_actions.py"),
        "the shot limit off by one",
    ),
    # The end_on_miss rule now has one copy for both fronts (env-end-on-scratch); the
    # vector front's own bug nearest to it is which finished tables it autoresets.
    Mutant(
        "vector-autoreset-truncated",
        "vector",
        "pool_env/vector.py",
        "done = terminated | truncated",
        "done = terminated.copy()",
        VECTOR,
        "the vector env does not autoreset a table truncated at its shot limit",
    ),
    Mutant(
        "settle-scratch-pocket-0",
        "vector",
        _G + "rules.py",
        "if pocketed[k, c] >= 0:",
        "if pocketed[k, c] > 0:",
        (*VECTOR, *SB3),
        "the rules miss a ball dropped into pocket 0 (pocket numbers start at 0)",
    ),
    Mutant(
        "sb3-terminal-observation",
        "sb3",
        "agents/native_vec.py",
        'infos[i]["terminal_observation"] = final_obs[i]',
        'infos[i]["terminal_observation"] = obs[i]',
        SB3,
        "the adapter reports the reset observation as the terminal one",
    ),
    Mutant(
        "sb3-time-limit-flag",
        "sb3",
        "agents/native_vec.py",
        "columns.append((truncated & ~terminated).tolist())",
        "columns.append(truncated.tolist())",
        SB3,
        "TimeLimit.truncated set on an episode that terminated at the limit",
    ),
    Mutant(
        "sb3-seed",
        "sb3",
        "agents/native_vec.py",
        "vec_env.seed(seed)",
        "vec_env.seed(seed + 1)",
        SB3,
        "make_native_vec_env seeds table 0 with seed + 1",
    ),
)

#: The mutants :mod:`bench.mutants` runs.
CATALOGUE: tuple[Mutant, ...] = _ALL
