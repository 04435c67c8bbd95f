"""``--azimuth worst`` on the catalogue (issue 33 item 5): without ``--records`` it runs the catalogue's own
pairs, a record whose second horizontal component the catalogue does not know (or whose file is missing) runs
as recorded and says so in one line, and ``--records A+B`` of catalogued files reads them with the
catalogue's units, time step and orientation (the same rows as the catalogue id of the pair)."""

from __future__ import annotations

import csv
import shutil

import pytest
from click.testing import CliRunner

from rockcli.cli import main

CHEAP = ["assess", "column", "bassae", "--isolation", "none", "--no-margin", "--azimuth", "worst"]


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_the_catalogue_under_azimuth_worst_is_its_pairs_and_its_single_records(records_dir):
    """The Table II suite: every record whose second component the catalogue knows (and finds) is a pair
    projected onto 0 deg; every other found record is the excitation it is without an azimuth, marked as run
    as recorded (one component known); nothing else changes."""
    from rockcli.assess import resolve_excitations
    from rockcli.assess.pairs import ONE_COMPONENT
    from rockcli.assess.excitations import table_ii_entries
    from rockcli.records.catalog import find_file

    worst, un_w = resolve_excitations(None, "auto", azimuth="worst")
    plain, un_p = resolve_excitations(None, "auto")
    assert [x.label for x in worst] == [x.label for x in plain] and un_w == un_p
    entries = {e.id: e for e in table_ii_entries()}
    pairs = 0
    for w, p in zip(worst, plain):
        e = entries[w.label]
        if e.file_2 and find_file(e) is not None and find_file(e, e.file_2) is not None:
            pairs += 1
            assert w.pair is not None and w.azimuth_deg == 0.0 and not w.as_recorded and not w.error
            assert {r.meta["path"].rsplit("/", 1)[-1] for r in w.pair} == {e.file, e.file_2}
        else:
            assert w.pair is None and w.kind == p.kind and w.source == p.source and w.pga_g == p.pga_g
            assert (w.motion.acc == p.motion.acc).all() if w.kind == "record" else w.motion == p.motion
            assert w.as_recorded == (ONE_COMPONENT if w.kind == "record" else "")
    assert pairs >= 1


def test_assess_column_worst_without_records_says_which_run_as_recorded(records_dir, tmp_path):
    """The CLI on catalogue ids (the catalogue's pair and a one-component record): the single record's row is
    its row without --azimuth, the one line says so, and the pair is turned (@A or @any)."""
    single, pair = "parkfield-1966-c02-065", "coyotelake-1979-gilroy6-230"
    res = CliRunner().invoke(main, [*CHEAP, "--records", single, "--records", pair, "--csv", str(tmp_path / "w.csv")])
    if "not found" in res.output:
        pytest.skip(res.output)
    assert res.exit_code == 0, res.output
    lines = [ln for ln in res.output.splitlines() if ln.startswith("Run as recorded")]
    assert lines == [f"Run as recorded, in one orientation (no pair to turn): {single} (the catalogue knows one "
                     "horizontal component)."], res.output
    plain = CliRunner().invoke(main, [*CHEAP[:-2], "--records", single, "--csv", str(tmp_path / "p.csv")])
    assert plain.exit_code == 0, plain.output
    w, p = _rows(tmp_path / "w.csv"), _rows(tmp_path / "p.csv")
    for key in ("verdict", "theta_max_over_alpha", "t_uplift_s", "n_impacts", "pga_g", "source"):
        assert w[0][key] == p[0][key], key
    assert w[0]["azimuths_run"] == "" and w[1]["azimuths_run"] == "36"


def test_a_pair_of_catalogued_files_reads_as_the_catalogue_says(find_record, tmp_path):
    """G06-230 and G06-320 state neither units nor time step: as ``A+B`` they are read with the catalogue's
    (g, 0.005 s) and its orientations (230 and 320 deg), the rows of the catalogue id; a pair of them with
    the second file missing runs the first as recorded and says why."""
    a, b = find_record("G06-230"), find_record("G06-320")
    out = {}
    for name, src in (("files", f"{a}+{b}"), ("id", "coyotelake-1979-gilroy6-230")):
        res = CliRunner().invoke(main, [*CHEAP, "--records", src, "--csv", str(tmp_path / f"{name}.csv")])
        assert res.exit_code == 0, res.output
        out[name] = _rows(tmp_path / f"{name}.csv")[0]
    for key in ("verdict", "theta_max_over_alpha", "azimuth_deg", "overturning_azimuths", "pga_g", "azimuths_run"):
        assert out["files"][key] == out["id"][key], key

    both = CliRunner().invoke(main, [*CHEAP, "--azimuth-step", "90", "--records", "coyotelake-1979-gilroy6-230",
                                     "--records", f"{a}+{b}"])
    assert both.exit_code == 0, both.output  # one record, counted once
    assert "Counted once: G06-230+320 is the same record as coyotelake-1979-gilroy6-230." in both.output

    alone = tmp_path / "alone"
    alone.mkdir()
    shutil.copy(a, alone)
    res = CliRunner().invoke(main, [*CHEAP, "--records", "coyotelake-1979-gilroy6-230"],
                             env={"ROCKCLI_RECORDS": str(alone)})
    assert res.exit_code == 0, res.output
    assert "(the file of its second component, G06-320, is not found)" in res.output


def test_a_projection_without_pairs_is_refused_in_one_sentence():
    res = CliRunner().invoke(main, ["assess", "column", "bassae", "--azimuth", "30"])
    assert res.exit_code == 2
    assert "--azimuth 30 projects pairs of horizontal components" in res.output and "Traceback" not in res.output
