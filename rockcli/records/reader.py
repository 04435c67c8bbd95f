"""One loader for every record source: :func:`read_record`."""

from __future__ import annotations

import math
import os
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.records.components import MultiComponent, NotARecord
from rockcli.records.record import Record
from rockcli.io.units import G

#: Format names rockcli parses itself (anything else is handed to ``obspy.read``).
TEXT_FORMATS = {"TEXT", "TXT", "ASCII"}
AT2_FORMATS = {"PEER_AT2", "AT2"}
#: Bytes probed to tell text formats apart.
_PROBE_BYTES = 8192
#: Supported time step of a record [s]: 1 us (1 MHz) to 10 s. Strong-motion records are sampled at 50 Hz
#: to a few kHz; a step outside this range is a unit mistake (``dt=10`` meant as ms), and ``dt=1e-300``
#: would make every time a denormal.
DT_RANGE_S = (1e-6, 10.0)
#: Largest peak of a record [g], as for pulses (:data:`rockcli.pulses.A_P_MAX_G`): recorded peaks reach
#: about 4 g; a record in cm/s^2 read as g peaks in the hundreds.
PGA_MAX_G = 100.0


def _check_units(units):
    if units is None:
        return None
    from rockcli.io.units import accel_factor

    accel_factor(units)  # raises on an unknown word
    return str(units)


def _num(x) -> str:
    """A number in a message exactly as it reads back (never rounded: 0.0100001 stays 0.0100001)."""
    from rockcli.io.inputs import format_number

    return format_number(x)


def _check_dt(dt):
    if dt is None:
        return None
    try:
        value = float(dt)
    except (TypeError, ValueError):
        raise RockcliInputError(f"time step dt={dt!r} is not a number") from None
    if not math.isfinite(value) or value <= 0:
        raise RockcliInputError(f"time step dt={_num(value)} s must be a positive finite number")
    return value


def check_gain(gain, units):
    """``gain`` as a positive finite float (None when not given); it needs ``units``, the units it yields."""
    if gain is None:
        return None
    from rockcli.io.inputs import parse_number

    value = parse_number(gain, "--gain", lo=0, lo_open=True)
    if units is None:
        raise RockcliInputError(f"--gain {_num(value)} needs --units: the units the gain yields from counts "
                                f"(g, m/s^2, cm/s^2, gal, mm/s^2, g/10)")
    return value


def _check_column(column):
    if column is None:
        return None
    try:
        value = int(column)
    except (TypeError, ValueError):
        raise RockcliInputError(f"column {column!r} is not a whole number (columns count from 1)") from None
    if value < 1 or value != float(column):
        raise RockcliInputError(f"column {column!r} must be a whole number >= 1 (columns count from 1)")
    return value


