"""``rockcli records list`` / ``show``: output, exit codes, bad input (CliRunner), import weight."""

from __future__ import annotations

import csv
import os
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main


def run(*args, env=None):
    return CliRunner().invoke(main, list(args), env=env, catch_exceptions=False)


def test_list_and_csv(tmp_path, records_dirs):
    env = {"ROCKCLI_RECORDS": os.pathsep.join(map(str, records_dirs))}
    out = tmp_path / "list.csv"
    res = run("records", "list", "--csv", str(out), env=env)
    assert res.exit_code == 0, res.output
    assert "kobe-1995-takarazuka-000" in res.output and "not available" in res.output
    with open(out, newline="") as fh:
        rows = list(csv.DictReader(fh))
    from rockcli.records.catalog import load_catalog

    assert [r["id"] for r in rows] == [e.id for e in load_catalog()]  # every row of the catalogue (14)
    assert len(rows) == 14
    assert {r["id"]: r["present"] for r in rows}["imperialvalley-1979-elcentro6-230"] == "230+140"
    status = {r["id"]: r["status"] for r in rows}
    assert status["vrancea-1977-bucharest"] == "not available" and status["aigio-1995-ote-fp"] == "not available"
    assert status["kobe-1995-takarazuka-000"] == "found"
    kobe = next(r for r in rows if r["id"] == "kobe-1995-takarazuka-000")
    assert kobe["path"].endswith("RSN1119_KOBE_TAZ000.AT2") and kobe["pga_published_g"] == "0.69"


def test_list_without_records(tmp_path):
    res = run("records", "list", env={"ROCKCLI_RECORDS": str(tmp_path)})
    assert res.exit_code == 0
    assert "missing" in res.output


def _text_record(tmp_path):
    dt = 0.01
    t = dt * np.arange(1001)
    acc_g = 0.3 * np.sin(2 * np.pi * t)  # PGV = 2 * 0.3 g / (2 pi) [m/s] by integration from rest
    path = tmp_path / "sine.txt"
    path.write_text("".join(f"{float(a)!r}\n" for a in acc_g))
    return path


def test_show_prints_peaks_and_plots(tmp_path):
    path = _text_record(tmp_path)
    png = tmp_path / "fig.png"
    res = run("records", "show", str(path), "--units", "g", "--dt", "0.01", "--plot", str(png))
    assert res.exit_code == 0, res.output
    lines = dict(l.split("  ", 1) for l in res.output.splitlines() if "  " in l)
    assert lines["npts"].strip() == "1001"
    assert lines["dt"].strip().startswith("0.01 s")
    assert lines["duration"].strip() == "10.000 s"
    assert lines["PGA"].strip().startswith("0.3000 g")
    pgv = float(lines["PGV"].split()[0])
    x = 2 * np.pi * 0.01 / 2  # trapezoid on a sine: exact result times x / tan(x)
    assert pgv == pytest.approx(2 * 0.3 * 9.80665 / (2 * np.pi) * x / np.tan(x), abs=6e-5)
    assert "trapezoidal integration of the record as given" in res.output
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temp file left


def test_show_catalogue_id(records_dirs):
    env = {"ROCKCLI_RECORDS": os.pathsep.join(map(str, records_dirs))}
    res = run("records", "show", "kobe-1995-takarazuka-000", env=env)
    assert res.exit_code == 0, res.output
    assert "4096" in res.output and "0.6973 g" in res.output


@pytest.mark.parametrize("setup,args,words", [
    ("missing", [], "no such file"),
    ("empty", [], "the file is empty"),
    ("truncated", [], "truncated AT2 file"),
    ("nan", ["--units", "g", "--dt", "0.01"], "not a finite number"),
    ("token", ["--units", "g", "--dt", "0.01"], "'abc' is not a number"),
    ("time-back", ["--units", "g"], "the time column is not increasing"),
    ("time-uneven", ["--units", "g"], "not uniformly sampled"),
    ("dt0", ["--units", "g", "--dt", "0"], "must be a positive finite number"),
    ("dtneg", ["--units", "g", "--dt", "-0.01"], "must be a positive finite number"),
    ("units", ["--units", "furlongs", "--dt", "0.01"], "unknown acceleration unit 'furlongs'"),
    ("nounits", ["--dt", "0.01"], "does not state its units; give them with --units"),
    ("nodt", ["--units", "g"], "does not state its time step; give it with --dt"),
])
def test_bad_input_exit_2_one_sentence(tmp_path, setup, args, words):
    p = tmp_path / "r.txt"
    if setup == "empty":
        p.write_text("")
    elif setup == "truncated":
        p = tmp_path / "r.AT2"
        p.write_text("PEER\nX, 1/1/2000, S, 0\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 10 DT= .01 SEC\n"
                     "0.1 0.2 0.3\n")
    elif setup == "nan":
        p.write_text("0.1\nnan\n0.2\n")
    elif setup == "token":
        p.write_text("0.1\n0.2\nabc\n")
    elif setup == "time-back":
        p.write_text("".join(f"{0.01 * i:.2f} 0.1\n" for i in (0, 1, 2, 3, 2, 5, 6, 7, 8, 9, 10, 11)))
    elif setup == "time-uneven":
        p.write_text("".join(f"{t:.3f} 0.1\n" for t in (0, 0.01, 0.02, 0.03, 0.045, 0.055, 0.065, 0.075)))
    elif setup != "missing":
        p.write_text("0.1\n0.2\n0.3\n")
    res = CliRunner().invoke(main, ["records", "show", str(p), *args])
    assert res.exit_code == 2, res.output
    assert words in res.output
    assert "Traceback" not in res.output
    err = [l for l in res.output.splitlines() if l.strip()]
    assert len(err) == 1 and err[0].startswith("Error: ")


def test_plot_into_missing_folder(tmp_path):
    path = _text_record(tmp_path)
    res = CliRunner().invoke(main, ["records", "show", str(path), "--units", "g", "--dt", "0.01",
                                    "--plot", str(tmp_path / "nope" / "f.png")])
    assert res.exit_code == 2 and "does not exist" in res.output


def test_help_imports_nothing_heavy():
    code = ("import sys, runpy; sys.argv=['rockcli','records','--help'];\n"
            "try:\n    runpy.run_module('rockcli', run_name='__main__')\nexcept SystemExit:\n    pass\n"
            "heavy=[m for m in ('obspy','numba','pandas','matplotlib') if m in sys.modules]\n"
            "print('HEAVY', heavy)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "HEAVY []" in out
    for args in (["--help"], ["--version"]):
        code2 = code.replace("'records','--help'", ",".join(repr(a) for a in args))
        out = subprocess.run([sys.executable, "-c", code2], capture_output=True, text=True, check=True).stdout
        assert "HEAVY []" in out, args


def test_import_records_is_light():
    code = "import sys, rockcli.records; print([m for m in ('obspy','pandas','matplotlib','numba') if m in sys.modules])"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
