"""Components of a record: their names, their orientations, and picking one by name.

A file may hold several components (GeoNet V1A/V2A, a multi-trace ObsPy stream); each becomes a
:class:`~rockcli.records.Record` whose ``meta`` carries

* ``component``: the name the file gives it (channel code ``HN1``/``HNE``/``HNZ``, ``NS``, ``EW2``,
  a bearing such as ``N28W``, an AT2 azimuth such as ``140``);
* ``azimuth_deg``: the direction of positive motion, degrees clockwise from north, in [0, 360),
  when the file states it (None otherwise: nothing is guessed);
* ``vertical``: True for an up/down component;
* ``orientation_source``: where the orientation was read (``header: component '140'``, ...).

:func:`parse_orientation` reads an orientation from what a file says: an azimuth in degrees
(``140``, ``022``, ``360``), a compass bearing (``N28W`` = 332, ``S16W`` = 196), a letter
(``N``, ``E``, ``S``, ``W``), ``NS``/``EW``/``UD`` (K-NET; ``NS2`` KiK-net), a SEED channel code
ending in ``N``/``E``/``Z`` (``HNE`` = 90), or a vertical word (``UP``, ``DWN``, ``V``, ``Z``).
Channel codes ending in ``1``/``2`` say nothing about the azimuth (it is in the station metadata):
None. :func:`select_component` picks a component by name, by ``N``/``E``/``UP``, or by azimuth.
"""

from __future__ import annotations

import math
import re
from typing import Sequence

from rockcli.errors import RockcliInputError

class MultiComponent(RockcliInputError):
    """A file holding several components was read without choosing one (``count`` of them, read with the
    ``columns`` 1 to ``count`` unless the reader names others: a CWB table's channels are its columns 2-4)."""

    def __init__(self, message: str, count: int, columns=None):
        super().__init__(message)
        self.count = count
        self.columns = list(columns) if columns is not None else list(range(1, count + 1))


class NotARecord(RockcliInputError):
    """No reader recognises the file's content (a README, a CSV of sources, a picture): a folder suite skips it."""


def pick_trace(traces, column, path, names: str, what: str = "traces"):
    """The ``column``-th (1-based) of a file's ``traces``; several without ``column``: :class:`MultiComponent`."""
    if not traces:
        raise RockcliInputError(f"{path}: the file holds no traces")
    if len(traces) > 1 and column is None:
        raise MultiComponent(f"{path}: the file holds {len(traces)} {what} ({names}); choose one with --component "
                             f"CHANNEL (or --record-column 1-{len(traces)})", len(traces))
    index = (column or 1) - 1
    if index >= len(traces):
        raise RockcliInputError(f"{path}: trace {column} does not exist (the file holds {len(traces)})")
    return traces[index]


_VERTICAL_WORDS = {"UP", "DWN", "DOWN", "UD", "V", "VER", "VERT", "VERTICAL", "Z"}
_LETTERS = {"N": 0.0, "E": 90.0, "S": 180.0, "W": 270.0, "NS": 0.0, "EW": 90.0, "SN": 180.0, "WE": 270.0}


def parse_orientation(text, *, given: bool = False) -> tuple[float | None, bool]:
    """``(azimuth_deg, vertical)`` from a component name; ``(None, False)`` when it states none.

    A file's name of a component may carry a leading ``_`` (``_H1``, cut from a file name), which is skipped;
    ``given=True`` reads a name the user gave (``--component``) as written: ``_242`` states nothing.

    Examples
    --------
    >>> parse_orientation("140"), parse_orientation("N28W"), parse_orientation("HNZ")
    ((140.0, False), (332.0, False), (None, True))
    """
    s = str(text or "").strip().upper()
    if not s:
        return None, False
    if not given:
        s = re.sub(r"^[_ ]+", "", s)  # "_H1"; a minus is a sign: -242 is 118 deg, and -S62W is no bearing
    if re.fullmatch(r"[-+]?\d{1,3}(\.\d+)?", s):
        value = float(s)
        return (value % 360.0, False) if abs(value) <= 360.0 else (None, False)
    m = re.fullmatch(r"([NS])\s*(\d{1,2}(?:\.\d+)?)\s*([EW])", s)
    if m:
        angle = float(m.group(2))
        if angle > 90.0:
            return None, False
        base = {("N", "E"): angle, ("N", "W"): 360.0 - angle, ("S", "E"): 180.0 - angle,
                ("S", "W"): 180.0 + angle}[(m.group(1), m.group(3))]
        return base % 360.0, False
    word = re.sub(r"\d$", "", s)  # KiK-net NS1/NS2, EW2, UD2
    if word in _VERTICAL_WORDS:
        return None, True
    if word in _LETTERS:
        return _LETTERS[word], False
    if re.fullmatch(r"[A-Z][A-Z0-9][NEZ]", s):  # SEED channel code: band, instrument, orientation
        return (None, True) if s[2] == "Z" else (_LETTERS[s[2]], False)
    return None, False


