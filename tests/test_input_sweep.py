"""A property-based hostile sweep of the inputs (issue 23): random malformed option values, specs and
record files fed to the commands.

Every example must end with exit code 2 and exactly one line ``Error: ...`` (no traceback), write
nothing, and return: each command runs in a worker thread watched for :data:`HANG_S` seconds, so a
hang fails the test instead of stalling the suite (a hang guard, not a timing assertion: a command
that exits 2 on its input takes milliseconds).

Bounded and reproducible: ``derandomize=True`` (the same examples on every run and in CI), no example
database written, a few hundred examples in all (about 20 s).
"""

from __future__ import annotations

import bz2
import gzip
import math
import re
import tempfile
import zipfile
from concurrent.futures import ThreadPoolExecutor
from concurrent.futures import TimeoutError as FutureTimeout
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.io.inputs import DECIMAL, parse_number

#: A command that has not returned after this long is hung (they exit 2 in milliseconds).
HANG_S = 120.0


def sweep(n: int):
    return settings(max_examples=n, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture,
                                           HealthCheck.filter_too_much])


_POOL = ThreadPoolExecutor(max_workers=1)


def snapshot(folder: Path) -> dict:
    return {str(p.relative_to(folder)): (p.stat().st_size, p.stat().st_mtime_ns) if p.is_file() else "folder"
            for p in sorted(folder.rglob("*"))}


def assert_refused(args, folder: Path):
    """Run ``rockcli ARGS``: exit 2, one ``Error:`` line, no traceback, ``folder`` unchanged, no hang."""
    before = snapshot(folder)
    future = _POOL.submit(CliRunner().invoke, main, [str(a) for a in args])
    try:
        res = future.result(timeout=HANG_S)
    except FutureTimeout:
        pytest.fail(f"rockcli {' '.join(map(str, args))} did not return within {HANG_S:g} s (hangs)")
    out = res.output
    lines = [ln for ln in out.splitlines() if ln.strip()]
    assert "Traceback" not in out and res.exit_code == 2, (args, res.exit_code, out, res.exception)
    assert len(lines) == 1 and lines[0].startswith("Error: "), (args, out)
    assert snapshot(folder) == before, args


def _plain(text: str) -> bool:
    s = text.strip()
    return re.fullmatch(DECIMAL, s) is not None and math.isfinite(float(s))


# --------------------------------------------------------------------------------------------------
# strategies
# --------------------------------------------------------------------------------------------------
_LITERALS = ["inf", "-inf", "+Infinity", "nan", "NaN", "-nan", "1_0", "1__0", "0_5", "1e1_0", "0x1A", "0X1p-3", "0b11",
             "0o7", "1e999", "-1e999", "1,5", "0,01", "-2,5e-3", "1.2.3", "", " ", "--1", "1e", "e5", ".", "+", "1d-2",
             "1D-02", "\u0663", "\u00bd", "1 0", "1e+", "0.5s", "abc", "\u2212" "1", "1,000.5", "\u00a01"]

#: Text that is not a plain decimal number: literals Python accepts and rockcli must not, and noise.
bad_numbers = st.one_of(
    st.sampled_from(_LITERALS),
    st.floats(allow_nan=False, allow_infinity=False, min_value=-1e6, max_value=1e6).map(repr)
    .filter(lambda t: re.search(r"[0-9][0-9]", t)).map(lambda t: re.sub(r"([0-9])([0-9])", r"\1_\2", t, count=1)),
    st.floats(allow_nan=False, allow_infinity=False, min_value=0.001, max_value=1e3)
    .map(lambda x: f"{x:.3f}".replace(".", ",")),
    st.text(alphabet="0123456789.,eE+-_xXinfaN ", min_size=1, max_size=7),
).filter(lambda t: not _plain(t))


# --------------------------------------------------------------------------------------------------
# the parser itself: a float equal to what was written, or one sentence; nothing else
# --------------------------------------------------------------------------------------------------
@sweep(400)
@given(text=st.one_of(bad_numbers, st.text(max_size=12),
                      st.floats(allow_nan=False, allow_infinity=False).map(repr)))
