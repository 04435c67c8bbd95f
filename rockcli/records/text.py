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
#: A time step stated in a comment: the keyword, then the number as written (a Fortran ``D``
#: exponent or a decimal comma are caught so that they are parsed or refused, never misread), then
#: an optional unit word (bare numbers are seconds).
_DT_RE = re.compile(r"\b(?:dt|time\s*step|delta|sampling\s*interval|sample\s*interval)\s*(?:=|:|is|of)?\s*"
                    r"(?P<dt>[-+]?[0-9.][0-9_.,]*(?:[eEdD][-+]?[0-9_]+)?)"
                    r"\s*[\[(]?\s*(?P<unit>[^\s\d,;:=()\[\]]+)?", re.I)
#: Time units of a stated time step -> factor to seconds.
TIME_UNITS = {"s": 1.0, "sec": 1.0, "secs": 1.0, "second": 1.0, "seconds": 1.0,
              "ms": 1e-3, "msec": 1e-3, "msecs": 1e-3, "millisecond": 1e-3, "milliseconds": 1e-3,
              "us": 1e-6, "usec": 1e-6, "usecs": 1e-6, "microsecond": 1e-6, "microseconds": 1e-6}
#: Spellings of the micro sign (also as UTF-8 bytes read as latin-1), read as ``u``.
_MICRO = ("\u00c2\u00b5", "\u00ce\u00bc", "\u00b5", "\u03bc")
#: Words after a time step that are units, but not of a time step rockcli can use as stated.
_REFUSED_TIME_WORDS = {"min", "mins", "minute", "minutes", "h", "hr", "hrs", "hour", "hours", "hz", "khz",
                       "ns", "nsec", "nanosecond", "nanoseconds", "sps"}
_UNITS_RE = re.compile(r"(?:\bunits?\s*(?:are|of|in)?\s*[:=]?|\bacc(?:eleration|el)?\.?\s*(?:\[|\(|in\b|:))\s*\(?\s*"
                       r"(?P<units>[A-Za-z][A-Za-z0-9/^*]*)", re.I)
#: A number of samples stated in a comment (``npts = 4000``, ``NPTS: 4000``, ``number of points: 4000``); only
#: these explicit forms count (``200 samples per second`` is no count).
_NPTS_RE = re.compile(r"\b(?:npts|number\s+of\s+(?:points|samples|data\s+points|data))\s*(?:=|:|is)?\s*(\d+)\b(?![.,]\d)",
                      re.I)
#: Fraction of increasing steps above which the first column is taken as time.
TIME_COLUMN_FRACTION = 0.9
#: Relative tolerance on the uniformity of a time column (fraction of a step).
TIME_UNIFORMITY_RTOL = 1e-3


def _known_unit(word: str) -> bool:
    from rockcli.io.units import ACCEL_UNITS

    return word.strip().lower().replace(" ", "").rstrip(".") in ACCEL_UNITS


def parse_comments(comments: list[str], filename: str = "text file") -> dict[str, Any]:
    """Time step [s] and units stated in comment lines (None when not stated)."""
    dt = units = None
    for line in comments:
        if dt is None:
            m = _DT_RE.search(line)
            if m:
                dt = _comment_dt(m, line, filename)
        if units is None:
            for m in _UNITS_RE.finditer(line):
                word = m.group("units").rstrip(".")
                if _known_unit(word):
                    units = word
                    break
    return {"dt": dt, "units": units}


def _comment_dt(m: re.Match, line: str, filename: str) -> float:
    """The time step [s] of a ``_DT_RE`` match: its number as written, times its unit (seconds when bare)."""
    from rockcli.io.inputs import parse_number

    what = f"{filename}: a comment states the time step as {line.strip()[:80]!r}:"
    value = parse_number(m.group("dt").rstrip(",."), f"{what} the number", fortran=True)
    written = (m.group("unit") or "").rstrip(".")
    word = written
    for micro in _MICRO:
        word = word.replace(micro, "u")
    word = word.lower()
    if word in TIME_UNITS:
        return value * TIME_UNITS[word]
    # a following word that is a unit but not a usable one, or a short unknown token, is refused; a plain
    # word ("dt = 0.01 sampling ...") leaves the number bare: seconds, as documented
    if word in _REFUSED_TIME_WORDS or (word and (len(word) <= 3 or not word.isascii() or not word.isalpha())):
        raise RockcliInputError(f"{what} {written!r} is not a unit of a time step rockcli reads (s, ms, us); "
                                f"give the time step with --dt in seconds")
    return value


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


