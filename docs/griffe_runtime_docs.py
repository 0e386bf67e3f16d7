"""A griffe extension for the docs build: docstrings that a module assigns at import.

``PoolEnv``'s specification is long, so it lives in :mod:`pool_env.env_doc` and the class
assigns it (``__doc__ = ENV_DOC``); griffe reads source statically and would show the short
literal docstring instead. For the classes of :data:`RUNTIME`, this takes the docstring
the imported class has (what ``help()`` shows).
"""

from __future__ import annotations

import importlib
import inspect
from typing import Any

import griffe

#: Objects whose docstring is assigned at import: path -> (module, attribute).
RUNTIME = {"pool_env.env.PoolEnv": ("pool_env.env", "PoolEnv")}


class RuntimeDocstrings(griffe.Extension):
    """Replace the static docstring of each object of :data:`RUNTIME` by its runtime one."""

    def on_object(self, *, obj: griffe.Object, **kwargs: Any) -> None:
        """Set ``obj``'s docstring text from the imported object, if it is one of ours."""
        where = RUNTIME.get(obj.path)
        if where is None or obj.docstring is None:
            return
        module, name = where
        doc = inspect.getdoc(getattr(importlib.import_module(module), name))
        if doc:
            obj.docstring.value = doc