def test_parse_number_reads_plain_decimals_and_refuses_the_rest_in_one_sentence(text):
    try:
        value = parse_number(text, "--x")
    except RockcliInputError as exc:
        msg = str(exc)
        assert "\n" not in msg and msg.startswith("--x") and not _plain(text)
        if text.strip():
            assert text.strip() in msg or repr(text.strip()) in msg
    else:
        assert _plain(text) and value == float(text.strip())


# --------------------------------------------------------------------------------------------------
# option values over every command
# --------------------------------------------------------------------------------------------------
SINE = ["--pulse", "sine:ap=0.5,Tp=0.5"]
#: (command line before the option, option); {out} is a file in the example's folder that must not appear
OPTIONS = [
    (["simulate", "--alpha", "10", *SINE, "--history", "{out}"], "--R"),
    (["simulate", "--R", "1", *SINE, "--history", "{out}"], "--alpha"),
    (["simulate", "--width", "0.5", *SINE, "--history", "{out}"], "--height"),
    (["simulate", "--height", "2", *SINE, "--history", "{out}"], "--width"),
    (["simulate", "--height", "2", "--width", "0.5", *SINE, "--history", "{out}"], "--tail"),
    (["simulate", "--height", "2", "--width", "0.5", *SINE, "--history", "{out}"], "--rtol"),
    (["simulate", "--height", "2", "--width", "0.5", *SINE, "--history", "{out}"], "--horizon"),
    (["simulate", "--height", "2", "--width", "0.5", "--record", "{rec}", "--history", "{out}"], "--scale"),
    (["simulate", "--height", "2", "--width", "0.5", "--record", "{rec}", "--units", "g", "--history", "{out}"],
     "--dt"),
    (["records", "show", "{rec}", "--units", "g", "--plot", "{out}.png"], "--dt"),
    (["records", "show", "{rec}", "--plot", "{out}.png"], "--record-column"),
    (["spectrum", "min-overturning", "--alpha", "10", "--csv", "{out}"], "--ap-max"),
    (["spectrum", "min-overturning", "--alpha", "10", "--csv", "{out}"], "--step"),
    (["spectrum", "min-overturning", "--alpha", "10", "--csv", "{out}"], "--tol"),
    (["assess", "column", "bassae", "--alpha", "10", "--records", "{rec}", "--csv", "{out}"], "--R"),
    (["assess", "column", "bassae", "--records", "{rec}", "--csv", "{out}"], "--dt"),
    (["assess", "fragility", "bassae", "--records", "{rec}", "--csv", "{out}"], "--bootstrap"),
    (["assess", "fragility", "bassae", "--records", "{rec}", "--csv", "{out}"], "--seed"),
    (["fit-pulse", "{rec}", "--csv", "{out}"], "--candidates"),
    (["bench", "stability", "--csv", "{out}"], "--random"),
    (["bench", "stability", "--random", "1", "--csv", "{out}"], "--seed"),
]

GOOD_RECORD = "# units: g\n# dt=0.01 sec\n" + "".join(f"{0.3 * math.sin(k / 7.0)!r}\n" for k in range(300))


def _fill(args, folder: Path):
    rec = folder / "rec.txt"
    if not rec.exists():
        rec.write_text(GOOD_RECORD)
    return [a.replace("{out}", str(folder / "out.csv")).replace("{rec}", str(rec)) for a in args]


@sweep(150)
@given(case=st.sampled_from(OPTIONS), value=bad_numbers)
def test_malformed_option_values_one_sentence(case, value):
    base, option = case
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        args = _fill(base, folder)
        (folder / "rec.txt").write_text(GOOD_RECORD)
        assert_refused([*args, f"{option}={value}"], folder)