def read_record(source, *, format=None, units=None, dt=None, column=None, component=None, gain=None,
                fill_in: bool = False) -> Record:
    """Read a ground-acceleration record from a file or the catalogue.

    Parameters
    ----------
    source : str or path-like
        A file path, or a catalogue id (see :func:`rockcli.records.catalog.load_catalog`).
        Files: PEER NGA ``.AT2`` (all header layouts), plain text, ESM ASCII, ITACA ``.cor.acc``,
        COSMOS V2, GeoNet V2A, CWB, and any format ObsPy reads (SAC, MiniSEED, K-NET/KiK-net, ...).
        Every reader checks what the file's header says against its data (counts, durations, peaks,
        scale factors, units words) and refuses a disagreement.
        The format is detected unless ``format`` is given.
    format : str, optional
        ``PEER_AT2``, ``TEXT``, ``ESM``, ``ITACA``, ``COSMOS``, ``GEONET_V2A``, ``CWB`` or an ObsPy
        format name (``SAC``, ``MSEED``, ``KNET``, ...).
    units : str, optional
        Units of the values in the file (``g``, ``m/s^2``, ``cm/s^2``, ``gal``, ``mm/s^2``,
        ``g/10``). Required when the file does not state them; must agree with the file when it does.
    dt : float, optional
        Time step [s]. Required when the file does not state it; must agree with the file when it does.
    column : int, optional
        1-based column of a multi-column text file or CWB table (a time column counts), or component of
        a multi-component file (GeoNet V2A) or trace of a multi-trace ObsPy stream; refused for a file
        of one component (AT2, ESM, ITACA, COSMOS).
    component : str, optional
        Component of a multi-component file by name: its channel code (``HN1``, ``HNE``, ``N28W``,
        ``EW2``), ``N``/``E``/``UP`` or an azimuth in degrees, its sign kept (-242 is 118 deg; see
        :func:`rockcli.records.components.select_component`).
    gain : float, optional
        Factor from raw counts to ``units`` (which must then be given: the units the gain yields,
        ``gain=1.2e-6, units="m/s^2"``). A file in raw counts (integer samples read by ObsPy, a text
        file or gmprocess stating ``counts``) is refused without it; a file that states physical
        units is refused with it (unless ``fill_in``); a file that states no units is taken as counts.
    fill_in : bool
        ``units``, ``dt`` and ``gain`` only fill in what the file does not state (a suite's defaults): a
        file that states other ones is read as it states them, not refused.

    Returns
    -------
    Record
        Acceleration [m/s^2] (float64), ``dt`` [s], ``t_start`` [s] as stated by the source, and
        ``meta`` with ``units`` (as stated in the file or given), ``units_source``, ``factor``
        (applied to reach m/s^2), ``format``, ``path`` and what the file says about the
        event, station and component. Catalogue records also carry ``catalog_id``.

    Raises
    ------
    RockcliInputError
        Missing, empty or malformed file; units or time step neither stated nor given, or given
        in contradiction with the file; unknown units word; non-positive dt; NaN/inf samples;
        uneven sampling; a format that is out of scope.

    Examples
    --------
    >>> rec = read_record("RSN1119_KOBE_TAZ000.AT2")                 # doctest: +SKIP
    >>> rec = read_record("kobe-1995-takarazuka-000")                # doctest: +SKIP
    >>> rec = read_record("C02-065", units="g", dt=0.01)             # doctest: +SKIP
    """
    _check_source(source)
    units = _check_units(units)
    dt = _check_dt(dt)
    gain = check_gain(gain, units)
    column = _check_column(column)
    fmt = str(format).strip().upper() if format else None
    if component is not None:
        if column is not None:
            raise RockcliInputError("give the component either by --component NAME or by --record-column N, not both")
        from rockcli.records.components import select_component

        comps = read_components(source, format=format, units=units, dt=dt, gain=gain, fill_in=fill_in)
        return select_component(comps, component, _label(source, comps))

    if isinstance(source, Record):
        return source
    if isinstance(source, str) and not path_exists(source):
        entry = _catalog_entry(source)
        if entry is not None:
            return _read_entry(entry, entry.component, entry.file, fmt, units, dt, column, gain)
        if os.sep not in source and "/" not in source:
            found = _in_records_folders(source)
            if found is None:
                from rockcli.records.catalog import did_you_mean

                raise RockcliInputError(f"{source}: no such file here or in the ROCKCLI_RECORDS folders, nor a "
                                        f"catalogue id{did_you_mean(source)} (see 'rockcli records list')")
            source = found
    return _read_path(Path(source), fmt, units, dt, column, given_by="suite" if fill_in else "caller", gain=gain)


def _check_source(source) -> None:
    """A record's source is a path (text or path-like), a catalogue id or a :class:`Record`: else one sentence."""
    from rockcli.io.inputs import check_type

    check_type(source, (str, os.PathLike, Record), "source", "a record file's path or a catalogue id (text)")


def path_exists(text) -> bool:
    """``Path(text).exists()``, True for a path that is there but cannot be looked at (a folder without
    permission: the reader then says "cannot be read (permission denied)") and False for text that is no path
    (a NUL byte), instead of the exceptions pathlib raises."""
    try:
        return Path(text).exists()
    except OSError:
        return True
    except ValueError:
        return False


