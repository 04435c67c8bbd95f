"""A record read as written (issue 34 items 1 and 5; issue 35): every reader checks what its header says
against the data it reads.

Property, per reader family: a real agency file (copied from ../shared/records/formats and extra into a
temporary folder) with ONE header field or data block mangled (a count, a scale factor, a time step, a units
word, lines cut from or added to a block) is either refused in one sentence that names the file, or read as
exactly the same record as the pristine file. Each mangle below changes what a reader that trusts the
header would read, so each must be refused. Bounded and reproducible: ``derandomize=True``, no example
database, a few hundred examples in all (about 20 s of CPU).

What cannot be seen from the file is left out, and said in docs/records.md: a time step stated once (AT2,
ITACA) or a units word replaced by another known word where no other field states units (AT2, CWB, text).
"""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from rockcli.errors import RockcliInputError
from rockcli.records.reader import read_components


def sweep(n: int):
    return settings(max_examples=n, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture,
                                           HealthCheck.filter_too_much])


#: What a refusal of a header-vs-data disagreement says (one of these, after the file's name).
REFUSAL_WORDS = ("header states", "file states units", "decimal comma", "does not state its units", "the time column")


@pytest.fixture(scope="session")
def find_record(records_dirs):
    """``find_record(name)``: a shared record file in a ROCKCLI_RECORDS folder or its ``formats``/``extra``
    subfolder (the agency samples); skips when absent."""

    def find(name: str) -> Path:
        for folder in records_dirs:
            for sub in (folder, folder / "formats", folder / "extra"):
                if (sub / name).is_file():
                    return sub / name
        pytest.skip(f"{name} not found in ROCKCLI_RECORDS (nor in its formats/ or extra/)")

    return find

_PRISTINE: dict[str, tuple[bytes, list]] = {}


def pristine(find_record, name: str):
    """The bytes of a shared record file and its components as read untouched (cached for the session)."""
    if name not in _PRISTINE:
        path = find_record(name)
        _PRISTINE[name] = (path.read_bytes(), read_components(path))
    return _PRISTINE[name]


def same(a, b) -> bool:
    return len(a) == len(b) and all(
        x.npts == y.npts and x.dt == y.dt and x.meta.get("units") == y.meta.get("units")
        and x.meta.get("factor") == y.meta.get("factor") and np.array_equal(x.acc, y.acc) for x, y in zip(a, b))


def check_mangled(find_record, name: str, mangle, must_refuse: bool = True):
    """Write ``mangle(text)`` as ``name`` in a temporary folder and read it: refused in one sentence naming the
    file, or (only when ``must_refuse`` is False) read as the pristine record."""
    raw, want = pristine(find_record, name)
    text = raw.decode("latin-1")
    changed = mangle(text)
    assert changed != text, "the mangle changed nothing"
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / name
        path.write_bytes(changed.encode("latin-1"))
        try:
            got = read_components(path)
        except RockcliInputError as exc:
            msg = str(exc)
            assert "\n" not in msg and msg.startswith(str(path)), msg
            assert any(w in msg for w in REFUSAL_WORDS), msg
            return msg
    assert not must_refuse and same(got, want), f"{name}: a mangled file was read as another record"
    return None


def sub_line(text: str, index: int, old_rx: str, new: str) -> str:
    """``text`` with ``old_rx`` replaced by ``new`` once, on line ``index`` (0-based)."""
    lines = text.split("\n")
    lines[index], n = re.subn(old_rx, new, lines[index], count=1)
    assert n == 1, (index, old_rx, lines[index])
    return "\n".join(lines)


def drop_or_add_lines(text: str, first: int, last: int, draw) -> str:
    """Remove 1-5 data lines from ``first..last`` (0-based, inclusive), or repeat 1-5 of them."""
    lines = text.split("\n")
    at = draw(st.integers(first, last - 5))
    k = draw(st.integers(1, 5))
    if draw(st.booleans()):
        del lines[at:at + k]
    else:
        lines[at:at] = lines[at:at + k]
    return "\n".join(lines)


