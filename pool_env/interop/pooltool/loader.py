"""pooltool itself: whether it is installed, how to install it, and importing it when called.

Importing :mod:`pool_env.interop.pooltool` never imports pooltool (it writes its settings
under ``~/.config`` on its first import); :func:`load_pooltool` does, when
:func:`~pool_env.interop.pooltool.to_system` or
:func:`~pool_env.interop.pooltool.from_system` needs it.
"""

from __future__ import annotations

from types import ModuleType

from pool_env.extras import require

#: How to install pooltool 0.6.0 beside this package. Not an extra: on Linux
#: pooltool-billiards 0.6.0 pins an unpublished panda3d build, so a plain pip install falls
#: back to pooltool 0.3.3; the script installs 0.6.0 with panda3d 1.10 (and numba <= 0.62,
#: which this package runs on too).
INSTALL = (
    "install pooltool-billiards 0.6.0 beside pool_env; on Linux, from this repository, "
    "bash bench/setup_pooltool.sh VENV (pooltool 0.6.0 with panda3d 1.10), then "
    "VENV/bin/python -m pip install -e ."
)


def load_pooltool() -> ModuleType:
    """pooltool, or a ModuleNotFoundError saying how to install it."""
    return require("pooltool", None, "pool_env.interop.pooltool", install=INSTALL)


def pooltool_available() -> bool:
    """Whether pooltool can be imported here (:func:`from_system` and :func:`to_system`).

    Only looks for the package: it does not import it (pooltool writes its settings under
    ``~/.config`` on its first import).
    """
    from importlib.util import find_spec

    return find_spec("pooltool") is not None
