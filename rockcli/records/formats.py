"""Strong-motion text formats that ObsPy does not read: small parsers, and clear refusals.

Each supported format has a cheap ``_is_<format>(head)`` probe on the first lines of the file
(returns False, never raises) and a ``_read_<format>(lines, filename, column)`` parser returning
a dict with ``values`` (units as stated), ``dt`` [s], ``units`` (as stated), ``t_start`` [s] and
``meta``. Formats that are out of scope are recognised too, so that the user gets one sentence
naming the format and why it is refused instead of a parse error.

Supported: ESM ASCII (DYNA 1.2), ITACA ``.cor.acc``, COSMOS Volume 2 (acceleration block),
GeoNet Volume 2A (one of its three components, chosen with ``column``).
Refused: USC Volume I (uneven sampling), BHRC VOL1 (uncorrected, several components in one file),
UNAM ASA 2.0 and USGS SMC (out of scope).
"""

from __future__ import annotations

import re
from typing import Any, Callable

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.records.at2 import parse_numbers

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"


# --------------------------------------------------------------------------------------------
# ESM ASCII (Engineering Strong Motion database, DYNA 1.2 header)
# --------------------------------------------------------------------------------------------

def _is_esm(lines: list[str]) -> bool:
    head = lines[:80]
    return bool(head) and head[0].startswith("EVENT_NAME:") and any(l.startswith("SAMPLING_INTERVAL_S:") for l in head)


