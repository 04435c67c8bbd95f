"""The excitations of an assessment: catalogue ids, files, folders, manifests and pairs of components.

:func:`resolve_excitations` turns what the user named into :class:`Excitation` objects (a record, or
the catalogued pulse of a record); a file that cannot be read is kept with its ``error`` (one bad
file in a folder of hundreds costs one row, not the run), files that are not records are
:class:`Skipped` (said how many and why). Two horizontal components make a pair projected onto the
body's rocking plane (``--azimuth``). A folder takes ``--glob``/``--exclude``; a manifest CSV gives
each file's units, dt, component and azimuth when the file does not state them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Sequence

import numpy as np

from rockcli.assess.manifest import MANIFEST_COLUMNS, is_manifest, read_manifest  # noqa: F401 (re-exported)
from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.io.units import G
from rockcli.records.unavailable import Duplicate, Skipped, Unavailable  # noqa: F401 (re-exported)
from rockcli.report.words import unavailable_notes  # noqa: F401 (re-exported)

EXCITATION_RECORD = "record"
EXCITATION_PULSE = "pulse"
#: How records are turned into excitations: the file where found, else the catalogued pulse
#: (``auto``); files only (``record``); catalogued pulses only (``pulse``).
EXCITATION_MODES = ("auto", "record", "pulse")


@dataclass(frozen=True)
class Excitation:
    """One ground motion of the assessment.

    Attributes
    ----------
    label : str
        Catalogue id or file name (``folder/name`` when two folders hold files of the same name).
    kind : str
        ``record`` (the accelerogram) or ``pulse`` (the catalogued Ricker pulse that idealises it).
    motion : Record or pulse or None
        What the solver runs (None when it could not be read: see ``error``).
    source : str
        File path, or ``catalogue pulse <shape> a_p=.. g T_p=.. s``.
    pga_g : float
        Peak ground acceleration of the motion [g] (|a_p| for a pulse).
    error : str
        Why the motion could not be read (runs then get this error in their rows).
    """

    label: str
    kind: str
    motion: object
    source: str
    pga_g: float = math.nan
    error: str = ""
    a_p_g: float = math.nan
    T_p_s: float = math.nan
    #: two horizontal components (checked, :func:`rockcli.records.orientation.check_pair`) when an azimuth
    #: was asked for: ``motion`` is their projection onto ``azimuth_deg`` (``--azimuth worst``: onto 0 deg,
    #: and :mod:`rockcli.assess.azimuth` runs every orientation)
    pair: tuple | None = None
    azimuth_deg: float = math.nan
    #: ``--azimuth worst`` on a catalogue record with one known horizontal component: why it runs as recorded
    #: (:func:`rockcli.assess.pairs.catalogue_worst`), in one orientation
    as_recorded: str = ""
    #: ``azimuth="worst"``: the orientations [deg] the pair is run in
    #: (:func:`rockcli.records.orientation.sweep_azimuths`); :func:`rockcli.assess.run_assessment` runs every one of
    #: them and keeps the most adverse (:mod:`rockcli.assess.azimuth`): ``motion``, the projection onto 0 deg, is
    #: no row's run by itself. Empty: ``motion`` is what runs.
    azimuths: tuple = ()


def _pulse_excitation(entry) -> Excitation:
    from rockcli.pulses import make_pulse

    pulse = make_pulse(entry.pulse_shape, entry.a_p_g * G, entry.T_p_s)
    source = f"catalogue pulse {entry.pulse_shape} a_p={entry.a_p_g:+.4f} g T_p={entry.T_p_s:.4f} s"
    return Excitation(entry.id, EXCITATION_PULSE, pulse, source, abs(entry.a_p_g), "", entry.a_p_g, entry.T_p_s)


def _read_excitation(label: str, path: Path, read_kwargs: dict, skip: bool = False) -> Excitation:
    from rockcli.records.components import NotARecord

    try:
        rec = _read_suite_record(path, dict(read_kwargs))
    except NotARecord as exc:
        if skip:
            return Skipped(label, str(exc))
        return Excitation(label, EXCITATION_RECORD, None, str(path), error=str(exc))
    except RockcliInputError as exc:
        return Excitation(label, EXCITATION_RECORD, None, str(path), error=str(exc))
    except Exception as exc:  # a file the reader chokes on: report it in its rows, keep the others
        return Excitation(label, EXCITATION_RECORD, None, str(path), error=f"{path}: {type(exc).__name__}: {exc}")
    if rec.npts < 2 or not np.all(np.isfinite(rec.acc)) or not rec.dt > 0:
        return Excitation(label, EXCITATION_RECORD, None, str(path),
                          error=f"{path}: not a usable record (needs >= 2 finite samples and dt > 0)")
    return Excitation(label, EXCITATION_RECORD, rec, str(path), rec.pga_g)


def _read_suite_record(path: Path, kwargs: dict):
    """A suite's record: ``component`` picks one of a multi-component file (a one-component file is taken as
    it is); ``units``/``dt`` fill in only what the file does not state."""
    from rockcli.records import read_record
    from rockcli.records.components import select_component
    from rockcli.records.reader import read_components

    component = kwargs.pop("component", None)
    if component is None:
        return read_record(path, **kwargs)
    comps = read_components(path, **{k: v for k, v in kwargs.items() if k != "column"})
    return comps[0] if len(comps) == 1 else select_component(comps, component, str(path))


def _entry_read_kwargs(entry) -> dict:
    return {"format": entry.format or None, "units": entry.units, "dt": entry.dt, "column": entry.column}


def _entry_excitation(entry, path: Path, label: str | None = None) -> Excitation:
    """A catalogue entry's file (or its pair's second file), read as the catalogue says and labelled ``label``
    (default the entry's id); the units and time step the catalogue supplies (for a file without a header) are
    credited to the catalogue, not to the command line."""
    x = _read_excitation(label or entry.id, path, _entry_read_kwargs(entry))
    if x.motion is not None:
        for key in ("units_source", "dt_source"):
            if x.motion.meta.get(key) == "caller":  # only the catalogue's values were passed
                x.motion.meta[key] = "catalogue"
    return x


def _has_pulse(entry) -> bool:
    return bool(entry.pulse_shape) and entry.a_p_g is not None and entry.T_p_s is not None


def _from_entry(entry, mode: str):
    """Excitation (or Unavailable) for a catalogue entry."""
    from rockcli.records.catalog import find_file, search_path

    path = find_file(entry) if (entry.available and mode != "pulse") else None
    if path is not None:
        return _entry_excitation(entry, path)
    if mode != "record" and _has_pulse(entry):
        return _pulse_excitation(entry)
    if not entry.available:
        why = "no public file is known"
    elif mode == "pulse":
        why = "it has no catalogued pulse"
    else:
        why = f"file {entry.file!r} not found in {', '.join(str(p) for p in search_path())}"
    if mode == "auto" and not _has_pulse(entry):
        why += " and it has no catalogued pulse"
    return Unavailable(entry.id, why)


def table_ii_entries() -> list:
    """The catalogue rows of the paper's Table II (those with a published PGA), in catalogue order."""
    from rockcli.records.catalog import load_catalog

    return [e for e in load_catalog() if e.pga_published_g is not None]


def resolve_excitations(sources: Sequence[str] | None = None, mode: str = "auto", *, units: str | None = None,
                        dt: float | None = None, gain=None, component: str | None = None, azimuth=None,
                        glob: Sequence[str] = (), exclude: Sequence[str] = (), azimuth_step: float | None = None):
    """Turn record sources into excitations.

    Parameters
    ----------
    sources : sequence of str, optional
        Catalogue ids, record files, or folders (every regular, non-hidden file in it, sorted;
        not recursive). Default: the catalogue's Table II records.
    mode : {"auto", "record", "pulse"}
        For catalogue records: the file where found, else the catalogued pulse (``auto``); files
        only (``record``); the catalogued pulses (``pulse``).
    units, dt : optional
        Units of the values and time step [s] of the files that do not state them (headerless
        text, SAC, ...), passed to :func:`rockcli.records.read_record` with ``fill_in=True``: they
        fill in only what a file does not state (a file that states others is read as it states
        them). Files the catalogue lists are read as the catalogue says.
    gain : float, optional
        Factor from raw counts to ``units`` for the files in counts (or stating no units).
    component : str, optional
        The component of each multi-component file (channel code, ``N``/``E``/``UP`` or azimuth);
        one-component files are taken as they are.
    azimuth : float or "worst", optional
        Project two horizontal components onto this azimuth (the normal to the rocking axis, degrees
        clockwise from north): a source ``A+B`` names the two files (each ``FILE`` or ``FILE@DEG``), a
        multi-component file gives its own two; anything else is an error row. ``"worst"``: every orientation
        of each pair (``Excitation.azimuths``), which :func:`rockcli.assess.run_assessment` runs, keeping the
        most adverse one's row (``azimuth_deg``), as ``assess column --azimuth worst`` does.
    glob, exclude : sequence of str
        Shell patterns of file names: a folder suite takes the files matching one of ``glob`` (all when
        empty) and none of ``exclude``. Files that are not records by their content are skipped and
        returned in ``unavailable`` as :class:`Skipped`.
    azimuth_step : float, optional
        With ``azimuth="worst"``: the step [deg] between the orientations run, 0.1 to 90 (``--azimuth-step``;
        default :data:`rockcli.records.orientation.AZIMUTH_STEP`, 5 deg: 36 orientations).

    Returns
    -------
    excitations : list of Excitation
        In the order given; a file that cannot be read is kept, with its ``error``. Each record once
        (:mod:`rockcli.assess.suite`): a file given twice (by its folder and by name, or through a
        symbolic link) is run once; two components of one file are two records labelled
        ``FILE:COMP``; two different files of the same name in different folders are labelled
        ``folder/name``.
    unavailable : list of Unavailable
        Default-set records that can be run neither from a file nor as a pulse, the files of folders
        that are not records (:class:`Skipped`), and sources naming a record already in the suite
        under another name (:class:`Duplicate`).

    Every file read (manifests, each file of a folder, both files of a pair) is an input of the open
    output transaction (:func:`rockcli.io.files.note_inputs`): an output on one of them is refused.

    Raises
    ------
    RockcliInputError
        A named source that is neither an existing file or folder nor a catalogue id, a named
        catalogue record that cannot be run, an empty folder, an unknown ``mode``, bad
        ``units``/``dt`` values.
    """
    if mode not in EXCITATION_MODES:
        raise RockcliInputError(f"excitation mode {mode!r} is not one of {', '.join(EXCITATION_MODES)}")
    azimuths = _worst_azimuths(azimuth, azimuth_step)
    out, unavailable = _resolve(sources, mode, units, dt, gain, component, azimuth, glob, exclude)
    if azimuths:  # every orientation of each pair runs (rockcli.assess.azimuth); a pair that failed is an error row
        from dataclasses import replace

        out = [replace(x, azimuths=azimuths) if x.pair is not None and x.motion is not None else x for x in out]
    return out, unavailable


def _worst_azimuths(azimuth, step) -> tuple:
    """The orientations [deg] of ``azimuth="worst"`` at ``step`` (none for another azimuth; a step without
    ``"worst"`` is refused)."""
    from rockcli.records.orientation import AZIMUTH_STEP, sweep_azimuths

    if azimuth != "worst":
        if step is not None:
            raise RockcliInputError(f"azimuth_step {step!r} is the step of azimuth='worst' (every orientation "
                                    f"of each pair); give azimuth='worst' with it, or no azimuth_step")
        return ()
    return tuple(float(a) for a in sweep_azimuths(AZIMUTH_STEP if step is None else step))


def _resolve(sources, mode, units, dt, gain, component, azimuth, glob, exclude):
    """:func:`resolve_excitations` without the orientations of ``azimuth="worst"``."""
    from rockcli.records.catalog import catalog_ids, expand_user, load_catalog

    if sources is not None:
        import os

        from rockcli.io.inputs import as_list, check_type

        sources = as_list(sources, "sources", "a list of catalogue ids, files or folders", one=(str, os.PathLike))
        for src in sources:
            check_type(src, (str, os.PathLike), "sources: each source", "a catalogue id, a file or a folder (text)")
    file_kwargs = _file_read_kwargs(units, dt, gain)
    if component is not None:
        file_kwargs["component"] = str(component)
    entries = load_catalog()
    by_id = catalog_ids(entries)  # former ids too
    by_file = {f: e for e in entries for f in (e.file_2, e.file) if f}  # a pair's second file is read as its first
    from rockcli.assess.suite import Suite
    from rockcli.io.files import note_inputs
    from rockcli.records.orientation import pair_sources, refuse_pair_without_azimuth, split_source

    from rockcli.assess.pairs import catalogue_worst, pair_excitation, pair_label

    suite = Suite()
    if not sources:
        if azimuth is not None and azimuth != "worst":
            raise RockcliInputError(f"--azimuth {format_number(float(azimuth))} projects pairs of horizontal "
                                    f"components: give them with --records A+B (or catalogue pairs by id); "
                                    f"--azimuth worst runs the catalogue's own pairs")
        for e in table_ii_entries():
            x = _from_entry(e, mode) if azimuth is None else catalogue_worst(e, mode)
            if isinstance(x, Unavailable):
                suite.skip(x)
            elif x.pair is not None:
                note_inputs([r.meta.get("path") for r in x.pair], "a record of the pair")
                suite.add(x)
            else:
                note_inputs([x.source] if x.kind == EXCITATION_RECORD else [], "the record")
                suite.add(x, x.source if x.kind == EXCITATION_RECORD else None)
        return suite.out, suite.unavailable

    if azimuth is not None and component is not None:
        raise RockcliInputError("--component picks one component; --azimuth projects two: give one of them")
    for src in sources:
        src = str(src)
        path = expand_user(src, "--records")
        kind = _path_kind(path)
        halves = pair_sources(src, "--records") if kind not in ("file", "folder") and src not in by_id else None
        if halves is not None and azimuth is None:
            refuse_pair_without_azimuth(src, "--records")
        if halves is not None:
            first, second = halves
            files = [split_source(f)[0] for f in (first, second)]
            note_inputs(files, "a record of the pair")
            suite.add(pair_excitation(pair_label(*(Path(f).name for f in files)), first, second, file_kwargs,
                                       azimuth))
            continue
        if kind == "file" and is_manifest(path):
            for label, first, second, kwargs in read_manifest(path, file_kwargs):
                file1 = split_source(first)[0]
                note_inputs([file1, split_source(second)[0] if second else None], f"a record of the manifest {path}")
                if azimuth is not None:
                    suite.add(pair_excitation(label, first, second, kwargs, azimuth), file1)
                else:  # without an azimuth a row is its first file
                    suite.add(_manifest_excitation(Path(file1).name if second else label, first, kwargs), file1,
                              kwargs.get("component"))
            continue
        if azimuth == "worst" and src in by_id and kind == "missing":
            x = catalogue_worst(by_id[src], mode)
            if isinstance(x, Unavailable):
                raise RockcliInputError(f"record {src!r} cannot be run: {x.reason}")
            note_inputs([r.meta.get("path") for r in x.pair] if x.pair else
                        [x.source] if x.kind == EXCITATION_RECORD else [], "the record")
            suite.add(x, None if x.pair or x.kind != EXCITATION_RECORD else x.source)
            continue
        is_file = kind in ("file", "unreadable")  # unreadable: the reader names it (an error row)
        if azimuth is not None and (is_file or src in by_id):
            note_inputs([path] if is_file else [], "the record")
            suite.add(pair_excitation(path.name if is_file else by_id[src].id, src, None, file_kwargs, azimuth),
                      path if is_file else None)
            continue
        if kind == "folder":
            try:
                files = sorted(p for p in path.iterdir() if _path_kind(p) in ("file", "unreadable")
                               and not p.name.startswith("."))
            except OSError as exc:
                raise RockcliInputError(f"--records {src}: the folder cannot be read "
                                        f"({(exc.strerror or str(exc)).lower()})") from None
            files = _select(files, glob, exclude)
            if not files:
                raise RockcliInputError(f"--records {src}: the folder holds no files"
                                        + (" that match --glob/--exclude" if glob or exclude else ""))
            note_inputs(files, f"a file of the suite folder {src}")
            for p in files:
                x = (_file_excitation(p, by_file, file_kwargs, skip=True) if azimuth is None else
                     pair_excitation(p.name, str(p), None, file_kwargs, azimuth, skip=True))
                suite.skip(x) if isinstance(x, Skipped) else suite.add(x, p, component)
        elif is_file:
            note_inputs([path], "the record")
            suite.add(_file_excitation(path, by_file, file_kwargs), path, component)
        elif src in by_id:
            x = _from_entry(by_id[src], mode)
            if isinstance(x, Unavailable):
                raise RockcliInputError(f"record {src!r} cannot be run: {x.reason}")
            note_inputs([x.source] if x.kind == EXCITATION_RECORD else [], "the record")
            suite.add(x, x.source if x.kind == EXCITATION_RECORD else None)
        else:
            from rockcli.records.catalog import did_you_mean

            raise RockcliInputError(f"--records {src}: no such file or folder, nor a catalogue id"
                                    f"{did_you_mean(src, entries)} (see 'rockcli records list')")
    return suite.out, suite.unavailable


def _path_kind(path: Path) -> str:
    """What is at ``path``: ``"file"`` (a regular file, after following links), ``"folder"``, ``"missing"``, or
    ``"unreadable"``: there, but it cannot be looked at (a folder on the way without permission, a loop of links),
    which is read as a file so that the reader names it and why (``cannot be read (permission denied)``) instead of
    the :class:`PermissionError` that ``path.is_file()`` raises."""
    import stat

    try:
        mode = path.stat().st_mode
    except (FileNotFoundError, NotADirectoryError, ValueError):  # ValueError: a NUL byte in the name
        return "missing"
    except OSError:
        return "unreadable"
    return "folder" if stat.S_ISDIR(mode) else "file" if stat.S_ISREG(mode) else "missing"


def _file_read_kwargs(units, dt, gain=None) -> dict:
    """``read_record`` keywords for files outside the catalogue (validated once, up front)."""
    from rockcli.records.reader import check_gain
    from rockcli.io.units import accel_factor

    kwargs = {}
    if gain is not None:
        kwargs["gain"] = check_gain(gain, units)
    if units is not None:
        accel_factor(units)  # an unknown units word is one error up front, not one per file
        kwargs["units"] = str(units)
    if dt is not None:
        if not (isinstance(dt, (int, float)) and math.isfinite(dt) and dt > 0):
            raise RockcliInputError(f"--dt {dt!r}: the time step must be a positive number of seconds")
        kwargs["dt"] = float(dt)
    if kwargs:
        kwargs["fill_in"] = True
    return kwargs


def _file_excitation(path: Path, by_file: dict, read_kwargs: dict | None = None, skip: bool = False) -> Excitation:
    """A record file; one the catalogue lists is read as the catalogue says and labelled by its id."""
    entry = by_file.get(path.name)
    if entry is not None:
        return _entry_excitation(entry, path, entry.id if path.name == entry.file else path.name)
    return _read_excitation(path.name, path, dict(read_kwargs or {}), skip=skip)


def _select(files, glob: Sequence[str], exclude: Sequence[str]) -> list:
    """The files whose names match one of ``glob`` (all when empty) and none of ``exclude``."""
    from fnmatch import fnmatch

    return [p for p in files if (not glob or any(fnmatch(p.name, g) for g in glob))
            and not any(fnmatch(p.name, x) for x in exclude)]


def _manifest_excitation(label: str, first: str, kwargs: dict) -> Excitation:
    """One manifest row without an azimuth: its file, with the row's orientation when it gives one."""
    from rockcli.records.orientation import oriented, split_source

    src, az = split_source(first)
    x = _read_excitation(label, Path(src), kwargs)
    if x.motion is None or az is None:
        return x
    try:
        rec = oriented(x.motion, az, src)
    except RockcliInputError as exc:
        return Excitation(label, EXCITATION_RECORD, None, src, error=str(exc))
    from dataclasses import replace

    return replace(x, motion=rec)
