"""Examples that cannot drift: sybil runs the code of README.md, docs/ and the docstrings.

* Markdown (README.md, docs/**/*.md): every ```python block runs, in order, in one namespace
  per file, in a scratch folder (``models/`` linked in), so blocks may build on earlier ones
  and write files freely. Every ```bash block runs with ``bash -e`` from the repository root
  (``python`` is this interpreter; this project's own commands run their ``main`` in this
  process, see :func:`in_process`); a long one is preceded by ``<!-- run: SHORTER -->``,
  the same command on a small budget, which the test runs instead (shown in the source
  beside the block, so a reader sees both). A block that cannot run here is preceded by
  ``<!-- skip: next "why not" -->`` and counts as skipped, with its reason.
* Docstrings of ``pool_env`` and ``agents``: every ``>>>`` example runs as a doctest.

``tests/repo/test_docs.py`` checks that no other kind of block hides in the docs.
"""

from __future__ import annotations

import doctest
import importlib
import os
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

from sybil import Example, Region, Sybil
from sybil.parsers.markdown import CodeBlockParser, PythonCodeBlockParser, SkipParser
from sybil.parsers.markdown.lexers import DirectiveInHTMLCommentLexer
from sybil.parsers.rest import DocTestParser

ROOT = Path(__file__).resolve().parent
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
BASH_TIMEOUT = 300  # s; a shortened command takes seconds
PACKAGES = ("agents", "pool_env")


def _enter(namespace: dict[str, Any], cwd: Path) -> None:
    namespace["_docs_old_cwd"] = Path.cwd()
    os.chdir(cwd)


def _leave(namespace: dict[str, Any]) -> None:
    os.chdir(namespace.pop("_docs_old_cwd"))
    scratch = namespace.pop("_docs_scratch", None)
    if scratch is not None:
        scratch.cleanup()


def markdown_setup(namespace: dict[str, Any]) -> None:
    """A scratch folder per document, with the committed models linked in."""
    scratch = tempfile.TemporaryDirectory(prefix="pool_env_docs_")
    (Path(scratch.name) / "models").symlink_to(ROOT / "models")
    namespace["_docs_scratch"] = scratch
    _enter(namespace, Path(scratch.name))


def docstring_setup(namespace: dict[str, Any]) -> None:
    """Docstrings name repository files (``models/...``) relative to the root."""
    _enter(namespace, ROOT)


class RunParser:
    """``<!-- run: COMMAND -->``: the next bash block is tested as COMMAND (a shorter run)."""

    def __init__(self) -> None:
        self.lexer = DirectiveInHTMLCommentLexer(directive="run", arguments=".+?")

    def __call__(self, document: Any) -> Any:
        """The directive regions of ``document``."""
        for lexed in self.lexer(document):
            yield Region(lexed.start, lexed.end, lexed.lexemes["arguments"].strip(), self.store)

    @staticmethod
    def store(example: Example) -> None:
        """Keep the command for the bash block that follows."""
        example.namespace["_docs_run_next"] = example.parsed


def in_process(command: str, env: dict[str, str]) -> list[str] | None:
    """``[module, *args]`` when ``command`` is one of this project's Python commands.

    ``python train.py ...`` and ``python -m agents.x ...`` / ``python -m pool_env.x ...`` run
    their ``main(argv)`` in this process: the same code path as the command, without paying
    for a new interpreter importing torch and loading the kernels again.
    """
    if any(token in command for token in ("&&", "||", "|", ";", "\n", "`", "$(")):
        return None
    words = shlex.split(os.path.expandvars(command.replace("$DOCS_TMP", env["DOCS_TMP"])))
    if len(words) < 2 or words[0] != "python":
        return None
    if words[1] == "-m" and len(words) > 2 and words[2].split(".")[0] in PACKAGES:
        return words[2:]
    if words[1] == "train.py":
        return ["train", *words[2:]]
    return None


def run_bash(example: Example) -> None:
    """Run a bash block (or its shortened form) from the root; fail with its output."""
    namespace = example.namespace
    command = namespace.pop("_docs_run_next", None) or example.parsed
    scratch = namespace.get("_docs_scratch")
    env = {
        **os.environ,
        "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
        "DOCS_TMP": scratch.name if scratch is not None else tempfile.gettempdir(),
        "MPLBACKEND": "Agg",
    }
    argv = in_process(command.strip(), env)
    if argv is not None:
        old = Path.cwd()
        os.chdir(ROOT)
        try:
            code = importlib.import_module(argv[0]).main(argv[1:])
        finally:
            os.chdir(old)
        assert code in (0, None), f"{command} returned {code}"
        return
    done = subprocess.run(
        ["bash", "-e", "-c", command.replace("python ", f"{sys.executable} ")],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=BASH_TIMEOUT,
    )
    if done.returncode != 0:
        raise AssertionError(
            f"bash block failed ({done.returncode}): {command}\n"
            f"--- stdout\n{done.stdout[-3000:]}\n--- stderr\n{done.stderr[-3000:]}"
        )


markdown = Sybil(
    parsers=[
        SkipParser(),
        RunParser(),
        PythonCodeBlockParser(doctest_optionflags=FLAGS),
        CodeBlockParser("bash", run_bash),
    ],
    patterns=["README.md", "docs/*.md", "docs/**/*.md"],
    setup=markdown_setup,
    teardown=_leave,
    name="markdown",
)
docstrings = Sybil(
    parsers=[DocTestParser(optionflags=FLAGS)],
    patterns=["pool_env/*.py", "pool_env/**/*.py", "agents/*.py", "agents/**/*.py"],
    setup=docstring_setup,
    teardown=_leave,
    name="docstrings",
)

pytest_collect_file = (markdown + docstrings).pytest()
