"""The record catalogue: the paper's records (Table II and Figure 3), by id.

The catalogue is ``records/catalog.csv`` at the root of the repository (found relative to this
package; the install is editable), or the file named by ``ROCKCLI_CATALOG``. The record files
themselves are never committed: :func:`find_file` looks them up in the folders named by
``ROCKCLI_RECORDS`` (``os.pathsep``-separated), then in the repository's ``records/``.
"""

from __future__ import annotations

import csv
import io
import os
from dataclasses import dataclass, fields
from pathlib import Path

from rockcli.errors import RockcliInputError

#: Repository folder holding catalog.csv (and where record files may be dropped, uncommitted).
REPO_RECORDS = Path(__file__).resolve().parents[2] / "records"


@dataclass(frozen=True)
class CatalogEntry:
    """One row of ``records/catalog.csv``.

    Attributes
    ----------
    id : str
        Catalogue id, e.g. ``kobe-1995-takarazuka-000``.
    event, year, station, component : str, int, str, str
        As in the paper.
    mw : float or None
        Moment magnitude.
    distance_km : float or None
        Distance to the fault [km] (paper's Table II).
    pga_published_g : float or None
        Peak ground acceleration published in Table II [g].
    pgv_published_mps : float or None
        Peak ground velocity published in Table II [m/s].
    file : str
        File name looked up on :func:`search_path` (empty when no public file exists).
    format : str
        Format passed to the loader (``PEER_AT2``, ``TEXT``, ...).
    units, dt, column : str, float, int or None
        What the loader needs when the file does not state it: units word, time step [s],
        1-based column.
    available : bool
        False when no public file of the record is known.
    notes : str
        Provenance and choices (which candidate file and why).
    pulse_shape, a_p_g, T_p_s, t0_s, pulse_energy : str, float, float, float, float or None
        Equivalent pulse, filled by the pulse fitter's generator command (empty until then).
    file_2, component_2 : str
        The other horizontal component of the record (file, and its azimuth in degrees or N/E), read
        like ``file`` (same format, units, dt); empty when the catalogue names one component. With it the
        id is a pair: ``--azimuth`` projects the two, ``--component`` picks one.
    file_vertical : str
        The vertical component's file (empty when none is named).
    former_ids : str
        Ids the row had before (space-separated; empty when none): still accepted wherever an id is
        (:func:`catalog_ids`), so that scripts and notes that name a record by its former id keep working.
    """

    id: str
    event: str
    year: int
    station: str
    component: str
    mw: float | None
    distance_km: float | None
    pga_published_g: float | None
    pgv_published_mps: float | None
    file: str
    format: str
    units: str | None
    dt: float | None
    column: int | None
    available: bool
    notes: str
    pulse_shape: str | None = None
    a_p_g: float | None = None
    T_p_s: float | None = None
    t0_s: float | None = None
    pulse_energy: float | None = None
    file_2: str = ""
    component_2: str = ""
    file_vertical: str = ""
    former_ids: str = ""

    @property
    def aliases(self) -> tuple[str, ...]:
        """The former ids (:attr:`former_ids`) as a tuple."""
        return tuple(self.former_ids.split())

    @property
    def components(self) -> list[tuple[str, str]]:
        """``(component, file)`` of every component the row names: the first, the other horizontal one,
        the vertical one (``UP``)."""
        out = [(self.component, self.file)] if self.file else []
        if self.file_2:
            out.append((self.component_2, self.file_2))
        if self.file_vertical:
            out.append(("UP", self.file_vertical))
        return out


COLUMNS = tuple(f.name for f in fields(CatalogEntry))
#: Columns a catalogue may leave out (written by :func:`format_catalog`; an older catalogue lacks them).
OPTIONAL_COLUMNS = ("file_2", "component_2", "file_vertical", "former_ids")
_FLOATS = {"mw", "distance_km", "pga_published_g", "pgv_published_mps", "dt", "a_p_g", "T_p_s", "t0_s", "pulse_energy"}
_INTS = {"year", "column"}
_OPTIONAL_STR = {"units", "pulse_shape"}


def catalog_path() -> Path:
    """The catalogue file: ``ROCKCLI_CATALOG`` if set, else the repository's ``records/catalog.csv``."""
    env = os.environ.get("ROCKCLI_CATALOG")
    return expand_user(env, "ROCKCLI_CATALOG") if env else REPO_RECORDS / "catalog.csv"


