"""Plain-text accelerograms: one column, time/acceleration columns, or a chosen column.

Rules (documented in the README, tested in ``tests/test_records_text.py``):

* Blank lines and comment lines (first non-blank character one of ``# % ! ;``) are skipped.
  Comments may state the time step (``dt=0.005 sec``) and the units (``Acc. in cm/sec^2``,
  ``units: g``); only unit words rockcli knows count as a statement.
* One leading line made only of words (column names such as ``time acc``) is kept as a header.
* Values are separated by blanks, tabs, commas or semicolons; every row has the same number of
  columns.
* The first of several columns is a **time column** when it increases at (at least) 90 % of its
  steps; it must then be strictly increasing and uniform (to 0.1 % of a step), gives ``dt`` and
  the start time. Otherwise every column is data.
* Columns are numbered from 1 as they appear in the file (a time column counts). With one data
  column it is taken; with several, ``column`` must say which.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError

COMMENT_CHARS = "#%!;"
_SEP_RE = re.compile(r"[\s,;]+")
_DT_RE = re.compile(r"\b(?:dt|time\s*step|delta|sampling\s*interval)\s*(?:=|:|is)?\s*"
                    r"(?P<dt>[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(?P<unit>ms|s|sec|secs|seconds)?\b", re.I)
_UNITS_RE = re.compile(r"(?:\bunits?\s*(?:are|of|in)?\s*[:=]?|\bacc(?:eleration|el)?\.?\s*(?:\[|\(|in\b|:))\s*\(?\s*"
                       r"(?P<units>[A-Za-z][A-Za-z0-9/^*]*)", re.I)
#: Fraction of increasing steps above which the first column is taken as time.
TIME_COLUMN_FRACTION = 0.9
#: Relative tolerance on the uniformity of a time column (fraction of a step).
TIME_UNIFORMITY_RTOL = 1e-3


def _known_unit(word: str) -> bool:
    from rockcli.units import ACCEL_UNITS

    return word.strip().lower().replace(" ", "").rstrip(".") in ACCEL_UNITS


def parse_comments(comments: list[str]) -> dict[str, Any]:
    """Time step [s] and units stated in comment lines (None when not stated)."""
    dt = units = None
    for line in comments:
        if dt is None:
            m = _DT_RE.search(line)
            if m:
                dt = float(m.group("dt")) * (1e-3 if (m.group("unit") or "").lower() == "ms" else 1.0)
        if units is None:
            for m in _UNITS_RE.finditer(line):
                word = m.group("units").rstrip(".")
                if _known_unit(word):
                    units = word
                    break
    return {"dt": dt, "units": units}


#: An explicit statement of units in a comment: ``units: furlongs``, ``unit = g``.
_EXPLICIT_UNITS_RE = re.compile(r"\bunits?\s*[:=]\s*\(?\s*(?P<units>[A-Za-z][A-Za-z0-9/^*.]*)", re.I)


def stated_unknown_units(comments: list[str]) -> str | None:
    """A unit word stated explicitly (``units: furlongs``) that rockcli does not know, else None.

    Only the explicit ``units:``/``units =`` form counts: looser phrases (``Acc. in ...``) are a
    statement only when the word is a known unit.
    """
    for line in comments:
        for m in _EXPLICIT_UNITS_RE.finditer(line):
            word = m.group("units").rstrip(".")
            if not _known_unit(word):
                return word
    return None


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def parse_text_table(text: str, filename: str = "text file") -> dict[str, Any]:
    """Split a text accelerogram into comments, optional column names and a numeric table.

    Returns
    -------
    dict
        ``table`` (ndarray, rows x columns, float64), ``comments`` (list of str),
        ``names`` (list of str or None), ``first_row_line`` (1-based line of the first data row).

    Raises
    ------
    RockcliInputError
        Empty file, non-numeric token, NaN/inf value, or rows of different lengths.
    """
    comments: list[str] = []
    names = None
    rows: list[list[str]] = []
    row_lines: list[int] = []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line:
            continue
        if line[0] in COMMENT_CHARS or line.startswith("//"):
            comments.append(line.lstrip(COMMENT_CHARS + "/").strip())
            continue
        tokens = [t for t in _SEP_RE.split(line) if t]
        if not rows and names is None and not any(_is_number(t) for t in tokens):
            names = tokens
            continue
        rows.append(tokens)
        row_lines.append(number)
    if not rows:
        raise RockcliInputError(f"{filename}: the file holds no numbers" if text.strip()
                                else f"{filename}: the file is empty")
    ncol = len(rows[0])
    for tokens, number in zip(rows, row_lines):
        if len(tokens) != ncol:
            raise RockcliInputError(
                f"{filename}, line {number}: {len(tokens)} values where the first data row has {ncol}")
    try:
        table = np.array(rows, dtype=np.float64)
    except ValueError:
        for tokens, number in zip(rows, row_lines):
            for token in tokens:
                if not _is_number(token):
                    raise RockcliInputError(f"{filename}, line {number}: {token!r} is not a number") from None
        raise  # pragma: no cover
    bad = ~np.isfinite(table)
    if bad.any():
        r, c = np.argwhere(bad)[0]
        raise RockcliInputError(
            f"{filename}, line {row_lines[r]}: value {float(table[r, c])!r} in column {c + 1} is not a finite number")
    return {"table": table, "comments": comments, "names": names, "row_lines": row_lines}


def looks_like_time(col: np.ndarray) -> bool:
    """True when ``col`` increases at ``TIME_COLUMN_FRACTION`` of its steps (or more)."""
    if col.size < 3:
        return False
    return float(np.mean(np.diff(col) > 0)) >= TIME_COLUMN_FRACTION


def check_time_column(t: np.ndarray, row_lines: list[int], filename: str) -> tuple[float, float]:
    """Validate a time column; return its time step and start time [s].

    Raises
    ------
    RockcliInputError
        If the column is not strictly increasing, or its steps are not uniform.
    """
    steps = np.diff(t)
    if (steps <= 0).any():
        i = int(np.argmax(steps <= 0))
        raise RockcliInputError(
            f"{filename}, line {row_lines[i + 1]}: the time column is not increasing "
            f"({t[i]:g} s then {t[i + 1]:g} s)")
    dt = (t[-1] - t[0]) / (t.size - 1)
    ref = float(np.median(steps))
    tol = TIME_UNIFORMITY_RTOL * ref
    off = np.abs(steps - ref) > tol
    dev = np.abs(t - (t[0] + dt * np.arange(t.size)))
    if off.any() or dev.max() > tol:
        i = int(np.argmax(off)) if off.any() else max(int(np.argmax(dev)) - 1, 0)
        raise RockcliInputError(
            f"{filename}, line {row_lines[i + 1]}: the time column is not uniformly sampled (step "
            f"{steps[i]:g} s where the usual step is {ref:g} s); resample the record to a constant time step first")
    return float(f"{dt:.10g}"), float(t[0])


def parse_text(text: str, filename: str = "text file", column: int | None = None) -> dict[str, Any]:
    """Parse a plain-text accelerogram.

    Parameters
    ----------
    text : str
        The file contents.
    filename : str
        Name used in error messages.
    column : int, optional
        1-based column of the acceleration (a time column counts). Required when the file has
        several data columns.

    Returns
    -------
    dict
        ``values`` (ndarray, units as in the file), ``dt`` [s] (from the time column or the
        comments, else None), ``dt_source`` (``"time column"``, ``"comment"`` or None),
        ``t_start`` [s], ``units`` (stated in a comment, else None), ``column`` (1-based),
        ``ncols``, ``time_column`` (bool), ``names``, ``comments``.
    """
    parsed = parse_text_table(text, filename)
    table, row_lines = parsed["table"], parsed["row_lines"]
    nrow, ncol = table.shape
    stated = parse_comments(parsed["comments"])
    if stated["units"] is None:  # "units: furlongs" is a statement too: reported, not ignored
        stated["units"] = stated_unknown_units(parsed["comments"])
    time_col = ncol >= 2 and looks_like_time(table[:, 0])
    data_cols = list(range(2, ncol + 1)) if time_col else list(range(1, ncol + 1))
    if column is None:
        if len(data_cols) > 1:
            what = f"a time column and {len(data_cols)} data columns" if time_col else f"{ncol} data columns"
            raise RockcliInputError(
                f"{filename}: the file has {what}; choose one with --column (1-based, counting the time column)"
                if time_col else
                f"{filename}: the file has {what}; choose one with --column (1-based)")
        column = data_cols[0]
    column = int(column)
    if column < 1 or column > ncol:
        raise RockcliInputError(f"{filename}: column {column} does not exist (the file has {ncol} columns)")
    if time_col and column == 1:
        raise RockcliInputError(f"{filename}: column 1 is the time column; choose a data column (2-{ncol})")
    out = {"values": table[:, column - 1].copy(), "dt": stated["dt"], "dt_source": "comment" if stated["dt"] else None,
           "t_start": 0.0, "units": stated["units"], "column": column, "ncols": ncol, "time_column": time_col,
           "names": parsed["names"], "comments": parsed["comments"]}
    if time_col:
        dt, t0 = check_time_column(table[:, 0], row_lines, filename)
        if stated["dt"] is not None and not np.isclose(stated["dt"], dt, rtol=1e-3):
            raise RockcliInputError(
                f"{filename}: a comment states dt={stated['dt']:g} s but the time column has steps of {dt:g} s")
        out.update(dt=dt, dt_source="time column", t_start=t0)
    return out


def format_text(values: np.ndarray, dt: float | None = None, t_start: float = 0.0,
                comments: list[str] | None = None, delimiter: str = " ") -> str:
    """Write samples as a text accelerogram that :func:`parse_text` reads back exactly.

    Parameters
    ----------
    values : ndarray
        Samples, 1-D (one column) or 2-D (rows x columns).
    dt : float, optional
        Time step [s]; when given a time column ``t_start + i*dt`` is written first.
    comments : list of str, optional
        Comment lines, written with a leading ``#``.
    """
    values = np.asarray(values, dtype=np.float64)
    if values.ndim == 1:
        values = values[:, None]
    lines = [f"# {c}" for c in (comments or [])]
    if dt is not None:
        t = t_start + dt * np.arange(values.shape[0])
        values = np.column_stack([t, values])
    lines.extend(delimiter.join(repr(float(v)) for v in row) for row in values)
    return "\n".join(lines) + "\n"
