"""CWB (Central Weather Bureau, Taiwan) ``.dat`` files: a ``#`` header, then a table of time and three channels.

::

    #StationCode: ECU
    #StartTime(GMT+08): 2018/02/06-23:50:29.000
    #RecordLength(sec): 120                  <- record length x sample rate samples (6000)
    #SampleRate(Hz): 50                      <- dt = 0.02 s, checked against the time column
    #AmplitudeUnit:  gal. DCoffset(corr)     <- the units (gal = cm/s^2)
    #AmplitudeMAX. U:    1.196~   -1.017     <- each channel's largest and smallest value
    #DataSequence: Time U(+); N(+); E(+)     <- the order of the columns: up, north, east
    #Data: 4F10.3                            <- the number of columns
         0.000     0.000     0.000     0.000

rockcli reads it itself (light install or not): each channel is a component named as the header names it
(``U``: vertical; ``N``: 0 deg; ``E``: 90 deg), in the units of ``#AmplitudeUnit``, picked with
``--component U|N|E`` or ``--record-column 2-4`` (a text table's columns, the time column counting). What
the header states is checked against the table: the number of columns, the rows (record length x sample
rate), the time step, and each channel's largest and smallest values (:mod:`rockcli.records.checks`).
"""

from __future__ import annotations

import math
import re
from typing import Any

from rockcli.errors import RockcliInputError
from rockcli.records import checks

_NUM = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[Ee][-+]?\d+)?"
#: What each channel letter of ``#DataSequence`` means.
_CHANNELS = {"U": None, "N": 0.0, "E": 90.0}


def is_cwb(lines: list[str]) -> bool:
    return any(l.startswith("#StationCode:") for l in lines[:20]) and any(l.startswith("#Earthquake Information")
                                                                          for l in lines[:3])


def _header(lines: list[str]) -> dict[str, tuple[int, str]]:
    """``key -> (line number, value)`` of the ``#Key: value`` lines before the table."""
    out = {}
    for number, line in enumerate(lines, start=1):
        if not line.startswith("#"):
            if line.strip():
                break
            continue
        key, sep, value = line[1:].partition(":")
        if sep:
            out[key.strip()] = (number, value.strip())
    return out