def expand_user(text: str, where: str) -> Path:
    """``text`` as a path with a leading ``~`` or ``~user`` expanded; one sentence when the user is unknown."""
    try:
        return Path(text).expanduser()
    except RuntimeError:  # pathlib: "Could not determine home directory."
        user = text[1:].split("/")[0].split(os.sep)[0]
        who = f"no user {user!r} on this machine" if user else "the home folder is not known (HOME is not set)"
        raise RockcliInputError(f"{where} names {text}, but {who}: '~' stands for a home folder; write the "
                                f"folder's full path") from None


def _parse_cell(name: str, text: str, where: str):
    text = text.strip()
    if name == "available":
        if text.lower() not in ("yes", "no"):
            raise RockcliInputError(f"{where}: column 'available' must be yes or no, not {text!r}")
        return text.lower() == "yes"
    if name in _FLOATS or name in _INTS:
        if not text:
            return None
        from rockcli.io.inputs import parse_number

        return parse_number(text, f"{where}: column {name!r} holds", integer=name in _INTS,
                            bad=f"{where}: column {name!r} holds {text!r}, not a number")
    if name == "units" and text:
        from rockcli.io.units import ACCEL_UNITS, KNOWN_UNITS, is_counts

        if text.lower().replace(" ", "") not in ACCEL_UNITS and not is_counts(text):
            raise RockcliInputError(f"{where}: column 'units' holds {text!r}, which is not a units word rockcli knows "
                                    f"({KNOWN_UNITS})")
    if name in _OPTIONAL_STR:
        return text or None
    return text


def _format_cell(name: str, value) -> str:
    if value is None:
        return ""
    if name == "available":
        return "yes" if value else "no"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def load_catalog(path: str | os.PathLike | None = None) -> list[CatalogEntry]:
    """Read the catalogue.

    Parameters
    ----------
    path : path-like, optional
        Catalogue CSV; default :func:`catalog_path`.

    Returns
    -------
    list of CatalogEntry
        In file order.

    Raises
    ------
    RockcliInputError
        If the file is missing, a column is missing, a cell is malformed, or an id repeats.
    """
    path = Path(path) if path is not None else catalog_path()
    text = _read_catalog_text(path)
    reader = csv.DictReader(io.StringIO(text))
    try:
        missing = [c for c in COLUMNS if c not in (reader.fieldnames or []) and c not in OPTIONAL_COLUMNS]
        if missing:
            raise RockcliInputError(f"record catalogue {path} lacks the columns {', '.join(missing)}")
        entries, seen = [], set()
        for row in reader:
            where = f"{path}, line {reader.line_num}"
            entry = CatalogEntry(**{c: _parse_cell(c, row.get(c) or "", where) for c in COLUMNS})
            for name in (entry.id, *entry.aliases):
                if name in seen:
                    raise RockcliInputError(f"{where}: id {name!r} appears twice (as an id or a former id)")
                seen.add(name)
            entries.append(entry)
    except csv.Error as exc:  # a field over csv's limit (128 KiB), a NUL byte, ...
        limit = csv.field_size_limit()
        line = next((k for k, t in enumerate(text.splitlines(), start=1) if len(t) > limit), reader.line_num)
        raise RockcliInputError(f"record catalogue {path}, line {line}: {exc} (a catalogue cell holds an id, "
                                f"a file name, a number or a note of a few lines)") from None
    return entries


def _read_catalog_text(path: Path) -> str:
    """The catalogue's text (UTF-8, a BOM allowed); one sentence when it is missing, not a regular file
    (a FIFO would block the read), unreadable or not UTF-8."""
    import stat

    try:
        st = os.stat(path)
    except OSError as exc:
        raise RockcliInputError(f"record catalogue {path} cannot be read ({(exc.strerror or str(exc)).lower()})"
                                ) from None
    if not stat.S_ISREG(st.st_mode):
        kind = "a folder" if stat.S_ISDIR(st.st_mode) else "not a regular file (a pipe, device or socket)"
        raise RockcliInputError(f"record catalogue {path} is {kind}; ROCKCLI_CATALOG must name a CSV file")
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise RockcliInputError(f"record catalogue {path} cannot be read ({(exc.strerror or str(exc)).lower()})"
                                ) from None
    try:
        return raw.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = raw[:exc.start].count(b"\n") + 1
        raise RockcliInputError(f"record catalogue {path}, line {line}: byte 0x{raw[exc.start]:02x} is not UTF-8; "
                                f"save the catalogue as UTF-8") from None


