"""Strong-motion text formats that ObsPy does not read: small parsers, and clear refusals.

Each supported format has a cheap ``_is_<format>(head)`` probe on the first lines of the file
(returns False, never raises) and a ``_read_<format>(lines, filename, column)`` parser returning
a dict with ``values`` (units as stated), ``dt`` [s], ``units`` (as stated), ``t_start`` [s] and
``meta``. Formats that are out of scope are recognised too, so that the user gets one sentence
naming the format and why it is refused instead of a parse error.

Supported: ESM ASCII (DYNA 1.2), ITACA ``.cor.acc``, COSMOS Volume 2 (acceleration block),
GeoNet Volume 2A (one of its three components, chosen with ``column``; :mod:`rockcli.records.geonet`),
CWB ``.dat`` (three channels; :mod:`rockcli.records.cwb`). Each reader checks what its header says against
the data it reads (:mod:`rockcli.records.checks`).
Refused: USC Volume I (uneven sampling), BHRC VOL1 (uncorrected, several components in one file),
UNAM ASA 2.0 and USGS SMC (out of scope).
"""

from __future__ import annotations

import math
import re
from typing import Any, Callable

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.records import checks
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
    line_of: dict[str, int] = {}
    start = None
    for i, line in enumerate(lines):
        m = re.match(r"^([A-Z0-9_/^.\-]+):\s?(.*)$", line)
        if m:
            header[m.group(1)] = m.group(2).strip()
            line_of[m.group(1)] = i + 1
            continue
        start = i
        break
    if start is None:
        raise RockcliInputError(f"{filename}: ESM file has a header but no samples")
    _refuse_column(column, filename, "ESM")
    dtype = header.get("DATA_TYPE", "").upper()
    if dtype and dtype != "ACCELERATION":
        raise RockcliInputError(f"{filename}: ESM file holds {dtype.lower()}, not acceleration")
    try:
        dt = _header_number(header["SAMPLING_INTERVAL_S"])
        npts = _header_number(header["NDATA"], integer=True)
    except (KeyError, ValueError):
        raise RockcliInputError(f"{filename}: ESM header lacks a valid SAMPLING_INTERVAL_S or NDATA") from None
    values = parse_numbers(lines[start:], start + 1, filename)

    def where(key):
        return f"line {line_of[key]}: '{key}: {header[key]}'"

    checks.check_count(filename, values.size, npts, where("NDATA"), f"values follow (lines {start + 1}-{len(lines)})")
    if header.get("DURATION_S"):
        checks.check_duration(filename, npts, dt, _header_value(header["DURATION_S"]), header["DURATION_S"],
                              where("DURATION_S"))
    units = checks.known_units(filename, header.get("UNITS"), where("UNITS") if "UNITS" in header else "UNITS")
    if units is not None and header.get("PGA_CM/S^2"):  # the peak in cm/s^2 whatever UNITS says: checks both
        from rockcli.io.units import accel_factor

        checks.check_peak(filename, values, _header_value(header["PGA_CM/S^2"]), header["PGA_CM/S^2"],
                          where("PGA_CM/S^2"), "cm/s^2", accel_factor(units) / accel_factor("cm/s^2"))
    meta = {"event": header.get("EVENT_NAME", ""), "event_id": header.get("EVENT_ID", ""),
            "station": ".".join(x for x in (header.get("NETWORK", ""), header.get("STATION_CODE", "")) if x),
            "station_name": header.get("STATION_NAME", ""), "component": header.get("STREAM", ""),
            "first_sample": header.get("DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS", ""), "header": header}
    out = {"values": values, "dt": dt, "units": units, "t_start": 0.0, "meta": meta}
    if units is None:
        out["units_missing"] = "its UNITS field is empty or missing"
    return out


# --------------------------------------------------------------------------------------------
# ITACA corrected record (.cor.acc): "Key : value" header, then 5E14.7 with no separators
# --------------------------------------------------------------------------------------------

def _is_itaca(lines: list[str]) -> bool:
    head = lines[:15]
    return any(l.startswith("Time Increment (s)") for l in head) and any(l.startswith("Number of Data") for l in head)


