"""GeoNet Volume 2A (New Zealand): three components, each a 26-line header and three data blocks.

Layout of one component (lines counted from its first line)::

    1      Corrected accelerogram <id> GNS Science
    2      Site <code> ...                                  <- station code
    7      <event>
    10     Number of points  8192    Duration 163.82 sec    <- samples per block, (npts - 1) x dt
    11     Instrument corrected data at 0.020 sec intervals <- dt
    13     Component N28W ...                               <- bearing of the component
    14     Acceleration:  peak  -9733.1 mm/s/s at ...       <- the peak and its units
    15     Velocity:      peak -1016.55 mm/s   at ...
    16     Displacement:  peak  234.852 mm     at ...
    17-20  integer header (10 a line); line 20 holds the points of the three blocks (values 4-6)
    21-26  real header (10 a line); line 23, value 6 is dt
    27-    acceleration, velocity and displacement blocks, 10 values a line (10F8.1)

Everything the header states about the data is checked against them (:mod:`rockcli.records.checks`):
the points on line 10 against the integer header and against the blocks (the component's values are
exactly its three blocks, and the acceleration block ends where its lines end), dt on line 11 against
the real header, the duration against points x dt, the peak on line 14 against the acceleration block,
and the units word of line 14 against those of lines 15-16 (one length unit: mm/s/s, mm/s, mm). A
line 14 without a units word states no units.
"""

from __future__ import annotations

import math
import re
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.records.checks import check_duration, check_peak, disagree, known_units, last_digit

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[EeDd][-+]?\d+)?"
#: Lines of a component's header before its data blocks: 16 text, 4 integer, 6 real.
HEADER_LINES = 26
TEXT_LINES = 16
#: Values per data line.
PER_LINE = 10
_START = re.compile(r"^Corrected accelerogram")


def is_geonet(lines: list[str]) -> bool:
    """A first line ``Corrected accelerogram`` and ``data at ... sec intervals`` in the header (the site line is
    not needed: a blank one leaves the station unnamed)."""
    return (len(lines) > 12 and _START.match(lines[0]) is not None
            and any("data at" in l and "sec intervals" in l for l in lines[:16]))


def component_starts(lines: list[str]) -> list[int]:
    return [k for k, line in enumerate(lines) if _START.match(line)]


def _component_name(lines: list[str], s: int) -> str:
    m = re.match(r"^Component\s+(\S+)", lines[s + 12]) if s + 12 < len(lines) else None
    return m.group(1) if m else "?"


