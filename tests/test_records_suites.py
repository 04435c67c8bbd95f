"""Record suites: folders that skip what is not a record, --glob/--exclude, manifests, fill-in --dt (issue 24 item 5)."""

from __future__ import annotations

import shutil

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.assess.scenes import Skipped, resolve_excitations
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
