"""Record suites: folders that skip what is not a record, --glob/--exclude, manifests, fill-in --dt (issue 24 item 5);
each record once, by file identity and component, pairs of two files, no output over an input (issue 34)."""

from __future__ import annotations

import os
import shutil

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.assess.excitations import Duplicate
from rockcli.assess.scenes import Skipped, resolve_excitations, unavailable_notes
from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.records import read_record


@pytest.fixture()
def mixed(tmp_path, find_record):
    """A folder like ../shared/records: records, a headerless file, and files that are not records."""
    folder = tmp_path / "mixed"
    folder.mkdir()
    write_pulse_record(folder / "a.txt", 0.4, 0.6)
    shutil.copy(find_record("RSN723_SUPER.B_B-PTS315.AT2"), folder)  # states dt = 0.01 s
    np.savetxt(folder / "bare", np.sin(np.arange(400) * 0.05) * 0.2)  # no units, no dt
    (folder / "SOURCES.csv").write_text("file,event,year\nx,y,1999\n")
    (folder / "README.md").write_text("# Records\n\nThese are records.\n")
    (folder / "pic.png").write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(range(256)))
    return folder


def test_folder_skips_files_that_are_not_records(mixed):
    xs, unavailable = resolve_excitations([str(mixed)], units="g", dt=0.005)
    labels = sorted(x.label for x in xs)
    assert labels == ["RSN723_SUPER.B_B-PTS315.AT2", "a.txt", "bare"]
    assert all(not x.error for x in xs), [x.error for x in xs]
    skipped = sorted(u.label for u in unavailable if isinstance(u, Skipped))
    assert skipped == ["README.md", "SOURCES.csv", "pic.png"]
    # --dt fills in only what a file does not state: the AT2 file keeps its 0.01 s, the bare file gets 0.005 s
    by = {x.label: x.motion for x in xs}
    assert by["RSN723_SUPER.B_B-PTS315.AT2"].dt == 0.01 and by["bare"].dt == 0.005
    assert by["RSN723_SUPER.B_B-PTS315.AT2"].meta["dt_source"] == "header"
    # named explicitly, a file that is not a record is an error row, not skipped
    xs, unavailable = resolve_excitations([str(mixed / "SOURCES.csv")])
    assert xs[0].error and "format not recognised" in xs[0].error and not unavailable


def test_glob_and_exclude(mixed):
    xs, _ = resolve_excitations([str(mixed)], glob=("*.AT2", "*.txt"))
    assert sorted(x.label for x in xs) == ["RSN723_SUPER.B_B-PTS315.AT2", "a.txt"]
    xs, _ = resolve_excitations([str(mixed)], exclude=("*.AT2", "bare"))
    assert [x.label for x in xs] == ["a.txt"]
    with pytest.raises(RockcliInputError, match="holds no files that match --glob/--exclude"):
        resolve_excitations([str(mixed)], glob=("*.xyz",))


def test_cli_counts_what_it_skipped(mixed, tmp_path):
    res = CliRunner().invoke(main, ["assess", "fragility", "small:R=0.6,alpha=12", "--records", str(mixed),
                                    "--isolation", "none", "--bootstrap", "0", "--units", "g", "--dt", "0.005",
                                    "--exclude", "bare", "--csv", str(tmp_path / "f.csv")])
    assert res.exit_code == 0, res.output
    assert ("Skipped 3 file(s) of the folder(s) that are not records (no reader recognises their content): "
            "README.md, SOURCES.csv, pic.png.") in res.output
    df = pd.read_csv(tmp_path / "f.csv")
    assert sorted(df.record) == ["RSN723_SUPER.B_B-PTS315.AT2", "a.txt"] and df.error.isna().all()


def test_manifest(tmp_path, find_record):
    folder = tmp_path / "m"
    folder.mkdir()
    np.savetxt(folder / "n.txt", np.sin(np.arange(500) * 0.04) * 30.0)  # cm/s^2, dt 0.01: stated nowhere
    np.savetxt(folder / "e.txt", np.cos(np.arange(500) * 0.04) * 30.0)
    shutil.copy(find_record("RSN1119_KOBE_TAZ000.AT2"), folder)
    manifest = folder / "suite.csv"
    manifest.write_text("file,units,dt,component,azimuth,file_2,azimuth_2\n"
                        "n.txt,cm/s^2,0.01,,0,e.txt,90\n"
                        "RSN1119_KOBE_TAZ000.AT2,,0.005,,,,\n")
    xs, _ = resolve_excitations([str(manifest)])
    assert [x.label for x in xs] == ["n.txt", "RSN1119_KOBE_TAZ000.AT2"]
    n = xs[0].motion
    assert n.dt == 0.01 and n.meta["azimuth_deg"] == 0.0 and n.pga == pytest.approx(0.30, rel=1e-3)
    assert xs[1].motion.dt == 0.01  # the file states 0.01 s: the manifest's dt fills in only what it lacks
    # with --azimuth, the row's pair is projected
    xs, _ = resolve_excitations([str(manifest)], azimuth=90.0)
    np.testing.assert_array_equal(xs[0].motion.acc, read_record(folder / "e.txt", units="cm/s^2", dt=0.01).acc)
    assert xs[1].error and "needs two horizontal components" in xs[1].error
    (folder / "bad.csv").write_text("file,units,colour\nn.txt,g,red\n")
    with pytest.raises(RockcliInputError, match="manifest column"):
        resolve_excitations([str(folder / "bad.csv")])