def nonzero(lo: int, hi: int):
    return st.integers(lo, hi).filter(lambda d: d != 0)


# --------------------------------------------------------------------------------------------------
# GeoNet Volume 2A: 20180212_211557_WPWS_20.V2A (three components of 5800 points)
# --------------------------------------------------------------------------------------------------
GEONET = "20180212_211557_WPWS_20.V2A"


def _geonet_starts(text):
    return [k for k, line in enumerate(text.split("\n")) if line.startswith("Corrected accelerogram")]


def _int_field(line: str, index: int, value: int) -> str:
    """Integer header line (10I8) with value ``index`` (0-based) replaced."""
    cells = [line[8 * k:8 * k + 8] for k in range(10)]
    cells[index] = f"{value:8d}"
    return "".join(cells) + line[80:]


@st.composite
def geonet_mangles(draw):
    comp = draw(st.integers(0, 2))
    op = draw(st.sampled_from(["points-text", "points-int", "points-all", "block", "no-units", "units-word", "dt"]))
    d = draw(nonzero(-600, 600))

    def mangle(text):
        s = _geonet_starts(text)[comp]
        lines = text.split("\n")
        n = int(re.search(r"Number of points\s+(\d+)", lines[s + 9]).group(1))
        if op in ("points-text", "points-all"):
            lines[s + 9] = lines[s + 9].replace(f"points  {n}", f"points  {n + d}")
        if op in ("points-int", "points-all"):
            for i in ((3, 4, 5) if op == "points-all" else (3,)):
                lines[s + 19] = _int_field(lines[s + 19], i, n + d)
        if op == "block":
            return drop_or_add_lines("\n".join(lines), s + 30, s + 26 + 580, draw)
        if op == "no-units":
            lines[s + 13] = re.sub(r"(peak\s+\S+)\s+mm/s/s", r"\1", lines[s + 13])
        if op == "units-word":
            lines[s + 13] = lines[s + 13].replace("mm/s/s", draw(st.sampled_from(["cm/s/s", "m/s/s", "furlong", "g"])))
        if op == "dt":
            lines[s + 10] = lines[s + 10].replace("0.020 sec", draw(st.sampled_from(["0.010 sec", "0.005 sec", "0.040 sec"])))
        return "\n".join(lines)

    return op, mangle


@sweep(25)
@given(case=geonet_mangles())
def test_geonet_header_against_data(find_record, case):
    check_mangled(find_record, GEONET, case[1])


# --------------------------------------------------------------------------------------------------
# K-NET / KiK-net: AOM0011801241951.NS (ObsPy reads it; rockcli checks the header)
# --------------------------------------------------------------------------------------------------
KNET = "AOM0011801241951.NS"


@st.composite
def knet_mangles(draw):
    op = draw(st.sampled_from(["scale-zero", "scale", "denominator", "cut", "duration", "rate"]))

    def mangle(text):
        lines = text.split("\n")
        if op == "scale-zero":
            return sub_line(text, 13, r"\d+\(gal\)", "0(gal)")
        if op == "scale":
            factor = draw(st.floats(0.05, 20.0).filter(lambda f: abs(f - 1.0) > 0.05))
            return sub_line(text, 13, r"(\d+)\(gal\)", lambda m: f"{round(int(m.group(1)) * factor)}(gal)")
        if op == "denominator":
            return sub_line(text, 13, r"/(\d+)", lambda m: f"/{int(m.group(1)) * draw(st.sampled_from([2, 10, 100]))}")
        if op == "cut":  # the data block ends early, or loses lines in its middle
            if draw(st.booleans()):
                return "\n".join(lines[:draw(st.integers(40, len(lines) - 3))]) + "\n"
            return drop_or_add_lines(text, 20, len(lines) - 10, draw)
        if op == "duration":
            return sub_line(text, 11, r"(\d+)\s*$", lambda m: str(int(m.group(1)) + draw(nonzero(-50, 50))))
        return sub_line(text, 10, r"100Hz", draw(st.sampled_from(["50Hz", "200Hz", "20Hz"])))

    return op, mangle