def _read_itaca(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    header: dict[str, str] = {}
    line_of: dict[str, int] = {}
    units = units_line = None
    start = None
    for i, line in enumerate(lines):
        m = re.match(r"^(.*?)\s*:\s(.*)$", line)
        if m and not re.match(rf"^\s*{_NUM}", line):
            header[m.group(1).strip()] = m.group(2).strip()
            line_of[m.group(1).strip()] = i + 1
            continue
        m = re.match(r"^\s*Accel\w*\s+time\s+series(?:\s+in)?(?:\s+(\S+))?", line, re.I)
        if m:
            units, units_line = m.group(1), i + 1
            start = i + 1
            break
        start = i
        break
    _refuse_column(column, filename, "ITACA")
    try:
        dt = _header_number(header["Time Increment (s)"])
        npts = _header_number(header["Number of Data"], integer=True)
    except (KeyError, ValueError):
        raise RockcliInputError(f"{filename}: ITACA header lacks a valid 'Time Increment (s)' or 'Number of Data'") from None
    values = parse_numbers(lines[start:], start + 1, filename)
    checks.check_count(filename, values.size, npts, f"line {line_of['Number of Data']}: 'Number of Data : {npts}'",
                       f"values follow (lines {start + 1}-{len(lines)})")
    units = checks.known_units(filename, units, f"line {units_line}")
    pga_key = next((k for k in header if re.match(r"PGA\s*\(", k)), None)
    if pga_key is not None and units is not None:  # "PGA (m/s/s) : 5.0693293E+00": a peak in stated units
        from rockcli.io.units import accel_factor

        pga_units = checks.known_units(filename, re.match(r"PGA\s*\((.*)\)", pga_key).group(1),
                                       f"line {line_of[pga_key]}")
        if pga_units is not None:
            checks.check_peak(filename, values, _header_value(header[pga_key]), header[pga_key],
                              f"line {line_of[pga_key]}: '{pga_key} : {header[pga_key]}'", pga_units,
                              accel_factor(units) / accel_factor(pga_units))
    station = header.get("Station Code / Name", "")
    meta = {"event": header.get("Event Date & Time", ""), "station": station,
            "component": header.get("Orientation", ""), "header": header}
    out = {"values": values, "dt": dt, "units": units, "t_start": 0.0, "meta": meta}
    if units is None:
        out["units_missing"] = ("no line 'Acceleration time series in UNITS' before the samples" if units_line is None
                                else f"line {units_line} names no units")
    return out


# --------------------------------------------------------------------------------------------
# COSMOS Volume 2 (v01.20): text lines, integer and real headers, comments, then data blocks
# --------------------------------------------------------------------------------------------

def _is_cosmos(lines: list[str]) -> bool:
    return bool(lines) and re.search(r"\(Format v\d+\.\d+ with\s+\d+ text lines\)", lines[0]) is not None


#: COSMOS physical-units codes (integer header value 3) of accelerations, as rockcli's units words.
_COSMOS_UNIT_CODES = {2: "g", 4: "cm/s^2", 10: "gal"}
#: COSMOS data-type codes (integer header value 2).
_COSMOS_TYPES = {1: "acceleration", 2: "velocity", 3: "displacement"}
_COSMOS_UNKNOWN = -999


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
    _refuse_column(column, filename, "COSMOS")
    ints = parse_numbers(lines[counts["int"][1]:counts["int"][2]], counts["int"][1] + 1, filename)
    reals = parse_numbers(lines[counts["real"][1]:counts["real"][2]], counts["real"][1] + 1, filename)
    for key, got in (("int", ints), ("real", reals)):
        n, first, stop = counts[key]
        if got.size != n:
            raise checks.disagree(filename, f"{n} {key}-header values (line {first})",
                                  f"lines {first + 1}-{stop} hold {got.size}")
    m = re.match(r"^\s*(\d+) Comment line", lines[i]) if i < len(lines) else None
    if not m:
        raise bad(f"line {i + 1} should announce the comment lines")
    i += 1 + int(m.group(1))
    m = re.match(r"^\s*(\d+)\s+(\w+) pts,(?:\s*approx\s+(\S+)\s+secs)?.*units=\s*([^\s,(]+)(?:\((\d+)\))?",
                 lines[i]) if i < len(lines) else None
    if not m:
        raise bad(f"line {i + 1} should announce the data block with its units")
    npts, quantity, units = int(m.group(1)), m.group(2).lower(), m.group(4)
    block_line = f"line {i + 1}: {lines[i].strip()[:48]!r}"
    if quantity != "acceleration":
        raise bad(f"the first data block holds {quantity}, not acceleration")
    type_code = int(ints[1]) if ints.size > 1 else _COSMOS_UNKNOWN
    if type_code in _COSMOS_TYPES and _COSMOS_TYPES[type_code] != quantity:
        raise checks.disagree(filename, f"{quantity} ({block_line})", f"its integer header (value 2) codes the data "
                              f"as {_COSMOS_TYPES[type_code]} ({type_code})")
    units = checks.known_units(filename, units, block_line)
    from rockcli.io.units import accel_factor

    for code, where in ((int(ints[2]) if ints.size > 2 else _COSMOS_UNKNOWN, "its integer header (value 3)"),
                        (int(m.group(5)) if m.group(5) else _COSMOS_UNKNOWN, "the units code in parentheses")):
        coded = _COSMOS_UNIT_CODES.get(code)
        if coded is not None and accel_factor(coded) != accel_factor(units):
            raise checks.disagree(filename, f"units {units} ({block_line})", f"{where} codes them as {coded} ({code})")
    # real header 62 (1-based): sampling interval [ms]
    dt_ms = reals[61] if reals.size > 61 else -999.0
    if not dt_ms > 0:
        raise bad("real header value 62 (sampling interval, ms) is missing")
    dt = dt_ms / 1000.0
    stop = _numeric_block_end(lines, i + 1)
    values = parse_numbers(lines[i + 1:stop], i + 2, filename)
    checks.check_count(filename, values.size, npts, block_line,
                       f"lines {i + 2}-{stop} hold {values.size} values before "
                       + (f"line {stop + 1} ({lines[stop].strip()[:40]!r})" if stop < len(lines) else "the end"))
    if m.group(3):
        checks.check_duration(filename, npts, dt, _header_value(m.group(3)), m.group(3), block_line)
    if reals.size > 62 and reals[62] != _COSMOS_UNKNOWN:
        checks.check_duration(filename, npts, dt, float(reals[62]), f"{reals[62]:g}", "real header value 63")
    if reals.size > 63 and reals[63] != _COSMOS_UNKNOWN:
        checks.check_peak(filename, values, float(reals[63]), f"{reals[63]:.6f}", "real header value 64", units)
    meta = {"event": lines[1].strip(), "station": lines[4].strip(), "component": "", "header_text": lines[:i]}
    return {"values": values, "dt": dt, "units": units, "t_start": 0.0, "meta": meta}


# --------------------------------------------------------------------------------------------
# GeoNet Volume 2A (rockcli.records.geonet)
# --------------------------------------------------------------------------------------------

def _is_geonet(lines: list[str]) -> bool:
    from rockcli.records.geonet import is_geonet

    return is_geonet(lines)


def _read_geonet(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    from rockcli.records.geonet import read_geonet

    return read_geonet(lines, filename, column)


def _is_cwb(lines: list[str]) -> bool:
    from rockcli.records.cwb import is_cwb

    return is_cwb(lines)


def _read_cwb(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    from rockcli.records.cwb import read_cwb

    return read_cwb(lines, filename, column)


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------

def _header_number(text: str, integer: bool = False):
    """A header value as a plain number (:func:`rockcli.io.inputs.parse_number`: ``1_0`` is not 10); raises
    ``RockcliInputError``, a ``ValueError``, which the readers turn into their sentence on the header."""
    from rockcli.io.inputs import parse_number

    return parse_number(text, "header value", integer=integer, fortran=True)


def _header_value(text: str) -> float:
    """A header value that is checked against the data (NaN, so that no check is made, when it is no number)."""
    try:
        return float(_header_number(text))
    except ValueError:
        return math.nan


_NUMERIC_LINE = re.compile(rf"\s*(?:{_NUM}\s*)*")


def _numeric_block_end(lines: list[str], start: int) -> int:
    """Index of the first line at or after ``start`` that holds something other than numbers (a block's
    end: the next block's header, ``End-of-data``), or ``len(lines)``."""
    k = start
    while k < len(lines) and _NUMERIC_LINE.fullmatch(lines[k]):
        k += 1
    return k


def _refuse_column(column, filename: str, fmt: str) -> None:
    """``--record-column`` picks a column of a text table or a component of a multi-component file; a
    one-component format has neither: refused rather than ignored."""
    if column is not None:
        raise RockcliInputError(f"{filename}: --record-column {column} applies to text tables (and picks a component "
                                f"of a multi-component file); this {fmt} file holds one component: leave it out")


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
    "CWB": (_is_cwb, _read_cwb),
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


#: How messages name the formats rockcli recognises but leaves to the extra.
FORMAT_NAMES = {"USC_VOL1": "USC Volume I", "BHRC_VOL1": "BHRC VOL1", "UNAM_ASA": "UNAM ASA 2.0", "SMC": "USGS SMC",
                "CWB": "CWB"}


def probe(lines: list[str]) -> str | None:
    """Name of the format of a text file from its first lines (None when not recognised)."""
    for name, is_fmt in {k: v[0] for k, v in {**READERS, **REFUSED}.items()}.items():
        try:
            if is_fmt(lines):
                return name
        except Exception:  # noqa: BLE001 -- a probe answers, never raises
            continue
    return None


def refusal(name: str, filename: str) -> RockcliInputError:
    """The error for a recognised but refused format."""
    from rockcli.records.extra import INSTALL_HINT

    return RockcliInputError(f"{filename}: {REFUSED[name][1]}; or {INSTALL_HINT}")
