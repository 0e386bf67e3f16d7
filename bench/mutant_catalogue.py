"""The catalogue of planted bugs for :mod:`bench.mutants`: data only.

Each entry is one realistic bug: the file, a short snippet of the current source that must
occur exactly once in it (``tests/test_mutant_catalogue.py`` checks that, so the catalogue
cannot rot silently), what replaces it, the focused test subset that should catch it, and
the real mistake it models. Snippets are kept short and stable so that unrelated edits of
the file do not move them.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Mutant:
    """One planted bug.

    Attributes:
        name: Short unique identifier (used on the command line and in the table).
        area: What it breaks: ``impacts``, ``cushions``, ``motion``, ``roots``, ``ties``,
            ``zeno``, ``pockets``, ``loop``, ``rewards``, ``observations``, ``actions``,
            ``seeding``, ``env``, ``vector``, ``sb3``.
        file: Path relative to the repository root.
        original: Exact source snippet; must occur exactly once in ``file``.
        mutated: What replaces it.
        tests: pytest arguments selecting the subset to run (files or node ids).
        models: The real bug it stands for.
    """

    name: str
    area: str
    file: str
    original: str
    mutated: str
    tests: tuple[str, ...]
    models: str


_K = "pool_env/sim/kernels/"
_G = "pool_env/game/"

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
    }
)

CATALOGUE: tuple[Mutant, ...] = (
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