@sweep(30)
@given(case=knet_mangles())
def test_knet_header_against_data(find_record, case):
    check_mangled(find_record, KNET, case[1])


# --------------------------------------------------------------------------------------------------
# ESM: HI.ARS1..HNN.D.20190728.160908.C.ACC.ASC (one value a line after 64 header lines)
# --------------------------------------------------------------------------------------------------
ESM = "HI.ARS1..HNN.D.20190728.160908.C.ACC.ASC"


@st.composite
def esm_mangles(draw):
    op = draw(st.sampled_from(["ndata", "block", "interval", "units", "no-units"]))

    def mangle(text):
        if op == "ndata":
            return re.sub(r"NDATA: (\d+)", lambda m: f"NDATA: {int(m.group(1)) + draw(nonzero(-900, 900))}", text)
        if op == "block":
            return drop_or_add_lines(text, 100, 19000, draw)
        if op == "interval":
            return text.replace("SAMPLING_INTERVAL_S: 0.005000",
                                f"SAMPLING_INTERVAL_S: {draw(st.sampled_from(['0.010000', '0.002500', '0.004000']))}")
        if op == "units":
            return text.replace("UNITS: cm/s^2", f"UNITS: {draw(st.sampled_from(['m/s^2', 'g', 'mm/s^2', 'furlong']))}")
        return text.replace("UNITS: cm/s^2", "UNITS: ")

    return op, mangle


@sweep(25)
@given(case=esm_mangles())
def test_esm_header_against_data(find_record, case):
    check_mangled(find_record, ESM, case[1])


# --------------------------------------------------------------------------------------------------
# ITACA: 16833_H1.cor.acc (5 values a line, no separators)
# --------------------------------------------------------------------------------------------------
ITACA = "16833_H1.cor.acc"


@st.composite
def itaca_mangles(draw):
    op = draw(st.sampled_from(["count", "block", "units", "no-units"]))

    def mangle(text):
        if op == "count":
            return re.sub(r"(Number of Data\s*: )(\d+)", lambda m: f"{m.group(1)}{int(m.group(2)) + draw(nonzero(-900, 900))}",
                          text)
        if op == "block":
            return drop_or_add_lines(text, 20, 11800, draw)
        if op == "units":
            return text.replace("time series in m/s/s", f"time series in {draw(st.sampled_from(['cm/s/s', 'g', 'gal']))}")
        return text.replace("time series in m/s/s", "time series")

    return op, mangle


@sweep(12)
@given(case=itaca_mangles())
def test_itaca_header_against_data(find_record, case):
    check_mangled(find_record, ITACA, case[1])


# --------------------------------------------------------------------------------------------------
# COSMOS V2: us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c (one value a line, End-of-data after)
# --------------------------------------------------------------------------------------------------
COSMOS = "us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c"


@st.composite
def cosmos_mangles(draw):
    op = draw(st.sampled_from(["count", "block", "interval", "units"]))

    def mangle(text):
        if op == "count":
            return re.sub(r"(\d+)( acceleration pts)", lambda m: f"{int(m.group(1)) + draw(nonzero(-900, 900))}{m.group(2)}",
                          text)
        if op == "block":
            return drop_or_add_lines(text, 60, 42000, draw)
        if op == "interval":  # real header value 62: 5 ms
            return text.replace("    -999.000000       5.000000     210.000000",
                                f"    -999.000000       {draw(st.sampled_from(['2.500000', '10.00000', '4.000000']))}"
                                f"     210.000000")
        return text.replace("units=cm/sec2(04)", f"units={draw(st.sampled_from(['g', 'm/s/s', 'gal(02)', 'cm/sec2(02)']))}")

    return op, mangle


