"""``rockcli fit-pulse``: output, files written, errors, catalogue generator."""

import csv
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.pulses import RickerAntisymmetric, RickerSymmetric
from rockcli.pulses_fit import fit_pulse
from rockcli.io.units import G

REPO = Path(__file__).resolve().parents[1]
PULSE_COLUMNS = ("pulse_shape", "a_p_g", "T_p_s", "t0_s", "pulse_energy")


def _write_g_column(path, pulse, dt, t_end, noise=0.0, seed=0):
    t = dt * np.arange(int(round(t_end / dt)) + 1)
    acc = pulse.acceleration(t)
    if noise:
        acc = acc + noise * G * np.random.default_rng(seed).standard_normal(t.size)
    np.savetxt(path, acc / G, fmt="%.10e")
    return path


@pytest.fixture
def two_files(tmp_path):
    a = _write_g_column(tmp_path / "sym.txt", RickerSymmetric(0.35 * G, 0.8, 5.0), 0.01, 12.0)
    b = _write_g_column(tmp_path / "anti.txt", RickerAntisymmetric(-0.2 * G, 2.0, 9.0), 0.01, 20.0, noise=0.01)
    return a, b


def _invoke(args, **kw):
    return CliRunner().invoke(main, args, catch_exceptions=False, **kw)


def _table_rows(output):
    lines = [ln for ln in output.splitlines() if ln.strip()]
    return lines[0], lines[1:]


def test_table_one_row_per_record_aligned(two_files):
    a, b = two_files
    res = _invoke(["fit-pulse", str(a), str(b), "--units", "g", "--dt", "0.01"])
    assert res.exit_code == 0, res.output
    head, rows = _table_rows(res.output)
    assert head.split() == ["record", "wavelet", "a_p_g", "T_p_s", "t0_s", "energy_fraction"]
    assert len(rows) == 2
    # right-aligned numeric columns end at the same character as their header
    for col in ("a_p_g", "T_p_s", "t0_s", "energy_fraction"):
        end = head.index(col) + len(col)
        for r in rows:
            assert r[end - 1] != " " and (len(r) == end or r[end] == " ")
    sym = rows[0].split()
    assert sym[0] == "sym.txt" and sym[1] == "symmetric"
    assert float(sym[2]) == pytest.approx(0.35, abs=1e-4) and float(sym[3]) == pytest.approx(0.8, abs=1e-4)
    assert float(sym[4]) == pytest.approx(5.0, abs=1e-3) and float(sym[5]) == pytest.approx(1.0, abs=1e-3)
    anti = rows[1].split()
    assert anti[1] == "antisymmetric"
    assert float(anti[2]) == pytest.approx(-0.2, rel=0.02) and float(anti[3]) == pytest.approx(2.0, rel=0.02)


def test_json_matches_the_library(two_files):
    from rockcli.records import read_record

    a, _ = two_files
    res = _invoke(["fit-pulse", str(a), "--units", "g", "--dt", "0.01", "--json", "--wavelet", "antisymmetric",
                   "--periods", "0.2:3"])
    assert res.exit_code == 0
    (row,) = json.loads(res.output)
    ref = fit_pulse(read_record(str(a), units="g", dt=0.01), "antisymmetric", periods=(0.2, 3.0))
    assert row["wavelet"] == "antisymmetric" and row["pulse_shape"] == "ricker-anti"
    for key in ("a_p_g", "T_p_s", "t0_s", "energy_fraction"):
        assert row[key] == pytest.approx(getattr(ref, key), rel=1e-12)
    assert row["periods_s"] == [0.2, 3.0] and "alternative" not in row


