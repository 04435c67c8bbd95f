"""What a record's header says, checked against the data it reads.

A header states numbers about the data that follow it: how many samples, how long the record lasts, its
peak, the factor from counts to units, the units word. A reader that trusts one of them without looking
reads a different record when the file is damaged or edited by hand: a sample count lower than the
data block cuts the record short, a higher one reads the next block (velocity) as acceleration, a scale
factor of 0 loads zeros. Every reader of rockcli checks each such statement against the data and refuses
a disagreement in one sentence naming the file, what the header says (and where) and what the data have
(:func:`disagree`).

Tolerances (a judgement call, written in docs/records.md and tested in tests/test_records_headers.py):

* counts agree exactly;
* a peak stated in a header (K-NET's Max. Acc., GeoNet's ``Acceleration: peak``, ESM's ``PGA_CM/S^2``,
  ITACA's ``PGA``, COSMOS's maximum, CWB's ``AmplitudeMAX``) agrees with the data's peak to 1 % of the
  stated value plus one unit in its last written digit (``4.078`` gal: 0.041 + 0.001 gal). Headers round
  their peaks to a few digits; a wrong scale factor, units word or block is off by far more;
* a stated duration agrees with ``npts x dt`` or ``(npts - 1) x dt`` (agencies use both) to one time step
  plus one unit in its last written digit.
"""

from __future__ import annotations

import math
import re

import numpy as np

from rockcli.errors import RockcliInputError

#: Relative tolerance of a stated peak against the data's peak.
PEAK_RTOL = 0.01


def disagree(filename, says: str, has: str, hint: str = "") -> RockcliInputError:
    """``FILE: the header states SAYS, but HAS`` (and why that matters, in ``hint``)."""
    tail = f"; {hint}" if hint else "; the file is damaged or was edited: it cannot be read as written"
    return RockcliInputError(f"{filename}: the header states {says}, but {has}{tail}")


def last_digit(text: str) -> float:
    """One unit in the last written digit of a number as written (``4.078``: 0.001; ``9733.1``: 0.1;
    ``120``: 1; ``6.85E+00``: 0.01)."""
    s = str(text).strip().lstrip("+-")
    m = re.fullmatch(r"(\d*)(?:\.(\d*))?(?:[EeDd]([-+]?\d+))?", s)
    if not m:
        return 0.0
    decimals = len(m.group(2) or "")
    exponent = int(m.group(3) or 0)
    return 10.0 ** (exponent - decimals)


def peak_agrees(stated: float, written: str, data_peak: float) -> bool:
    """True when the data's peak ``data_peak`` is the stated peak (``stated``, written as ``written``) to
    :data:`PEAK_RTOL` plus one unit in its last written digit."""
    tol = PEAK_RTOL * abs(stated) + last_digit(written)
    return math.isfinite(data_peak) and abs(abs(data_peak) - abs(stated)) <= tol


def check_peak(filename, values: np.ndarray, stated: float, written: str, where: str, units: str = "",
               factor: float = 1.0) -> None:
    """Refuse when the peak |value| x ``factor`` of ``values`` is not the peak the header states (``where``:
    the header field, e.g. ``"Max. Acc. (gal) 4.078"``)."""
    if not values.size or not math.isfinite(stated):
        return
    peak = float(np.max(np.abs(values))) * factor
    if not peak_agrees(stated, written, peak):
        from rockcli.io.inputs import format_number

        unit = f" {units}" if units else ""
        raise disagree(filename, f"a peak of {written}{unit} ({where})",
                       f"the data it reads peak at {format_number(float(f'{peak:.6g}'))}{unit}")


def check_count(filename, n_values: int, stated: int, where: str, what: str = "values follow") -> None:
    """Refuse when ``n_values`` differs from the count the header states (``where``: the field; ``what``: how
    the data are said, ``"values follow (lines 10-12)"``)."""
    if n_values != stated:
        hint = ("the file is cut short" if n_values < stated else
                f"reading {stated} would drop the rest, or read another block as this one")
        raise disagree(filename, f"{stated} samples ({where})", f"{n_values} {what}", hint)


def check_duration(filename, npts: int, dt: float, stated: float, written: str, where: str) -> None:
    """Refuse when a stated duration is neither ``npts x dt`` nor ``(npts - 1) x dt`` (to one step plus one unit
    in the last written digit)."""
    if not math.isfinite(stated):
        return
    tol = dt + last_digit(written)
    if min(abs(stated - npts * dt), abs(stated - (npts - 1) * dt)) > tol:
        from rockcli.io.inputs import format_number

        raise disagree(filename, f"a duration of {written} s ({where})",
                       f"its {npts} samples at dt = {format_number(dt)} s last "
                       f"{format_number(float(f'{npts * dt:.6g}'))} s")


def check_positive_scale(filename, value: float, written: str, where: str) -> None:
    """Refuse a factor from counts to units that is zero, negative or not finite."""
    if not (math.isfinite(value) and value > 0):
        raise RockcliInputError(f"{filename}: the header states a scale factor of {written} ({where}); a factor "
                                f"from counts to units must be a positive number (0 would make every sample 0)")


def known_units(filename, word: str | None, where: str) -> str | None:
    """``word`` when it is a units word rockcli knows, None when the header holds none there (the file does not
    state its units); an unknown word is one sentence naming where the header holds it."""
    from rockcli.io.units import ACCEL_UNITS, KNOWN_UNITS

    if word is None or not str(word).strip():
        return None
    if str(word).strip().lower().replace(" ", "").rstrip(".") not in ACCEL_UNITS:
        raise RockcliInputError(f"{filename}: the header states units {word!r} ({where}), which is not a units "
                                f"word rockcli knows ({KNOWN_UNITS})")
    return str(word).strip().rstrip(".")
