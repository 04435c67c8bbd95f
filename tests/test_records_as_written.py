"""The examples of issues 34 and 35 on the record readers, each as a new user meets it: one sentence and exit 2,
or the right record (the properties behind them are in tests/test_records_headers.py)."""

from __future__ import annotations

import csv
import errno
import os
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.records.reader import read_components


def run(*args, env=None):
    res = CliRunner().invoke(main, [str(a) for a in args], env=env)
    assert res.exception is None or isinstance(res.exception, SystemExit), repr(res.exception)
    return res


def refused(res, *words):
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert res.exit_code == 2 and len(lines) == 1 and lines[0].startswith("Error: "), res.output
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


@pytest.fixture(scope="module")
def agency(records_dirs):
    def find(name: str) -> Path:
        for folder in records_dirs:
            for sub in (folder, folder / "formats", folder / "extra"):
                if (sub / name).is_file():
                    return sub / name
        pytest.skip(f"{name} not found in ROCKCLI_RECORDS (nor in its formats/ or extra/)")

    return find


# --------------------------------------------------------------------------------------------------
# GeoNet V2A
# --------------------------------------------------------------------------------------------------
def _geonet(agency, tmp_path, edit) -> Path:
    lines = agency("20161113_110259_WTMC_20.V2A").read_text(encoding="latin-1").split("\n")
    edit(lines)
    out = tmp_path / "w.V2A"
    out.write_text("\n".join(lines), encoding="latin-1")
    return out


@pytest.mark.parametrize("points", [100, 8000, 9000, 16384])
def test_geonet_points_other_than_the_block_are_refused(agency, tmp_path, points):
    """Issue 34: 'Number of points' lower than the block cut the record (PGA 0.0004 g of a 0.99 g record), higher
    read the velocity block as acceleration; both exited 0. Now the header is checked against the integer header
    and both against the blocks, whichever was edited."""
    def text_only(lines):
        lines[9] = lines[9].replace("points  8192", f"points  {points}")

    def everywhere(lines):
        text_only(lines)
        lines[19] = lines[19].replace("    8192    8192    8192", f"{points:8d}{points:8d}{points:8d}")

    for edit, words in ((text_only, [f"{points} points (line 10", "integer header (line 20, value 4) states 8192"]),
                        (everywhere, [f"{points} acceleration + {points} velocity", "lines 27-2486 hold 24576 values"])):
        path = _geonet(agency, tmp_path, edit)
        msg = refused(run("records", "show", path, "--component", "N28W"), str(path), *words)
        assert "header states" in msg


def test_geonet_without_units_word_states_no_units(agency, tmp_path):
    """Issue 34: a GeoNet file with no units word 'states units 'at''; it states none, and says where."""
    path = _geonet(agency, tmp_path, lambda lines: lines.__setitem__(13, lines[13].replace(" mm/s/s at", " at")))
    msg = refused(run("records", "show", path, "--component", "N28W"), "does not state its units",
                  "line 14 has no units word after the peak")
    assert "'at'" not in msg
    rec = read_record(path, component="N28W", units="mm/s^2")  # given, it reads as the pristine file
    assert rec.meta["units_source"] == "caller"
    np.testing.assert_array_equal(rec.acc, read_record(agency("20161113_110259_WTMC_20.V2A"), component="N28W").acc)


@pytest.mark.parametrize("site", ["", "Site", "Site "])
def test_geonet_blank_site_line_reads_without_a_station(agency, tmp_path, site):
    """Issue 34: a blank site line was an IndexError traceback; the station is only a name: read without it."""
    want = read_components(agency("20161113_110259_WTMC_20.V2A"))
    for k in (1, 2487):  # the first component's site line, then the second's
        path = _geonet(agency, tmp_path, lambda lines: lines.__setitem__(k, site))
        got = read_components(path)
        assert [r.meta["component"] for r in got] == ["N28W", "S62W", "Up"]
        assert all(np.array_equal(a.acc, b.acc) for a, b in zip(got, want))
        assert got[0 if k == 1 else 1].meta["station"] == ""