def format_catalog(entries) -> str:
    """The catalogue as CSV text (the canonical layout of ``catalog.csv``)."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(COLUMNS)
    for e in entries:
        writer.writerow([_format_cell(c, getattr(e, c)) for c in COLUMNS])
    return buf.getvalue()


def write_catalog(entries, path: str | os.PathLike | None = None) -> Path:
    """Write the catalogue atomically (temporary file in the same folder, then rename).

    ``load_catalog(write_catalog(load_catalog()))`` gives the same entries, and the file is
    byte-identical when it was written by this function.
    """
    from rockcli.io.files import write_text

    path = Path(path) if path is not None else catalog_path()
    return write_text(path, format_catalog(entries))


def catalog_ids(entries=None) -> dict:
    """``{id: entry}`` over the catalogue (``entries``, default :func:`load_catalog`), each entry also under its
    former ids (:attr:`CatalogEntry.aliases`): the one lookup of a record id, wherever one is taken."""
    entries = load_catalog() if entries is None else entries
    return {**{a: e for e in entries for a in e.aliases}, **{e.id: e for e in entries}}


def get_entry(record_id: str) -> CatalogEntry:
    """The catalogue entry with this id (or former id).

    Raises
    ------
    RockcliInputError
        If no entry has this id.
    """
    entries = load_catalog()
    e = catalog_ids(entries).get(record_id)
    if e is not None:
        return e
    raise RockcliInputError(f"{record_id!r} is neither a file nor a catalogue id{did_you_mean(record_id, entries)} "
                            f"(see 'rockcli records list')")


def did_you_mean(name: str, entries=None) -> str:
    """`` (did you mean 'kobe-1995-takarazuka-000'?)`` for a mistyped catalogue id (empty when nothing is close)."""
    import difflib

    try:
        ids = [e.id for e in (entries if entries is not None else load_catalog())]
    except RockcliInputError:
        return ""
    close = difflib.get_close_matches(str(name), ids, n=2, cutoff=0.75)
    return f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""


def is_catalog_id(source) -> bool:
    """True when ``source`` names an entry of the catalogue."""
    if not isinstance(source, str) or os.sep in source or "/" in source:
        return False
    try:
        return source in catalog_ids()
    except RockcliInputError:
        return False


def search_path() -> list[Path]:
    """Folders searched for record files: ``ROCKCLI_RECORDS`` entries, then the repository's ``records/``."""
    folders = [expand_user(p, "ROCKCLI_RECORDS") for p in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep)
               if p.strip()]
    for folder in folders:
        _check_records_folder(folder)
    folders.append(REPO_RECORDS)
    out = []
    for f in folders:
        if f not in out:
            out.append(f)
    return out


def _check_records_folder(folder: Path) -> None:
    """One sentence when a ``ROCKCLI_RECORDS`` entry is not a readable folder: a typo there must not
    quietly turn every catalogue record into "file not found" (and ``assess`` into its pulses)."""
    import stat

    where = f"ROCKCLI_RECORDS names {folder}"
    try:
        st = os.stat(folder)
    except FileNotFoundError:
        raise RockcliInputError(f"{where}, which does not exist (set it to the folders holding the record files, "
                                f"separated by '{os.pathsep}')") from None
    except OSError as exc:
        raise RockcliInputError(f"{where}, which cannot be read ({(exc.strerror or str(exc)).lower()})") from None
    if not stat.S_ISDIR(st.st_mode):
        raise RockcliInputError(f"{where}, which is not a folder (set it to the folders holding the record files, "
                                f"separated by '{os.pathsep}')")
    if not os.access(folder, os.R_OK | os.X_OK):
        raise RockcliInputError(f"{where}, which cannot be read (permission denied)")


def find_file(entry: CatalogEntry, file: str | None = None) -> Path | None:
    """Path of the entry's file (or of ``file``, another of its components) in the first folder of
    :func:`search_path` that holds it (None if none)."""
    name = entry.file if file is None else file
    if not name:
        return None
    for folder in search_path():
        candidate = folder / name
        if is_file(candidate):
            return candidate
    return None


def is_file(path: Path) -> bool:
    """``path.is_file()``, and False rather than a PermissionError for a path in a folder that cannot be read
    (the reader then names the file and why: ``cannot be read (permission denied)``)."""
    try:
        return path.is_file()
    except OSError:
        return False