def read_geonet(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    """Component ``column`` (1-based) of a GeoNet V2A file, its header checked against its data."""
    starts = component_starts(lines)
    comps = [_component_name(lines, s) for s in starts]
    if column is None:
        from rockcli.records.components import MultiComponent

        raise MultiComponent(
            f"{filename}: GeoNet V2A file holds {len(starts)} components ({', '.join(comps)}); "
            f"choose one with --component NAME (or --record-column 1-{len(starts)})", len(starts))
    if not 1 <= column <= len(starts):
        raise RockcliInputError(f"{filename}: column {column} does not exist (the file holds {len(starts)} components)")
    s = starts[column - 1]
    end = starts[column] if column < len(starts) else len(lines)
    which = f"component {column} ({comps[column - 1]})"
    if end - s < HEADER_LINES:
        raise RockcliInputError(f"{filename}, line {s + 1}: the header of {which} has {end - s} lines where a GeoNet "
                                f"V2A component has {HEADER_LINES} before its data")
    head = lines[s:s + TEXT_LINES]

    def field(pattern: str, what: str):
        for k, line in enumerate(head):
            m = re.search(pattern, line)
            if m:
                return m, s + k + 1
        raise RockcliInputError(f"{filename}: the GeoNet V2A header of {which} (lines {s + 1}-{s + TEXT_LINES}) "
                                f"lacks {what}")

    m_n, n_line = field(r"Number of points\s+(\d+)", "its number of points ('Number of points  8192')")
    m_dt, dt_line = field(rf"data at\s+({_NUM}) sec intervals", "its interval ('data at 0.020 sec intervals')")
    m_acc, acc_line = field(rf"Acceleration:\s+peak\s+({_NUM})\s+(\S+)", "its peak ('Acceleration:  peak  -9733.1 "
                                                                        "mm/s/s at ...')")
    npts, dt_text = int(m_n.group(1)), m_dt.group(1)
    dt = float(dt_text)
    ints = _header_numbers(lines, s + TEXT_LINES, 4, filename, which, "integer")
    reals = _header_numbers(lines, s + TEXT_LINES + 4, 6, filename, which, "real")
    n_acc, n_vel, n_disp = (int(v) for v in ints[33:36])
    where_n = f"line {n_line}: 'Number of points  {npts}'"
    if n_acc != npts:
        raise disagree(filename, f"{npts} points ({where_n})", f"its integer header (line {s + TEXT_LINES + 4}, value "
                       f"4) states {n_acc}: the two disagree")
    dt_real = float(reals[25])
    if abs(dt_real - dt) > max(last_digit(dt_text), 1e-12):
        raise disagree(filename, f"data at {dt_text} s intervals (line {dt_line})", f"its real header (line "
                       f"{s + TEXT_LINES + 7}, value 6) states {dt_real:g} s: the two disagree")
    # the blocks: the component's values are exactly its three blocks, and the acceleration block ends
    # with its lines (ceil(npts / 10) of them)
    from rockcli.records.at2 import parse_numbers

    data = lines[s + HEADER_LINES:end]
    values = parse_numbers(data, s + HEADER_LINES + 1, filename)
    total = n_acc + n_vel + n_disp
    if values.size != total:
        blocks = f"{n_acc} acceleration + {n_vel} velocity + {n_disp} displacement values"
        raise disagree(filename, f"{blocks} for {which} ({where_n} and the integer header, line "
                       f"{s + TEXT_LINES + 4})", f"lines {s + HEADER_LINES + 1}-{end} hold {values.size} values"
                       f" ({'fewer' if values.size < total else 'more'})",
                       "the file is cut short" if values.size < total else
                       "reading the stated count would cut the record or read the velocity block as acceleration")
    acc_rows = math.ceil(n_acc / PER_LINE)
    in_rows = parse_numbers(data[:acc_rows], s + HEADER_LINES + 1, filename).size
    if in_rows != n_acc:
        raise disagree(filename, f"{n_acc} acceleration values ({where_n}), {acc_rows} lines of {PER_LINE}",
                       f"lines {s + HEADER_LINES + 1}-{s + HEADER_LINES + acc_rows} hold {in_rows} values")
    acc = values[:n_acc]
    m_dur = re.search(rf"Duration\s+({_NUM})", lines[n_line - 1])
    if m_dur:
        check_duration(filename, npts, dt, float(m_dur.group(1)), m_dur.group(1), f"line {n_line}")


    units = _units(filename, m_acc.group(2), acc_line, head, s)
    check_peak(filename, acc, float(m_acc.group(1)), m_acc.group(1), f"line {acc_line}: 'Acceleration:  peak  "
               f"{m_acc.group(1)}'", units or "")
    site = lines[s + 1].split()
    meta = {"event": lines[s + 6].strip(), "station": site[1] if len(site) > 1 and site[0] == "Site" else "",
            "component": comps[column - 1]}
    out = {"values": acc, "dt": dt, "units": units, "t_start": 0.0, "meta": meta}
    if units is None:
        out["units_missing"] = f"line {acc_line} has no units word after the peak"
    return out


def _header_numbers(lines, start: int, count: int, filename, which: str, kind: str) -> np.ndarray:
    """The ``count`` lines of the integer or real header (10 values each)."""
    from rockcli.records.at2 import parse_numbers

    values = parse_numbers(lines[start:start + count], start + 1, filename)
    if values.size != count * PER_LINE:
        raise RockcliInputError(f"{filename}, lines {start + 1}-{start + count}: the {kind} header of {which} holds "
                                f"{values.size} values where a GeoNet V2A header has {count * PER_LINE}")
    return values


def _units(filename, word: str, line: int, head: list[str], s: int) -> str | None:
    """The units word after the acceleration peak (None when the line has none: ``peak -9733.1 at``), known,
    and of the length unit the velocity and displacement lines use."""
    if word.lower() == "at":
        return None
    units = known_units(filename, word, f"line {line}")
    length = units.split("/")[0].lower()
    for k, line_text in enumerate(head):
        m = re.search(rf"^(Velocity|Displacement):\s+peak\s+{_NUM}\s+(\S+)", line_text)
        if m and m.group(2).lower() != "at" and m.group(2).split("/")[0].lower() != length:
            raise disagree(filename, f"acceleration in {units} (line {line})", f"line {s + k + 1} states the "
                           f"{m.group(1).lower()} in {m.group(2)}: the length units disagree")
    return units