# --------------------------------------------------------------------------------------------------
# K-NET / KiK-net
# --------------------------------------------------------------------------------------------------
def test_knet_scale_factor_zero_and_cut_block(agency, tmp_path):
    """Issue 34: a scale factor of 0 loaded all zeros, a cut data block half the record; both exited 0."""
    src = agency("AOM0011801241951.EW")
    lines = src.read_text(encoding="latin-1").split("\n")
    zero = tmp_path / "zero.EW"
    zero.write_text("\n".join(lines).replace("3920(gal)/6182761", "0(gal)/6182761"), encoding="latin-1")
    refused(run("records", "show", zero), "scale factor of 0(gal)/6182761", "line 14", "0 would make every sample 0")
    cut = tmp_path / "cut.EW"
    cut.write_text("\n".join(lines[:len(lines) // 2]) + "\n", encoding="latin-1")
    refused(run("records", "show", cut), "a record of 102 s at 100Hz (lines 11-12): 10200 samples",
            f"{(len(lines) // 2 - 17) * 8} values follow the header", "cut short")
    rec = read_record(src)  # the pristine file: the header's Max. Acc. is the peak after removing the mean
    assert abs(rec.pga * 100.0 - 4.078) < 5e-4


# --------------------------------------------------------------------------------------------------
# AT2: a decimal comma, and --record-column
# --------------------------------------------------------------------------------------------------
def test_at2_decimal_comma_and_record_column(agency, tmp_path):
    src = agency("RSN1119_KOBE_TAZ000.AT2")
    comma = tmp_path / "comma.AT2"
    comma.write_bytes(src.read_bytes().replace(b"DT=   .0100", b"DT=0,01"))
    refused(run("records", "show", comma), "line 4: DT=0,01 is written with a decimal comma", "write DT=0.01",
            "would read it as DT=0")
    refused(run("records", "show", src, "--record-column", "7"), "--record-column 7 applies to text tables",
            "a PEER AT2 file holds one component")
    refused(run("simulate", "--body", "bassae", "--record", src, "--record-column", "2"), "applies to text tables")


# --------------------------------------------------------------------------------------------------
# CWB in the light install (issue 35)
# --------------------------------------------------------------------------------------------------
def test_cwb_units_and_channel_order_without_the_extra(agency, monkeypatch):
    """Issue 35: without gmprocess a CWB file 'did not state its units' although its header says gal, and the
    suggested --record-column 2 loaded the vertical as 'component ?'. Its header's units and channel order
    (#DataSequence: Time U N E) are read by rockcli, with or without the extra."""
    from rockcli.records import extra

    monkeypatch.setattr(extra, "available", lambda: False)
    path = agency("2-ECU.dat")
    comps = read_components(path)
    assert [(c.meta["component"], c.meta["azimuth_deg"], c.meta["vertical"]) for c in comps] == [
        ("U", None, True), ("N", 0.0, False), ("E", 90.0, False)]
    assert all(c.meta["units"] == "gal" and c.meta["format"] == "CWB" and c.dt == 0.02 and c.npts == 6000
               for c in comps)
    assert [round(c.pga * 100.0, 3) for c in comps] == [1.196, 2.931, 2.811]  # the header's AmplitudeMAX
    res = run("records", "show", path, "--record-column", "2")
    assert res.exit_code == 0 and "U (vertical" in res.output and "gal" in res.output, res.output
    res = run("records", "show", path, "--component", "N")
    assert res.exit_code == 0 and "N (0 deg" in res.output, res.output
    refused(run("records", "show", path, "--record-column", "1"), "column 1 is the time column", "U = 2, N = 3, E = 4")


# --------------------------------------------------------------------------------------------------
# catalogue and search path: tracebacks to one sentence, 'did you mean'
# --------------------------------------------------------------------------------------------------
def test_unknown_user_in_records_path(monkeypatch):
    refused(run("records", "show", "kobe-1995-takarazuka-000", env={"ROCKCLI_RECORDS": "~nosuchuser_rockcli/records"}),
            "ROCKCLI_RECORDS names ~nosuchuser_rockcli/records", "no user 'nosuchuser_rockcli'")
    refused(run("records", "list", env={"ROCKCLI_CATALOG": "~nosuchuser_rockcli/catalog.csv"}),
            "ROCKCLI_CATALOG names ~nosuchuser_rockcli/catalog.csv")


def _catalogue_with(tmp_path, row: int, column: str, value: str) -> Path:
    from rockcli.records.catalog import catalog_path

    with open(catalog_path(), newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    rows[row][column] = value
    out = tmp_path / "catalog.csv"
    with open(out, "w", newline="", encoding="utf-8") as fh:
        writer = csv.DictWriter(fh, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    return out


def test_catalogue_field_over_the_csv_limit_and_unknown_units(tmp_path):
    big = _catalogue_with(tmp_path, 2, "notes", "x" * (140 * 1024))
    refused(run("records", "list", env={"ROCKCLI_CATALOG": str(big)}), f"record catalogue {big}, line 4:",
            "field larger than field limit")
    furlongs = _catalogue_with(tmp_path, 0, "units", "furlongs")
    refused(run("records", "show", "parkfield-1966-c02-065", env={"ROCKCLI_CATALOG": str(furlongs)}),
            f"{furlongs}, line 2: column 'units' holds 'furlongs'")


def test_did_you_mean_a_catalogue_id(records_dirs):
    refused(run("records", "show", "kobe-1995-takarazka-000"), "did you mean 'kobe-1995-takarazuka-000'?")
    refused(run("assess", "column", "bassae", "--records", "kobe-1995-takarazuka-00"),
            "did you mean 'kobe-1995-takarazuka-000'?")
    refused(run("records", "show", "nothing-like-an-id"), "nor a catalogue id (see")


def test_record_in_a_folder_that_cannot_be_read(agency, tmp_path, monkeypatch):
    """Issue 34: a record in a folder without permission was a PermissionError traceback (records show,
    fit-pulse). Tests run as root, which reads any folder: the refusal of the operating system is simulated."""
    locked = tmp_path / "locked"
    locked.mkdir()
    (locked / "k.AT2").write_bytes(agency("RSN1119_KOBE_TAZ000.AT2").read_bytes())
    real_stat = os.stat

    def stat(path, *args, **kwargs):
        if str(os.fspath(path)).startswith(str(locked) + os.sep):
            raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
        return real_stat(path, *args, **kwargs)

    monkeypatch.setattr(os, "stat", stat)
    for args in (["records", "show", locked / "k.AT2"], ["fit-pulse", locked / "k.AT2"]):
        refused(run(*args), f"{locked / 'k.AT2'}: cannot be read (permission denied)")


@pytest.fixture
def locked_folder(agency, tmp_path, monkeypatch):
    """``(locked, free)``: a folder whose files cannot be looked at (``os.stat`` refuses them as the operating system
    does for a folder without permission; tests run as root, which reads any folder) and a readable folder, each
    holding Kobe as ``k.AT2``; the readable one also holds manifests naming the locked files."""
    locked, free = tmp_path / "locked", tmp_path / "free"
    for folder in (locked, free):
        folder.mkdir()
        (folder / "k.AT2").write_bytes(agency("RSN1119_KOBE_TAZ000.AT2").read_bytes())
    (free / "m.csv").write_text(f"file,units\n{locked / 'k.AT2'},g\n")
    (free / "link.AT2").symlink_to(locked / "k.AT2")
    real_stat = os.stat

    def stat(path, *args, **kwargs):
        if os.path.realpath(path).startswith(str(locked) + os.sep):  # followed as the system follows links
            raise PermissionError(errno.EACCES, "Permission denied", os.fspath(path))
        return real_stat(path, *args, **kwargs)

    monkeypatch.setattr(os, "stat", stat)
    return locked, free


@pytest.mark.parametrize("command", ["column", "fragility"])
def test_assess_record_in_a_folder_that_cannot_be_read(locked_folder, command):
    """Polish of issue 34: ``assess column --records locked/k.AT2`` raised PermissionError from ``path.is_file()``
    (also a pair, ``--azimuth``, a manifest row); now the reader's sentence, exit 2, before any run (``--vertical``
    said it already)."""
    locked, free = locked_folder
    k = locked / "k.AT2"
    for records in ([k], [k, "--azimuth", "0"], [f"{k}+{locked / 'k2.AT2'}", "--azimuth", "0"], [free / "m.csv"],
                    [free / "k.AT2", "--vertical", k]):
        refused(run("assess", command, "bassae", "--isolation", "none", "--records", *records),
                f"{k}: cannot be read (permission denied)")


def test_suite_folder_with_a_link_into_a_folder_that_cannot_be_read(locked_folder):
    """A link in a suite folder to a file that cannot be looked at is that file's error row, not a refusal of
    the whole folder (one bad file costs one row)."""
    from rockcli.assess.excitations import resolve_excitations

    locked, free = locked_folder
    xs, skipped = resolve_excitations([str(free)], "record", units="g")
    by_label = {x.label: x for x in xs}
    assert by_label["link.AT2"].motion is None
    assert "cannot be read (permission denied)" in by_label["link.AT2"].error
    assert by_label["k.AT2"].motion is not None and not by_label["k.AT2"].error
    assert [u.label for u in skipped] == ["m.csv"]


@pytest.mark.parametrize("args", [
    ["assess", "column", "bassae", "--isolation", "none", "--records", "FREE", "--csv", "LOCKED/out.csv"],
    ["assess", "fragility", "bassae", "--records", "FREE", "--report", "LOCKED/out.html"],
    ["assess", "column", "bassae", "--isolation", "none", "--records", "FREE", "--history-dir", "LOCKED/h/i"],
    ["records", "export", "FREE", "LOCKED/out.txt"],
])
def test_output_in_a_folder_that_cannot_be_read(locked_folder, args):
    """An output path in a folder without permission: ``path.is_dir()`` raised PermissionError in the output check;
    now one sentence naming the option and the reason, before any run, nothing written."""
    locked, free = locked_folder
    args = [str(a).replace("FREE", str(free / "k.AT2")).replace("LOCKED", str(locked)) for a in args]
    refused(run(*args), "cannot write there: permission denied")
    assert sorted(p.name for p in free.iterdir()) == ["k.AT2", "link.AT2", "m.csv"]


def test_records_source_with_an_unknown_user():
    """``--records ~nosuchuser/x.AT2`` raised RuntimeError from ``Path.expanduser()``."""
    refused(run("assess", "column", "bassae", "--records", "~nosuchuser-rockcli/x.AT2"),
            "--records names ~nosuchuser-rockcli/x.AT2, but no user 'nosuchuser-rockcli' on this machine")


# --------------------------------------------------------------------------------------------------
# a folder suite reads a catalogue pair's second file with the catalogue's units (issue 35)
# --------------------------------------------------------------------------------------------------
def test_folder_suite_reads_catalogue_pairs_with_the_catalogues_units(agency, tmp_path):
    from rockcli.assess.excitations import resolve_excitations

    folder = tmp_path / "suite"
    folder.mkdir()
    for name in ("G06-230", "G06-320", "TCU128-000", "TCU128-090"):
        (folder / name).write_bytes(agency(name).read_bytes())
    xs, _ = resolve_excitations([str(folder)], "record")
    by_label = {x.label: x for x in xs}
    assert sorted(by_label) == ["G06-320", "TCU128-090", "chichi-1999-tcu128-n", "coyotelake-1979-gilroy6-230"]
    assert not any(x.error for x in xs), [x.error for x in xs]
    for label in ("G06-320", "TCU128-090"):
        rec = by_label[label].motion
        assert rec.meta["units"] == "g" and rec.dt == 0.005
    np.testing.assert_array_equal(by_label["G06-320"].motion.acc,
                                  read_record(agency("G06-320"), units="g", dt=0.005).acc)
