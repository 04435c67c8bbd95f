"""``rockcli assess column``: printout, CSV schema and values, histories/plots, errors (exit 2)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.cli import main
from rockcli.models import column, parse_isolation_spec
from rockcli.records import catalog as catalog_mod
from rockcli.records import read_record
from rockcli.report.tables import CSV_COLUMNS, read_assessment_csv
from rockcli.solve import simulate


#: The columns the issue asks for (more are welcome).
REQUIRED = ("column", "R_m", "alpha_deg", "record", "excitation", "isolation", "Tb_s", "xi", "mu", "gamma",
            "overturned", "theta_max_over_alpha", "t_overturn_s", "n_impacts", "base_disp_max_m")


def invoke(*args):
    return CliRunner().invoke(main, ["assess", "column", *map(str, args)])


def test_csv_schema_and_values_equal_simulate(pulse_records, tmp_path):
    out = tmp_path / "t.csv"
    res = invoke("small:R=0.6,alpha=12", "--R", 1.5, "--alpha", 8, "--name", "tall", "--records", pulse_records,
                 "--isolation", "none", "--isolation", "linear:Tb=2,xi=0.1", "--isolation", "linear:Tb=1,gamma=0.3",
                 "--csv", out)
    assert res.exit_code == 0, res.output
    df = read_assessment_csv(out)
    assert tuple(df.columns) == CSV_COLUMNS and set(REQUIRED) <= set(df.columns)
    assert len(df) == 2 * 2 * 3  # one row per column x record x configuration
    assert set(zip(df.column, df.record, df.configuration)) == {
        (c, r, k) for c in ("small", "tall") for r in ("anti.txt", "sym.txt") for k in ("none", "Tb=2s", "Tb=1s")}
    for row in df.itertuples():
        b = {"small": column("bassae").__class__.from_degrees(0.6, 12, "small"),
             "tall": column("bassae").__class__.from_degrees(1.5, 8, "tall")}[row.column]
        f = parse_isolation_spec(row.isolation)
        r = simulate(b, f, read_record(pulse_records / row.record))
        assert row.excitation == "record" and row.error == ""
        assert bool(row.overturned) is r.overturned and row.verdict == r.verdict
        assert row.n_impacts == r.n_impacts
        for name in ("theta_max_over_alpha", "t_overturn_s", "base_disp_max_m", "t_uplift_s"):
            got, want = getattr(row, name), getattr(r, name)
            assert (math.isnan(got) and math.isnan(want)) or got == pytest.approx(want, rel=1e-5, abs=1e-12)
        assert row.R_m == pytest.approx(b.R, rel=1e-5) and row.alpha_deg == pytest.approx(b.alpha_deg, rel=1e-5)
        if row.configuration == "none":
            assert math.isnan(row.Tb_s) and row.gamma == 0 and row.isolation == "none"
        else:
            assert row.Tb_s == f.T_b and row.xi == f.xi and row.gamma == f.gamma
        assert math.isnan(row.mu)
        if math.isfinite(row.overturn_scale):
            assert row.overturn_scale_survives < row.overturn_scale <= 1.01 * row.overturn_scale_survives
    # the printout: per column a matrix and one count per configuration
    text = res.output
    assert text.count("survives") >= 2 and "Tb=1s" in text
    n_over = df[(df.column == "small") & (df.configuration == "none")].overturned.sum()
    assert f"{2 - n_over} of 2" in text.split("tall")[0]
    assert "wrote" in text and "(12 rows)" in text


def test_no_progress_bar_when_piped_and_no_margin(pulse_records):
    res = invoke("s:R=1,alpha=10", "--records", pulse_records / "sym.txt", "--isolation", "none", "--no-margin")
    assert res.exit_code == 0, res.output
    row = res.output.splitlines()[3]
    assert row.startswith("sym.txt") and " x" not in row
    assert "runs" not in res.output and "[#" not in res.output
    assert "xS:" not in res.output


def test_junk_file_in_folder_is_reported_in_its_rows(pulse_records, tmp_path):
    # a damaged record is an error row; a file that is not a record by its content is skipped and counted (issue 24)
    (pulse_records / "notes.md").write_text("# a note, not a record\nhello\n")
    (pulse_records / "bad.AT2").write_text("PEER NGA STRONG MOTION DATABASE RECORD\nx\ny\nNPTS=-4\n")
    out = tmp_path / "t.csv"
    res = invoke("s:R=1,alpha=10", "--records", pulse_records, "--isolation", "none", "--no-margin", "--csv", out)
    assert res.exit_code == 0, res.output
    df = read_assessment_csv(out)
    assert "notes.md" not in set(df.record)
    assert "Skipped 1 file(s) of the folder(s) that are not records (no reader recognises their content): notes.md." \
        in res.output
    bad = df[df.record == "bad.AT2"]
    assert len(bad) == 1 and "bad.AT2" in bad.error.iloc[0] and pd.isna(bad.overturned.iloc[0])
    assert (df[df.record != "bad.AT2"].error == "").all() and df[df.record != "bad.AT2"].overturned.notna().all()
    assert "ERROR" in res.output and "Could not run bad.AT2" in res.output
    survivors = int((~df[df.record != "bad.AT2"].overturned.astype(bool)).sum())
    assert res.output.splitlines()[7].split() == ["survives", str(survivors), "of", "2"]  # junk not counted


@pytest.mark.parametrize("args, words", [
    (["doric"], "unknown body 'doric'"),
    (["bassae", "--isolation", "linear:Tb=-2"], "isolation period Tb must be positive"),
    (["bassae", "--isolation", "springs"], "unknown isolation 'springs'"),
    (["bassae", "--records", "no/such/file.AT2"], "no/such/file.AT2: no such file or folder"),
    (["bassae", "--records", "kobe-1995"], "nor a catalogue id"),
    (["bassae", "--records", "vrancea-1977-bucharest"], "cannot be run: no public file is known"),
    (["--R", "2"], "--R and --alpha go together"),
    ([], "name at least one column"),
    (["bassae", "bassae"], "given twice"),
    (["bassae", "--csv", "no/such/dir/t.csv"], "folder"),
])
def test_bad_input_exit_2_one_sentence(args, words, tmp_path):
    res = invoke(*args)
    assert res.exit_code == 2, res.output
    assert words in res.output and "Traceback" not in res.output
    assert res.output.startswith("Error:") and len(res.output.strip().splitlines()) == 1


def test_an_unproven_run_is_not_counted_as_surviving(tmp_path):
    """A very slender block on sliding bearings still rocking at the solver's horizon: the table says
    NOT PROVEN and counts it apart, the CSV's proven column is False, the margin says which scaled
    runs were unproven; a longer horizon proves the same peak. (It used to read "survives 0.67".)"""
    rec = write_pulse_record(tmp_path / "weak.txt", 6 * math.tan(math.radians(1.5)), 0.5, "ricker-sym", dt=0.005)
    out = tmp_path / "t.csv"
    args = ("stele:R=2,alpha=1.5", "--records", rec, "--isolation", "scss:Tb=3,mu=0.06", "--isolation", "none")
    res = invoke(*args, "--no-margin", "--csv", out)
    assert res.exit_code == 0, res.output
    row = next(line for line in res.output.splitlines() if line.startswith("weak.txt"))
    assert "NOT PROVEN 0.67" in row and "survives 0.68" in row
    counts = next(line for line in res.output.splitlines() if line.startswith("survives "))
    assert "0 of 1 (1 not proven)" in counts and counts.rstrip().endswith("1 of 1")
    assert "NOT PROVEN r: still moving 600 s after the record ended" in res.output
    df = pd.read_csv(out)
    assert list(df["proven"]) == [False, True] and list(df["overturned"]) == [False, False]
    res = invoke(*args[:-2], "--horizon", 100, "--csv", out)  # the margin's hundreds of scaled runs: 100 s each
    assert res.exit_code == 0, res.output
    assert "not proven at the solver's horizon, counted as surviving" in pd.read_csv(out)["margin_note"][0]
    res = invoke(*args[:-2], "--no-margin", "--horizon", 3600, "--csv", out)
    assert res.exit_code == 0, res.output
    assert "survives 0.67" in res.output and "NOT PROVEN" not in res.output
    df2 = pd.read_csv(out)
    assert bool(df2["proven"][0]) and df2["theta_max_over_alpha"][0] == df["theta_max_over_alpha"][0]


def test_horizon_out_of_range_is_refused(pulse_records):
    res = invoke("bassae", "--records", pulse_records, "--horizon", 4000)
    assert res.exit_code == 2 and res.output.startswith("Error: horizon must be a time between 0 and 3600 s")
    assert len(res.output.strip().splitlines()) == 1


def test_nothing_written_on_bad_input(pulse_records, tmp_path):
    out = tmp_path / "t.csv"
    res = invoke("bassae", "--records", pulse_records, "--records", tmp_path / "missing.txt", "--csv", out)
    assert res.exit_code == 2 and not out.exists() and list(tmp_path.glob(".t*")) == []


def test_histories_and_plots(pulse_records, tmp_path):
    hist, figs = tmp_path / "h", tmp_path / "f"
    res = invoke("s:R=0.8,alpha=12", "--records", pulse_records / "anti.txt", "--isolation", "none",
                 "--isolation", "linear:Tb=2", "--no-margin", "--history-dir", hist, "--plot-dir", figs)
    assert res.exit_code == 0, res.output
    csvs = sorted(p.name for p in hist.glob("*.csv"))
    assert csvs == ["s_anti.txt_Tb=2s.csv", "s_anti.txt_none.csv"]
    assert sorted(p.name for p in figs.glob("*.png")) == [c.replace(".csv", ".png") for c in csvs]
    assert all(p.stat().st_size > 5000 for p in figs.glob("*.png"))
    b = column("bassae").__class__.from_degrees(0.8, 12, "s")
    r = simulate(b, parse_isolation_spec("linear:Tb=2"), read_record(pulse_records / "anti.txt"), history=True)
    h = pd.read_csv(hist / "s_anti.txt_Tb=2s.csv")
    assert len(h) == r.history.t.size
    np.testing.assert_allclose(h["theta_rad"].to_numpy(), r.history.theta, rtol=1e-8, atol=1e-14)


def test_pulses_when_no_record_file_is_found(tmp_path, monkeypatch):
    monkeypatch.setenv("ROCKCLI_CATALOG", str(catalog_mod.catalog_path()))
    monkeypatch.setenv("ROCKCLI_RECORDS", str(tmp_path))
    monkeypatch.setattr(catalog_mod, "REPO_RECORDS", tmp_path / "nothing")
    out = tmp_path / "t.csv"
    res = invoke("bassae", "--isolation", "none", "--no-margin", "--csv", out)
    assert res.exit_code == 0, res.output
    assert "kobe-1995-takarazuka-000 (pulse)" in res.output
    assert "Idealised (record file not found" in res.output
    assert "Not available: vrancea-1977-bucharest" in res.output
    df = read_assessment_csv(out)
    assert len(df) == 10 and (df.excitation == "pulse").all()
    survivors = int((~df.overturned.astype(bool)).sum())
    assert [line.split() for line in res.output.splitlines() if line.startswith("survives ") and line.endswith(" of 10")] == [
        ["survives", "(10", "of", "10", "are", "pulses)", str(survivors), "of", "10"]]  # the summary says so too


def test_default_assessment_of_both_columns_table_iii_layout(records_dirs, tmp_path):
    """The README's main job: both temple columns, the Table II records, the Table III configurations."""
    found = [e for e in catalog_mod.load_catalog() if e.pga_published_g is not None and catalog_mod.find_file(e)]
    out = tmp_path / "table.csv"
    res = invoke("bassae", "nemea", "--csv", out)
    assert res.exit_code == 0, res.output
    df = read_assessment_csv(out)
    n = len(found)
    assert len(df) == 2 * 10 * 4 and (df.excitation == "record").sum() == 2 * n * 4
    for col in ("bassae", "nemea"):
        assert list(df[df.column == col].configuration.unique()) == ["none", "Tb=2s", "Tb=2.5s", "Tb=3s"]
    lines = res.output.splitlines()
    assert sum(line.startswith("survives ") and line.count(" of 10") == 4 for line in lines) == 2
    assert "Not available: vrancea-1977-bucharest" in res.output
    # margins: every scene has a finite margin or the note
    assert (df.overturn_scale.notna() | (df.margin_note != "")).all()
    over = df.overturned.astype(bool)
    assert (df[over].overturn_scale <= 1.0).all()


def test_help_imports_nothing_heavy():
    code = ("import sys; from click.testing import CliRunner; from rockcli.cli import main; "
            "r = CliRunner().invoke(main, ['assess', 'column', '--help']); assert r.exit_code == 0, r.output; "
            "print(sorted(m for m in ('numba', 'pandas', 'matplotlib', 'obspy', 'scipy') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