# --------------------------------------------------------------------------------------------------
# specs: a key given twice, or a value that is no plain number
# --------------------------------------------------------------------------------------------------
SPEC_KINDS = {
    # kind -> (command line with {spec}, keys of the spec, a good value for each key)
    "pulse": (["simulate", "--height", "2", "--width", "0.5", "--pulse", "{spec}", "--history", "{out}"],
              "sine", {"ap": "0.5", "Tp": "0.5", "t0": "0.1"}),
    "isolation": (["simulate", "--height", "2", "--width", "0.5", *SINE, "--isolation", "{spec}", "--history",
                   "{out}"], "linear", {"Tb": "2.5", "xi": "0.1", "gamma": "0.01"}),
    "scss": (["simulate", "--height", "2", "--width", "0.5", *SINE, "--isolation", "{spec}"], "scss",
             {"Tb": "3", "mu": "0.05", "uy": "0.00025"}),
    "column": (["assess", "column", "{spec}", "--records", "{rec}", "--csv", "{out}"], "statue",
               {"R": "1.2", "alpha": "14"}),
    "spectrum-pulse": (["spectrum", "min-overturning", "--alpha", "10", "--pulse", "{spec}", "--csv", "{out}"],
                       "ricker-sym", {"Tp": "0.6"}),
    "spectrum-isolation": (["spectrum", "min-overturning", "--alpha", "10", "--isolation", "{spec}", "--csv",
                            "{out}"], "linear", {"TbTp": "2", "xi": "0.05"}),
}


@st.composite
def bad_specs(draw):
    kind = draw(st.sampled_from(sorted(SPEC_KINDS)))
    args, head, good = SPEC_KINDS[kind]
    items = [(k, v) for k, v in good.items()]
    if draw(st.booleans()):  # a key given twice (in any letter case), with any value
        k, _ = draw(st.sampled_from(items))
        twin = draw(st.sampled_from([k, k.upper(), k.lower()]))
        items.insert(draw(st.integers(0, len(items))), (twin, draw(st.one_of(bad_numbers, st.sampled_from(
            list(good.values()))))))
    else:  # one value that is no plain number
        i = draw(st.integers(0, len(items) - 1))
        items[i] = (items[i][0], draw(bad_numbers))
    spec = f"{head}:" + ",".join(f"{k}={v}" for k, v in items)
    return kind, [a.replace("{spec}", spec) for a in args]


@sweep(120)
@given(case=bad_specs())
def test_malformed_specs_one_sentence(case):
    _, args = case
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        assert_refused(_fill(args, folder), folder)


# --------------------------------------------------------------------------------------------------
# malformed record files
# --------------------------------------------------------------------------------------------------
BAD_SAMPLES = ["1_0", "nan", "-inf", "1e308", "1e999", "0x1", "abc", "1.0O0E-02", "2e3", "-5e2", "\u0661"]
BAD_DT = ["1,0e-2 s", "0.01 min", "1e-300", "-0.01", "0", "1_0 ms", "10 xyz", "1e999", "100 s", "0.01 hours"]


def _at2(values, dt_text=".0100") -> bytes:
    head = ["PEER NGA STRONG MOTION DATABASE RECORD", "Synthetic, 1/1/2000, Test station, 0",
            "ACCELERATION TIME SERIES IN UNITS OF G", f"NPTS=   {len(values)}  DT=   {dt_text} SEC,"]
    rows = [" ".join(values[i:i + 5]) for i in range(0, len(values), 5)]
    return ("\r\n".join(head + rows) + "\r\n").encode("utf-8")


