"""Tests of the repository: docs, references, import contracts, mutants, benches' helpers."""
