"""PEER NGA ``.AT2`` accelerograms, readable on their own and as an ObsPy waveform plugin.

Registered in ``pyproject.toml`` under the ``obspy.plugin.waveform`` entry points (format name
``PEER_AT2``), so that after ``pip install`` a plain ``obspy.read("RSN1119_KOBE_TAZ000.AT2")``
returns a :class:`~obspy.core.stream.Stream`.

Layout of an AT2 file: four header lines, then the samples, several per line::

    PEER NGA STRONG MOTION DATABASE RECORD
    Kobe Japan, 1/16/1995, Takarazuka, 0                 <- event, date, station, component
    ACCELERATION TIME SERIES IN UNITS OF G               <- quantity and units
    NPTS=   4096  DT=   .0100 SEC,                       <- one of :data:`NPTS_DT_PATTERNS`
      -.6833536E-03  -.6799507E-03  ...

The fourth line comes in several layouts (NGA-West2 with and without a comma after NPTS, the
older NGA-West1 ``14488    0.0029    NPTS, DT``, ...); they are matched against a table of
regular expressions. Line endings may be LF, CRLF or CR.

Data units of the plugin: the Trace data are in **m/s^2** (float64). The file's values were
multiplied by ``stats.peer_at2.factor`` (9.80665 for a file in g); ``stats.peer_at2.units`` keeps
the units as stated in the file. ``stats.calib`` is left at 1.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError

#: Header line with the number of points and the time step, one regex per layout met in the
#: PEER databases and in files that imitate them. Groups: ``npts`` and ``dt`` [s].
_NUM = r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[EeDd][-+]?[0-9]+)?"
NPTS_DT_PATTERNS: tuple[tuple[str, re.Pattern], ...] = (
    # NGA-West2: "NPTS=   4096  DT=   .0100 SEC," and "NPTS=   4172, DT=   .0100 SEC,"
    ("nga-west2", re.compile(rf"^\s*NPTS\s*=\s*(?P<npts>\d+)\s*[,;]?\s*DT\s*=\s*(?P<dt>{_NUM})\s*(?:SEC|S)?\b", re.I)),
    # NGA-West1 (old PEER strong-motion database): "14488    0.0029    NPTS, DT"
    ("nga-west1", re.compile(rf"^\s*(?P<npts>\d+)\s*[,;]?\s+(?P<dt>{_NUM})\s*(?:SEC)?\s*[,;]?\s*NPTS\s*[,;]?\s*DT\b", re.I)),
    # DT before NPTS: "DT= .0050 SEC, NPTS= 7818"
    ("dt-first", re.compile(rf"^\s*DT\s*=\s*(?P<dt>{_NUM})\s*(?:SEC|S)?\s*[,;]?\s*NPTS\s*=\s*(?P<npts>\d+)", re.I)),
)

#: Units stated in the header lines: "... IN UNITS OF G", "The units are (g)", "UNITS: cm/s^2".
_UNITS_RE = re.compile(r"\bUNITS\s*(?:OF|ARE|IN|:|=)\s*[:=]?\s*\(?\s*(?P<units>[A-Za-z][A-Za-z0-9/^*.]*)\s*\)?", re.I)
_QUANTITY_RE = re.compile(r"\b(ACCELERATION|VELOCITY|DISPLACEMENT)\b", re.I)
_DATE_RE = re.compile(r"^\d{1,2}/\d{1,2}/\d{2,4}$")
_TIME_RE = re.compile(r"^\d{1,2}:\d{2}(?::\d{2})?$")
_FLOAT_RE = re.compile(_NUM)
#: Text made only of what plain decimal numbers are written with (the fast path of :func:`parse_numbers`).
_PLAIN_CHARS = re.compile(r"[0-9eE.+\-\s]*")

#: Number of header lines before the samples.
HEADER_LINES = 4


#: A PEER NGA file name: ``RSN983_NORTHR_JGB022.AT2``, the record sequence number first.
_RSN_NAME = re.compile(r"^RSN(?P<rsn>\d+)_", re.I)


def rsn_of(name) -> int | None:
    """The PEER NGA record sequence number (RSN) a file's name gives (``RSN983_NORTHR_JGB022.AT2``: 983), or None: the
    AT2 header does not state it, and two stations of one site (Jensen's Generator and Administrative Buildings, RSN
    983 and 982) differ by it and by their station name only."""
    from pathlib import Path

    m = _RSN_NAME.match(Path(str(name)).name)
    return int(m.group("rsn")) if m else None


def _split_lines(text: str) -> list[str]:
    """Lines of ``text`` whatever the line endings (LF, CRLF, CR, or CR CR LF).

    ``\r\r\n`` is a CRLF file converted once more as text (a Windows copy of a CRLF download):
    one line break, not a blank line after every line.
    """
    if "\r\r\n" in text:
        text = text.replace("\r\r\n", "\n")
    return text.splitlines()


#: Line 4 as this reader expects it, for messages.
_LINE4_EXAMPLES = "a layout such as 'NPTS=  4096, DT= .0100 SEC', 'DT= .01 SEC, NPTS= 4096' or '4096  .0100  NPTS, DT'"
_LOOSE_NPTS = re.compile(r"\bNPTS\s*=\s*(?P<v>[^\s,;]*)", re.I)
_LOOSE_DT = re.compile(r"\bDT\s*=\s*(?P<v>[^\s,;]*)", re.I)


def _diagnose_line4(line: str, filename: str) -> RockcliInputError:
    """One sentence on what is wrong with header line 4 (it matched none of the layouts)."""
    npts = _LOOSE_NPTS.search(line)
    dt = _LOOSE_DT.search(line)
    if npts is not None and not re.fullmatch(r"\d+", npts.group("v")):
        return RockcliInputError(f"{filename}, line 4: NPTS={npts.group('v')} is not a positive whole number "
                                 f"of samples (expected {_LINE4_EXAMPLES})")
    if dt is not None:
        token = dt.group("v")
        try:
            value = float(token.replace("D", "E").replace("d", "e"))
        except ValueError:
            value = None
        if value is None or not (value > 0 and value < float("inf")):
            return RockcliInputError(f"{filename}, line 4: DT={token} is not a positive time step in seconds "
                                     f"(expected {_LINE4_EXAMPLES})")
    shown = line.strip()
    shown = repr(shown[:60] + ("..." if len(shown) > 60 else "")) if shown else "an empty line"
    return RockcliInputError(f"{filename}, line 4: {shown} does not state NPTS and DT in a known AT2 layout "
                             f"(expected {_LINE4_EXAMPLES})")


def _match_npts_dt(line: str) -> tuple[str, int, float] | None:
    for layout, pattern in NPTS_DT_PATTERNS:
        m = pattern.match(line)
        if m:
            return layout, int(m.group("npts")), float(m.group("dt").replace("D", "E").replace("d", "e"))
    return None


def _parse_title(line: str) -> dict[str, str]:
    """Event, date, time, station and component from header line 2 (comma-separated)."""
    parts = [p.strip() for p in line.split(",")]
    if len(parts) < 3:
        return {}
    component = parts[-1]
    if component.isdigit() and int(component) < 360:  # an azimuth [deg]: three digits, as the catalogue and
        component = f"{int(component):03d}"          # PEER's file names write it (Takarazuka "0" is "000")
    out = {"event": parts[0], "component": component}
    station = []
    for p in parts[1:-1]:
        if "date" not in out and _DATE_RE.match(p):
            out["date"] = p
        elif "time" not in out and _TIME_RE.match(p):
            out["time"] = p
        else:
            station.append(p)
    out["station"] = ", ".join(station)
    return out


def parse_at2_header(lines: list[str], filename: str = "AT2 file") -> dict[str, Any]:
    """Parse the four header lines of an AT2 file.

    Parameters
    ----------
    lines : list of str
        At least the first four lines of the file.
    filename : str
        Name used in error messages.

    Returns
    -------
    dict
        ``npts``, ``dt`` [s], ``layout`` (key of :data:`NPTS_DT_PATTERNS`), ``units`` (as stated,
        or None), ``quantity`` (``acceleration``, ``velocity``, ``displacement`` or None), ``title``
        (line 2), ``description`` (line 3), ``database`` (line 1) and, when line 2 is a
        comma-separated list, ``event``, ``date``, ``time``, ``station``, ``component``.

    Raises
    ------
    RockcliInputError
        If there are fewer than four lines or line 4 matches none of the layouts.
    """
    if len(lines) < HEADER_LINES:
        raise RockcliInputError(
            f"{filename}: truncated AT2 header: the file has {len(lines)} line(s) where an AT2 file has 4 header "
            f"lines before its samples (line 4 states NPTS and DT, e.g. 'NPTS=  4096, DT= .0100 SEC')")
    comma = (re.search(r"\b(?:NPTS|DT)\s*=\s*[-+]?\d*,\d+", lines[3], re.I)  # DT=0,01 would read as DT=0
             or re.search(r"[-+]?\d+,\d+", lines[3]))
    if comma is not None:
        written = comma.group(0).strip()
        before = written.split(",")[0]
        misread = f", which would read it as {before}" if re.search(r"\d", before) else ""
        raise RockcliInputError(f"{filename}, line 4: {written} is written with a decimal comma; rockcli reads a "
                                f"point as the decimal mark (write {written.replace(',', '.')}) and a comma as a "
                                f"separator{misread}")
    found = _match_npts_dt(lines[3])
    if found is None:
        raise _diagnose_line4(lines[3], filename)
    layout, npts, dt = found
    head = {"database": lines[0].strip(), "title": lines[1].strip(), "description": lines[2].strip(),
            "layout": layout, "npts": npts, "dt": dt, "units": None, "quantity": None}
    for line in lines[:3]:
        m = _UNITS_RE.search(line)
        if m and head["units"] is None:
            head["units"] = m.group("units")
    m = _QUANTITY_RE.search(" ".join(lines[:3]))
    if m:
        head["quantity"] = m.group(1).lower()
    head.update(_parse_title(lines[1]))
    return head


def parse_numbers(lines: list[str], first_line: int, filename: str) -> np.ndarray:
    """All numbers in ``lines`` as float64, in order.

    Values are separated by blanks; fixed-width Fortran fields that run together
    (``1.1365572E-02-5.7981615E-03``) are split too.

    Parameters
    ----------
    lines : list of str
        Data lines.
    first_line : int
        1-based line number of ``lines[0]`` in the file (for error messages).
    filename : str
        Name used in error messages.

    Raises
    ------
    RockcliInputError
        On a token that is not a number, or a NaN or infinite value (naming the line).
    """
    text = " ".join(lines)
    values = None
    if _PLAIN_CHARS.fullmatch(text):  # numpy's parser also takes 1_0 (as 10) and other scripts' digits
        try:
            values = np.array(text.split(), dtype=np.float64)
        except ValueError:
            values = None
    if values is None:
        from rockcli.io.inputs import parse_number

        out: list[float] = []
        for k, line in enumerate(lines):
            where = f"{filename}, line {first_line + k}:"
            for token in line.split():
                if token.lower().lstrip("+-") in ("nan", "inf", "infinity"):
                    out.append(float(token))  # named with its sample number below
                    continue
                pieces = _FLOAT_RE.findall(token)
                if not pieces or "".join(pieces) != token:
                    parse_number(token, f"{where} value", fortran=True, bad=f"{where} {token!r} is not a number")
                # each piece matched _NUM, a plain decimal with an optional E or D exponent: float() reads it as
                # parse_number would, about 20 times faster; parse_number says why a piece overflows (1E999)
                for p in pieces:
                    v = float(p.replace("D", "E").replace("d", "e"))
                    out.append(v if np.isfinite(v) else parse_number(p, f"{where} value", fortran=True))
        values = np.array(out, dtype=np.float64)
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        line = _line_of_value(lines, i)
        tokens = lines[line].split()
        token = next((t for t in tokens if not np.isfinite(float(t.replace("D", "E").replace("d", "e")))), None) \
            if _PLAIN_CHARS.fullmatch(lines[line]) else None
        if token is not None:  # written as a number, e.g. 1e999: said as written
            raise RockcliInputError(f"{filename}, line {first_line + line}: sample {i + 1} is {token}, too large for "
                                    f"double precision")
        raise RockcliInputError(
            f"{filename}, line {first_line + line}: sample {i + 1} is {float(values[i])!r}, not a finite number")
    return values


def _line_of_value(lines: list[str], index: int) -> int:
    count = 0
    for k, line in enumerate(lines):
        count += len(line.split())
        if count > index:
            return k
    return len(lines) - 1


def check_record_file(filename) -> int:
    """Size in bytes of the record file ``filename``; one sentence when it is not a readable regular file.

    Devices (``/dev/zero``), pipes and sockets are refused: reading them may never end.
    """
    import os
    import stat

    try:
        st = os.stat(filename)
    except FileNotFoundError:
        raise RockcliInputError(f"{filename}: no such file") from None
    except NotADirectoryError:
        raise RockcliInputError(f"{filename}: no such file (a part of the path is a file, not a folder)") from None
    except OSError as exc:
        raise RockcliInputError(f"{filename}: cannot be read ({(exc.strerror or str(exc)).lower()})") from None
    if stat.S_ISDIR(st.st_mode):
        raise RockcliInputError(f"{filename}: is a folder, not a record file")
    if not stat.S_ISREG(st.st_mode):
        raise RockcliInputError(f"{filename}: is not a regular file (a device, pipe or socket); save the record "
                                f"to a file first")
    return st.st_size


def read_text(filename) -> str:
    """The whole file as text (latin-1, so that any byte decodes); clear errors when unreadable."""
    check_record_file(filename)
    try:
        with open(filename, "rb") as fh:
            raw = fh.read()
    except FileNotFoundError:
        raise RockcliInputError(f"{filename}: no such file") from None
    except IsADirectoryError:
        raise RockcliInputError(f"{filename}: is a folder, not a record file") from None
    except OSError as exc:
        raise RockcliInputError(f"{filename}: cannot be read ({(exc.strerror or str(exc)).lower()})") from None
    return strip_bom(raw).decode("latin-1")


#: The UTF-8 byte order mark some editors put before the first line.
UTF8_BOM = b"\xef\xbb\xbf"


def strip_bom(raw: bytes) -> bytes:
    """``raw`` without a leading UTF-8 byte order mark (it would hide the first header word)."""
    return raw[len(UTF8_BOM):] if raw.startswith(UTF8_BOM) else raw


def parse_at2(filename, headonly: bool = False) -> tuple[np.ndarray, dict[str, Any]]:
    """Read an AT2 file: samples in the units stated in the file, and the header.

    Parameters
    ----------
    filename : str or path-like
        The ``.AT2`` file.
    headonly : bool
        Skip the samples (an empty array is returned).

    Returns
    -------
    values : ndarray
        ``npts`` samples [units as stated in ``header["units"]``], float64.
    header : dict
        See :func:`parse_at2_header`.

    Raises
    ------
    RockcliInputError
        If the file is missing or empty, the header is not recognised, NPTS or DT is not
        positive, a value is not a finite number, or the number of values differs from NPTS.
    """
    text = read_text(filename)
    if not text.strip():
        raise RockcliInputError(f"{filename}: the file is empty" if not text else
                                f"{filename}: the file holds only blank space")
    lines = _split_lines(text)
    header = parse_at2_header(lines, str(filename))
    if header["npts"] <= 0:
        raise RockcliInputError(f"{filename}, line 4: the AT2 header states NPTS={header['npts']}; it must be positive")
    if not header["dt"] > 0:
        from rockcli.io.inputs import format_number

        raise RockcliInputError(f"{filename}, line 4: the AT2 header states DT={format_number(header['dt'])} s; "
                                f"the time step must be positive")
    if headonly:
        return np.empty(0), header
    values = parse_numbers(lines[HEADER_LINES:], HEADER_LINES + 1, str(filename))
    if values.size < header["npts"]:
        raise RockcliInputError(
            f"{filename}: truncated AT2 file: the header states NPTS={header['npts']} but only "
            f"{values.size} values follow")
    if values.size > header["npts"]:
        raise RockcliInputError(
            f"{filename}: the AT2 header states NPTS={header['npts']} but {values.size} values follow")
    return values, header


# --------------------------------------------------------------------------------------------
# ObsPy plugin
# --------------------------------------------------------------------------------------------

def _is_at2(filename) -> bool:
    """True when ``filename`` looks like a PEER AT2 file (cheap; never raises).

    Checks that the file is text and its line 4 states NPTS and DT in a known layout.
    """
    try:
        if hasattr(filename, "read"):  # file-like objects: ObsPy passes paths or buffers
            pos = filename.tell()
            raw = filename.read(4096)
            filename.seek(pos)
        else:
            with open(filename, "rb") as fh:
                raw = fh.read(4096)
        if isinstance(raw, str):
            raw = raw.encode("latin-1", "replace")
        raw = strip_bom(raw)
        if b"\x00" in raw:
            return False
        lines = _split_lines(raw.decode("latin-1"))
        return len(lines) >= HEADER_LINES and _match_npts_dt(lines[3]) is not None
    except Exception:  # noqa: BLE001 -- a format probe must answer, not raise
        return False


def at2_factor(header: dict[str, Any], filename="AT2 file") -> float:
    """Factor from the file's stated units to m/s^2 (raises if the units are unknown)."""
    from rockcli.io.units import accel_factor

    if header.get("units") is None:
        raise RockcliInputError(f"{filename}: the AT2 header states no units; give them (--units g, ...)")
    return accel_factor(header["units"])