@sweep(20)
@given(case=cosmos_mangles())
def test_cosmos_header_against_data(find_record, case):
    check_mangled(find_record, COSMOS, case[1])


# --------------------------------------------------------------------------------------------------
# CWB: 2-ECU.dat (time, U, N, E)
# --------------------------------------------------------------------------------------------------
CWB = "2-ECU.dat"


@st.composite
def cwb_mangles(draw):
    op = draw(st.sampled_from(["rate", "length", "rows", "no-units", "unknown-units", "sequence"]))

    def mangle(text):
        if op == "rate":
            return text.replace("#SampleRate(Hz): 50", f"#SampleRate(Hz): {draw(st.sampled_from(['100', '25', '200']))}")
        if op == "length":
            return text.replace("#RecordLength(sec): 120", f"#RecordLength(sec): {120 + draw(nonzero(-60, 60))}")
        if op == "rows":
            lines = text.split("\n")
            if draw(st.booleans()):
                return "\n".join(lines[:draw(st.integers(100, len(lines) - 3))]) + "\n"
            return drop_or_add_lines(text, 30, 6000, draw)
        if op == "no-units":
            return text.replace("#AmplitudeUnit:  gal.", "#AmplitudeUnit: ")
        if op == "unknown-units":
            return text.replace("#AmplitudeUnit:  gal.", "#AmplitudeUnit:  counts-ish")
        order = draw(st.sampled_from(["N(+); U(+); E(+)", "E(+); N(+); U(+)", "U(+); E(+); N(+)"]))
        return text.replace("#DataSequence: Time U(+); N(+); E(+)", f"#DataSequence: Time {order}")

    return op, mangle


@sweep(20)
@given(case=cwb_mangles())
def test_cwb_header_against_data(find_record, case):
    check_mangled(find_record, CWB, case[1])


# --------------------------------------------------------------------------------------------------
# PEER AT2: RSN1044_NORTHR_NWH360.AT2 (2000 points)
# --------------------------------------------------------------------------------------------------
AT2 = "RSN1044_NORTHR_NWH360.AT2"


@st.composite
def at2_mangles(draw):
    op = draw(st.sampled_from(["npts", "block", "decimal-comma", "no-units", "unknown-units"]))

    def mangle(text):
        if op == "npts":
            return sub_line(text, 3, r"NPTS=\s+(\d+)", lambda m: f"NPTS=   {int(m.group(1)) + draw(nonzero(-300, 300))}")
        if op == "block":
            return drop_or_add_lines(text, 6, 395, draw)
        if op == "decimal-comma":
            return sub_line(text, 3, r"DT=\s+\.0200", draw(st.sampled_from(["DT= 0,02", "DT=0,0200", "DT= ,02"])))
        if op == "no-units":
            return sub_line(text, 2, r" IN UNITS OF G", "")
        return sub_line(text, 2, r"UNITS OF G", f"UNITS OF {draw(st.sampled_from(['FURLONG', 'KG', 'GALLONS']))}")

    return op, mangle


@sweep(25)
@given(case=at2_mangles())
def test_at2_header_against_data(find_record, case):
    check_mangled(find_record, AT2, case[1])


# --------------------------------------------------------------------------------------------------
# plain text: sylmar.txt (two columns) with a stated npts; the right count is read as the pristine file
# --------------------------------------------------------------------------------------------------
TEXT = "sylmar.txt"


