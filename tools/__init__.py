"""Developer tools that are not benchmarks: the checkers and the mutation runner.

The checkers: ``fuzz`` (with ``fuzz_spin``: every invariant over random scenes and shots,
``python -m tools.fuzz``), ``hard_cases`` (scenes where a simulator is most easily wrong,
with what must happen) and ``chaos`` (how a 1e-12 m change of the cue ball grows over a
break); ``shots`` holds the records they share with the benchmarks (a scene, an engine's
outcome). The mutation runner: ``python -m tools.mutants`` and its catalogue of planted bugs
(``mutant_catalogue``, ``mutant_runner``, ``mutant_report``); ``rack_picks`` (how often a
9-ball model's pick differs from its planner's). The benchmarks (``bench/``) may use the
checkers, never the reverse.
"""
