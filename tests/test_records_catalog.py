"""The record catalogue: ids, round trip, search path, resolution by id."""

from __future__ import annotations

import dataclasses
import os

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.records.catalog import (COLUMNS, CatalogEntry, catalog_path, find_file, format_catalog, get_entry,
                                     load_catalog, search_path, write_catalog)

IDS = ["parkfield-1966-c02-065", "vrancea-1977-bucharest", "imperialvalley-1979-elcentro6-230",
       "irpinia-1980-sturno-270", "sansalvador-1986-gic", "superstition-1987-parachute-225",
       "erzincan-1992-erzincan-ew", "northridge-1994-jensen-022", "kobe-1995-takarazuka-000",
       "chichi-1999-chy101-e", "chichi-1999-chy128-n", "coyotelake-1979-gilroy6-230", "aigio-1995-ote-fp"]

#: Table II of the paper: id -> (Mw, distance [km], PGA [g], PGV [m/s]).
TABLE_II = {
    "parkfield-1966-c02-065": (6.1, 0.1, 0.48, 0.75), "vrancea-1977-bucharest": (7.2, 160, 0.20, 0.74),
    "imperialvalley-1979-elcentro6-230": (6.5, 9.3, 0.41, 0.65), "irpinia-1980-sturno-270": (6.5, 32, 0.36, 0.52),
    "sansalvador-1986-gic": (5.4, 4.3, 0.48, 0.48), "superstition-1987-parachute-225": (6.7, 0.7, 0.45, 1.12),
    "erzincan-1992-erzincan-ew": (6.9, 13, 0.50, 0.64), "northridge-1994-jensen-022": (6.7, 6.2, 0.57, 0.76),
    "kobe-1995-takarazuka-000": (6.9, 1.2, 0.69, 0.69), "chichi-1999-chy101-e": (7.6, 11.2, 0.35, 0.71),
    "chichi-1999-chy128-n": (7.6, 9.7, 0.17, 0.69),
}


def test_ids_and_published_values():
    entries = load_catalog()
    assert [e.id for e in entries] == IDS
    for e in entries:
        if e.id in TABLE_II:
            assert (e.mw, e.distance_km, e.pga_published_g, e.pgv_published_mps) == TABLE_II[e.id]
    unavailable = {e.id for e in entries if not e.available}
    assert unavailable == {"vrancea-1977-bucharest", "aigio-1995-ote-fp"}
    for e in entries:
        assert e.notes
        assert (e.file != "") == e.available
        assert e.pulse_shape is None and e.a_p_g is None  # filled later by the pulse fitter


def test_pulse_columns_present():
    for c in ("pulse_shape", "a_p_g", "T_p_s", "t0_s", "pulse_energy"):
        assert c in COLUMNS
    header = catalog_path().read_text().splitlines()[0].split(",")
    assert tuple(header) == COLUMNS


def test_round_trip_is_byte_identical(tmp_path):
    text = catalog_path().read_text()
    assert format_catalog(load_catalog()) == text
    # with pulse columns filled in, as the generator command will do
    entries = [dataclasses.replace(e, pulse_shape="ricker-sym", a_p_g=0.1 * (i + 1) / 3, T_p_s=0.45 + i,
                                   t0_s=1.0 / 3, pulse_energy=0.875) for i, e in enumerate(load_catalog())]
    out = write_catalog(entries, tmp_path / "c.csv")
    assert load_catalog(out) == entries
    assert format_catalog(load_catalog(out)) == out.read_text()


def test_catalog_env_override(tmp_path, monkeypatch):
    entries = load_catalog()[:2]
    write_catalog(entries, tmp_path / "mine.csv")
    monkeypatch.setenv("ROCKCLI_CATALOG", str(tmp_path / "mine.csv"))
    assert [e.id for e in load_catalog()] == IDS[:2]


def test_bad_catalog(tmp_path, monkeypatch):
    p = tmp_path / "c.csv"
    p.write_text("id,event\nx,y\n")
    with pytest.raises(RockcliInputError, match=r"lacks the columns"):
        load_catalog(p)
    text = format_catalog(load_catalog())
    p.write_text(text.replace(",yes,", ",maybe,", 1))
    with pytest.raises(RockcliInputError, match=r"'available' must be yes or no"):
        load_catalog(p)


def test_search_path_order(tmp_path, monkeypatch):
    a, b = tmp_path / "a", tmp_path / "b"
    a.mkdir(), b.mkdir()
    monkeypatch.setenv("ROCKCLI_RECORDS", os.pathsep.join([str(a), "", str(b)]))
    path = search_path()
    assert path[:2] == [a, b] and path[-1].name == "records"
    entry = get_entry("kobe-1995-takarazuka-000")
    assert find_file(entry) is None or find_file(entry).parent not in (a, b)
    (b / entry.file).write_text("x")
    assert find_file(entry) == b / entry.file
    (a / entry.file).write_text("x")
    assert find_file(entry) == a / entry.file


def test_missing_catalogue_file_names_id_and_folders(tmp_path, monkeypatch):
    monkeypatch.setenv("ROCKCLI_RECORDS", str(tmp_path))
    entry = get_entry("kobe-1995-takarazuka-000")
    if find_file(entry) is not None:
        pytest.skip("a copy sits in the repository's records/")
    with pytest.raises(RockcliInputError, match=rf"'kobe-1995-takarazuka-000': file 'RSN1119_KOBE_TAZ000.AT2' not found in {tmp_path}"):
        read_record("kobe-1995-takarazuka-000")


def test_not_available_record():
    with pytest.raises(RockcliInputError, match=r"'aigio-1995-ote-fp' has no public file"):
        read_record("aigio-1995-ote-fp")


def test_unknown_id():
    with pytest.raises(RockcliInputError, match=r"no such file, nor a catalogue id"):
        read_record("kobe-1995-takarazuka-999")


def test_every_available_id_loads(records_dirs, monkeypatch):
    """Each id resolves through the catalogue; measured PGA near Table II where the notes say so."""
    from rockcli.records.motion import calc_peaks

    monkeypatch.setenv("ROCKCLI_RECORDS", os.pathsep.join(map(str, records_dirs)))
    for e in load_catalog():
        if not e.available:
            continue
        if find_file(e) is None:
            pytest.skip(f"{e.file} not in ROCKCLI_RECORDS")
        rec = read_record(e.id)
        assert rec.name == e.id and rec.meta["catalog_id"] == e.id
        assert rec.npts > 1000 and np.isfinite(rec.acc).all()
        if "agree with Table II" in e.notes or "matching Table II" in e.notes:
            p = calc_peaks(rec)
            assert p.pga_g == pytest.approx(e.pga_published_g, abs=0.01), e.id
            assert p.pgv_mps == pytest.approx(e.pgv_published_mps, abs=0.015), e.id


def test_caller_overrides_catalogue_units_only_when_consistent(find_record, monkeypatch):
    find_record("RSN1119_KOBE_TAZ000.AT2")
    with pytest.raises(RockcliInputError, match=r"states units 'G' but 'gal' was given"):
        read_record("kobe-1995-takarazuka-000", units="gal")
