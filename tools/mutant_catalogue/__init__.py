"""The catalogue of planted bugs for :mod:`tools.mutants`: data only, one module an area.

Each entry is one realistic bug: the file, a short snippet of the current source that must
occur exactly once in it (``tests/repo/test_mutant_catalogue.py`` checks that, so the catalogue
cannot rot silently), what replaces it, the focused test subset that should catch it, and
the real mistake it models. Snippets are kept short and stable so that unrelated edits of
the file do not move them.

Dropped as equivalent (each was run, survived every test, and no observable behaviour
tells it apart from the code):

* ``jaw_geometry._facing_entry`` without ``or along > extent``: an offset facing ends ``2R`` past
  the fall line (``R (n . fall_normal) - 2R < 0``: behind it), so a contact beyond its end
  lies behind the fall line, which a straight path from the throat reaches first, and a
  centre there is potted.
* ``pockets.kernel_rows`` anchoring the fall line at one end instead of its middle: any
  point of the line gives the same half-plane (up to rounding).
* ``predict.predict_own`` without ``or enter_b == enter_a``: folding one pocket twice into
  the earliest event changes nothing (same times, kinds and tie rules).
* ``rules._first_ball`` returning ``j`` for ``j if i == CUE else i``: a shot's first
  impact always involves the cue ball (only it moves at the start), which is column 0, so
  the ``else`` branch is dead.

Not equivalent, not killed, left out: ``jaw_impacts.unpress_lump`` without the facing's extent
check (a lump touching a facing's line beyond its ends); no scene of the suite puts a
sticking lump there.
"""

from __future__ import annotations

from tools.mutant_catalogue import actions, env, physics, pockets, rules, spin, three_cushion
from tools.mutant_catalogue.base import INTERPRETABLE, Mutant

__all__ = ["AREAS", "CATALOGUE", "INTERPRETABLE", "Mutant"]

#: The area modules, each with its ``MUTANTS``; the runner reads them all.
AREAS = (physics, pockets, rules, actions, env, spin, three_cushion)

#: The mutants :mod:`tools.mutants` runs.
CATALOGUE: tuple[Mutant, ...] = tuple(m for area in AREAS for m in area.MUTANTS)