def test_csv_and_plot_written(two_files, tmp_path):
    a, b = two_files
    out_csv, out_png = tmp_path / "fits.csv", tmp_path / "fits.png"
    res = _invoke(["fit-pulse", str(a), str(b), "--units", "g", "--dt", "0.01", "--csv", str(out_csv),
                   "--plot", str(out_png)])
    assert res.exit_code == 0, res.output
    with open(out_csv, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["record"] for r in rows] == ["sym.txt", "anti.txt"]
    assert float(rows[0]["a_p_g"]) == pytest.approx(0.35, abs=1e-4)
    assert float(rows[1]["T_p_s"]) == pytest.approx(2.0, rel=0.02)
    assert rows[0]["period_min_s"] == "0.1" and rows[0]["period_max_s"] == "6.0"
    assert out_png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    import matplotlib.image

    h, w = matplotlib.image.imread(out_png).shape[:2]
    assert h > w * 0.5  # two stacked panels
    assert not [p.name for p in tmp_path.iterdir() if p.name.startswith(".")]  # no temp files left


@pytest.mark.parametrize(
    "args,match",
    [
        (["--periods", "6:0.1"], "--periods"),
        (["--periods", "x"], "--periods"),
        (["--update-catalog"], "--update-catalog needs --catalog"),
        (["--catalog", "--units", "g"], "apply to files"),
        ([], "give at least one SOURCE"),
        (["no-such-file-or-id"], "no-such-file-or-id"),
    ],
)
def test_errors_are_one_sentence_exit_2(args, match, two_files, tmp_path):
    a, _ = two_files
    src = [str(a), "--units", "g", "--dt", "0.01"] if args[:1] in (["--periods"],) else []
    res = _invoke(["fit-pulse", *src, *args])
    assert res.exit_code == 2
    assert match in res.output and "Traceback" not in res.output


def test_nothing_written_when_a_source_fails(two_files, tmp_path):
    a, _ = two_files
    bad = tmp_path / "bad.txt"
    bad.write_text("1.0\nnot-a-number\n")
    out_csv, out_png = tmp_path / "out.csv", tmp_path / "out.png"
    res = _invoke(["fit-pulse", str(a), str(bad), "--units", "g", "--dt", "0.01", "--csv", str(out_csv),
                   "--plot", str(out_png)])
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert not out_csv.exists() and not out_png.exists()