def orientation_meta(component, source: str, *, azimuth=None) -> dict:
    """``azimuth_deg``, ``vertical`` and ``orientation_source`` for a component name (or a stated azimuth)."""
    if azimuth is not None:
        return {"azimuth_deg": float(azimuth) % 360.0, "vertical": False, "orientation_source": source}
    az, vertical = parse_orientation(component)
    if az is None and not vertical:
        return {"azimuth_deg": None, "vertical": False, "orientation_source": ""}
    return {"azimuth_deg": az, "vertical": vertical, "orientation_source": f"{source}: component {str(component)!r}"}


def describe(rec) -> str:
    """``HN1  196 deg  0.0042 g`` for a listing."""
    return f"{component_name(rec)} ({orientation_text(rec)}), PGA {rec.pga_g:.4g} g"


def component_name(rec) -> str:
    return str(rec.meta.get("component") or "?")


def orientation_text(rec) -> str:
    if rec.meta.get("vertical"):
        return "vertical"
    az = rec.meta.get("azimuth_deg")
    return "orientation not stated" if az is None else f"{az:g} deg"


def _same_angle(a: float, b: float) -> bool:
    return abs((a - b + 180.0) % 360.0 - 180.0) < 1e-9


def select_component(records: Sequence, name, filename: str):
    """The component of ``records`` named ``name``: a channel code as the file gives it (letter case
    ignored), ``N``/``E``/``S``/``W``/``UP`` (matched by orientation) or an azimuth in degrees."""
    wanted = str(name).strip()
    listing = "; ".join(describe(r) for r in records)
    exact = [r for r in records if component_name(r).upper() == wanted.upper()]
    if len(exact) == 1:
        return exact[0]
    az, vertical = parse_orientation(wanted, given=True)  # as written: "_242" is no azimuth
    if vertical:
        found = [r for r in records if r.meta.get("vertical")]
    elif az is not None:
        found = [r for r in records if r.meta.get("azimuth_deg") is not None and _same_angle(r.meta["azimuth_deg"], az)]
    else:
        found = []
    if len(found) == 1:
        return found[0]
    if len(found) > 1:
        raise RockcliInputError(f"{filename}: --component {wanted} matches {len(found)} components ({listing}); "
                                f"name one by its channel code")
    given = _plain_angle(wanted)
    said = f" ({wanted} deg is {az:g} deg clockwise from north)" if az is not None and given not in (None, az) else ""
    raise RockcliInputError(f"{filename}: no component {wanted!r}{said} (the file holds: {listing})")


def _plain_angle(text: str):
    try:
        return float(text)
    except ValueError:
        return None


def horizontal_pair(records: Sequence, filename: str):
    """The two horizontal components of a multi-component file (refused unless exactly two, both oriented)."""
    horiz = [r for r in records if not r.meta.get("vertical")]
    if len(horiz) != 2:
        raise RockcliInputError(f"{filename}: an azimuth needs two horizontal components, the file holds "
                                f"{len(horiz)} ({'; '.join(describe(r) for r in records)})")
    return horiz[0], horiz[1]


def check_angle(value, what: str) -> float:
    """A finite angle in degrees."""
    v = float(value)
    if not math.isfinite(v):
        raise RockcliInputError(f"{what} must be a finite angle in degrees, got {value!r}")
    return v


def record_text(rec) -> str:
    """``rec`` as a plain text record that rockcli reads back identically: comments with its source, time step
    and units (m/s^2), then one sample per line written with 17 significant digits (a float64 round trip)."""
    from rockcli.io.inputs import format_number

    head = [f"# rockcli export of {rec.meta.get('path') or rec.name}",
            f"# component: {component_name(rec)} ({orientation_text(rec)})",
            f"# dt={format_number(rec.dt)} sec", "# units: m/s^2"]
    if rec.t_start:
        head.append(f"# start time {format_number(rec.t_start)} s (not read back: the record starts at 0)")
    return "\n".join(head + [format(float(v), ".17g") for v in rec.acc]) + "\n"
