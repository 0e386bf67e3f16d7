"""Developer tools that are not benchmarks: the mutation runner (``python -m tools.mutants``)."""
