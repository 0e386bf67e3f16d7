"""Engines compared by the speed-against-error benchmark."""
