"""Optional dependencies: import one, or say which extra of this package installs it.

The core install is numpy, numba and Gymnasium. Rendering, training, two players and the
other RL libraries come with extras (``pyproject.toml``); a missing one is named by the
extra that brings it, not by another package's hint (``gymnasium[other]``) or a bare
``No module named 'yaml'``.
"""

from __future__ import annotations

import importlib
from types import ModuleType


def require(
    module: str,
    extra: str | None,
    needed_for: str,
    error: type[Exception] = ModuleNotFoundError,
    *,
    install: str | None = None,
) -> ModuleType:
    """Import ``module``, or raise ``error`` naming the extra that installs it.

    Args:
        module: The dotted module name to import.
        extra: The extra of this package that installs it (``"train"``, ``"render"``, ...),
            or ``None`` when no extra can (then ``install`` says how).
        needed_for: What needs it, for the message (``'render_mode="human"'``).
        error: The exception type raised when it is missing (Gymnasium's
            ``DependencyNotInstalled`` for rendering, as Gymnasium's own envs raise).
        install: The install step named instead of ``pip install "pool_env[extra]"``
            (pooltool 0.6.0, which pip cannot install on Linux as an extra would).

    Returns:
        The module.

    Raises:
        Exception: ``error``, when ``module`` or a package it needs is not installed; an
            import failure inside an installed package is raised as it is.
        ValueError: Neither ``extra`` nor ``install`` given (a caller's mistake, caught
            whether or not the module is installed).
    """
    if extra is None and install is None:
        raise ValueError("require needs the extra or the install step that brings the module")
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        top = module.split(".")[0]
        if exc.name is not None and exc.name.split(".")[0] != top and _installed(top):
            raise  # the package is there and something inside it is broken: show that
        step = install if install is not None else f'pip install "pool_env[{extra}]"'
        message = f"{needed_for} needs {top}: {step}"
        raise error(message) from exc


def _installed(top: str) -> bool:
    from importlib.util import find_spec

    try:
        return find_spec(top) is not None
    except (ImportError, ValueError):
        return False
