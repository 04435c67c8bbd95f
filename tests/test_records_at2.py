"""PEER NGA .AT2: every header layout, line endings, the ObsPy plugin, and bad AT2 files."""

from __future__ import annotations

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.records.at2 import _is_at2, parse_at2, parse_at2_header
from rockcli.io.units import G

#: (layout key, header lines) for every layout met in ../shared/records and extra/.
LAYOUTS = {
    "nga-west2": ["PEER NGA STRONG MOTION DATABASE RECORD", "Kobe Japan, 1/16/1995, Takarazuka, 0",
                  "ACCELERATION TIME SERIES IN UNITS OF G", "NPTS=   {npts}  DT=   {dt} SEC,              "],
    "nga-west2-comma": ["PEER NGA STRONG MOTION DATABASE RECORD", "San Fernando, 2/9/1971, Pacoima Dam (upper left abut), 164",
                        "ACCELERATION TIME SERIES IN UNITS OF G", "NPTS=   {npts}, DT=   {dt} SEC,      "],
    "nga-west2-filter": ["PEER NGA STRONG MOTION DATABASE RECORD",
                         "Northridge-01, 1/17/1994, Jensen Filter Plant Generator Building, 22",
                         "ACCELERATION TIME SERIES IN UNITS OF G",
                         "NPTS=   {npts}  DT=   {dt} SEC,   4 POLE @    30.00000 HZ,  -5 POLE @      .08000"],
    "nga-west2-nocomma-end": ["PEER NGA STRONG MOTION DATABASE RECORD", "Northridge-01, 1/17/1994, Newhall - Fire Sta, 360",
                              "ACCELERATION TIME SERIES IN UNITS OF G", "NPTS=   {npts}  DT=   {dt} SEC      "],
    "nga-west1": ["PEER NGA STRONG MOTION DATABASE RECORD", "IRPINIA EQ, 11/23/80, 19:35, BAGNOLI IRPINO, 270",
                  "ACCELERATION TIME HISTORY IN UNITS OF G", "{npts}    {dt}    NPTS, DT"],
    "free-text": ["Data for El Centro 1940 North South Component (Peknold Version)",
                  "1559 points at equal spacing of 0.02 sec Points are listed in the format of 8F10.5",
                  "The units are (g)", "NPTS=  {npts}, DT= {dt} SEC"],
    "dt-first": ["PEER NGA STRONG MOTION DATABASE RECORD", "Kobe Japan, 1/16/1995, KJMA, 0",
                 "ACCELERATION TIME SERIES IN UNITS OF G", "DT= {dt} SEC, NPTS= {npts}"],
}
EXPECTED_LAYOUT = {"nga-west2": "nga-west2", "nga-west2-comma": "nga-west2", "nga-west2-filter": "nga-west2",
                   "nga-west2-nocomma-end": "nga-west2", "nga-west1": "nga-west1", "free-text": "nga-west2",
                   "dt-first": "dt-first"}


def write_at2(path, values, dt, layout="nga-west2", newline="\r\n", per_line=5, fmt="{:15.7E}", npts=None):
    head = [h.format(npts=len(values) if npts is None else npts, dt=f"{dt:.4f}".lstrip("0")) for h in LAYOUTS[layout]]
    rows = ["".join(fmt.format(v) for v in values[i:i + per_line]) for i in range(0, len(values), per_line)]
    path.write_bytes(newline.join(head + rows).encode("latin-1") + newline.encode())
    return path


@pytest.mark.parametrize("layout", sorted(LAYOUTS))
@pytest.mark.parametrize("newline", ["\r\n", "\n", "\r"], ids=["CRLF", "LF", "CR"])
def test_every_layout_and_line_ending_parses(tmp_path, layout, newline):
    rng = np.random.default_rng(7)
    values = np.round(rng.normal(0, 0.1, 23), 7)  # 23: last line incomplete
    path = write_at2(tmp_path / "x.AT2", values, 0.005, layout, newline)
    data, head = parse_at2(path)
    assert head["layout"] == EXPECTED_LAYOUT[layout]
    assert head["npts"] == 23 and head["dt"] == 0.005
    assert head["units"].lower() == "g"
    assert head["quantity"] == (None if layout == "free-text" else "acceleration")
    np.testing.assert_array_equal(data, values)
    assert _is_at2(path)
    rec = read_record(path)
    assert rec.npts == 23 and rec.dt == 0.005
    np.testing.assert_array_equal(rec.acc, values * G)
    assert rec.meta["factor"] == G and rec.meta["format"] == "PEER_AT2"


def test_title_line_fields():
    head = parse_at2_header([l.format(npts=10, dt=".01") for l in LAYOUTS["nga-west1"]])
    assert (head["event"], head["date"], head["time"], head["station"], head["component"]) == (
        "IRPINIA EQ", "11/23/80", "19:35", "BAGNOLI IRPINO", "270")
    head = parse_at2_header([l.format(npts=10, dt=".01") for l in LAYOUTS["nga-west2-comma"]])
    assert head["station"] == "Pacoima Dam (upper left abut)" and head["component"] == "164"


def test_fixed_width_fields_that_touch(tmp_path):
    """5E14.7 fields with no blank between a value and a following negative one."""
    values = np.array([1.1365572e-02, -5.7981615e-03, 3.3413449e-03, -2.4960367e-02, -1.0e-05, 2.5e-3])
    path = write_at2(tmp_path / "t.AT2", values, 0.01, fmt="{:14.7E}")
    assert "E-02-5.79" in path.read_text()
    np.testing.assert_array_equal(parse_at2(path)[0], values)