def _in_records_folders(name: str) -> Path | None:
    """A bare file name that is not in the current folder: the file of that name in the first folder of
    :func:`rockcli.records.catalog.search_path` (``ROCKCLI_RECORDS``) that holds one, as for a catalogue
    record's file (None when none does)."""
    from rockcli.records.catalog import is_file, search_path

    for folder in search_path():
        candidate = folder / name
        if is_file(candidate):
            return candidate
    return None


def _catalog_entry(source):
    """The catalogue entry ``source`` names (None when it is not a catalogue id); a catalogue that cannot be
    read is said as such, not as "no such file, nor a catalogue id"."""
    if not isinstance(source, str) or os.sep in source or "/" in source or path_exists(source):
        return None
    from rockcli.records.catalog import catalog_ids

    return catalog_ids().get(source)


def _read_entry(entry, component: str, file: str, fmt, units, dt, column, gain) -> Record:
    """One component (``component``, in ``file``) of a catalogue entry, read as the catalogue says."""
    from rockcli.records.catalog import find_file, search_path
    from rockcli.records.components import orientation_meta

    if not entry.available:
        raise RockcliInputError(f"catalogue record {entry.id!r} has no public file ({entry.notes})")
    path = find_file(entry, file)
    if path is None:
        folders = ", ".join(str(f) for f in search_path())
        which = "" if file == entry.file else f" (component {component})"
        raise RockcliInputError(f"catalogue record {entry.id!r}: file {file!r}{which} not found in {folders} "
                                f"(set ROCKCLI_RECORDS to the folder holding it)")
    rec = _read_path(path, fmt or entry.format or None, units or entry.units, dt or entry.dt,
                     column or entry.column, given_by="caller" if units else "catalogue", gain=gain)
    orient = orientation_meta(component, "catalogue")
    if orient["azimuth_deg"] is None and not orient["vertical"]:
        orient = {k: rec.meta.get(k) for k in ("azimuth_deg", "vertical", "orientation_source")}
    meta = {**rec.meta, "catalog_id": entry.id, "event": entry.event, "year": entry.year,
            "station": entry.station, "component": component, **orient,
            "file_meta": {k: rec.meta.get(k) for k in ("event", "station", "component")}}
    return Record(acc=rec.acc, dt=rec.dt, name=entry.id, t_start=rec.t_start, meta=meta)


def _label(source, comps) -> str:
    return str(comps[0].meta.get("path") or source) if comps else str(source)


def read_components(source, *, format=None, units=None, dt=None, gain=None, fill_in: bool = False) -> list[Record]:
    """Every component of a record file (or catalogue id), each a :class:`Record` with its name and
    orientation in ``meta`` (``component``, ``azimuth_deg``, ``vertical``); one for a one-component file."""
    _check_source(source)
    kw = {"format": format, "units": units, "dt": dt, "gain": gain, "fill_in": fill_in}
    entry = _catalog_entry(source)
    if entry is not None and len(entry.components) > 1:  # a catalogue row naming several components
        fmt = str(format).strip().upper() if format else None
        return [_read_entry(entry, comp, file, fmt, _check_units(units), _check_dt(dt), None, check_gain(gain, units))
                for comp, file in entry.components]
    try:
        return [read_record(source, **kw)]
    except MultiComponent as multi:
        return [read_record(source, column=k, **kw) for k in multi.columns]


