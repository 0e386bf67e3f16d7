"""The shared parts of the mutation catalogue: the :class:`Mutant` record, paths, test subsets."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Mutant:
    """One planted bug.

    Attributes:
        name: Short unique identifier (used on the command line and in the table).
        area: What it breaks: ``impacts``, ``cushions``, ``motion``, ``roots``, ``ties``,
            ``zeno``, ``pockets``, ``jaws``, ``loop``, ``rewards``, ``observations``, ``actions``,
            ``seeding``, ``env``, ``vector``, ``sb3``, ``ball in hand``, ``strike``.
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


K = "pool_env/sim/kernels/"
G = "pool_env/game/"
W = G + "games/wpa/rules.py"

# Focused subsets: each a few files that pin the physics or rules the mutant breaks.
SIM = (
    "tests/sim/test_event_ties.py",
    "tests/sim/test_zeno_rules.py",
    "tests/sim/test_closed_forms.py",
    "tests/sim/test_hard_cases.py",
    "tests/sim/test_pinned_hard_cases.py",
)
SIM_AND_REFERENCE = (*SIM, "tests/sim/test_reference_compare.py")
SIM_AND_PROPERTIES = (*SIM, "tests/sim/test_properties.py")
OUTCOME = ("tests/game/test_shot_outcome.py", "tests/sim/test_batch.py")
POCKETS = (
    "tests/sim/test_pocket_geometry.py",
    "tests/sim/test_closed_forms.py",
    "tests/sim/test_reference_compare.py",
)
# The most focused files come first: with -x a killed mutant stops at its first failure.
DECISION = (
    "tests/envs/test_env_expectations.py",
    "tests/game/test_game_actions.py",
    "tests/envs/test_env.py",
)
VECTOR = ("tests/envs/test_env_expectations.py", "tests/envs/test_vector.py")
SB3 = ("tests/agents/test_native_vec_expectations.py", "tests/agents/test_native_vec.py")
REFERENCE = ("tests/game/test_game_reference.py",)
# The product's compiled rules: the rule cases through the env first (each a shot and its
# verdict, and the property test against the plain-Python reference), then the rule cases
# shot by the physics (tests/game/test_rule_cases.py judges only the reference: no use here).
GAMES = ("tests/game/test_games.py", "tests/game/test_wpa.py")
# The two-player front (PettingZoo), on the same compiled step as the env (so, like
# tests/game/test_games.py, it needs the compiled random-number intrinsics: never interpreted).
DUEL = ("tests/envs/test_multiagent.py",)
# The first contact as the rules read it (issue 20): simultaneous hits and the kitchen,
# through the env and against the reference reading the recorded trajectory.
CONTACT = ("tests/game/test_first_contact_rules.py", "tests/game/test_games.py")
# Jaw tables: the regulation numbers and closed forms first, then the hard cases and the
# reference scenes (facings, points and fall lines against the 50-digit reference).
JAWS = (
    "tests/sim/test_jaw_closed_forms.py",
    "tests/sim/test_jaws.py",
    "tests/sim/test_reference_compare.py::test_jaw_scenes_match_reference",
)

#: Test files that never reach the vector env's compiled random-number intrinsics, so they
#: can run with the kernels interpreted (``NUMBA_DISABLE_JIT=1``): a mutant whose subset is
#: all such files skips the ~25 s of compiling a fresh kernel cache.
INTERPRETABLE = frozenset(
    {
        *SIM,
        "tests/sim/test_reference_compare.py",
        "tests/sim/test_properties.py",
        "tests/sim/test_pocket_geometry.py",
        "tests/sim/test_batch.py",
        "tests/game/test_shot_outcome.py",
        "tests/sim/test_jaws.py",
        "tests/sim/test_jaw_closed_forms.py",
        "tests/game/test_wpa.py",
        "tests/game/test_layout_rules.py",
        "tests/sim/test_spin_resolve.py",
        "tests/sim/test_spin_cushion.py",
        "tests/sim/test_spin_strike.py",
        "tests/game/three_cushion/test_reference.py",
    }
)