def _read_esm(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    header: dict[str, str] = {}
    start = None
    for i, line in enumerate(lines):
        m = re.match(r"^([A-Z0-9_/^.\-]+):\s?(.*)$", line)
        if m:
            header[m.group(1)] = m.group(2).strip()
            continue
        start = i
        break
    if start is None:
        raise RockcliInputError(f"{filename}: ESM file has a header but no samples")
    dtype = header.get("DATA_TYPE", "").upper()
    if dtype and dtype != "ACCELERATION":
        raise RockcliInputError(f"{filename}: ESM file holds {dtype.lower()}, not acceleration")
    try:
        dt = _header_number(header["SAMPLING_INTERVAL_S"])
        npts = _header_number(header["NDATA"], integer=True)
    except (KeyError, ValueError):
        raise RockcliInputError(f"{filename}: ESM header lacks a valid SAMPLING_INTERVAL_S or NDATA") from None
    values = parse_numbers(lines[start:], start + 1, filename)
    _check_count(values, npts, filename, "NDATA")
    meta = {"event": header.get("EVENT_NAME", ""), "event_id": header.get("EVENT_ID", ""),
            "station": ".".join(x for x in (header.get("NETWORK", ""), header.get("STATION_CODE", "")) if x),
            "station_name": header.get("STATION_NAME", ""), "component": header.get("STREAM", ""),
            "first_sample": header.get("DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS", ""), "header": header}
    return {"values": values, "dt": dt, "units": header.get("UNITS") or None, "t_start": 0.0, "meta": meta}


# --------------------------------------------------------------------------------------------
# ITACA corrected record (.cor.acc): "Key : value" header, then 5E14.7 with no separators
# --------------------------------------------------------------------------------------------

def _is_itaca(lines: list[str]) -> bool:
    head = lines[:15]
    return any(l.startswith("Time Increment (s)") for l in head) and any(l.startswith("Number of Data") for l in head)


def _read_itaca(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    header: dict[str, str] = {}
    units = None
    start = None
    for i, line in enumerate(lines):
        m = re.match(r"^(.*?)\s*:\s(.*)$", line)
        if m and not re.match(rf"^\s*{_NUM}", line):
            header[m.group(1).strip()] = m.group(2).strip()
            continue
        m = re.match(r"^\s*Accel\w*\s+time\s+series\s+in\s+(\S+)", line, re.I)
        if m:
            units = m.group(1)
            start = i + 1
            break
        start = i
        break
    try:
        dt = _header_number(header["Time Increment (s)"])
        npts = _header_number(header["Number of Data"], integer=True)
    except (KeyError, ValueError):
        raise RockcliInputError(f"{filename}: ITACA header lacks a valid 'Time Increment (s)' or 'Number of Data'") from None
    values = parse_numbers(lines[start:], start + 1, filename)
    _check_count(values, npts, filename, "Number of Data")
    station = header.get("Station Code / Name", "")
    meta = {"event": header.get("Event Date & Time", ""), "station": station,
            "component": header.get("Orientation", ""), "header": header}
    return {"values": values, "dt": dt, "units": units, "t_start": 0.0, "meta": meta}


# --------------------------------------------------------------------------------------------
# COSMOS Volume 2 (v01.20): text lines, integer and real headers, comments, then data blocks
# --------------------------------------------------------------------------------------------

def _is_cosmos(lines: list[str]) -> bool:
    return bool(lines) and re.search(r"\(Format v\d+\.\d+ with\s+\d+ text lines\)", lines[0]) is not None


def _read_cosmos(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    def bad(what):
        return RockcliInputError(f"{filename}: COSMOS file: {what}")

    m = re.search(r"with\s+(\d+) text lines", lines[0])
    i = int(m.group(1))
    counts = {}
    for key, rx in (("int", r"^\s*(\d+)\s+Integer-header values follow on\s+(\d+) lines"),
                    ("real", r"^\s*(\d+)\s+Real-header values follow on\s+(\d+) lines")):
        m = re.match(rx, lines[i]) if i < len(lines) else None
        if not m:
            raise bad(f"line {i + 1} should announce the {key} header")
        counts[key] = (int(m.group(1)), i + 1, i + 1 + int(m.group(2)))
        i += 1 + int(m.group(2))
    reals = parse_numbers(lines[counts["real"][1]:counts["real"][2]], counts["real"][1] + 1, filename)
    m = re.match(r"^\s*(\d+) Comment line", lines[i]) if i < len(lines) else None
    if not m:
        raise bad(f"line {i + 1} should announce the comment lines")
    i += 1 + int(m.group(1))
    m = re.match(r"^\s*(\d+)\s+(\w+) pts,.*units=\s*([^\s,(]+)", lines[i]) if i < len(lines) else None
    if not m:
        raise bad(f"line {i + 1} should announce the data block with its units")
    npts, quantity, units = int(m.group(1)), m.group(2).lower(), m.group(3)
    if quantity != "acceleration":
        raise bad(f"the first data block holds {quantity}, not acceleration")
    # real header 62 (1-based): sampling interval [ms]
    dt_ms = reals[61] if reals.size > 61 else -999.0
    if not dt_ms > 0:
        raise bad("real header value 62 (sampling interval, ms) is missing")
    values = _take_numbers(lines, i + 1, npts, filename, "acceleration pts")
    meta = {"event": lines[1].strip(), "station": lines[4].strip(), "component": "", "header_text": lines[:i]}
    return {"values": values, "dt": dt_ms / 1000.0, "units": units, "t_start": 0.0, "meta": meta}


# --------------------------------------------------------------------------------------------
# GeoNet Volume 2A: three components, each 16 text + 4 integer + 6 real header lines and
# acceleration, velocity, displacement blocks (10F8.1)
# --------------------------------------------------------------------------------------------

def _is_geonet(lines: list[str]) -> bool:
    return (len(lines) > 12 and re.match(r"^(Un)?[Cc]orrected accelerogram", lines[0]) is not None
            and lines[1].startswith("Site ") and any("data at" in l and "sec intervals" in l for l in lines[:16]))


def _read_geonet(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    starts = [k for k, l in enumerate(lines) if re.match(r"^(Un)?[Cc]orrected accelerogram", l)]
    comps = []
    for s in starts:
        m = re.match(r"^Component\s+(\S+)", lines[s + 12]) if s + 12 < len(lines) else None
        comps.append(m.group(1) if m else "?")
    if column is None:
        from rockcli.records.components import MultiComponent

        raise MultiComponent(
            f"{filename}: GeoNet V2A file holds {len(starts)} components ({', '.join(comps)}); "
            f"choose one with --component NAME (or --record-column 1-{len(starts)})", len(starts))
    if not 1 <= column <= len(starts):
        raise RockcliInputError(f"{filename}: column {column} does not exist (the file holds {len(starts)} components)")
    s = starts[column - 1]
    text = "\n".join(lines[s:s + 16])
    m_n = re.search(r"Number of points\s+(\d+)", text)
    m_dt = re.search(rf"data at\s+({_NUM}) sec intervals", text)
    m_u = re.search(rf"Acceleration:\s+peak\s+{_NUM}\s+(\S+)", text)
    if not (m_n and m_dt and m_u):
        raise RockcliInputError(f"{filename}: GeoNet V2A header of component {column} lacks its points, interval or units")
    npts = int(m_n.group(1))
    values = _take_numbers(lines, s + 26, npts, filename, f"component {column}")
    meta = {"event": lines[s + 6].strip(), "station": lines[s + 1].split()[1], "component": comps[column - 1]}
    return {"values": values, "dt": float(m_dt.group(1)), "units": m_u.group(1), "t_start": 0.0, "meta": meta}


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------

def _header_number(text: str, integer: bool = False):
    """A header value as a plain number (:func:`rockcli.inputs.parse_number`: ``1_0`` is not 10); raises
    ``RockcliInputError``, a ``ValueError``, which the readers turn into their sentence on the header."""
    from rockcli.inputs import parse_number

    return parse_number(text, "header value", integer=integer, fortran=True)


def _check_count(values: np.ndarray, npts: int, filename: str, key: str) -> None:
    if values.size < npts:
        raise RockcliInputError(f"{filename}: truncated file: the header states {key}={npts} but only {values.size} values follow")
    if values.size > npts:
        raise RockcliInputError(f"{filename}: the header states {key}={npts} but {values.size} values follow")


def _take_numbers(lines: list[str], start: int, npts: int, filename: str, what: str) -> np.ndarray:
    """The first ``npts`` numbers from ``lines[start:]`` (read line by line until enough)."""
    chunk: list[str] = []
    count = 0
    k = start
    while count < npts and k < len(lines):
        chunk.append(lines[k])
        count += len(re.findall(_NUM, lines[k]))
        k += 1
    values = parse_numbers(chunk, start + 1, filename)
    if values.size < npts:
        raise RockcliInputError(f"{filename}: truncated file: {what} announces {npts} values but only {values.size} follow")
    return values[:npts]


# --------------------------------------------------------------------------------------------
# formats recognised only to be refused
# --------------------------------------------------------------------------------------------

def _is_usc1(lines):
    return bool(lines) and "OF VOLUME I" in lines[0].upper() and "UNCORRECTED" in lines[0].upper()


def _is_bhrc(lines):
    return bool(lines) and re.match(r"^\*\s*VOL\dDS", lines[0]) is not None


def _is_unam(lines):
    return any("ARCHIVO ESTANDAR DE ACELERACION" in l.upper() for l in lines[:12])


def _is_smc(lines):
    return len(lines) > 30 and any("-32768" in l for l in lines[11:17]) and any("0.1700000E+39" in l for l in lines[17:27])


#: name -> (probe, reader). Probed in this order.
READERS: dict[str, tuple[Callable, Callable]] = {
    "ESM": (_is_esm, _read_esm),
    "ITACA": (_is_itaca, _read_itaca),
    "COSMOS": (_is_cosmos, _read_cosmos),
    "GEONET_V2A": (_is_geonet, _read_geonet),
}

#: name -> (probe, reason for refusing). Probed after :data:`READERS`.
REFUSED: dict[str, tuple[Callable, str]] = {
    "USC_VOL1": (_is_usc1, "USC Volume I uncorrected data are (time, acceleration) pairs at uneven spacing; "
                           "rockcli needs a constant time step: use the corrected (Volume II) record or resample "
                           "it yourself and load it as text"),
    "BHRC_VOL1": (_is_bhrc, "BHRC VOL1 (uncorrected, several components per file) is out of scope; use the "
                            "corrected record or export one component as text"),
    "UNAM_ASA": (_is_unam, "UNAM ASA 2.0 is out of scope; export the chosen component as text "
                           "(one column, with --dt and --units)"),
    "SMC": (_is_smc, "USGS SMC is out of scope; load the original record (e.g. the PEER AT2 file) or "
                     "export it as text"),
}


def _is_cwb(lines):
    return any(l.startswith("#StationCode:") for l in lines[:20]) and any(l.startswith("#Earthquake Information")
                                                                          for l in lines[:3])


#: name -> probe: text tables rockcli reads column by column (``--record-column``, ``--units``), which the
#: ``formats`` extra reads with their units and orientations when it is installed.
EXTRA_FIRST: dict[str, Callable] = {"CWB": _is_cwb}


#: How messages name the formats rockcli recognises but leaves to the extra.
FORMAT_NAMES = {"USC_VOL1": "USC Volume I", "BHRC_VOL1": "BHRC VOL1", "UNAM_ASA": "UNAM ASA 2.0", "SMC": "USGS SMC",
                "CWB": "CWB"}


def probe(lines: list[str]) -> str | None:
    """Name of the format of a text file from its first lines (None when not recognised)."""
    for name, is_fmt in {**{k: v[0] for k, v in {**READERS, **REFUSED}.items()}, **EXTRA_FIRST}.items():
        try:
            if is_fmt(lines):
                if name in EXTRA_FIRST:
                    from rockcli.records.extra import available

                    return name if available() else None  # without the extra: a text table, as before
                return name
        except Exception:  # noqa: BLE001 -- a probe answers, never raises
            continue
    return None


def refusal(name: str, filename: str) -> RockcliInputError:
    """The error for a recognised but refused format."""
    from rockcli.records.extra import INSTALL_HINT

    return RockcliInputError(f"{filename}: {REFUSED[name][1]}; or {INSTALL_HINT}")