def _read_at2(filename, headonly: bool = False, **kwargs):
    """Read a PEER AT2 file into an ObsPy Stream of one Trace (ObsPy plugin entry point).

    Parameters
    ----------
    filename : str or path-like
        The ``.AT2`` file.
    headonly : bool
        Read the header only (``stats.npts`` is set, ``data`` is empty).
    **kwargs
        Ignored (ObsPy passes its own options through).

    Returns
    -------
    obspy.core.stream.Stream
        One Trace; data in m/s^2 (float64). ``stats.peer_at2`` holds the header: ``units`` (as
        stated in the file), ``factor`` (multiplier applied to reach m/s^2), ``data_units``
        (``"m/s^2"``), ``event``, ``date``, ``station``, ``component``, ``title``, ``layout``, ...
        ``stats.channel`` is the component (at most 3 characters are not enforced). Start time
        is 1970-01-01 (AT2 files state no clock time).
    """
    from obspy import Stream, Trace
    from obspy.core.util import AttribDict

    values, header = parse_at2(filename, headonly=headonly)
    factor = at2_factor(header, filename)
    peer = AttribDict({k: v for k, v in header.items() if v is not None})
    peer["factor"] = factor
    peer["data_units"] = "m/s^2"
    stats = {"delta": header["dt"], "station": header.get("station", "")[:64],
             "channel": header.get("component", ""), "peer_at2": peer}
    if headonly:
        tr = Trace(header=stats)
        tr.stats.npts = header["npts"]
    else:
        tr = Trace(data=values * factor, header=stats)
    return Stream([tr])
