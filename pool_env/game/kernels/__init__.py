"""Compiled kernels of the decision process (per-table work around a batch of shots)."""
