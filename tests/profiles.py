"""The hypothesis profiles of the suite, chosen with ``HYPOTHESIS_PROFILE``.

* ``ci`` (the default): derandomized, so the property tests check the same examples on
  every run and machine, and a failure reproduces.
* ``nightly``: fresh random examples, ten times as many, to look further
  (``HYPOTHESIS_PROFILE=nightly python -m pytest tests/sim/test_properties.py``).
* ``deep``: fresh random examples, two hundred times as many: a one-off search (the rules
  against their reference on 120,000 random shots: ``HYPOTHESIS_PROFILE=deep python -m
  pytest tests/game/test_games.py -k random_outcomes``).

A test that sets its own ``max_examples`` passes it through :func:`examples`, which scales
it by the profile.
"""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

#: Examples of the ``ci`` profile; the scale of :func:`examples`.
CI_EXAMPLES = 100

#: Each profile's scale of :data:`CI_EXAMPLES`; only ``ci`` repeats its examples.
SCALES = {"ci": 1, "nightly": 10, "deep": 200}

for _name, _scale in SCALES.items():
    settings.register_profile(
        _name,
        derandomize=_name == "ci",
        max_examples=_scale * CI_EXAMPLES,
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow],
    )


def load() -> str:
    """Load the profile named by ``HYPOTHESIS_PROFILE`` (``ci`` by default); return its name."""
    name = os.environ.get("HYPOTHESIS_PROFILE", "ci")
    settings.load_profile(name)
    return name


def examples(n: int) -> int:
    """``n`` examples under ``ci``, scaled by the loaded profile (``nightly``: ``10 n``)."""
    return max(1, n * settings.default.max_examples // CI_EXAMPLES)