def test_help_imports_nothing_heavy():
    code = (
        "import sys; from click.testing import CliRunner; from rockcli.cli import main; "
        "r = CliRunner().invoke(main, ['fit-pulse', '--help']); assert r.exit_code == 0, r.output; "
        "print(','.join(m for m in ('obspy', 'numba', 'pandas', 'matplotlib', 'pywt', 'scipy') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == ""


# --- catalogue ---------------------------------------------------------------------------------------


def _catalog_files_available():
    from rockcli.records.catalog import find_file, load_catalog

    entries = [e for e in load_catalog() if e.available]
    found = [e for e in entries if find_file(e) is not None]
    return entries, found


@pytest.fixture
def catalogue_records():
    if not os.environ.get("ROCKCLI_RECORDS"):
        pytest.skip("ROCKCLI_RECORDS not set")
    entries, found = _catalog_files_available()
    if not found:
        pytest.skip("no catalogue record file on ROCKCLI_RECORDS")
    return entries, found


def test_catalog_fits_every_available_record(catalogue_records):
    entries, found = catalogue_records
    res = _invoke(["fit-pulse", "--catalog", "--json"])
    assert res.exit_code == 0
    rows = json.loads(res.stdout)
    assert [r["record"] for r in rows] == [e.id for e in found]
    for r in rows:
        assert 0.0 < r["energy_fraction"] < 1.0 and 0.1 <= r["T_p_s"] <= 6.0


def test_update_catalog_changes_only_the_pulse_columns(catalogue_records, tmp_path, monkeypatch):
    from rockcli.records.catalog import catalog_path

    original = catalog_path()
    work = tmp_path / "catalog.csv"
    shutil.copy(original, work)
    with open(work, newline="") as fh:
        before = list(csv.DictReader(fh))
    blank = [{**r, **{c: "" for c in PULSE_COLUMNS}} for r in before]
    with open(work, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(before[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(blank)
    monkeypatch.setenv("ROCKCLI_CATALOG", str(work))
    res = _invoke(["fit-pulse", "--catalog", "--update-catalog"])
    assert res.exit_code == 0, res.output
    with open(work, newline="") as fh:
        after = list(csv.DictReader(fh))
    assert [r["id"] for r in after] == [r["id"] for r in before]
    _, found = catalogue_records
    fitted = {e.id for e in found}
    for b, r in zip(before, after):
        assert {k: v for k, v in r.items() if k not in PULSE_COLUMNS} == {
            k: v for k, v in b.items() if k not in PULSE_COLUMNS}
        if r["id"] in fitted:
            assert r["pulse_shape"] in ("ricker-sym", "ricker-anti") and float(r["T_p_s"]) > 0
        else:
            assert all(r[c] == "" for c in PULSE_COLUMNS)


def test_committed_catalog_holds_the_current_fits(catalogue_records):
    """records/catalog.csv is generated by `rockcli fit-pulse --catalog --update-catalog`, not typed in."""
    from rockcli.records import read_record
    from rockcli.records.catalog import load_catalog

    _, found = catalogue_records
    by_id = {e.id: e for e in load_catalog(REPO / "records" / "catalog.csv")}
    for e in found[:4]:
        stored = by_id[e.id]
        if stored.a_p_g is None:
            pytest.fail(f"{e.id}: pulse columns empty; run rockcli fit-pulse --catalog --update-catalog")
        f = fit_pulse(read_record(e.id))
        assert stored.pulse_shape == f.pulse.shape
        assert stored.a_p_g == pytest.approx(f.a_p_g, abs=6e-5)
        assert stored.T_p_s == pytest.approx(f.T_p_s, abs=6e-5)
        assert stored.t0_s == pytest.approx(f.t0_s, abs=6e-4)
        assert stored.pulse_energy == pytest.approx(f.energy_fraction, abs=6e-5)


def test_candidates_table_json_csv_and_plot(tmp_path):
    first, second = RickerSymmetric(0.5 * G, 0.6, 4.0), RickerAntisymmetric(-0.25 * G, 1.6, 12.0)
    t = 0.01 * np.arange(2001)
    path = tmp_path / "two.txt"
    np.savetxt(path, (first.acceleration(t) + second.acceleration(t)) / G, fmt="%.10e")
    args = ["fit-pulse", str(path), "--units", "g", "--dt", "0.01", "--candidates", "2"]
    res = _invoke(args + ["--csv", str(tmp_path / "c.csv"), "--plot", str(tmp_path / "c.png")])
    assert res.exit_code == 0, res.output
    lines = res.output.splitlines()
    assert lines[0].split() == ["record", "rank", "wavelet", "a_p_g", "T_p_s", "t0_s", "energy_fraction"]
    one, two = lines[1].split(), lines[2].split()  # the longer pulse explains more energy (52 %)
    assert one[:3] == ["two.txt", "1", "antisymmetric"] and one[-2:] == ["<-", "fit"]
    assert float(one[4]) == pytest.approx(1.6, rel=0.01)
    assert two[:2] == ["2", "symmetric"] and float(two[3]) == pytest.approx(0.6, rel=0.01)
    rows = list(csv.DictReader(open(tmp_path / "c.csv")))
    assert [(r["rank"], r["fit"], r["pulse_shape"]) for r in rows] == [("1", "True", "ricker-anti"),
                                                                       ("2", "False", "ricker-sym")]
    assert (tmp_path / "c.png").stat().st_size > 10_000
    data = json.loads(_invoke(args + ["--json"]).output)
    cands = data[0]["candidates"]
    assert [c["rank"] for c in cands] == [1, 2] and cands[0]["fit"] and not cands[1]["fit"]
    assert cands[1]["a_p_g"] == pytest.approx(0.5, rel=0.01)
    res = CliRunner().invoke(main, args[:-2] + ["--candidates", "0"])
    assert res.exit_code == 2
