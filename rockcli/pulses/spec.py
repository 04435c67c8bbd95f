"""Pulses by name: the shape names (and their aliases) and the CLI pulse spec ``SHAPE:ap=<g>,Tp=<s>[,t0=<s>]``.

This is the input edge of the pulses (``ap`` in g on the command line, SI everywhere else); the
shapes themselves are in :mod:`rockcli.pulses.shapes`.
"""

from __future__ import annotations

import math
from typing import Optional, Union

from rockcli.errors import RockcliInputError
from rockcli.pulses.shapes import A_P_MAX_G, PULSE_SHAPES, OneCosine, OneSine, RickerAntisymmetric, RickerSymmetric
from rockcli.io.units import G

__all__ = ["PulseLike", "make_pulse", "parse_pulse_spec"]

_ALIASES = {"one-sine": "sine", "one-cosine": "cosine"}

PulseLike = Union[RickerSymmetric, RickerAntisymmetric, OneSine, OneCosine]


def _shape_class(shape: str):
    key = str(shape).strip().lower()
    key = _ALIASES.get(key, key)
    if key not in PULSE_SHAPES:
        raise RockcliInputError(
            f"unknown pulse shape {shape!r} (expected one of: {', '.join(PULSE_SHAPES)})"
        )
    return PULSE_SHAPES[key]


def make_pulse(shape: str, a_p: float, T_p: float, t0: Optional[float] = None) -> PulseLike:
    """Build a pulse by shape name (``ricker-sym``, ``ricker-anti``, ``sine``, ``cosine``), SI units.

    Parameters
    ----------
    shape : str
        Shape name (case-insensitive).
    a_p : float
        Amplitude [m/s^2], signed.
    T_p : float
        Period [s], > 0.
    t0 : float, optional
        Centre (Rickers) or start (sine, cosine) [s]; default ``3 T_p`` for Rickers, 0 otherwise.
    """
    return _shape_class(shape)(a_p, T_p, t0)


def parse_pulse_spec(text: str) -> PulseLike:
    """Parse a CLI pulse spec such as ``ricker-sym:ap=0.3,Tp=0.6`` or ``sine:ap=-0.2,Tp=1,t0=0.5``.

    ``ap`` is in g (this is an input edge), ``Tp`` and the optional ``t0`` in seconds; keys are
    case-insensitive. Raises :class:`~rockcli.errors.RockcliInputError` with one sentence on any
    problem (unknown shape, unknown or repeated key, missing ``ap``/``Tp``, non-numeric value,
    ``Tp <= 0``).

    Examples
    --------
    >>> p = parse_pulse_spec("ricker-anti:ap=0.25,Tp=1.2")
    >>> p.shape, round(p.a_p_g, 6), p.T_p, p.t0
    ('ricker-anti', 0.25, 1.2, 3.5999999999999996)
    """
    raw = str(text).strip()
    if ":" in raw:
        shape, _, rest = raw.partition(":")
    else:
        shape, rest = raw, ""
    from rockcli.io.inputs import parse_number, spec_items

    cls = _shape_class(shape)
    values, texts = {}, {}
    names = {"ap": "ap", "tp": "Tp", "t0": "t0"}
    for key, val, eq in spec_items(rest, f"pulse spec {raw!r}"):
        k = key.lower()
        if not eq or k not in names:
            raise RockcliInputError(
                f"pulse spec {raw!r}: unknown parameter {key!r} (expected ap=<g>, Tp=<s>, optional t0=<s>)"
            )
        if val.lower().lstrip("+-") in ("nan", "inf", "infinity"):
            raise RockcliInputError(f"pulse spec {raw!r}: {names[k]} must be finite, got {val!r}")
        values[names[k]] = parse_number(val, f"pulse spec {raw!r}: {names[k]}",
                                        bad=f"pulse spec {raw!r}: {names[k]}={val!r} is not a number")
        texts[names[k]] = val
    if "ap" in values and abs(values["ap"]) > A_P_MAX_G:  # said here as written: g -> m/s^2 -> g may round
        raise RockcliInputError(f"pulse spec {raw!r}: pulse amplitude a_p = {texts['ap']} g is beyond the supported "
                                f"{A_P_MAX_G:g} g (recorded peaks reach about 4 g)")
    missing = [k for k in ("ap", "Tp") if k not in values]
    if missing:
        raise RockcliInputError(
            f"pulse spec {raw!r} is missing {' and '.join(missing)} (write e.g. {cls.shape}:ap=0.3,Tp=0.6)"
        )
    if values["Tp"] <= 0.0:
        raise RockcliInputError(f"pulse spec {raw!r}: Tp must be > 0 s")
    try:
        return cls(values["ap"] * G, values["Tp"], values.get("t0"))
    except RockcliInputError as exc:
        raise RockcliInputError(f"pulse spec {raw!r}: {exc}") from None
