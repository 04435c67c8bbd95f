"""K-NET / KiK-net ASCII (NIED, Japan): the header checked against the samples ObsPy reads.

ObsPy's ``KNET`` reader returns the samples as raw counts and the factor to m/s^2 in ``stats.calib``; it
reads every number after the header, whatever the header says about them. The 17 header lines state::

    Sampling Freq(Hz) 100Hz
    Duration Time(s)  102                 <- the record holds duration x frequency samples (10200)
    Dir.              E-W
    Scale Factor      3920(gal)/6182761   <- gal per count
    Max. Acc. (gal)   4.078               <- peak of the record after removing its mean

:func:`knet_gal` reads them again and refuses a file whose samples disagree: a number of samples other
than duration x frequency (a data block cut short or run on: USGS gmprocess reads exactly that many), a
scale factor that is not a positive number (0 would load zeros), or a peak (after removing the mean, as
NIED measures it) that is not the stated Max. Acc. (:mod:`rockcli.records.checks`).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.records.checks import check_peak, check_positive_scale, disagree

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[Ee][-+]?\d+)?"
#: Header lines of a K-NET / KiK-net ASCII file (the last one is ``Memo.``).
HEADER_LINES = 17
_SCALE = re.compile(rf"^\s*({_NUM})\s*\(gal\)\s*/\s*({_NUM})\s*$", re.I)


def _header(path: Path) -> dict[str, tuple[int, str]]:
    """``key -> (line number, value)`` of the header lines (key: the text before the value column)."""
    from rockcli.records.at2 import read_text

    out = {}
    for number, line in enumerate(read_text(path).splitlines()[:HEADER_LINES], start=1):
        key, value = line[:18].strip(), line[18:].strip()
        out[key] = (number, value)
    return out


def knet_gal(path: Path, counts: np.ndarray, obspy_calib: float) -> np.ndarray:
    """``counts`` (ObsPy's samples) in gal, the header checked against them.

    ObsPy's factor (``counts x calib x 100``, bit for bit as before these checks) when it is the header's
    ``N(gal)/D``, else the header's (ObsPy keeps only the leading digits of ``N``: 3920.5 is read as 3920).
    """
    head = _header(path)

    def field(key: str, what: str) -> tuple[int, str]:
        if key not in head:
            raise RockcliInputError(f"{path}: the K-NET header lacks its '{key}' line ({what})")
        return head[key]

    line, text = field("Scale Factor", "gal per count, e.g. '3920(gal)/6182761'")
    m = _SCALE.match(text)
    if m is None:
        raise RockcliInputError(f"{path}, line {line}: the scale factor {text!r} is not written as N(gal)/D "
                                f"(gal per count, e.g. '3920(gal)/6182761')")
    num, den = float(m.group(1)), float(m.group(2))
    factor = num / den if den != 0 else math.inf
    check_positive_scale(path, factor, text, f"line {line}: 'Scale Factor {text}'")
    obspy_agrees = math.isclose(float(obspy_calib) * 100.0, factor, rel_tol=1e-12)

    f_line, f_text = field("Sampling Freq(Hz)", "e.g. '100Hz'")
    d_line, d_text = field("Duration Time(s)", "e.g. '102'")
    m_f, m_d = re.match(rf"({_NUM})\s*(?:Hz)?$", f_text, re.I), re.fullmatch(_NUM, d_text)
    if m_f and m_d:
        expected = float(m_d.group(0)) * float(m_f.group(1))
        if not math.isclose(expected, counts.size, rel_tol=0.0, abs_tol=0.5):
            more = "fewer" if counts.size < expected else "more"
            raise disagree(path, f"a record of {d_text} s at {f_text} (lines {f_line}-{d_line}): {expected:.0f} "
                           f"samples", f"{counts.size} values follow the header ({more})",
                           "the data block is cut short" if counts.size < expected else
                           "the data block runs on past the stated duration")
    a_line, a_text = field("Max. Acc. (gal)", "e.g. '4.078'")
    if re.fullmatch(_NUM, a_text):
        check_peak(path, counts - counts.mean(), float(a_text), a_text,
                   f"line {a_line}: 'Max. Acc. (gal) {a_text}', the peak after removing the mean; the scale factor "
                   f"is {text}", "gal", factor)
    return counts * float(obspy_calib) * 100.0 if obspy_agrees else counts * factor