def test_obspy_reads_at2_without_format(tmp_path):
    obspy = pytest.importorskip("obspy")
    values = np.round(np.linspace(-0.3, 0.2, 12), 7)
    path = write_at2(tmp_path / "RSN1_X.AT2", values, 0.01, "nga-west1", "\n")
    st = obspy.read(str(path))
    tr = st[0]
    assert tr.stats._format == "PEER_AT2"
    assert tr.stats.npts == 12 and tr.stats.delta == 0.01
    np.testing.assert_allclose(tr.data, values * G, rtol=0, atol=1e-15)
    assert tr.stats.peer_at2.factor == G and tr.stats.peer_at2.units == "G"
    assert tr.stats.peer_at2.data_units == "m/s^2"
    assert tr.stats.peer_at2.station == "BAGNOLI IRPINO" and tr.stats.peer_at2.component == "270"
    head = obspy.read(str(path), headonly=True)[0]
    assert head.stats.npts == 12 and len(head.data) == 0


def test_is_at2_false_for_other_files(tmp_path):
    (tmp_path / "b.bin").write_bytes(bytes(range(256)) * 8)
    (tmp_path / "t.txt").write_text("0.1\n0.2\n0.3\n0.4\n0.5\n")
    assert not _is_at2(tmp_path / "b.bin")
    assert not _is_at2(tmp_path / "t.txt")
    assert not _is_at2(tmp_path / "missing.AT2")


# ---------------------------------------------------------------- real files (ROCKCLI_RECORDS)

def _sources(records_dirs):
    import csv

    rows = []
    for folder in records_dirs:
        if (folder / "SOURCES.csv").is_file():
            with open(folder / "SOURCES.csv", newline="") as fh:
                rows += [(folder, r) for r in csv.DictReader(fh) if r["file"].endswith(".AT2")]
    return rows


def test_obspy_read_kobe_npts(find_record):
    obspy = pytest.importorskip("obspy")
    tr = obspy.read(str(find_record("RSN1119_KOBE_TAZ000.AT2")))[0]
    assert tr.stats.npts == 4096 and tr.stats.delta == 0.01
    assert abs(np.abs(tr.data).max() / G - 0.69735) < 5e-6


def test_every_shared_at2_matches_sources(records_dirs):
    obspy = pytest.importorskip("obspy")
    rows = _sources(records_dirs)
    if not rows:
        pytest.skip("no SOURCES.csv with AT2 files")
    layouts = set()
    for folder, row in rows:
        path = folder / row["file"]
        tr = obspy.read(str(path))[0]
        assert tr.stats.npts == int(row["npts"]), row["file"]
        assert tr.stats.delta == pytest.approx(float(row["dt"]), rel=1e-12), row["file"]
        assert np.abs(tr.data).max() / G == pytest.approx(float(row["pga_measured_g"]), abs=6e-4), row["file"]
        layouts.add(tr.stats.peer_at2.layout)
        rec = read_record(path)
        np.testing.assert_array_equal(rec.acc, tr.data)
    assert {"nga-west1", "nga-west2"} <= layouts


# ---------------------------------------------------------------- bad AT2 files

def test_truncated_at2(tmp_path):
    path = write_at2(tmp_path / "t.AT2", np.ones(8) * 0.01, 0.01, npts=10)
    with pytest.raises(RockcliInputError, match=r"truncated AT2 file: the header states NPTS=10 but only 8 values"):
        read_record(path)


def test_at2_more_values_than_npts(tmp_path):
    path = write_at2(tmp_path / "t.AT2", np.ones(12) * 0.01, 0.01, npts=10)
    with pytest.raises(RockcliInputError, match=r"NPTS=10 but 12 values follow"):
        read_record(path)


@pytest.mark.parametrize("token", ["nan", "inf", "-Infinity", "NaN"])
def test_at2_nonfinite(tmp_path, token):
    path = write_at2(tmp_path / "t.AT2", np.ones(10) * 0.01, 0.01)
    text = path.read_text().replace("1.0000000E-02", token, 1)
    path.write_text(text)
    with pytest.raises(RockcliInputError, match=r"line 5: sample 1 is .* not a finite number"):
        read_record(path)


def test_at2_non_numeric_token(tmp_path):
    path = write_at2(tmp_path / "t.AT2", np.ones(10) * 0.01, 0.01, newline="\n")
    lines = path.read_text().splitlines()
    lines[5] = lines[5].replace("1.0000000E-02", "1.0O00000E-02", 1)
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(RockcliInputError, match=r"line 6: '1.0O00000E-02' is not a number"):
        read_record(path)


@pytest.mark.parametrize("dt_text", ["0.0000", "-.0100"])
def test_at2_zero_or_negative_dt(tmp_path, dt_text):
    path = write_at2(tmp_path / "t.AT2", np.ones(10) * 0.01, 0.01, newline="\n")
    path.write_text(path.read_text().replace(".0100", dt_text, 1))
    with pytest.raises(RockcliInputError, match=r"time step must be positive"):
        read_record(path)


def test_at2_unknown_units_word(tmp_path):
    path = write_at2(tmp_path / "t.AT2", np.ones(10) * 0.01, 0.01, newline="\n")
    path.write_text(path.read_text().replace("UNITS OF G", "UNITS OF FURLONGS"))
    with pytest.raises(RockcliInputError, match=r"states units 'FURLONGS', which rockcli does not know"):
        read_record(path)


def test_at2_units_contradicted_by_caller(tmp_path):
    path = write_at2(tmp_path / "t.AT2", np.ones(10) * 0.01, 0.01)
    with pytest.raises(RockcliInputError, match=r"states units 'G' but 'cm/s\^2' was given"):
        read_record(path, units="cm/s^2")
    assert read_record(path, units="g").pga_g == pytest.approx(0.01)