def _read_path(path: Path, fmt, units, dt, column, given_by: str = "caller", gain=None) -> Record:
    from rockcli.records.at2 import check_record_file

    name = str(path)
    if check_record_file(path) == 0:
        raise RockcliInputError(f"{name}: the file is empty")

    try:
        with open(path, "rb") as fh:
            head = fh.read(_PROBE_BYTES)
    except OSError as exc:
        raise RockcliInputError(f"{name}: cannot be read ({(exc.strerror or str(exc)).lower()})") from None
    kind = compression(head)
    if kind is not None:
        from rockcli.records.compressed import read_compressed

        return read_compressed(path, kind, lambda inner: _read_path(inner, fmt, units, dt, column, given_by, gain))
    from rockcli.records.at2 import strip_bom

    head = strip_bom(head)
    is_text = b"\x00" not in head
    head_lines = head.decode("latin-1").splitlines() if is_text else []

    if fmt is None:
        fmt = _detect(path, head_lines, is_text)
    if fmt in AT2_FORMATS:
        if column is not None:
            raise RockcliInputError(f"{name}: --record-column {column} applies to text tables (and picks a component "
                                    f"of a multi-component file); a PEER AT2 file holds one component: leave it out")
        out = _from_at2(path)
    elif fmt in TEXT_FORMATS:
        out = _from_text(path, column)
    else:
        from rockcli.records import formats

        from rockcli.records import extra

        if fmt in formats.REFUSED:
            if not extra.available():
                raise formats.refusal(fmt, name)
            out = extra.read_with_extra(path, column, recognised=fmt)
        elif fmt in formats.READERS:
            from rockcli.records.at2 import read_text

            lines = read_text(path).splitlines()
            out = formats.READERS[fmt][1](lines, name, column)
            out.setdefault("dt_source", "header")
        else:
            try:
                out = _from_obspy(path, fmt, column)
            except NotARecord as exc:
                if fmt != "OBSPY":
                    raise
                if not extra.available():
                    raise NotARecord(f"{exc}; if it is an agency format, {extra.INSTALL_HINT}") from None
                out = extra.read_with_extra(path, column)  # imported only now: rockcli's readers and ObsPy failed
    out.setdefault("format", fmt)
    return _finish(path, out, units, dt, given_by, gain)


def compression(head: bytes) -> str | None:
    """``gzip``, ``bzip2``, ``zip`` or ``xz`` when the first bytes of a file say it is compressed, else None."""
    from rockcli.records.compressed import MAGIC

    for magic, kind in MAGIC.items():
        if head.startswith(magic):
            return kind
    return None


def _looks_like_text_table(lines: list[str]) -> bool:
    """True when the first data line (after comments and at most one line of column names) is numeric."""
    from rockcli.records.text import COMMENT_CHARS, _SEP_RE, _is_number

    seen_names = False
    for raw in lines[:50]:
        line = raw.strip()
        if not line or line[0] in COMMENT_CHARS or line.startswith("//"):
            continue
        tokens = [t for t in _SEP_RE.split(line) if t]
        numeric = [_is_number(t) for t in tokens]
        if all(numeric):
            return True
        if seen_names or any(numeric):
            return False
        seen_names = True
    return False


def _claims_at2(path: Path, head_lines: list[str]) -> bool:
    """True when a text file that is not a valid AT2 says it is one: ``.AT2`` suffix, a first line
    naming PEER, or NPTS on line 4."""
    from rockcli.records.at2 import _split_lines

    lines = _split_lines("\n".join(head_lines)) if head_lines else []
    if path.suffix.lower() == ".at2":
        return True
    if lines and "PEER" in lines[0].upper():
        return True
    # line 4 opens with NPTS or DT, or is the old "n  dt  NPTS, DT" layout (a CSV that merely mentions
    # NPTS in a note is not an AT2)
    return len(lines) >= 4 and re.match(r"\s*(NPTS\b|DT\b|\d+\s+\S+\s+NPTS)", lines[3].upper()) is not None


def _detect(path: Path, head_lines: list[str], is_text: bool) -> str:
    from rockcli.records.at2 import _is_at2

    if is_text:
        if _is_at2(path):
            return "PEER_AT2"
        from rockcli.records import formats

        found = formats.probe(head_lines)
        if found:
            return found
        if _claims_at2(path, head_lines):  # a broken AT2: its parser names the line and what it expected
            return "PEER_AT2"
        if _looks_like_text_table(head_lines):
            return "TEXT"
    return "OBSPY"  # let ObsPy try its own detection


def _from_at2(path: Path) -> dict[str, Any]:
    from rockcli.records.at2 import parse_at2

    values, header = parse_at2(path)
    if header["quantity"] not in (None, "acceleration"):
        raise RockcliInputError(f"{path}: the AT2 file holds {header['quantity']}, not acceleration")
    meta = {k: header.get(k, "") for k in ("event", "station", "component", "date")}
    meta["header"] = header
    return {"values": values, "dt": header["dt"], "dt_source": "header", "units": header["units"],
            "t_start": 0.0, "meta": meta, "format": "PEER_AT2"}