@pytest.mark.parametrize("header, cells", [("file", ""), ("file,label", ",kobe")])
def test_manifest_of_files_that_state_everything(tmp_path, find_record, header, cells):
    """A manifest with only a ``file`` column (or ``file,label``) is a manifest: it was read as a record and
    refused ("format not recognised")."""
    from rockcli.assess.manifest import is_manifest

    shutil.copy(find_record("RSN1119_KOBE_TAZ000.AT2"), tmp_path)
    manifest = tmp_path / "files.csv"
    manifest.write_text(f"{header}\nRSN1119_KOBE_TAZ000.AT2{cells}\n")
    assert is_manifest(manifest)
    xs, _ = resolve_excitations([str(manifest)])
    assert [x.label for x in xs] == ["kobe" if cells else "RSN1119_KOBE_TAZ000.AT2"] and not xs[0].error
    np.testing.assert_array_equal(xs[0].motion.acc, read_record(tmp_path / "RSN1119_KOBE_TAZ000.AT2").acc)
    (tmp_path / "notes.csv").write_text("file,colour\na,red\n")  # not a manifest's header: read as a record
    assert not is_manifest(tmp_path / "notes.csv")


@pytest.mark.parametrize("name, extra", [
    ("20161113_110259_WTMC_20.V2A", ["--component", "S62W"]),
    ("RSN1119_KOBE_TAZ000.AT2", []),
    ("AOM0011801241951.EW", []),
])
def test_export_reads_back_identically(find_record, tmp_path, name, extra):
    path = find_record(name)
    out = tmp_path / "out.txt"
    res = CliRunner().invoke(main, ["records", "export", str(path), str(out), *extra])
    assert res.exit_code == 0, res.output
    original = read_record(path, component=extra[1] if extra else None)
    back = read_record(out)
    np.testing.assert_array_equal(back.acc, original.acc)
    assert back.dt == original.dt and back.meta["azimuth_deg"] == original.meta["azimuth_deg"]
    assert back.meta["component"] == original.meta["component"]
    # a multi-component file without --component: refused in one sentence, nothing written
    if extra:
        res = CliRunner().invoke(main, ["records", "export", str(path), str(tmp_path / "x.txt")])
        assert res.exit_code == 2 and "choose one with --component" in res.output
        assert not (tmp_path / "x.txt").exists()


# --------------------------------------------------------------------------------------------------
# issue 34: each record of a suite once (file identity and component), a pair of two files, every input
# protected by the output transaction
# --------------------------------------------------------------------------------------------------
V2A = "20161113_110259_WTMC_20.V2A"  # three components: N28W (332 deg), S62W (242 deg), Up


def test_manifest_two_components_of_one_file_are_two_records(tmp_path, find_record):
    shutil.copy(find_record(V2A), tmp_path)
    manifest = tmp_path / "two.csv"
    manifest.write_text(f"file,component\n{V2A},N28W\n{V2A},S62W\n{V2A},332\n")  # 332 deg is N28W again
    xs, unavailable = resolve_excitations([str(manifest)])
    assert [x.label for x in xs] == [f"{V2A}:N28W", f"{V2A}:S62W"]
    assert [x.motion.meta["component"] for x in xs] == ["N28W", "S62W"]
    assert xs[0].motion.pga_g != xs[1].motion.pga_g  # two different motions, both run
    notes = unavailable_notes(unavailable)
    assert notes == [f"Counted once: {V2A} is the same record as {V2A}:N28W."]


