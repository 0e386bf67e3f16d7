"""Deprecated aliases of public modules that moved: the old import path keeps working.

The Gymnasium and PettingZoo fronts moved into :mod:`pool_env.envs` on 2026-12-04
(``pool_env.env`` is now ``pool_env.envs.env``, and so on). Each old path is a module of two
lines that calls :func:`alias`: importing it warns once (``DeprecationWarning``, naming the
new path) and hands back the new module itself, so classes and functions are the very same
objects under both names. The aliases are kept for one release (see ``CHANGELOG.md``).
"""

from __future__ import annotations

import importlib
import sys
import warnings


def alias(old: str, new: str) -> None:
    """Make the module being imported as ``old`` the module ``new``, with a warning.

    Args:
        old: The old dotted path (the calling module's ``__name__``).
        new: Where the module lives now.
    """
    warnings.warn(
        f"{old} moved to {new}; import it from there ({old} is a deprecated alias, kept for "
        "one release)",
        DeprecationWarning,
        stacklevel=3,
    )
    sys.modules[old] = importlib.import_module(new)