def read_cwb(lines: list[str], filename: str, column: int | None) -> dict[str, Any]:
    """Channel ``column`` (a table column: 2-4 for ``Time U N E``) of a CWB file, its header checked."""
    from rockcli.records.text import check_time_column, parse_text_table

    head = _header(lines)

    def field(key: str, example: str) -> tuple[int, str]:
        if key not in head:
            raise RockcliInputError(f"{filename}: the CWB header lacks its '#{key}:' line (e.g. '#{key}: {example}')")
        return head[key]

    seq_line, seq_text = field("DataSequence", "Time U(+); N(+); E(+)")
    names = [re.sub(r"\(.*?\)", "", t).strip() for t in re.split(r"[;,\s]+", seq_text) if t.strip()]
    if not names or names[0].lower() != "time" or not all(n.upper() in _CHANNELS for n in names[1:]) or len(names) < 2:
        raise RockcliInputError(f"{filename}, line {seq_line}: '#DataSequence: {seq_text}' does not name a time column "
                                f"then channels U, N, E (e.g. 'Time U(+); N(+); E(+)')")
    channels = [n.upper() for n in names[1:]]
    columns = list(range(2, len(names) + 1))
    if column is None:
        from rockcli.records.components import MultiComponent

        raise MultiComponent(f"{filename}: the CWB file holds {len(channels)} components ({', '.join(channels)}); "
                             f"choose one with --component NAME (or --record-column {columns[0]}-{columns[-1]}, "
                             f"the time column counting)", len(channels), columns)
    if column == 1:
        raise RockcliInputError(f"{filename}: column 1 is the time column ('#DataSequence: {seq_text}'); choose a "
                                f"channel: {', '.join(f'{c} = {k}' for c, k in zip(channels, columns))}")
    if column not in columns:
        raise RockcliInputError(f"{filename}: column {column} does not exist (the CWB file holds the columns "
                                f"{' '.join(names)}: 1-{len(names)})")
    parsed = parse_text_table("\n".join(lines), filename)
    table, row_lines = parsed["table"], parsed["row_lines"]
    if table.shape[1] != len(names):
        raise checks.disagree(filename, f"the columns {' '.join(names)} (line {seq_line})",
                              f"its table has {table.shape[1]} columns (line {row_lines[0]})")
    m = re.match(r"(\d+)F", head.get("Data", (0, ""))[1])
    if m and int(m.group(1)) != table.shape[1]:
        raise checks.disagree(filename, f"{m.group(1)} columns (line {head['Data'][0]}: '#Data: {head['Data'][1]}')",
                              f"its table has {table.shape[1]}")

    dt_step, t0 = check_time_column(table[:, 0], row_lines, filename)
    rate_line, rate_text = field("SampleRate(Hz)", "50")
    rate = _number(rate_text)
    if not (rate > 0 and math.isfinite(rate)):
        raise RockcliInputError(f"{filename}, line {rate_line}: '#SampleRate(Hz): {rate_text}' is not a positive "
                                f"number of samples per second")
    dt = 1.0 / rate
    if not math.isclose(dt_step, dt, rel_tol=1e-3):
        raise checks.disagree(filename, f"{rate_text} samples per second (line {rate_line}: dt = {dt:g} s)",
                              f"its time column steps by {dt_step:g} s")
    npts = table.shape[0]
    if "RecordLength(sec)" in head:
        len_line, len_text = head["RecordLength(sec)"]
        length = _number(len_text)
        if math.isfinite(length) and not math.isclose(length * rate, npts, rel_tol=0.0, abs_tol=1.0):
            more = "fewer" if npts < length * rate else "more"
            raise checks.disagree(filename, f"a record of {len_text} s at {rate_text} Hz (lines {len_line}, "
                                  f"{rate_line}): {length * rate:.0f} rows", f"the table holds {npts} ({more})",
                                  "the file is cut short" if npts < length * rate else
                                  "the table runs on past the stated record length")

    unit_line, unit_text = field("AmplitudeUnit", "gal")
    units = checks.known_units(filename, unit_text.split()[0] if unit_text.split() else None,
                               f"line {unit_line}: '#AmplitudeUnit: {unit_text}'")
    k = columns.index(column)
    name = channels[k]
    values = table[:, column - 1].copy()
    key = next((h for h in head if re.fullmatch(rf"AmplitudeMAX\.\s*{name}", h)), None)
    if key is not None:
        amp_line, amp_text = head[key]
        extremes = re.fullmatch(rf"\s*({_NUM})\s*~\s*({_NUM})\s*", amp_text)
        if extremes:
            for written, value, what in ((extremes.group(1), float(values.max()), "largest"),
                                         (extremes.group(2), float(values.min()), "smallest")):
                stated = float(written)
                if abs(value - stated) > checks.PEAK_RTOL * abs(stated) + checks.last_digit(written):
                    raise checks.disagree(filename, f"{written} {units or ''} as the {what} value of channel {name} "
                                          f"(line {amp_line}: '#{key}: {amp_text}')",
                                          f"column {column} holds {value:g} as its {what}")
    from rockcli.records.components import orientation_meta

    az = _CHANNELS[name]
    orient = ({"azimuth_deg": None, "vertical": True, "orientation_source": f"CWB header line {seq_line}: '{name}'"}
              if az is None else orientation_meta(name, f"CWB header line {seq_line}", azimuth=az))
    meta = {"station": head.get("StationCode", (0, ""))[1], "station_name": head.get("StationName", (0, ""))[1],
            "event": head.get("Origin Time(GMT+08)", (0, ""))[1], "component": name, "column": column, **orient}
    out = {"values": values, "dt": dt, "units": units, "t_start": t0, "meta": meta}
    if units is None:
        out["units_missing"] = f"line {unit_line} holds no units word"
    return out


def _number(text: str) -> float:
    m = re.fullmatch(_NUM, text.strip())
    return float(m.group(0)) if m else math.nan