def test_a_link_or_a_second_name_is_the_file_it_names(tmp_path, find_record):
    folder = tmp_path / "suite"
    folder.mkdir()
    shutil.copy(find_record("RSN1119_KOBE_TAZ000.AT2"), folder / "kobe.AT2")
    write_pulse_record(folder / "a.txt", 0.4, 0.6)
    (folder / "link.AT2").symlink_to("kobe.AT2")
    os.link(folder / "a.txt", folder / "hard.txt")
    xs, unavailable = resolve_excitations([str(folder), str(folder / "kobe.AT2")])
    assert sorted(x.label for x in xs) == ["a.txt", "kobe.AT2"]
    assert sorted(u.label for u in unavailable if isinstance(u, Duplicate)) == ["hard.txt", "link.AT2"]
    # the same name given twice is read once, silently
    xs, unavailable = resolve_excitations([str(folder / "a.txt"), str(folder / "a.txt")])
    assert [x.label for x in xs] == ["a.txt"] and not unavailable
    # two different files of one name in two folders both run, labelled by their folders
    other = tmp_path / "other"
    other.mkdir()
    write_pulse_record(other / "a.txt", 0.2, 0.9)
    xs, _ = resolve_excitations([str(folder / "a.txt"), str(other / "a.txt")])
    assert [x.label for x in xs] == ["a.txt", "other/a.txt"]


def test_fragility_counts_a_linked_record_once(tmp_path):
    folder = tmp_path / "suite"
    folder.mkdir()
    write_pulse_record(folder / "a.txt", 0.4, 0.6)
    write_pulse_record(folder / "b.txt", 0.3, 0.8)
    (folder / "c.txt").symlink_to("a.txt")
    res = CliRunner().invoke(main, ["assess", "fragility", "small:R=0.6,alpha=12", "--records", str(folder),
                                    "--isolation", "none", "--bootstrap", "0", "--csv", str(tmp_path / "f.csv")])
    assert res.exit_code == 0, res.output
    assert sorted(pd.read_csv(tmp_path / "f.csv").record) == ["a.txt", "b.txt"]
    assert "Counted once: c.txt is the same record as a.txt." in res.output


def test_a_pair_is_two_files(tmp_path, find_record):
    shutil.copy(find_record("TCU128-000"), tmp_path)
    (tmp_path / "same").symlink_to("TCU128-000")
    f = str(tmp_path / "TCU128-000")
    for second in (f"{f}@90", f"{tmp_path / 'same'}@90"):
        res = CliRunner().invoke(main, ["simulate", "--R", "1", "--alpha", "14", "--record", f"{f}@0", "--record-2",
                                        second, "--azimuth", "30", "--units", "g", "--dt", "0.005"])
        assert res.exit_code == 2 and "are one file" in res.output and "two different horizontal" in res.output
        assert len(res.output.strip().splitlines()) == 1, res.output
    xs, _ = resolve_excitations([f"{f}@0+{f}@90"], units="g", dt=0.005, azimuth=30.0)
    assert xs[0].motion is None and "are one file" in xs[0].error


def _bytes(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


@pytest.mark.parametrize("command", ["column", "fragility"])
@pytest.mark.parametrize("target", ["manifest", "pair", "folder-file"])
def test_no_output_over_any_input(tmp_path, find_record, command, target):
    """--csv/--report on the manifest being read, on a file of a pair that cannot be read (an error row), on a file
    of a suite folder that is not a record: refused in one sentence, every file as it was."""
    for n in ("G06-230", "G06-320"):
        shutil.copy(find_record(n), tmp_path)
    (tmp_path / "notes.txt").write_text("not a record\n")
    (tmp_path / "m.csv").write_text("file,units,dt\nG06-230,g,0.005\n")
    sources = {"manifest": ["m.csv"], "pair": ["G06-230@230+G06-320@0", "m.csv"], "folder-file": ["."]}[target]
    out = {"manifest": "m.csv", "pair": "G06-320", "folder-file": "notes.txt"}[target]
    before = _bytes(tmp_path)
    extra = ["--azimuth", "10"] if target == "pair" else []
    for option in ("--csv", "--report"):
        args = ["assess", command, "small:R=0.6,alpha=12", "--isolation", "none", "--units", "g", "--dt", "0.005",
                *(["--no-margin"] if command == "column" else ["--bootstrap", "0"]), *extra, option, out]
        for s in sources:
            args += ["--records", s]
        cwd = os.getcwd()
        try:
            os.chdir(tmp_path)
            res = CliRunner().invoke(main, args)
        finally:
            os.chdir(cwd)
        assert res.exit_code == 2, res.output
        # --report: refused by its suffix first (the report is an HTML page whatever its name)
        said = f"{option} {out} is also an input" if option == "--csv" else f"{option} {out}: this file is written as HTML"
        assert said in res.output and "Traceback" not in res.output
        assert _bytes(tmp_path) == before
