"""Pairs of horizontal components in a suite (``--azimuth``): ``A+B`` sources, multi-component files and the
catalogue's pairs.

:func:`pair_excitation` reads two components (or the two horizontal ones of one file) and projects them
onto the azimuth asked for (``worst``: onto 0 deg; :mod:`rockcli.assess.azimuth` runs every orientation).
Each side of ``A+B`` is read as what it is: a catalogue id is its first component as the catalogue says
(units, time step, orientation); a file the catalogue lists (``G06-320``, wherever it is) is read with the
catalogue's units, time step and format and, when the file states no orientation, the catalogue's; any other
file with the suite's ``--units``/``--dt``/``--gain`` and its own or a given ``FILE@DEG`` orientation.

:func:`catalogue_worst` is ``--azimuth worst`` on the catalogue's own records (no ``--records``): a record
whose second horizontal component the catalogue knows runs as its pair; one with a single known component
runs as recorded, and says so (``Excitation.as_recorded``).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from rockcli.assess.excitations import (EXCITATION_RECORD, Excitation, Skipped, Unavailable, _entry_read_kwargs,
                                        _from_entry)
from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number

#: ``Excitation.as_recorded`` of a catalogue record that names one horizontal component.
ONE_COMPONENT = "the catalogue knows one horizontal component"
#: ... and of one whose second component's file is not found.
SECOND_MISSING = "the file of its second component, {}, is not found"


def pair_label(first: str, second: str) -> str:
    """``RSN181_IMPVALL.H_H-E06140.AT2+E06230.AT2``, ``TCU128-000+090``: the second name without the part
    both share up to a separator."""
    import os

    common = os.path.commonprefix([first, second])
    cut = max((common.rfind(c) for c in "-_."), default=-1) + 1
    return f"{first}+{second[cut:] or second}"


def one_file_pair(first, second, names=("", "")) -> str:
    """Why ``first`` and ``second`` (each ``FILE`` or ``FILE@DEG``) are no pair: one file named twice (after
    following symbolic links, or by inode); ``""`` when they are two files (or ``second`` is None).
    ``names`` are the options that gave them (``--record``, ``--record-2``), for the sentence."""
    from rockcli.io.files import same_file
    from rockcli.records.orientation import split_source

    if second is None:
        return ""
    f1, f2 = (split_source(s)[0] for s in (first, second))
    if not same_file(f1, f2):
        return ""
    a, b = (f"{n} {s}".strip() for n, s in zip(names, (first, second)))
    return (f"{a} and {b} are one file ({f1}): a pair is two different horizontal components; give the other "
            f"component's file (a multi-component file alone gives its own two)")


def _catalogued(entries=None) -> tuple[dict, dict]:
    """The catalogue by id, and by file name (first and second component files)."""
    from rockcli.records.catalog import catalog_ids, load_catalog

    entries = load_catalog() if entries is None else entries
    return catalog_ids(entries), {f: e for e in entries for f in (e.file_2, e.file) if f}


def _side(text: str, kwargs: dict, by_id: dict, by_file: dict):
    """One component of ``A+B``, oriented (see the module notes)."""
    from rockcli.records import read_record
    from rockcli.records.components import orientation_meta
    from rockcli.records.orientation import oriented, split_source
    from rockcli.records.reader import path_exists

    src, az = split_source(text)
    if src in by_id and not path_exists(src):
        return oriented(read_record(src), az, src)
    entry = by_file.get(Path(src).name)
    if entry is None:
        return oriented(read_record(src, **kwargs), az, src)
    rec = read_record(src, **{k: v for k, v in _entry_read_kwargs(entry).items() if v is not None})
    meta = dict(rec.meta)
    for key in ("units_source", "dt_source"):
        if meta.get(key) == "caller":  # only the catalogue's values were passed
            meta[key] = "catalogue"
    comp = entry.component if Path(src).name == entry.file else entry.component_2
    if meta.get("component") is None and comp:  # as the id reads it (the suite knows it for the same record)
        meta["component"] = comp
    if az is None and meta.get("azimuth_deg") is None and not meta.get("vertical"):
        meta.update(orientation_meta(comp, "catalogue"))
    return oriented(replace(rec, meta=meta), az, src)


def _read(first, second, kwargs: dict):
    from rockcli.records.orientation import check_pair, read_pair

    if second is None:
        return read_pair(first, None, **kwargs)
    by_id, by_file = _catalogued()
    return check_pair(_side(first, kwargs, by_id, by_file), _side(second, kwargs, by_id, by_file))


def pair_excitation(label: str, first, second, read_kwargs: dict, azimuth, skip: bool = False) -> Excitation:
    """Two horizontal components (``second`` None: those of the multi-component file or catalogue id
    ``first``) projected onto ``azimuth`` [deg] (``"worst"``: onto 0 deg, every orientation run later); a pair
    that cannot be read or checked is kept with its ``error``."""
    from rockcli.records.components import NotARecord
    from rockcli.records.orientation import project

    kwargs = {k: v for k, v in read_kwargs.items() if k != "component"}
    one = one_file_pair(first, second)
    if one:
        return Excitation(label, EXCITATION_RECORD, None, f"{first} + {second}", error=one)
    try:
        pair = _read(first, second, kwargs)
    except NotARecord as exc:
        if skip:
            return Skipped(label, str(exc))
        return Excitation(label, EXCITATION_RECORD, None, str(first), error=str(exc))
    except RockcliInputError as exc:
        return Excitation(label, EXCITATION_RECORD, None, f"{first} + {second}" if second else str(first),
                          error=str(exc))
    theta = 0.0 if azimuth == "worst" else float(azimuth)
    rec = project(*pair, theta)
    source = " + ".join(f"{r.meta.get('path')} ({format_number(r.meta['azimuth_deg'])} deg)" for r in pair)
    if azimuth != "worst":
        label = f"{label}@{format_number(theta)}"
    return Excitation(label, EXCITATION_RECORD, rec, source, rec.pga_g, pair=pair, azimuth_deg=theta)


def catalogue_worst(entry, mode: str):
    """``--azimuth worst`` on a catalogue record: its pair when the catalogue names its second horizontal
    component and both files are found (not with ``mode`` ``pulse``), else the record as it would run without
    an azimuth (its file, or its pulse), with ``as_recorded`` saying why; or :class:`Unavailable`."""
    from rockcli.records.catalog import find_file

    why = ONE_COMPONENT
    if entry.file_2 and entry.available and mode != "pulse":
        if find_file(entry) is not None and find_file(entry, entry.file_2) is None:
            why = SECOND_MISSING.format(entry.file_2)
        elif find_file(entry) is not None:
            return pair_excitation(entry.id, entry.id, None, {}, "worst")
    x = _from_entry(entry, mode)
    if isinstance(x, Unavailable) or x.kind != EXCITATION_RECORD:
        return x  # a pulse has no orientation (the notes call it idealised)
    return replace(x, as_recorded=why)
