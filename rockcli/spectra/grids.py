"""Parsing of the sweeps' number inputs: ``start:stop:count`` grids and comma lists.

Every problem is one sentence naming the option (:class:`rockcli.errors.RockcliInputError`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from rockcli.errors import RockcliInputError

#: A decimal number as written on the command line (sign, point, exponent optional).
_NUMBER = r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?"  # ASCII digits (\d also takes other scripts)


#: Most cells one overturning-maps run takes (about 10,000 verdict-only runs a second on 2 cores, so up to
#: about 20 minutes; the arrays of the cells then take about 1 GB).
MAX_CELLS = 10_000_000


@dataclass(frozen=True)
class Grid:
    """``count`` values from ``start`` to ``stop``, both ends included (``numpy.linspace``)."""

    start: float
    stop: float
    count: int

    @property
    def values(self) -> np.ndarray:
        return np.linspace(self.start, self.stop, self.count)

    def __str__(self) -> str:
        return f"{self.start:g}:{self.stop:g}:{self.count}"


def parse_grid(text: str, option: str = "grid", *, positive: bool = False) -> Grid:
    """Parse ``start:stop:count`` (both ends included), e.g. ``0.5:12:200``.

    ``positive``: the start must be > 0 (otherwise >= 0). One clear sentence on any problem.
    """
    raw = str(text).strip()
    parts = raw.split(":")
    example = "0.5:12:200" if positive else "0:10:200"
    if len(parts) != 3:
        raise RockcliInputError(f"{option} {raw!r}: give start:stop:count (both ends included), e.g. {example}")
    if not all(re.fullmatch(r"\s*" + _NUMBER + r"\s*", p) for p in parts[:2]) \
            or not re.fullmatch(r"\s*\d+\s*", parts[2]):
        raise RockcliInputError(f"{option} {raw!r}: start and stop must be numbers and count a whole number, "
                                f"e.g. {example}")
    start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise RockcliInputError(f"{option} {raw!r}: start and stop must be finite")
    if count < 1 or count > 100_000:
        raise RockcliInputError(f"{option} {raw!r}: count must lie between 1 and 100000")
    if (start <= 0 if positive else start < 0):
        raise RockcliInputError(f"{option} {raw!r}: start must be {'> 0' if positive else '>= 0'}")
    if count == 1 and stop != start:
        raise RockcliInputError(f"{option} {raw!r}: a single value needs start = stop")
    if count > 1 and not stop > start:
        raise RockcliInputError(f"{option} {raw!r}: stop must be larger than start")
    return Grid(start, stop, count)


def parse_list(text: str, option: str, *, lo: float = -math.inf, hi: float = math.inf,
               lo_open: bool = False, hi_open: bool = False) -> tuple:
    """Parse a comma-separated list of numbers within ``[lo, hi]`` (open ends as told)."""
    raw = str(text).strip()
    out = []
    for item in raw.split(","):
        item = item.strip()
        if not re.fullmatch(_NUMBER, item):
            raise RockcliInputError(f"{option} {raw!r}: {item!r} is not a number (write e.g. 10,20)")
        v = float(item)
        if not (math.isfinite(v) and (v > lo if lo_open else v >= lo) and (v < hi if hi_open else v <= hi)):
            lo_s = f"{'>' if lo_open else '>='} {lo:g}"
            hi_s = f"{'<' if hi_open else '<='} {hi:g}"
            raise RockcliInputError(f"{option} {raw!r}: {item} must be {lo_s} and {hi_s}")
        out.append(v)
    return tuple(out)
