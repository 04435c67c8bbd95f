"""The input layer (issue 23): every example of the issue's input classes, one test each.

Numbers the user writes (options, specs, samples, time steps in comments) go through
:func:`rockcli.io.inputs.parse_number`; compressed records are read with the units they state, once;
odd environments (``ROCKCLI_RECORDS``, the catalogue) get one sentence and exit code 2. Every CLI case
asserts exit 2, exactly one line ``Error: ...`` quoting what was written, no traceback, nothing written.
"""

from __future__ import annotations

import bz2
import gzip
import lzma
import math
import os
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number, parse_number, spec_items
from rockcli.pulses import RickerSymmetric
from rockcli.records import read_record
from rockcli.io.units import G
from test_bad_input import assert_one_sentence as _one_sentence
from test_bad_input import snapshot

DT = 0.01
#: a symmetric Ricker of 0.697 g (the Kobe record's PGA in the issue), 6 s of record [g]
PULSE_G = RickerSymmetric(0.697 * G, 0.8).acceleration(DT * np.arange(600)) / G
HEAD = ["PEER NGA STRONG MOTION DATABASE RECORD", "Synthetic, 1/1/2000, Test station, 0",
        "ACCELERATION TIME SERIES IN UNITS OF G"]


def at2_bytes(values=PULSE_G, bom=False) -> bytes:
    rows = ["".join(f"{v:15.7E}" for v in values[i:i + 5]) for i in range(0, len(values), 5)]
    text = "\r\n".join([*HEAD, f"NPTS=   {len(values)}  DT=   .0100 SEC,", *rows]) + "\r\n"
    return (b"\xef\xbb\xbf" if bom else b"") + text.encode("latin-1")


def text_record(samples, comments=("units: g", "dt=0.01 sec")) -> str:
    return "".join(f"# {c}\n" for c in comments) + "".join(f"{s}\n" for s in samples)


def run_cli(args, env=None):
    return CliRunner().invoke(main, [str(a) for a in args], env=env)


def assert_one_sentence(res, *words):
    """Exit 2, one line ``Error: ...`` holding every one of ``words``, no traceback (as in test_bad_input)."""
    _one_sentence(res, words)