def _from_text(path: Path, column) -> dict[str, Any]:
    from rockcli.records.at2 import read_text
    from rockcli.records.text import parse_text

    parsed = parse_text(read_text(path), str(path), column)
    meta = {"column": parsed["column"], "ncols": parsed["ncols"], "time_column": parsed["time_column"],
            "comments": parsed["comments"]}
    if parsed["names"]:
        meta["column_names"] = parsed["names"]
    for line in parsed["comments"] or ():  # "# component: N28W (332 deg)", as `records export` writes it
        m = re.search(r"component:\s*(\S+)\s*\((vertical|[\d.]+ deg)\)", str(line))
        if m:
            from rockcli.records.components import orientation_meta

            az = None if m.group(2) == "vertical" else float(m.group(2).split()[0])
            meta.update(component=m.group(1), **orientation_meta(m.group(1), "comment", azimuth=az))
            if az is None:
                meta.update(vertical=True, azimuth_deg=None, orientation_source="comment: vertical")
            break
    return {"values": parsed["values"], "dt": parsed["dt"], "dt_source": parsed["dt_source"],
            "units": parsed["units"], "t_start": parsed["t_start"], "meta": meta, "format": "TEXT"}


def _from_obspy(path: Path, fmt: str, column) -> dict[str, Any]:
    import obspy

    try:
        with warnings.catch_warnings():  # a K-NET scale factor of 0 is refused below, in one sentence
            warnings.filterwarnings("ignore", message="Calibration factor set to 0")
            st = obspy.read(str(path), format=None if fmt == "OBSPY" else fmt)
    except TypeError as exc:  # ObsPy: "Unknown format for file ..." / "Format ... is not supported"
        if fmt != "OBSPY" and "not supported" in str(exc):
            raise RockcliInputError(
                f"{path}: unknown format {fmt!r} (rockcli reads PEER_AT2, TEXT, ESM, ITACA, COSMOS, GEONET_V2A, CWB "
                f"and ObsPy's formats such as SAC, MSEED, KNET)") from None
        raise NotARecord(f"{path}: format not recognised{reason_words(exc)}; "
                         f"give it with --format, or convert the record to text") from None
    except Exception as exc:  # noqa: BLE001 -- ObsPy readers raise many kinds; one sentence for the user
        sizes = re.search(r"Actual/Theoretical:\s*(\d+)/(\d+)", str(exc))  # SAC: NPTS against the file's size
        if sizes:
            from rockcli.records.checks import disagree

            raise disagree(path, f"a SAC file of {sizes.group(2)} bytes (its NPTS samples after the header)",
                           f"the file holds {sizes.group(1)} bytes") from None
        raise RockcliInputError(f"{path}: format not recognised, or a damaged file{reason_words(exc, 'ObsPy')}; "
                                f"give the format with --format, or convert the record to text") from None
    from rockcli.records.components import pick_trace

    tr = pick_trace(list(st), column, path, ", ".join(tr.id for tr in st))
    stats = tr.stats
    fmt_name = str(stats.get("_format", fmt))
    values = np.asarray(tr.data, dtype=np.float64)
    meta: dict[str, Any] = {"station": ".".join(x for x in (stats.network, stats.station) if x),
                            "component": stats.channel, "trace_id": tr.id, "starttime": str(stats.starttime)}
    units = None
    if "peer_at2" in stats:  # rockcli's own ObsPy plugin already converted the file's units: never twice
        units = str(stats.peer_at2.get("data_units", "m/s^2"))
        meta["units_note"] = (f"the file states {stats.peer_at2.get('units')}; ObsPy's PEER_AT2 reader converted "
                              f"them to m/s^2")
    if fmt_name == "KNET":
        # ObsPy's calib converts counts to m/s^2 from the stated "Scale Factor ...(gal)/..."; the
        # NIED peak ("Max. Acc.") is measured after removing the mean, so we remove it too.
        from rockcli.records.knet import knet_gal

        values = knet_gal(path, values, stats.calib)  # counts x the header's gal per count, checked
        values = values - values.mean()
        units = "gal"
        meta.update(units_note="counts x the stated scale factor (gal)",
                    processing="mean removed (as the header's Max. Acc.)", knet=dict(stats.knet))
    elif values.size and np.issubdtype(tr.data.dtype, np.integer):
        # integer samples (MiniSEED, GSE2, ... in counts): raw digitizer output, refused unless a gain is given
        units = "counts"
        meta["units_note"] = f"integer samples in the {fmt_name} file"
    if fmt_name == "SAC":
        # SAC's IDEP says what the quantity is, not its units (and writers rarely follow its nm
        # convention): the units are not stated.
        meta["sac_idep"] = int(stats.sac.get("idep", -12345))
        cmpaz, cmpinc = float(stats.sac.get("cmpaz", -12345.0)), float(stats.sac.get("cmpinc", -12345.0))
        if cmpinc == 0.0 or cmpinc == 180.0:
            meta.update(vertical=True, azimuth_deg=None, orientation_source="SAC header CMPINC")
        elif cmpinc == 90.0 and cmpaz != -12345.0:
            meta.update(vertical=False, azimuth_deg=cmpaz % 360.0, orientation_source="SAC header CMPAZ")
    if float(stats.calib) != 1.0 and fmt_name != "KNET":
        meta["calib"] = float(stats.calib)
    if values.size and not np.all(np.isfinite(values)):
        i = int(np.argmax(~np.isfinite(values)))
        raise RockcliInputError(f"{path}: sample {i + 1} is {float(values[i])!r}, not a finite number")
    return {"values": values, "dt": float(stats.delta), "dt_source": "header", "units": units,
            "units_source": meta.get("units_note", "file") if units == "counts" else "file",
            "t_start": 0.0, "meta": meta, "format": fmt_name}


