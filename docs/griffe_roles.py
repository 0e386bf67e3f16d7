"""A griffe extension for the docs build: Sphinx roles in docstrings read as inline code.

The docstrings cross-reference in Sphinx's style (``:class:`~pool_env.Table```), which
Markdown shows as raw text. This turns each role into inline code with the name a reader
would see (the last component after ``~``); it links nothing, so it cannot break the
strict build.
"""

from __future__ import annotations

import re
from typing import Any

import griffe

ROLE = re.compile(r":(?:func|class|mod|meth|data|attr|obj|exc|const):`(~?)([^`]+)`")


def plain(text: str) -> str:
    """``:role:`~a.b.c``` to ```c```, ``:role:`a.b.c``` to ```a.b.c```."""
    return ROLE.sub(
        lambda m: f"`{m.group(2).rsplit('.', 1)[-1] if m.group(1) else m.group(2)}`", text
    )


class SphinxRolesAsCode(griffe.Extension):
    """Rewrite the roles of every docstring griffe loads."""

    def on_object(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        """Rewrite ``obj``'s docstring, if it has one."""
        if obj.docstring is not None:
            obj.docstring.value = plain(obj.docstring.value)

    def on_package(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        """The top-level package: griffe calls ``on_object`` for it before its docstring."""
        self.on_object(obj=pkg)
