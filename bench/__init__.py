"""Speed-against-error benchmarks (not part of the installed package)."""