def _is_name(token: str) -> bool:
    """A column name (``time``, ``acc_g``, ``[s]``): not a number, and not starting like one. A malformed
    first sample (``0x1``, ``1.2.3``) is a data row, refused there, not taken as a header."""
    return not _is_number(token) and re.match(r"[-+]?\.?[0-9]", token) is None


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
        if not rows and names is None and all(_is_name(t) for t in tokens):
            names = tokens
            continue
        rows.append(tokens)
        row_lines.append(number)
    if not rows:
        raise RockcliInputError(f"{filename}: the file holds no numbers" if text.strip()
                                else f"{filename}: the file is empty")
    _refuse_decimal_commas(text, row_lines, filename)
    ncol = len(rows[0])
    for tokens, number in zip(rows, row_lines):
        if len(tokens) != ncol:
            raise RockcliInputError(
                f"{filename}, line {number}: {len(tokens)} values where the first data row has {ncol}")
    _check_plain_numbers(rows, row_lines, filename)
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
        token = rows[r][c]
        why = ("is not a finite number" if token.lower().lstrip("+-") in _NON_FINITE
               else "is too large for double precision")
        raise RockcliInputError(f"{filename}, line {row_lines[r]}: value {token} in column {c + 1} {why}")
    return {"table": table, "comments": comments, "names": names, "row_lines": row_lines}


_PLAIN_CHARS = re.compile(r"[0-9eE.+\-]*")
_NON_FINITE = ("nan", "inf", "infinity")


def _check_plain_numbers(rows: list[list[str]], row_lines: list[int], filename: str) -> None:
    """Refuse what numpy's parser would take but is no plain number (``1_0`` read as 10, other scripts'
    digits); NaN and infinities pass here and are named with their column below."""
    if _PLAIN_CHARS.fullmatch("".join("".join(r) for r in rows)):
        return
    from rockcli.io.inputs import parse_number

    for tokens, number in zip(rows, row_lines):
        for token in tokens:
            if not _PLAIN_CHARS.fullmatch(token) and token.lower().lstrip("+-") not in _NON_FINITE:
                parse_number(token, f"{filename}, line {number}: value",
                             bad=f"{filename}, line {number}: {token!r} is not a number")


def _refuse_decimal_commas(text: str, row_lines: list[int], filename: str) -> None:
    """One sentence when the numbers are written with decimal commas (``0,123``): no data row holds a point
    and some hold a comma between digits. Read as a column separator, the comma would turn 0,123 into
    two columns, 0 and 123 (the advice to pick a column then reads every sample a thousand times too big)."""
    lines = text.splitlines()
    data = [(n, lines[n - 1].strip()) for n in row_lines]
    if any("." in line for _, line in data):
        return
    for n, line in data:
        m = re.search(r"[0-9],[0-9]", line)
        if m:
            raise RockcliInputError(
                f"{filename}, line {n}: {line[:60]!r} is written with decimal commas (no value in the file has "
                f"a decimal point); rockcli reads a point as the decimal mark and a comma as a column separator: "
                f"write the numbers with points (0,123 -> 0.123)")


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
    stated = parse_comments(parsed["comments"], filename)
    if stated["units"] is None:  # "units: furlongs" is a statement too: reported, not ignored
        stated["units"] = stated_unknown_units(parsed["comments"])
    for line in parsed["comments"]:  # a stated count is checked against the rows: a cut file is refused
        m = _NPTS_RE.search(line)
        if m:
            from rockcli.records.checks import check_count

            check_count(filename, nrow, int(m.group(1)), f"a comment: {line.strip()[:60]!r}",
                        f"rows of values follow (lines {row_lines[0]}-{row_lines[-1]})")
            break
    time_col = ncol >= 2 and looks_like_time(table[:, 0])
    data_cols = list(range(2, ncol + 1)) if time_col else list(range(1, ncol + 1))
    if column is None:
        if len(data_cols) > 1:
            what = f"a time column and {len(data_cols)} data columns" if time_col else f"{ncol} data columns"
            raise RockcliInputError(
                f"{filename}: the file has {what}; choose one with --record-column (1-based, counting the time column)"
                if time_col else
                f"{filename}: the file has {what}; choose one with --record-column (1-based)")
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
            from rockcli.io.inputs import format_number

            raise RockcliInputError(f"{filename}: a comment states dt={format_number(stated['dt'])} s but the time "
                                    f"column has steps of {format_number(dt)} s")
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
