"""Suite manifests: a CSV naming one record file per row, with what the file does not state.

A manifest has a ``file`` column (relative to the manifest's folder) and what its files lack: ``units``,
``dt``, ``gain``, ``component``, ``azimuth``, and for a pair ``file_2``, ``azimuth_2``, with an optional
``label``; a ``file`` column alone lists files that state everything themselves. :func:`is_manifest` tells it
from a record by its first line: it names ``file`` and either one of the columns a file may lack or nothing
but manifest columns (a record's first line never names a column ``file``). :func:`read_manifest` reads it
strictly: UTF-8 text (a byte order mark is fine), known columns each given once, as many cells per row
as the header has, at least one row, each naming a file; every refusal is one sentence naming the
manifest and the line. The manifest is an input of the run: an output on it is refused
(:func:`rockcli.io.files.note_inputs`).
"""

from __future__ import annotations

from pathlib import Path

from rockcli.errors import RockcliInputError

#: Columns of a manifest CSV: ``file`` and what the files lack.
MANIFEST_COLUMNS = ("file", "units", "dt", "gain", "component", "azimuth", "file_2", "azimuth_2", "label")


def is_manifest(path: Path) -> bool:
    """A CSV whose header names a ``file`` column and one of units, dt, gain, component, azimuth, or only
    manifest columns (``file`` alone, ``file,label``); never raises. A header with an unknown column besides
    units, ... is a manifest too, refused by :func:`read_manifest` naming the column."""
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as fh:
            head = fh.readline()
    except OSError:
        return False
    names = [h.strip().lower() for h in head.split(",")]
    return "file" in names and (any(k in names for k in ("units", "dt", "gain", "component", "azimuth"))
                                or all(n in MANIFEST_COLUMNS for n in names))


def _text(path: Path) -> str:
    """The manifest's text, or one sentence: not readable, not UTF-8 (naming the line and the byte)."""
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise RockcliInputError(f"{path}: the manifest cannot be read ({(exc.strerror or str(exc)).lower()})") from None
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise RockcliInputError(f"{path}, line {line}: the manifest is not UTF-8 text (byte 0x{data[exc.start]:02x}); "
                                f"save it as UTF-8 (in a spreadsheet: CSV UTF-8)") from None


def _rows(path: Path) -> list:
    """``(line, {column: cell})`` of every row, after the header is checked."""
    import csv
    import io

    reader = csv.reader(io.StringIO(_text(path), newline=""))
    try:
        header = next(reader, None)
        if header is None or not any(h.strip() for h in header):
            raise RockcliInputError(f"{path}: the manifest is empty; its first line names the columns "
                                    f"({', '.join(MANIFEST_COLUMNS)})")
        names = [h.strip().lower() for h in header]
        unknown = [h for h, n in zip(header, names) if n not in MANIFEST_COLUMNS]
        if unknown:
            raise RockcliInputError(f"{path}: manifest column(s) {', '.join(map(repr, unknown))} unknown (known: "
                                    f"{', '.join(MANIFEST_COLUMNS)})")
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise RockcliInputError(f"{path}: manifest column {twice[0]!r} is given twice")
        rows = []
        for cells in reader:
            if not any(c.strip() for c in cells):
                continue  # a blank line
            if len(cells) > len(names):
                raise RockcliInputError(f"{path}, line {reader.line_num}: the row has {len(cells)} cells, the header "
                                        f"names {len(names)} columns")
            rows.append((reader.line_num, {n: c.strip() for n, c in zip(names, cells)}))
    except csv.Error as exc:
        raise RockcliInputError(f"{path}, line {reader.line_num}: not a readable CSV row ({exc})") from None
    if not rows:
        raise RockcliInputError(f"{path}: the manifest names no record: it has its header line and no row (one row "
                                f"per record file, e.g. 'record.AT2' under the column 'file')")
    return rows


def _angle_text(value: float) -> str:
    """An azimuth as ``FILE@DEG`` writes it: plain decimal digits, never an exponent (``1e-07``)."""
    import numpy as np

    return np.format_float_positional(value, trim="-")


def read_manifest(path: Path, defaults: dict) -> list:
    """``(label, first, second, read_kwargs)`` per row of a manifest CSV (files relative to its folder;
    ``FILE@DEG`` when the row gives an azimuth). A row's units and dt fill in only what its file does not
    state, like ``--units``/``--dt`` (which fill in what a row leaves empty)."""
    from rockcli.assess.pairs import pair_label
    from rockcli.io.files import note_inputs
    from rockcli.io.inputs import parse_number

    path = Path(path)
    note_inputs([path], "the manifest")
    out = []
    for n, row in _rows(path):
        where = f"{path}, line {n}"
        if not row.get("file"):
            raise RockcliInputError(f"{where}: the row names no file")
        kwargs = dict(defaults)
        if row.get("units"):
            kwargs["units"] = row["units"]
        if row.get("dt"):
            kwargs["dt"] = parse_number(row["dt"], f"{where}: dt", lo=0, lo_open=True, unit="s")
        if row.get("gain"):
            kwargs["gain"] = parse_number(row["gain"], f"{where}: gain", lo=0, lo_open=True)
            if not kwargs.get("units"):
                raise RockcliInputError(f"{where}: the gain needs the units it yields in the row's units column "
                                        f"(or --units)")
        if kwargs.get("units") or kwargs.get("dt"):
            kwargs["fill_in"] = True
        if row.get("component"):
            kwargs["component"] = row["component"]

        def located(name, az, what):
            p = Path(name) if Path(name).is_absolute() else path.parent / name
            if az:
                return f"{p}@{_angle_text(parse_number(az, f'{where}: {what}'))}"
            return str(p)

        first = located(row["file"], row.get("azimuth"), "azimuth")
        second = located(row["file_2"], row.get("azimuth_2"), "azimuth_2") if row.get("file_2") else None
        if row.get("azimuth_2") and not second:
            raise RockcliInputError(f"{where}: azimuth_2 is given without file_2")
        label = row.get("label") or (pair_label(Path(row["file"]).name, Path(row["file_2"]).name) if second
                                     else Path(row["file"]).name)
        out.append((label, first, second, kwargs))
    return out