@st.composite
def bad_records(draw):
    """(file name, bytes) of a record that must be refused."""
    n = draw(st.integers(8, 60))
    values = [f"{0.2 * math.sin(k / 3.0):.6E}" for k in range(n)]
    layout = draw(st.sampled_from(["text", "at2"]))
    fault = draw(st.sampled_from(["sample", "dt", "count", "empty"] if layout == "at2" else ["sample", "dt", "empty"]))
    dt = "0.01"
    if fault == "sample":
        values[draw(st.integers(0, n - 1))] = draw(st.sampled_from(BAD_SAMPLES))
    elif fault == "dt":
        dt = draw(st.sampled_from(BAD_DT + ["1.0D-02 min"]))
    if layout == "at2":
        name = "r.AT2"
        dt_text = dt if fault == "dt" and " " not in dt else (".0100" if fault != "dt" else "-1")
        data = _at2(values[:-1] if fault == "count" else values, dt_text).replace(
            f"NPTS=   {n - 1}".encode(), f"NPTS=   {n}".encode()) if fault == "count" else _at2(values, dt_text)
    else:
        name = "r.txt"
        data = (f"# units: g\n# dt = {dt}\n" + "\n".join(values) + "\n").encode("utf-8")
    if fault == "empty":
        data = draw(st.sampled_from([b"", b"   \n", b"# units: g\n", b"\xef\xbb\xbf"]))
    if draw(st.booleans()):
        data = b"\xef\xbb\xbf" + data  # a BOM changes nothing
    wrap = draw(st.sampled_from(["none", "gz", "bz2", "zip", "cut-gz"]))
    if wrap == "gz":
        return name + ".gz", gzip.compress(data)
    if wrap == "bz2":
        return name + ".bz2", bz2.compress(data)
    if wrap == "cut-gz":
        good = gzip.compress(_at2(values) if layout == "at2" else data)
        return name + ".gz", good[: max(10, len(good) // 2)]
    if wrap == "zip":
        import io

        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w") as zf:
            zf.writestr(name, data)
        return name + ".zip", buf.getvalue()
    return name, data


RECORD_COMMANDS = [
    ["records", "show", "{file}", "--plot", "{out}.png"],
    ["simulate", "--height", "2", "--width", "0.5", "--record", "{file}", "--history", "{out}"],
    ["fit-pulse", "{file}", "--csv", "{out}"],
]


@sweep(150)
@given(record=bad_records(), command=st.sampled_from(RECORD_COMMANDS))
def test_malformed_records_one_sentence(record, command):
    name, data = record
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / name).write_bytes(data)
        args = [a.replace("{file}", str(folder / name)).replace("{out}", str(folder / "out.csv")) for a in command]
        assert_refused(args, folder)


def test_the_sweep_generates_what_it_claims():
    """The strategies are not vacuous: the malformed numbers are refused and the good record is read."""
    from rockcli.records import read_record

    for text in _LITERALS:
        if not _plain(text):
            with pytest.raises(RockcliInputError):
                parse_number(text, "x")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rec.txt"
        path.write_text(GOOD_RECORD)
        rec = read_record(path)
        assert rec.npts == 300 and rec.dt == 0.01 and np.isclose(rec.pga_g, 0.3, rtol=1e-3)


# --------------------------------------------------------------------------------------------------
# issue 34: manifests, scale factors, option sizes, Python calls with wrong types
# --------------------------------------------------------------------------------------------------
_CELL = {
    "units": ["", "g", "cm/s^2", "furlongs", "G"],
    "dt": ["", "0.01", "0.005", "0", "-1", "1,5", "nan", "1e999", "abc"],
    "gain": ["", "1e-3", "0", "x"],
    "component": ["", "N", "UP", "x", "-242"],
    "azimuth": ["", "0", "90", "1e-7", "1e2", "nan", "x"],
    "azimuth_2": ["", "90", "x"],
    "label": ["", "a", "a", "b"],  # a label given twice
}


@st.composite
def manifests(draw):
    """(bytes of a manifest, True when it must be refused as a whole) over a folder holding rec.txt (good),
    link.txt -> rec.txt, other.txt (good) and notes.txt (not a record)."""
    extra = draw(st.sampled_from(["", "", "colour", "FILE"]))  # an unknown column, or file given twice
    key = draw(st.sampled_from(["units", "dt", "gain", "component", "azimuth"]))  # what makes it a manifest
    cols = ["file", key, *draw(st.lists(st.sampled_from(sorted(set(_CELL) - {key})), max_size=3, unique=True))]
    cols += ["file_2"] if draw(st.booleans()) else []
    cols += [extra] if extra else []
    rows = []
    for _ in range(draw(st.integers(0, 4))):
        row = []
        for c in cols:
            if c.lower() == "file":
                row.append(draw(st.sampled_from(["rec.txt", "link.txt", "other.txt", "notes.txt", "missing.txt", ""])))
            elif c == "file_2":
                row.append(draw(st.sampled_from(["", "other.txt", "rec.txt", "link.txt"])))
            elif c in _CELL:
                row.append(draw(st.sampled_from(_CELL[c])))
            else:
                row.append("red")
        if draw(st.integers(0, 9)) == 0:
            row.append("surplus")
        rows.append(row)
    text = "\n".join(",".join(r) for r in [cols, *rows]) + "\n"
    coding = draw(st.sampled_from(["utf-8", "utf-8", "utf-8-sig", "latin-1-accent", "nul"]))
    data = text.encode("utf-8-sig" if coding == "utf-8-sig" else "utf-8")
    if coding == "latin-1-accent":
        data = data.replace(b"\n", "\n# caf\u00e9\n".encode("latin-1"), 1)
    elif coding == "nul":
        data = data.replace(b"\n", b"\x00\n", 1)
    whole = (bool(extra) or not rows or coding in ("latin-1-accent", "nul") or any(len(r) > len(cols) for r in rows))
    return data, whole


def _suite_folder(folder: Path) -> None:
    (folder / "rec.txt").write_text(GOOD_RECORD)
    (folder / "other.txt").write_text(GOOD_RECORD.replace("0.3 *", "0.2 *") + "0.0\n")
    (folder / "link.txt").symlink_to("rec.txt")
    (folder / "notes.txt").write_text("not a record\n")


@sweep(150)
@given(manifest=manifests(), azimuth=st.sampled_from([None, None, 30.0]))
def test_manifests_give_records_or_one_sentence(manifest, azimuth):
    """Whatever a manifest holds: each record once (by file and component), or one sentence naming the manifest
    (and its line); never a traceback; the manifest and its files unchanged."""
    from rockcli.assess import resolve_excitations

    data, whole = manifest
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        _suite_folder(folder)
        path = folder / "m.csv"
        path.write_bytes(data)
        before = snapshot(folder)
        try:
            xs, _ = resolve_excitations([str(path)], azimuth=azimuth)
        except RockcliInputError as exc:
            msg = str(exc)
            assert "\n" not in msg and (str(path) in msg or "--dt" in msg or "units" in msg), msg
        else:
            assert not whole, data
            labels = [x.label for x in xs]
            assert len(labels) == len(set(labels)), labels
            read = [(x.motion.meta.get("path"), x.motion.meta.get("component")) for x in xs
                    if x.motion is not None and x.pair is None]
            assert len({(str(Path(p).resolve()), c) for p, c in read}) == len(read), read  # a link is its file
            assert all("\n" not in x.error for x in xs)
        assert snapshot(folder) == before


@sweep(40)
@given(manifest=manifests(), option=st.sampled_from(["--csv", "--report"]),
       command=st.sampled_from(["column", "fragility"]))
def test_an_output_on_the_manifest_is_refused_whatever_it_holds(manifest, option, command):
    data, _ = manifest
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        _suite_folder(folder)
        path = folder / "m.csv"
        path.write_bytes(data)
        assert_refused(["assess", command, "bassae", "--records", path, "--isolation", "none", option, path], folder)


_MOTIONS = st.one_of(
    st.tuples(st.just("pulse"), st.floats(min_value=0.01, max_value=100.0)),  # a_p [g]
    st.tuples(st.just("record"), st.just(0.2999)),  # GOOD_RECORD peaks at 0.3 sin(30/7) = 0.29996 g
)


@sweep(300)
@given(k=st.floats(allow_nan=True, allow_infinity=True), peak=st.floats(min_value=0.0, max_value=1e3))
def test_scale_factors_keep_the_peak_within_100_g(k, peak):
    """check_scale: accepted exactly when finite, non-zero and |k| peak <= 100 g (to rounding), the factor quoted as
    given otherwise."""
    from fractions import Fraction

    from rockcli.io.inputs import check_scale, format_number

    try:
        got = check_scale(k, peak, "--scale")
    except RockcliInputError as exc:
        msg = str(exc)
        assert "\n" not in msg and msg.startswith("--scale") and format_number(k) in msg
        assert not math.isfinite(k) or k == 0 or Fraction(abs(k)) * Fraction(peak) > 100 * (1 - 1e-15)
    else:
        assert got == k and math.isfinite(k) and k != 0
        assert Fraction(abs(k)) * Fraction(peak) <= 100 * (1 + 1e-15)


@sweep(60)
@given(motion=_MOTIONS, k=st.one_of(st.floats(min_value=101.0, max_value=1e308),
                                    st.floats(min_value=-1e308, max_value=-101.0)),
       where=st.sampled_from(["--scale", "--vertical-scale", "rocking"]))
def test_scale_factors_past_100_g_are_one_sentence(motion, k, where):
    kind, amplitude = motion if where != "rocking" else ("record", 0.2999)  # a rocking spectrum is of a record
    k = k / amplitude  # |k| a >= 101 g (the record peaks just under 0.3 g: >= 100.99 g); past the limit either way
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        rec = folder / "rec.txt"
        rec.write_text(GOOD_RECORD)
        pulse = f"sine:ap={amplitude!r},Tp=0.5"
        if where == "rocking":
            args = ["spectrum", "rocking", rec, "--alpha", "10", "--scale", repr(k), "--csv", folder / "o.csv"]
        elif where == "--scale":
            args = ["simulate", "--R", "1", "--alpha", "10", *(["--pulse", pulse] if kind == "pulse" else
                                                               ["--record", rec]), "--scale", repr(k)]
        else:
            args = ["simulate", "--R", "1", "--alpha", "10", "--record", rec,
                    *(["--vertical-pulse", pulse] if kind == "pulse" else ["--vertical", rec]), "--vertical-scale",
                    repr(k)]
        assert_refused(args, folder)


#: (command line before the option, option, values the option's limits refuse): each example must be refused
#: before any work, in one sentence, without hanging (the hang guard of assert_refused)
SIZES = [
    (["simulate", "--R", "1", "--alpha", "10", "--record", "{rec}@0", "--record-2", "{rec2}@90", "--azimuth", "worst"],
     "--azimuth-step", st.one_of(st.floats(min_value=1e-300, max_value=0.0999), st.floats(min_value=90.001,
                                                                                          max_value=1e300))),
    (["assess", "column", "bassae", "--records", "{rec}@0+{rec2}@90", "--azimuth", "worst", "--csv", "{out}"],
     "--azimuth-step", st.floats(min_value=1e-300, max_value=0.0999)),
    (["simulate", "--R", "1", "--alpha", "10", "--record", "{rec}", "--history", "{out}"], "--history-dt",
     st.floats(min_value=1e-300, max_value=1.4e-6)),  # 3 s + 10 s of tail: more than 2,000,000 rows
    (["spectrum", "min-overturning", "--alpha", "10", "--wp-over-p", "2:2:1", "--csv", "{out}"], "--ap-max",
     st.floats(min_value=10000.001, max_value=1e308)),
    (["spectrum", "min-overturning", "--alpha", "10", "--wp-over-p", "2:2:1", "--csv", "{out}"], "--step",
     st.floats(min_value=1e-300, max_value=9.99e-5)),
    (["spectrum", "critical-size", "--alpha", "10", "--csv", "{out}"], "--xtol", st.floats(min_value=1e-300,
                                                                                          max_value=9.9e-13)),
    (["spectrum", "overturning", "--alpha", "10", "--csv", "{out}"], "--wp-over-p",
     st.integers(100_001, 10**12).map(lambda n: f"1:2:{n}")),
    (["spectrum", "rocking", "{rec}", "--alpha", "10", "--csv", "{out}"], "--R",
     st.integers(100_001, 10**12).map(lambda n: f"0.2:20:{n}")),
    (["assess", "fragility", "bassae", "--records", "{rec}", "--csv", "{out}"], "--bootstrap",
     st.integers(100_001, 10**18)),
    (["bench", "stability", "--csv", "{out}"], "--random", st.integers(100_001, 10**18)),
    (["fit-pulse", "{rec}", "--csv", "{out}"], "--candidates", st.integers(21, 10**18)),
]


@sweep(120)
@given(case=st.sampled_from(range(len(SIZES))), data=st.data())
def test_options_that_set_a_size_are_bounded_before_the_work(case, data):
    base, option, values = SIZES[case]
    value = data.draw(values)
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        (folder / "rec.txt").write_text(GOOD_RECORD)
        (folder / "rec2.txt").write_text(GOOD_RECORD.replace("0.3 *", "0.2 *"))
        args = [a.replace("{out}", str(folder / "out.csv")).replace("{rec}", str(folder / "rec.txt"))
                .replace("{rec2}", str(folder / "rec2.txt")) for a in base]
        assert_refused([*args, option, value if isinstance(value, str) else repr(value)], folder)


def _python_calls():
    """(name of the argument, call taking the wrong value) of the documented Python entry points."""
    from rockcli import (Block, Rigid, critical_sizes, default_rtol, make_pulse, min_overturning_curves,
                         overturning_map, parse_configurations, parse_grid, resolve_excitations, run_assessment,
                         run_fragility, simulate, simulate_many, simulate_verdicts)
    from rockcli.spectra import rocking_spectrum
    from rockcli.io.units import G

    b, p = Block.from_dimensions(2.0, 0.5), make_pulse("sine", 0.5 * G, 0.5)
    grid = parse_grid("2:3:2")
    confs = parse_configurations(["none"])
    return {  # name: (None is a wrong value too, a word the sentence names, the call)
        "block": (True, "block", lambda w: simulate(w, Rigid(), p)),
        "foundation": (False, "foundation", lambda w: simulate(b, w, p)),
        "jobs": (False, "job", lambda w: simulate_many(w)),
        "jobs-verdicts": (False, "job", lambda w: simulate_verdicts(w)),
        "alpha_deg": (True, "alpha_deg", lambda w: overturning_map(w, "ricker-sym", "none", grid, grid)),
        "pulse": (True, "pulse", lambda w: overturning_map(14.0, w, "none", grid, grid)),
        "isolation": (True, "isolation", lambda w: overturning_map(14.0, "ricker-sym", w, grid, grid)),
        "wp_grid": (True, "wp_grid", lambda w: overturning_map(14.0, "ricker-sym", "none", w, grid)),
        "ap_grid": (True, "ap_grid", lambda w: overturning_map(14.0, "ricker-sym", "none", grid, w)),
        "alphas_deg": (True, "alphas_deg", lambda w: min_overturning_curves(w, ["ricker-sym"], ["none"], [2.0])),
        "pulses": (True, "pulse", lambda w: min_overturning_curves([14.0], w, ["none"], [2.0])),
        "isolations": (True, "isolation", lambda w: critical_sizes(["sine:Tp=0.5"], [10.0], w)),
        "wp_values": (True, "wp_values", lambda w: min_overturning_curves([14.0], ["ricker-sym"], ["none"], w)),
        "R": (True, "R", lambda w: rocking_spectrum(p.sampled(0.01), [10.0], [Rigid()], w)),
        "record": (True, "record", lambda w: rocking_spectrum(w, [10.0], [Rigid()], [1.0])),
        "sources": (False, "sources", lambda w: resolve_excitations(w)),
        "specs": (False, "specs", lambda w: parse_configurations(w)),
        "columns": (True, "columns", lambda w: run_assessment(w, [], confs)),
        "excitations": (True, "excitations", lambda w: run_fragility([b], w, confs)),
        "configurations": (True, "configurations", lambda w: run_assessment([b], [], w)),
        "default_rtol": (False, "foundation", lambda w: default_rtol(w)),
    }


#: Values of no argument's type (None is a default for some: those marked False above do not take it).
_WRONG = [None, {"a": 1}, object(), b"bytes", [[1, 2]], 1 + 2j, np.zeros((2, 2)), True, [None], ["x", 3.5], float]


@sweep(200)
@given(name=st.sampled_from(sorted(_python_calls())), wrong=st.sampled_from(range(len(_WRONG))))
def test_python_entry_points_refuse_wrong_types_in_one_sentence(name, wrong):
    none_is_wrong, word, call = _python_calls()[name]
    value = _WRONG[wrong]
    if value is None and not none_is_wrong:
        return
    try:
        out = call(value)
    except RockcliInputError as exc:
        msg = str(exc)
        assert "\n" not in msg and word in msg, (name, msg)
    else:  # simulate_many keeps a job that fails its checks as a row
        assert name == "jobs" and all(getattr(r, "verdict", None) == "error" and "job " in r.error for r in out), \
            (name, out)


def _more_python_calls():
    """(word the sentence names, call taking the wrong value) of entry points that gave a raw TypeError or
    AttributeError (polish of issue 34): each refuses every value of ``_WRONG`` in one sentence."""
    from rockcli import Block, Rigid, find_overturn_scales, format_verdicts, make_pulse
    from rockcli.records import read_record
    from rockcli.records.orientation import sweep_azimuths
    from rockcli.io.units import G

    scene = (Block.from_dimensions(2.0, 0.5), Rigid(), make_pulse("sine", 0.5 * G, 0.5))
    return {
        "read_record": ("source", read_record),
        "sweep_azimuths": ("step", sweep_azimuths),
        "scenes": ("scenes", find_overturn_scales),
        "scene": ("scene 0", lambda w: find_overturn_scales([w])),
        "grid": ("grid", lambda w: find_overturn_scales([scene], grid=w)),
        "known": ("known", lambda w: find_overturn_scales([scene], known=w)),
        "assessment": ("assessment", format_verdicts),
    }


@pytest.mark.parametrize("name", sorted(_more_python_calls()))
def test_more_python_entry_points_refuse_wrong_types_in_one_sentence(name):
    word, call = _more_python_calls()[name]
    for value in _WRONG:
        if value is None and name == "known":
            continue  # its default
        with pytest.raises(RockcliInputError) as info:
            call(value)
        assert "\n" not in str(info.value) and word in str(info.value), (name, value, str(info.value))


def test_python_limits_are_the_clis():
    """sweep_azimuths has the floor of --azimuth-step (1e-9 built 1.8e11 orientations); Record.scaled the 100 g
    of --scale (1e308 gave numpy overflow warnings and an infinite record)."""
    import warnings

    from rockcli.records.orientation import AZIMUTH_STEP_RANGE_DEG, sweep_azimuths
    from rockcli.records.record import Record
    from rockcli.io.units import G

    lo, hi = AZIMUTH_STEP_RANGE_DEG
    assert len(sweep_azimuths(lo)) == 1800 and list(sweep_azimuths(hi)) == [0.0, 90.0]
    for step in (1e-9, np.nextafter(lo, 0), np.nextafter(hi, 180), 0.0, -5.0):
        with pytest.raises(RockcliInputError, match="sweep_azimuths: step .* must lie between 0.1 deg"):
            sweep_azimuths(step)
    with pytest.raises(RockcliInputError, match="sweep_azimuths: step nan is not a finite number"):
        sweep_azimuths(math.nan)
    rec = Record(np.array([0.0, 0.5 * G, -0.25 * G]), 0.01, "r")  # peaks at 0.5 g
    assert rec.scaled(-200.0).pga_g == pytest.approx(100.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow warning on the way to the sentence
        for k in (1e308, -200.0001, 0.0, math.inf, math.nan):
            with pytest.raises(RockcliInputError, match="Record.scaled: the factor"):
                rec.scaled(k)


def test_no_exception_name_in_a_refusal(tmp_path, monkeypatch):
    """A file of one word was refused "format not recognised by rockcli, ObsPy or gmprocess (StopIteration)":
    the name of an exception raised inside a reader means nothing to a user. gmprocess is stood in for by a
    module whose reader raises StopIteration() as gmprocess 2.8 does on such a file (no 1.8 GB import)."""
    import sys
    import types

    from rockcli.records import extra, read_record
    from rockcli.records.reader import reason_words

    assert reason_words(StopIteration()) == "" and reason_words(KeyError()) == ""
    assert reason_words(ValueError("No format found for file PosixPath('x').")) == ""
    assert reason_words(ValueError("bad header\nmore"), "ObsPy") == " (ObsPy: bad header)"

    def read_data(path):
        raise StopIteration()

    for name in ("gmprocess", "gmprocess.io", "gmprocess.io.read"):
        monkeypatch.setitem(sys.modules, name, types.ModuleType(name))
    sys.modules["gmprocess.io.read"].read_data = read_data
    monkeypatch.setattr(extra, "available", lambda: True)
    monkeypatch.setattr(extra, "_loaded", True)  # no "reading with gmprocess" notice
    for text in ("hello\n", "\n\n\n"):
        path = tmp_path / "one.txt"
        path.write_text(text)
        with pytest.raises(RockcliInputError) as info:
            read_record(path)
        msg = str(info.value)
        start = f"{path}: format not recognised by rockcli, ObsPy or gmprocess; give it with --format"
        assert msg.startswith(start), msg
        assert "Iteration" not in msg and "Error" not in msg, msg