def reason_words(exc: BaseException, who: str = "") -> str:
    """`` (<who>: <the first line of exc's message>)`` for a refusal, or ``""`` when the message says nothing
    (empty, or only that no format was found): an exception's class name (``StopIteration``) means nothing
    to a user."""
    text = str(exc).strip().splitlines()
    line = text[0].strip().rstrip(".") if text else ""
    if not line or line.lower().startswith("no format found"):
        return ""
    return f" ({who}: {line})" if who else f" ({line})"


def _orientation(path: Path, fmt, component) -> dict:
    """Orientation from the component name the file gives; for an AT2 file whose header names none, from
    the PEER file name (station code and a three-digit azimuth: ``RSN181_IMPVALL.H_H-E06140.AT2``: 140)."""
    from rockcli.records.components import orientation_meta

    where = "AT2 header line 2" if fmt == "PEER_AT2" else f"{fmt} header"
    found = orientation_meta(component, where)
    if found["azimuth_deg"] is None and not found["vertical"] and fmt == "PEER_AT2":
        # PEER NGA names end in station code + three-digit azimuth: ..._H-E06140, ..._TAZ000, ..._A-STU270
        m = re.search(r"[-_.][A-Z][A-Z0-9]*?(\d{3})$", re.sub(r"(?i)\.at2$", "", path.name).upper())
        if m and int(m.group(1)) <= 360:
            found = orientation_meta(m.group(1), "AT2 file name")
    return found


