"""A table's CSV text as pandas writes it (``DataFrame.to_csv(index=False, float_format="%.6g",
lineterminator="\\n")``), without importing pandas: the main job writes its CSV in a few milliseconds
instead of importing pandas for a third of a second (issue 33).

:func:`csv_text` formats only columns whose values it knows how pandas formats, and returns None for any
other column (the caller then asks pandas). Each column's kind is the dtype pandas infers from its values:

=========================================  ==========================  ========================================
values (None is missing)                   pandas dtype                cell
=========================================  ==========================  ========================================
all missing                                object                      empty
str (and missing)                          str                         the string (empty when missing)
bool (and missing)                         bool / object               ``True`` / ``False`` (empty)
int, no missing                            int64                       ``str(int)``
float or int (and missing, NaN)            float64                     ``"%.6g" % value`` (empty for NaN)
a column cast to ``boolean`` / ``Int64``   boolean / Int64             as bool / int, empty when missing
=========================================  ==========================  ========================================

Cells are written by :mod:`csv` (quoted where a comma, a quote or a line break needs it), as pandas does.
Tested byte for byte against pandas on random tables of every kind and on real assessments
(tests/test_csv_text.py).
"""

from __future__ import annotations

import csv
import io
import math
import numbers

import numpy as np

#: a column's kind when its values are not inferred: ``boolean`` or ``Int64`` (pandas' nullable dtypes)
BOOLEAN, INT64 = "boolean", "Int64"


def _missing(v) -> bool:
    return v is None


def _is_bool(v) -> bool:
    return isinstance(v, (bool, np.bool_))


def _is_int(v) -> bool:
    return isinstance(v, numbers.Integral) and not _is_bool(v)


def _is_float(v) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, numbers.Integral) and not _is_bool(v)


def _cells(values, cast: str | None):
    """The column's cells, or None when pandas might format one of them otherwise."""
    if cast == BOOLEAN:
        if not all(_missing(v) or _is_bool(v) for v in values):
            return None
        return ["" if _missing(v) else str(bool(v)) for v in values]
    if cast == INT64:
        if not all(_missing(v) or _is_int(v) for v in values):
            return None
        return ["" if _missing(v) else str(int(v)) for v in values]
    present = [v for v in values if not _missing(v)]
    if not present:
        return [""] * len(values)
    if all(isinstance(v, str) for v in present):
        return ["" if _missing(v) else v for v in values]
    if all(_is_bool(v) for v in present):
        return ["" if _missing(v) else str(bool(v)) for v in values]
    if all(_is_int(v) for v in present) and len(present) == len(values):
        if not all(-2**63 <= int(v) < 2**63 for v in present):
            return None
        return [str(int(v)) for v in values]
    if all(_is_int(v) or _is_float(v) for v in present):
        out = []
        for v in values:
            if _missing(v):
                out.append("")
                continue
            f = float(v)
            out.append("" if math.isnan(f) else "%.6g" % f)
        return out
    return None


def csv_text(columns: dict, casts: dict | None = None) -> str | None:
    """The CSV of ``columns`` (name -> list of values, one per row, in order) as pandas writes it (module
    notes), or None when a column holds values of another kind. ``casts`` names columns cast to ``boolean``
    or ``Int64``."""
    casts = casts or {}
    names = list(columns)
    cells = []
    for name in names:
        col = _cells(list(columns[name]), casts.get(name))
        if col is None:
            return None
        cells.append(col)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(names)
    writer.writerows(zip(*cells))
    return buf.getvalue()
