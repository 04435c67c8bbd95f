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
from rockcli.inputs import DECIMAL, parse_number

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