def _finish(path: Path, out: dict[str, Any], units, dt, given_by: str, gain=None) -> Record:
    """Reconcile stated and given units and time step, convert to m/s^2, build the Record."""
    from rockcli.io.units import accel_factor, is_counts

    name = str(path)
    stated_units = out.get("units")
    counts = stated_units is not None and is_counts(stated_units)
    if stated_units is not None and not counts and gain is not None and given_by != "suite":
        raise RockcliInputError(f"{name}: the file states units {stated_units!r}, not raw counts; --gain applies "
                                f"only to a file in counts")
    if counts or (stated_units is None and gain is not None):
        if gain is None:
            said = out.get("units_source") if out.get("units_source") not in (None, "file") else "stated by the file"
            raise RockcliInputError(f"{name}: the samples are raw counts ({said}); give --gain FACTOR with --units "
                                    f"UNITS, the factor from counts to those units (e.g. --gain 1.2e-6 --units m/s^2)")
        factor = gain * accel_factor(units)
        used_units = "counts"
        units_source = (f"{out.get('units_source') or 'file'}; gain {_num(gain)} {units} per count "
                        f"({'given' if given_by != 'catalogue' else 'from the catalogue'})")
    elif stated_units is not None:
        try:
            factor = accel_factor(stated_units)
        except RockcliInputError:
            from rockcli.io.units import KNOWN_UNITS

            raise RockcliInputError(f"{name}: the file states units {stated_units!r}, which rockcli does not know "
                                    f"(known: {KNOWN_UNITS}; give the file's units in one of these words)") from None
        if units is not None and given_by != "suite" and not math.isclose(accel_factor(units), factor, rel_tol=1e-9):
            raise RockcliInputError(f"{name}: the file states units {stated_units!r} but {units!r} was given")
        used_units, units_source = stated_units, out.get("units_source", "file")
    elif units is not None:
        used_units, units_source = units, given_by
        factor = accel_factor(units)
    else:
        why = f" ({out['units_missing']})" if out.get("units_missing") else ""
        raise RockcliInputError(f"{name}: the file does not state its units{why}; give them with --units "
                                f"(g, m/s^2, cm/s^2, gal, mm/s^2, g/10)")

    stated_dt = out.get("dt")
    if stated_dt is not None:
        if not stated_dt > 0:
            raise RockcliInputError(f"{name}: the file states a time step of {_num(stated_dt)} s; it must be positive")
        if dt is not None and given_by != "suite" and not math.isclose(dt, stated_dt, rel_tol=1e-6):
            raise RockcliInputError(f"{name}: the file states dt={_num(stated_dt)} s but dt={_num(dt)} s was given")
        used_dt, dt_source = float(stated_dt), out.get("dt_source") or "file"
    elif dt is not None:
        used_dt, dt_source = dt, given_by
    else:
        raise RockcliInputError(f"{name}: the file does not state its time step; give it with --dt (seconds)")

    lo, hi = DT_RANGE_S
    if not lo <= used_dt <= hi:
        said = {"caller": "given", "suite": "given", "catalogue": "from the catalogue"}.get(dt_source, f"from the {dt_source}")
        raise RockcliInputError(f"{name}: time step dt = {_num(used_dt)} s ({said}) lies outside the "
                                f"supported {lo:g} s to {hi:g} s (strong-motion records are sampled at 50 Hz to "
                                f"a few kHz); check its unit")
    values = np.asarray(out["values"], dtype=np.float64)
    if not np.all(np.isfinite(values)):
        i = int(np.argmax(~np.isfinite(values)))
        raise RockcliInputError(f"{name}: sample {i + 1} is {float(values[i])!r}, not a finite number")
    if values.size < 2:
        raise RockcliInputError(f"{name}: the record has {values.size} sample(s); at least 2 are needed")
    peak = float(np.max(np.abs(values)))
    if not np.isfinite(peak * factor) or peak * factor > PGA_MAX_G * G:
        i = int(np.argmax(np.abs(values)))
        said = {"caller": "given", "suite": "given", "catalogue": "from the catalogue"}.get(units_source, f"from the {units_source}")
        raise RockcliInputError(f"{name}: sample {i + 1} is {_num(values[i])} {used_units} (units {said}), "
                                f"a peak beyond the supported {PGA_MAX_G:g} g (recorded peaks reach about 4 g); "
                                f"check the units")
    meta = dict(out.get("meta", {}))
    if "azimuth_deg" not in meta:
        meta.update(_orientation(path, out.get("format"), meta.get("component")))
    meta.update(units=used_units, units_source=units_source, factor=factor, dt_source=dt_source,
                format=out.get("format"), path=str(path))
    if used_units == "counts":
        meta.update(gain=gain, gain_units=units)
    return Record(acc=values * factor, dt=used_dt, name=path.name, t_start=float(out.get("t_start", 0.0)), meta=meta)