@sweep(20)
@given(d=st.integers(-300, 300), cut=st.booleans())
def test_text_stated_npts_against_rows(find_record, d, cut):
    from rockcli.records import read_record

    text = find_record(TEXT).read_bytes().decode("latin-1")
    rows = sum(1 for line in text.splitlines() if line.strip() and not line.lstrip().startswith("%"))
    stated = f"%npts = {rows + d}\n"
    if cut:  # the count is right for the file as written, the file is cut afterwards
        stated = f"%npts = {rows}\n"
        text = "\n".join(text.split("\n")[:-(abs(d) + 2)]) + "\n"
    want = read_record(find_record(TEXT), column=1)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / TEXT
        path.write_text(stated + text, encoding="latin-1")
        if d == 0 and not cut:
            got = read_record(path, column=1)
            assert got.npts == want.npts and np.array_equal(got.acc, want.acc)  # the control: read as written
        else:
            with pytest.raises(RockcliInputError, match=r"the header states \d+ samples \(a comment: 'npts = \d+'\), "
                                                        r"but \d+ rows of values follow"):
                read_record(path, column=1)


# --------------------------------------------------------------------------------------------------
# SAC: the header's NPTS against the file's size
# --------------------------------------------------------------------------------------------------
SAC = "20190706031952.CJ.T001230.HNE.sac"


@sweep(15)
@given(d=nonzero(-2000, 2000), cut=st.booleans())
def test_sac_npts_against_size(find_record, d, cut):
    import struct

    raw = bytearray(find_record(SAC).read_bytes())
    npts = struct.unpack("<i", raw[316:320])[0]
    if cut:
        raw = raw[:632 + 4 * max(npts - abs(d), 2)]
    else:
        raw[316:320] = struct.pack("<i", npts + d)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / SAC
        path.write_bytes(bytes(raw))
        with pytest.raises(RockcliInputError, match=r"the header states a SAC file of \d+ bytes .*but the file holds"):
            read_components(path, units="m/s^2")


# --------------------------------------------------------------------------------------------------
# component names keep their sign and exact value
# --------------------------------------------------------------------------------------------------
def _angle_texts():
    plain = st.one_of(st.integers(-720, 720).map(str), st.integers(-720, 720).map(lambda v: f"{v:+d}"),
                      st.floats(-400, 400, allow_nan=False).map(lambda v: f"{v:.3f}"),
                      st.integers(0, 359).map(lambda v: f"{v:03d}"), st.integers(0, 99).map(lambda v: f"0{v:03d}"))
    return st.one_of(plain, st.sampled_from(["-242", "-332", "-S62W", "-N28W", "+242", "242.0000001", "-0", "242.",
                                             "1e2", "-UP", "S62W", "n28w", "Up"]))


@sweep(150)
@given(wanted=_angle_texts())
def test_component_names_keep_sign_and_value(find_record, wanted):
    """A component picked by name is the one so named, or the one whose stated azimuth is exactly the given
    angle (sign kept, taken modulo 360); anything else is refused."""
    from rockcli.records.components import select_component

    _, comps = pristine(find_record, "20161113_110259_WTMC_20.V2A")  # N28W 332, S62W 242, Up
    try:
        got = select_component(comps, wanted, "f")
    except RockcliInputError as exc:
        assert "\n" not in str(exc) and f"no component {wanted!r}" in str(exc)
        return
    if got.meta["component"].upper() == wanted.upper():
        return
    if got.meta.get("vertical"):
        assert wanted.upper() in ("UP", "Z", "V", "UD")
        return
    value = float(wanted)  # only a plain number may pick a component by azimuth
    assert abs(value) <= 360 and got.meta["azimuth_deg"] == value % 360.0, (wanted, got.meta["component"])


def test_component_sign_examples(find_record):
    from rockcli.records import read_record

    path = find_record("20161113_110259_WTMC_20.V2A")
    with pytest.raises(RockcliInputError, match=r"no component '-242' \(-242 deg is 118 deg clockwise from north\)"):
        read_record(path, component=-242)
    assert read_record(path, component="-118").meta["component"] == "S62W"  # -118 deg is 242 deg
    assert read_record(path, component=242).meta["component"] == "S62W"
