"""``--noise``: the execution noise a command plays at, parsed, checked and named.

The commands that play (``agents.evaluate``, the run-outs, the break search) take the
env's ``noise`` keyword as text: sigmas, FastFiz's model (times ``K``) or none.
:func:`parse_noise` checks it with the env's own check; :func:`noise_label` names the
noise in force in a command's header.
"""

from __future__ import annotations

import argparse
from typing import Any

from pool_env import Table
from pool_env.game.checks import parse_noise as parse_env_noise
from pool_env.game.noise import NOISE_MODELS, NoiseSpec

__all__ = ["FIELD_NOISE", "NO_NOISE", "noise_kwargs", "noise_label", "parse_noise"]

#: ``--noise`` spellings of no noise at all (exact shots).
NO_NOISE = ("none", "0")


#: The noise the game ids play at unless told otherwise: the field's, FastFiz's model x1
#: (the computer billiards championships' "low noise", :mod:`pool_env.game.noise`).
FIELD_NOISE = "fastfiz"


def parse_noise(text: str) -> NoiseSpec | None:
    """``--noise``'s text as the env's ``noise`` value, checked by the env's own check.

    ``"0.003,0.05[,0.05]"``: the sigmas (aim rad, speed m/s[, tip in fractions of R]);
    ``"fastfiz"``: FastFiz's model, the computer billiards championships' (x1);
    ``"fastfiz:K"``: that model times ``K >= 0`` (``fastfiz:5``: the championships' "high"
    noise; :mod:`pool_env.game.noise`); ``"none"`` or ``"0"``: exact shots (``None``).

    Raises:
        ValueError: Naming ``--noise`` and what is wrong with the text.
    """
    if text.strip().lower() in NO_NOISE:
        return None
    name, colon, multiple = text.partition(":")
    value: NoiseSpec
    try:
        if name in NOISE_MODELS:
            value = (name, float(multiple)) if colon else name
        else:
            value = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(
            f"--noise takes 2 or 3 comma-separated sigmas, {' or '.join(NOISE_MODELS)}"
            f"[:K] with a number K, or none; got {text!r}"
        ) from None
    try:  # a spin table takes every spelling: a roll env refuses a tip sigma itself
        parse_env_noise(value, Table(model="spin"))
    except ValueError as err:
        raise ValueError(f"--noise {text!r}: {err}") from None
    return value


def noise_label(noise: object) -> str:
    """The noise in force, in words: ``"none (exact shots)"``, ``"fastfiz (FastFiz x1)"``."""
    if noise is None:
        return "none (exact shots)"
    if isinstance(noise, str) and noise in NOISE_MODELS:  # a list (YAML sigmas) is no name
        return f"{noise} (FastFiz x1, the field's)"
    if isinstance(noise, tuple | list) and noise and noise[0] in NOISE_MODELS:
        return f"{noise[0]}:{noise[1]:g} (FastFiz x{noise[1]:g})"
    return "sigmas " + ", ".join(f"{float(v):g}" for v in noise)  # type: ignore[union-attr]


def noise_kwargs(parser: argparse.ArgumentParser, text: str) -> dict[str, Any]:
    """The env's keywords for a command's ``--noise`` text: ``{"noise": ...}``, or none.

    A value :func:`parse_noise` refuses is the command's usage error (``parser.error``:
    one line, status 2).
    """
    try:
        noise = parse_noise(text)
    except ValueError as err:
        parser.error(str(err))
    return {} if noise is None else {"noise": noise}