@pytest.fixture
def work(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


# --------------------------------------------------------------------------------------------------
# the number parser
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("text, value", [("0.5", 0.5), (" -2e-3 ", -2e-3), (".5", 0.5), ("5.", 5.0), ("+1E2", 100.0)])
def test_plain_decimals_are_read(text, value):
    assert parse_number(text, "x") == value


@pytest.mark.parametrize("text, words", [
    ("1_0", "underscores"), ("inf", "not a finite number"), ("-Infinity", "not a finite number"),
    ("nan", "not a finite number"), ("0x10", "hexadecimal"), ("1,5", "decimal comma"), ("1e999", "too large"),
    ("\u0661\u0660", "digits 0-9"), ("1d-2", "exponent with e"), ("", "is empty"), ("abc", "is not a number")])
def test_python_only_forms_are_refused_quoting_the_text(text, words):
    with pytest.raises(RockcliInputError) as info:
        parse_number(text, "--x")
    msg = str(info.value)
    assert words in msg and "\n" not in msg
    if text:
        assert text in msg


def test_fortran_exponents_only_where_asked():
    assert parse_number("1.0D-02", "dt", fortran=True) == 0.01
    with pytest.raises(RockcliInputError):
        parse_number("1.0D-02", "dt")


@pytest.mark.parametrize("x", [100.0001, 1e-6, 0.1 + 0.2, 2.5, 1e300, -7.77])
def test_format_number_is_exact_and_short(x):
    assert float(format_number(x)) == x
    assert format_number(2.5) == "2.5" and format_number(100.0001) == "100.0001"


def test_models_write_their_sentences_only_for_a_check_that_fails(monkeypatch):
    """A block, a bearing or a plinth built within its ranges formats no number (a sweep builds thousands of
    them); out of range, the sentence quotes the number as written."""
    import rockcli.io.inputs as inputs
    from rockcli.models import (Block, DoubleConcaveSliding, LeadRubber, LinearIsolation, Plinth,
                                SingleConcaveSliding, Stack)

    def build():
        body = Block.from_dimensions(1.79, 0.5)
        return [Block(1.0, 0.2), Block.from_degrees(1.2, 14.0), body, LinearIsolation(2.5, 0.1, 0.05),
                SingleConcaveSliding(2.0, 0.05), LeadRubber(2.0, 0.05, 0.02), DoubleConcaveSliding(0.5, 0.5, 0.03, 0.07),
                Stack(body, Plinth(1.0, 0.6))]

    expected = build()
    monkeypatch.setattr(inputs, "format_number", lambda *a, **k: pytest.fail("a number formatted for no message"))
    assert build() == expected
    monkeypatch.undo()
    for make, words in [(lambda: Block(1.0, 0.001), "0.001 rad"), (lambda: Block.from_degrees(200.0, 14.0), "200"),
                        (lambda: Block.from_dimensions(0.01, 0.002), "from height 0.01 m and width 0.002 m"),
                        (lambda: LinearIsolation(2.5, 11.5), "xi = 11.5"), (lambda: Plinth(0.5, -1.25), "-1.25")]:
        with pytest.raises(RockcliInputError, match=words.replace(".", r"\.")):
            make()


def test_spec_items_refuse_a_key_given_twice_case_insensitively():
    with pytest.raises(RockcliInputError, match="ap is given twice"):
        spec_items("ap=1,ap=2", "pulse spec")
    with pytest.raises(RockcliInputError, match=r"Tb \(as TB\) is given twice"):
        spec_items("Tb=1,TB=2", "isolation")
    with pytest.raises(RockcliInputError, match="decimal comma.*write Tb=2.5"):
        spec_items("Tb=2,5", "isolation")


# --------------------------------------------------------------------------------------------------
# options and specs on the command line
# --------------------------------------------------------------------------------------------------
SIM = ["simulate", "--height", "2", "--width", "0.5"]
SINE = ["--pulse", "sine:ap=0.5,Tp=0.5"]

OPTION_CASES = {
    "R-rounded": (["simulate", "--R", "100.0001", "--alpha", "10", *SINE], ["R = 100.0001 m", "0.01 m to 100 m"]),
    "R-underscore": (["simulate", "--R", "1_0", "--alpha", "10", *SINE], ["--R '1_0'", "underscores"]),
    "R-comma": (["simulate", "--R", "1,5", "--alpha", "10", *SINE], ["--R '1,5'", "decimal comma", "write 1.5"]),
    "R-inf": (["simulate", "--R", "inf", "--alpha", "10", *SINE], ["--R 'inf' is not a finite number"]),
    "R-hex": (["simulate", "--R", "0x10", "--alpha", "10", *SINE], ["--R '0x10'", "hexadecimal"]),
    "tail-huge": ([*SIM, *SINE, "--tail", "1e999"], ["--tail 1e999 is too large"]),
    "seed-negative": (["assess", "fragility", "bassae", "--seed", "-1"], ["--seed -1 must lie between 0 and"]),
    "bootstrap-underscore": (["assess", "fragility", "bassae", "--bootstrap", "1_000"], ["--bootstrap '1_000'"]),
    "column-word": (["records", "show", "x.txt", "--record-column", "two"], ["--record-column 'two'"]),
    "pulse-ap-twice": ([*SIM, "--pulse", "sine:ap=0.5,ap=0.9,Tp=0.5"], ["ap is given twice"]),
    "pulse-ap-rounded": ([*SIM, "--pulse", "sine:ap=100.0001,Tp=0.5"], ["a_p = 100.0001 g", "100 g"]),
    "pulse-ap-1e308": ([*SIM, "--pulse", "sine:ap=1e308,Tp=0.5"], ["a_p = 1e308 g"]),
    "pulse-Tp-rounded": ([*SIM, "--pulse", "sine:ap=0.5,Tp=1000.0001"], ["T_p = 1000.0001 s"]),
    "pulse-underscore": ([*SIM, "--pulse", "sine:ap=0.5,Tp=1_0"], ["Tp '1_0'", "underscores"]),
    "pulse-comma": ([*SIM, "--pulse", "sine:ap=0,5,Tp=1"], ["ap=0,5 is written with a decimal comma", "ap=0.5"]),
    "isolation-twice": ([*SIM, *SINE, "--isolation", "linear:Tb=2,xi=0.1,Tb=3"], ["Tb is given twice"]),
    "isolation-twice-case": ([*SIM, *SINE, "--isolation", "linear:Tb=2,TB=3"], ["Tb (as TB) is given twice"]),
    "isolation-comma": ([*SIM, *SINE, "--isolation", "linear:Tb=2,5"], ["decimal comma", "Tb=2.5"]),
    "isolation-inf": ([*SIM, *SINE, "--isolation", "linear:Tb=inf"], ["Tb 'inf' is not a finite number"]),
    "isolation-Tb-rounded": ([*SIM, *SINE, "--isolation", "linear:Tb=0.0049999"], ["Tb = 0.0049999 s"]),
    "column-spec-twice": (["assess", "column", "statue:R=1,alpha=10,R=2", "--records", "x.AT2"],
                          ["column 'statue:R=1,alpha=10,R=2': R is given twice"]),
    "spectrum-Tp-twice": (["spectrum", "min-overturning", "--alpha", "10", "--pulse", "ricker-sym:Tp=1,Tp=2"],
                          ["Tp is given twice"]),
    "spectrum-TbTp-twice": (["spectrum", "min-overturning", "--alpha", "10", "--isolation",
                             "linear:TbTp=2,TbTp=3"], ["TbTp is given twice"]),
    "spectrum-param-twice": (["spectrum", "min-overturning", "--alpha", "10", "--isolation",
                              "linear:TbTp=2,xi=0.1,xi=0.2"], ["xi is given twice"]),
    "spectrum-ap-1e306": (["spectrum", "overturning", "--alpha", "10", "--ap", "1e306:1e306:1"],
                          ["--ap '1e306:1e306:1' reaches a_p = 1.76e+305 g at alpha = 10 deg", "supported 100 g"]),
    "periods-underscore": (["fit-pulse", "x.AT2", "--periods", "0.1:1_0"], ["--periods '0.1:1_0'", "underscores"]),
}


@pytest.mark.parametrize("case", OPTION_CASES.values(), ids=list(OPTION_CASES))
def test_options_and_specs_one_sentence(work, case):
    args, words = case
    before = snapshot(work)
    assert_one_sentence(run_cli(args), *words)
    assert snapshot(work) == before


# --------------------------------------------------------------------------------------------------
# records: compressed, units once; samples and time steps as written
# --------------------------------------------------------------------------------------------------
def _compress(kind: str, name: str, data: bytes, folder: Path) -> Path:
    if kind == "zip":
        path = folder / f"{name}.zip"
        with zipfile.ZipFile(path, "w") as zf:
            zf.writestr(name, data)
        return path
    suffix, packer = {"gz": (".gz", gzip.compress), "bz2": (".bz2", bz2.compress), "xz": (".xz", lzma.compress)}[kind]
    path = folder / f"{name}{suffix}"
    path.write_bytes(packer(data))
    return path


@pytest.mark.parametrize("kind", ["gz", "bz2", "zip", "xz"])
def test_compressed_record_is_read_with_its_units_once(work, kind):
    plain = work / "k.AT2"
    plain.write_bytes(at2_bytes())
    packed = _compress(kind, "k.AT2", at2_bytes(), work)
    ref = read_record(plain)
    rec = read_record(packed)
    np.testing.assert_array_equal(rec.acc, ref.acc)
    assert rec.pga_g == pytest.approx(0.697, rel=1e-6)  # not 0.697 x 9.80665 = 6.84
    assert rec.meta["units"] == "G" and rec.meta["units_source"] == "file" and rec.meta["compression"]
    assert rec.meta["path"] == str(packed) and rec.name == packed.name
    # the units the file states, given again, agree (and are not applied a second time)
    np.testing.assert_array_equal(read_record(packed, units="g").acc, ref.acc)
    with pytest.raises(RockcliInputError, match="states units 'G' but 'gal' was given"):
        read_record(packed, units="gal")
    res = run_cli(["records", "show", packed])
    assert res.exit_code == 0 and "PGA                   0.6970 g" in res.output, res.output


def test_compressed_text_record_states_its_units_in_a_comment(work):
    data = text_record([repr(float(v)) for v in PULSE_G]).encode()
    rec = read_record(_compress("gz", "r.txt", data, work))
    assert rec.pga_g == pytest.approx(0.697, rel=1e-9) and rec.dt == 0.01


def test_obspy_reading_an_at2_is_not_converted_twice(work):
    """Through ObsPy (as ``obspy.read`` of a compressed AT2 went before) the plugin's m/s^2 are stated."""
    from rockcli.records.reader import _finish, _from_obspy

    path = work / "k.AT2"
    path.write_bytes(at2_bytes())
    out = _from_obspy(path, "OBSPY", None)
    assert out["units"] == "m/s^2"
    rec = _finish(path, out, None, None, "caller")
    assert rec.pga_g == pytest.approx(0.697, rel=1e-6)
    with pytest.raises(RockcliInputError, match="states units 'm/s\\^2' but 'g' was given"):
        _finish(path, out, "g", None, "caller")


BAD_COMPRESSED = {
    "two.zip": (lambda d: _zip_of(d, {"a.AT2": at2_bytes(), "b.AT2": at2_bytes()}), ["holds 2 files (a.AT2, b.AT2)"]),
    "empty.zip": (lambda d: _zip_of(d, {}), ["holds 0 files"]),
    "twice.gz": (lambda d: (d / "twice.gz").write_bytes(gzip.compress(gzip.compress(at2_bytes()))),
                 ["holds another compressed file"]),
    "cut.gz": (lambda d: (d / "cut.gz").write_bytes(gzip.compress(at2_bytes())[:200]), ["damaged gzip file"]),
    "nan.AT2.gz": (lambda d: (d / "nan.AT2.gz").write_bytes(gzip.compress(at2_bytes().replace(b"E-", b"X-", 1))),
                   ["nan.AT2.gz (nan.AT2 inside), line 5"]),
}


def _zip_of(folder: Path, members: dict) -> None:
    name = "two.zip" if members else "empty.zip"
    with zipfile.ZipFile(folder / name, "w") as zf:
        for k, v in members.items():
            zf.writestr(k, v)


@pytest.mark.parametrize("name", list(BAD_COMPRESSED))
def test_bad_compressed_files_one_sentence(work, name):
    make, words = BAD_COMPRESSED[name]
    make(work)
    before = snapshot(work)
    assert_one_sentence(run_cli(["records", "show", name]), name, *words)
    assert snapshot(work) == before


@pytest.mark.parametrize("stated, dt", [("dt=1.0D-02 sec", 0.01), ("dt = 10 msec", 0.01), ("dt: 10000 us", 0.01),
                                        ("dt=10 ms", 0.01), ("time step 0.005 s", 0.005), ("dt=.02", 0.02),
                                        ("dt = 5000 \u00b5s", 0.005)])
def test_time_step_in_a_comment_is_read_as_written(work, stated, dt):
    (work / "r.txt").write_text(text_record(["0.1", "-0.2", "0.3"], ("units: g", stated)), encoding="utf-8")
    rec = read_record("r.txt")
    assert rec.dt == pytest.approx(dt, rel=1e-12) and rec.meta["dt_source"] == "comment"


@pytest.mark.parametrize("stated, words", [("dt = 1,0e-2 s", ["'1,0e-2' is written with a decimal comma", "1.0e-2"]),
                                           ("dt=0.01 min", ["'min' is not a unit of a time step"]),
                                           ("dt=10 xyz", ["'xyz' is not a unit"]),
                                           ("dt=1_0 ms", ["'1_0'", "underscores"]),
                                           ("dt=1e999", ["the number 1e999 is too large"])])
def test_time_step_in_a_comment_never_guessed(work, stated, words):
    (work / "r.txt").write_text(text_record(["0.1", "-0.2", "0.3"], ("units: g", stated)))
    assert_one_sentence(run_cli(["records", "show", "r.txt"]), "r.txt: a comment states the time step", *words)


SAMPLE_CASES = {
    "underscore.txt": (text_record(["0.1", "1_0", "-0.3"]), ["underscore.txt, line 4", "'1_0'", "underscores"]),
    "arabic.txt": (text_record(["0.1", "\u0661", "-0.3"]), ["arabic.txt, line 4", "is not a number"]),
    "huge.txt": (text_record(["0.1", "1e308", "-0.3"]), ["huge.txt: sample 2 is 1e+308 g", "beyond the supported 100 g"]),
    "over.txt": (text_record(["0.1", "1e999", "-0.3"]), ["over.txt, line 4", "value 1e999 in column 1", "too large"]),
    "over.AT2": (at2_bytes().replace(b"-6.", b"1e999 -6.", 1).replace(b"NPTS=   600", b"NPTS=   601"),
                 ["over.AT2, line", "is 1e999, too large for double precision"]),
    "comma.txt": ("0,1\n-0,2\n0,3\n0,1\n", ["comma.txt, line 1", "decimal commas", "0,123 -> 0.123"]),
    "semicolon.txt": ("0,00;0,1\n0,01;-0,2\n0,02;0,3\n", ["semicolon.txt, line 1", "decimal commas"]),
    "underscore.AT2": (at2_bytes().replace(b"-6.", b"-6_", 1), ["underscore.AT2, line", "underscores"]),
    "huge.AT2": (at2_bytes(np.r_[PULSE_G[:10], 1e308, PULSE_G[11:]]), ["huge.AT2: sample 11 is 1e+308 G"]),
}


@pytest.mark.parametrize("name", list(SAMPLE_CASES))
def test_samples_as_written_or_refused(work, name):
    content, words = SAMPLE_CASES[name]
    (work / name).write_bytes(content if isinstance(content, bytes) else content.encode("utf-8"))
    before = snapshot(work)
    assert_one_sentence(run_cli(["records", "show", name, "--units", "g", "--dt", "0.01"]
                                if name in ("comma.txt", "semicolon.txt") else ["records", "show", name]), *words)
    assert snapshot(work) == before


def test_a_bom_before_the_header_is_accepted(work):
    (work / "bom.txt").write_bytes(b"\xef\xbb\xbf" + text_record(["0.1", "-0.2", "0.3"]).encode())
    (work / "bom.AT2").write_bytes(at2_bytes(bom=True))
    (work / "plain.AT2").write_bytes(at2_bytes())
    rec = read_record("bom.txt")
    assert rec.meta["units"] == "g" and rec.dt == 0.01
    np.testing.assert_array_equal(read_record("bom.AT2").acc, read_record("plain.AT2").acc)


def test_records_show_tiny_time_step_one_sentence(work):
    (work / "s.txt").write_text("0.1\n0.2\n-0.3\n0.1\n")
    assert_one_sentence(run_cli(["records", "show", "s.txt", "--units", "g", "--dt", "1e-300"]),
                        "time step dt = 1e-300 s (given) lies outside the supported 1e-06 s to 10 s")


# --------------------------------------------------------------------------------------------------
# environments: ROCKCLI_RECORDS, the catalogue
# --------------------------------------------------------------------------------------------------
KOBE = "kobe-1995-takarazuka-000"


def test_records_folder_that_does_not_exist_is_refused(work):
    env = {"ROCKCLI_RECORDS": str(work / "nope")}
    assert_one_sentence(run_cli(["records", "show", KOBE], env=env),
                        f"ROCKCLI_RECORDS names {work / 'nope'}, which does not exist")
    # assess does not quietly run the catalogued pulses instead of the records
    before = snapshot(work)
    assert_one_sentence(run_cli(["assess", "column", "bassae", "--isolation", "none", "--no-margin", "--csv", "t.csv"],
                                env=env), "which does not exist")
    assert snapshot(work) == before


def test_records_folder_that_is_a_file_is_refused(work):
    (work / "afile").write_text("x")
    assert_one_sentence(run_cli(["records", "show", KOBE], env={"ROCKCLI_RECORDS": str(work / "afile")}),
                        "which is not a folder")


@pytest.mark.skipif(hasattr(os, "geteuid") and os.geteuid() == 0, reason="root reads every folder")
def test_unreadable_records_folder_is_refused(work):
    folder = work / "locked"
    folder.mkdir(mode=0)
    try:
        assert_one_sentence(run_cli(["records", "show", KOBE], env={"ROCKCLI_RECORDS": str(folder)}),
                            "cannot be read")
    finally:
        folder.chmod(0o755)


def test_pulse_in_place_of_a_record_is_announced_on_every_row_and_in_the_summary(work):
    """``--excitation auto`` runs the catalogued pulse where the file is missing: said in the row, on the count
    line and on stderr, never silently (``--excitation record`` refuses instead)."""
    (work / "empty").mkdir()
    env = {"ROCKCLI_RECORDS": str(work / "empty")}
    res = run_cli(["assess", "column", "bassae", "--records", KOBE, "--isolation", "none", "--no-margin"], env=env)
    assert res.exit_code == 0, res.output
    assert f"{KOBE} (pulse)" in res.stdout and "(1 of 1 are pulses)" in res.stdout
    assert "Warning: 1 of 1 records ran as their catalogued pulse" in res.stderr
    res = run_cli(["assess", "column", "bassae", "--records", KOBE, "--isolation", "none", "--no-margin",
                   "--excitation", "record"], env=env)
    assert_one_sentence(res, f"record {KOBE!r} cannot be run", "not found")


def _catalogue(work: Path, text: bytes) -> dict:
    from rockcli.records.catalog import catalog_path

    good = catalog_path().read_bytes()
    path = work / "cat.csv"
    path.write_bytes(text(good) if callable(text) else text)
    return {"ROCKCLI_CATALOG": str(path)}


def test_catalogue_not_utf8_one_sentence(work):
    env = _catalogue(work, lambda good: good.replace(b"Parkfield", "Parkfi\u00e9ld".encode("latin-1"), 1))
    assert_one_sentence(run_cli(["records", "list"], env=env), "cat.csv, line 2: byte 0xe9 is not UTF-8")


def test_catalogue_with_a_bom_is_read(work):
    env = _catalogue(work, lambda good: b"\xef\xbb\xbf" + good)
    res = run_cli(["records", "list"], env=env)
    assert res.exit_code == 0 and KOBE in res.output, res.output


def test_catalogue_cell_underscore_refused(work):
    env = _catalogue(work, lambda good: good.replace(b",6.1,0.1,0.48,", b",6.1,0.1,0_48,", 1))
    assert_one_sentence(run_cli(["records", "list"], env=env), "cat.csv, line 2: column 'pga_published_g'", "'0_48'")


def test_catalogue_fifo_does_not_block(work):
    """A FIFO as the catalogue: refused without opening it (opening it would wait for a writer forever).
    Run in a child process so that a regression shows as a failed test, not a hung suite."""
    if not hasattr(os, "mkfifo"):
        pytest.skip("no FIFOs here")
    os.mkfifo(work / "cat.csv")
    env = {**os.environ, "ROCKCLI_CATALOG": str(work / "cat.csv"),
           "PYTHONPATH": os.pathsep.join([str(Path(__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.run([sys.executable, "-m", "rockcli", "records", "list"], env=env, capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr
    assert proc.stderr.strip().splitlines() == [f"Error: record catalogue {work / 'cat.csv'} is not a regular file "
                                                f"(a pipe, device or socket); ROCKCLI_CATALOG must name a CSV file"]


# --------------------------------------------------------------------------------------------------
# fragility over too few records: said, not printed as a measured beta
# --------------------------------------------------------------------------------------------------
def _curve(n, beta):
    from rockcli.assess.fragility import FragilityCurve

    return FragilityCurve("bassae", None, n, n, 0, 0, 1.0, beta)


def test_fragility_over_two_records_warns():
    from rockcli.assess.fragility import MIN_RECORDS_FOR_BETA, _thin_fit_note

    assert "curve is a step" in _thin_fit_note(_curve(2, 0.0))
    assert "fitted over 3 records only" in _thin_fit_note(_curve(3, 0.4))
    assert _thin_fit_note(_curve(MIN_RECORDS_FOR_BETA, 0.4)) == ""
    assert math.isnan(_curve(2, math.nan).beta)  # no fit: no note of this kind (the "no fit" note says it)


def test_records_folder_without_read_permission_one_sentence(work, monkeypatch):
    """``assess column --records DIR`` on a folder it may not list (simulated: the tests may run as root)."""
    (work / "locked").mkdir()

    def denied(self):
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(Path, "iterdir", denied)
    assert_one_sentence(run_cli(["assess", "column", "bassae", "--records", "locked", "--isolation", "none"]),
                        "--records locked: the folder cannot be read (permission denied)")


def test_catalogue_id_with_a_broken_catalogue_names_the_catalogue(work):
    env = _catalogue(work, lambda good: good.replace(b"Parkfield", "Parkfi\u00e9ld".encode("latin-1"), 1))
    assert_one_sentence(run_cli(["records", "show", KOBE], env=env), "record catalogue", "is not UTF-8")


@pytest.mark.parametrize("interval, ndata, ok", [("0.01", "4", True), ("0_01", "4", False), ("0.01", "1_0", False),
                                                 ("1.0D-02", "4", True)])
def test_esm_header_numbers_as_written(work, interval, ndata, ok):
    (work / "r.esm").write_text(f"EVENT_NAME: test\nSAMPLING_INTERVAL_S: {interval}\nNDATA: {ndata}\nUNITS: cm/s^2\n"
                                f"DATA_TYPE: ACCELERATION\n0.1\n-0.2\n0.3\n0.1\n")
    if ok:
        rec = read_record("r.esm")
        assert rec.meta["format"] == "ESM" and rec.dt == 0.01 and rec.npts == 4
    else:
        assert_one_sentence(run_cli(["records", "show", "r.esm"]), "r.esm: ESM header lacks a valid")


def test_time_step_conflict_quotes_both_values_unrounded(work):
    (work / "k.AT2").write_bytes(at2_bytes())
    with pytest.raises(RockcliInputError, match=r"states dt=0.01 s but dt=0.0100001 s was given"):
        read_record("k.AT2", dt=0.0100001)
    assert_one_sentence(run_cli(["records", "show", "k.AT2", "--dt", "0"]), "dt=0 s must be a positive")
