"""read_record on every shared record (npts, dt, PGA against SOURCES.csv), formats, bad files."""

from __future__ import annotations

import csv
import os

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.records.extra import available
from rockcli.records.motion import calc_peaks, cumtrapz, integrate
from rockcli.records.reader import read_components
from rockcli.records.record import Record
from rockcli.io.units import G, accel_factor

#: What the caller must say for files that do not state it (from SOURCES.csv notes).
OPTIONS = {
    "C02-065": dict(units="g", dt=0.01), "TCU128-000": dict(units="g", dt=0.005),
    "TCU128-090": dict(units="g", dt=0.005), "G06-230": dict(units="g", dt=0.005),
    "G06-320": dict(units="g", dt=0.005), "SanSalvador1986GIC090.txt": dict(units="m/s^2"),
    "erzikan.txt": dict(column=2), "sylmar.txt": dict(column=1), "sct190985.txt": dict(column=2, units="g"),
    "20161113_110259_WTMC_20.V2A": dict(column=1), "20190706031952.CJ.T001230.HNE.sac": dict(units="m/s^2"),
}
#: Files refused on purpose, with a key phrase of the message.
REFUSED = {
    "017m30cc.y0a": "uneven spacing", "5522-1.V1": "BHRC VOL1", "ACAC1709.191": "UNAM ASA 2.0",
    "A-CAT090.AT2.smc": "USGS SMC",
}
#: Files refused without the ``formats`` extra that it reads (gmprocess resamples USC Volume I's uneven pairs, so
#: npts and dt differ from SOURCES.csv; the peak of the listed component is checked).
EXTRA_READS = {"017m30cc.y0a", "5522-1.V1", "ACAC1709.191"}
#: Formats expected per file (detection).
FORMATS = {
    ".AT2": "PEER_AT2", "HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC": "ESM", "16833_H1.cor.acc": "ITACA",
    "us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c": "COSMOS", "20161113_110259_WTMC_20.V2A": "GEONET_V2A",
    "AOM0011801241951.EW": "KNET", "AICH040010061330.EW2": "KNET", "20190706031952.CJ.T001230.HNE.sac": "SAC",
}


def _rows(records_dirs):
    out = []
    for folder in records_dirs:
        if (folder / "SOURCES.csv").is_file():
            with open(folder / "SOURCES.csv", newline="") as fh:
                out += [(folder, r) for r in csv.DictReader(fh)]
    if not out:
        pytest.skip("no SOURCES.csv in ROCKCLI_RECORDS")
    return out


def _native_peak(row):
    """Peak in the file's own units, from the 'pga_measured_native' column ('486.1 cm/s^2')."""
    return float(row["pga_measured_native"].split()[0])


def test_every_shared_record_loads_or_is_refused(records_dirs):
    loaded = refused = 0
    rows = _rows(records_dirs)
    for folder, row in rows:
        name = row["file"]
        path = folder / name
        if name in EXTRA_READS and available():
            comps = read_components(path)  # every component, as gmprocess reads them (cm/s^2)
            assert all(c.meta["reader"] == "gmprocess" for c in comps), name
            got = [c.pga_g for c in comps]
            assert any(g == pytest.approx(float(row["pga_measured_g"]), abs=6e-4) for g in got), (name, got)
            loaded += 1
            continue
        if name in REFUSED:
            with pytest.raises(RockcliInputError, match=REFUSED[name]):
                read_record(path)
            refused += 1
            continue
        rec = read_record(path, **OPTIONS.get(name, {}))
        assert rec.npts == int(row["npts"]), name
        assert rec.dt == pytest.approx(float(row["dt"]), rel=1e-9), name
        expected = FORMATS.get(name) or FORMATS.get(path.suffix)
        if expected:
            assert rec.meta["format"] == expected, name
        acc_native = rec.acc / rec.meta["factor"]
        if name.endswith(".sac"):  # SOURCES lists the peak after removing the DC offset
            acc_native = acc_native - acc_native.mean()
        assert np.abs(acc_native).max() == pytest.approx(_native_peak(row), rel=2e-4), name
        if row["pga_measured_g"]:
            assert rec.pga_g == pytest.approx(float(row["pga_measured_g"]), abs=6e-4), name
        assert rec.acc.dtype == np.float64 and np.isfinite(rec.acc).all()
        loaded += 1
    read_by_extra = EXTRA_READS if available() else set()
    assert refused == sum(row["file"] in REFUSED and row["file"] not in read_by_extra for _, row in rows)
    assert loaded + refused == len(rows)


def test_sac_without_units_asks_for_them(find_record):
    path = find_record("20190706031952.CJ.T001230.HNE.sac")
    with pytest.raises(RockcliInputError, match=r"does not state its units; give them with --units"):
        read_record(path)


def test_knet_is_mean_removed_si(find_record):
    rec = read_record(find_record("AOM0011801241951.EW"))
    assert rec.meta["format"] == "KNET" and rec.meta["processing"].startswith("mean removed")
    assert abs(rec.acc.mean()) < 1e-12
    assert rec.meta["units"] == "gal" and rec.pga * 100 == pytest.approx(4.078, abs=6e-4)  # header Max. Acc. (gal)


def test_geonet_needs_component(find_record):
    path = find_record("20161113_110259_WTMC_20.V2A")
    with pytest.raises(RockcliInputError, match=r"holds 3 components \(N28W, S62W, Up\); choose one with --component NAME \(or --record-column 1-3\)"):
        read_record(path)
    vert = read_record(path, column=3)
    assert vert.meta["component"] == "Up" and vert.npts == 8192


def test_time_column_start_time(find_record):
    rec = read_record(find_record("sct190985.txt"), column=2, units="g")
    assert rec.t_start == 0.02 and rec.dt == 0.02


# ---------------------------------------------------------------- formats written in tmp_path

def test_esm_synthetic(tmp_path):
    values = [0.5, -1.25, 2.0, 0.0]
    head = ["EVENT_NAME: TEST", "NETWORK: XX", "STATION_CODE: ABC", "SAMPLING_INTERVAL_S: 0.010000",
            f"NDATA: {len(values)}", "STREAM: HNE", "UNITS: cm/s^2", "DATA_TYPE: ACCELERATION", "USER5: "]
    path = tmp_path / "x.ASC"
    path.write_text("\n".join(head + [f"{v:f}" for v in values]) + "\n")
    rec = read_record(path)
    assert rec.meta["format"] == "ESM" and rec.dt == 0.01 and rec.meta["station"] == "XX.ABC"
    np.testing.assert_allclose(rec.acc, np.array(values) / 100, rtol=1e-15)
    path.write_text("\n".join(head + [f"{v:f}" for v in values[:3]]) + "\n")
    with pytest.raises(RockcliInputError, match=r"the header states 4 samples \(line 5: 'NDATA: 4'\), but 3 values follow .*cut short"):
        read_record(path)


def test_sac_synthetic_round_trip(tmp_path):
    obspy = pytest.importorskip("obspy")
    rng = np.random.default_rng(3)
    data = rng.normal(0, 0.1, 200).astype(np.float32)
    tr = obspy.Trace(data=data, header={"delta": 0.005, "station": "S1", "channel": "HNE"})
    tr.write(str(tmp_path / "x.sac"), format="SAC")
    tr.write(str(tmp_path / "x.mseed"), format="MSEED")
    for name in ("x.sac", "x.mseed"):
        rec = read_record(tmp_path / name, units="g")
        assert rec.dt == 0.005 and rec.npts == 200
        np.testing.assert_array_equal(rec.acc, data.astype(np.float64) * G)


def test_obspy_unknown_binary(tmp_path):
    path = tmp_path / "noise.bin"
    path.write_bytes(bytes(np.random.default_rng(0).integers(0, 256, 500, dtype=np.uint8)) + b"\x00")
    with pytest.raises(RockcliInputError, match=r"format not recognised"):
        read_record(path, units="g", dt=0.01)


# ---------------------------------------------------------------- missing/empty, parameters

def test_missing_file(tmp_path):
    with pytest.raises(RockcliInputError, match=r"no such file"):
        read_record(tmp_path / "nope.AT2")
    with pytest.raises(RockcliInputError, match=r"nope: no such file here or in the ROCKCLI_RECORDS folders, "
                                                r"nor a catalogue id"):
        read_record("nope")


def test_a_bare_file_name_is_found_in_the_records_folders(tmp_path, monkeypatch):
    """``RSN1119_KOBE_TAZ000.AT2`` typed as a bare name: not in the current folder, so the first
    ROCKCLI_RECORDS folder that holds a file of that name gives it (as for a catalogue record's file);
    a file of that name in the current folder comes first."""
    from conftest import write_pulse_record

    first, second, here = tmp_path / "a", tmp_path / "b", tmp_path / "here"
    for d in (first, second, here):
        d.mkdir()
    write_pulse_record(second / "pulse.txt", a_p_g=0.3)
    monkeypatch.setenv("ROCKCLI_RECORDS", f"{first}{os.pathsep}{second}")
    monkeypatch.chdir(here)
    rec = read_record("pulse.txt")
    assert rec.meta["path"] == str(second / "pulse.txt")
    assert rec.pga_g == pytest.approx(0.3, rel=1e-3)
    write_pulse_record(first / "pulse.txt", a_p_g=0.4)
    assert read_record("pulse.txt").pga_g == pytest.approx(0.4, rel=1e-3)
    write_pulse_record(here / "pulse.txt", a_p_g=0.5)
    assert read_record("pulse.txt").pga_g == pytest.approx(0.5, rel=1e-3)


def test_empty_file(tmp_path):
    (tmp_path / "e.AT2").write_bytes(b"")
    with pytest.raises(RockcliInputError, match=r"the file is empty"):
        read_record(tmp_path / "e.AT2")


def test_folder_is_not_a_record(tmp_path):
    with pytest.raises(RockcliInputError, match=r"is a folder"):
        read_record(tmp_path)


@pytest.mark.parametrize("column", [0, -1, 1.5, "x"])
def test_bad_column(tmp_path, column):
    (tmp_path / "a.txt").write_text("1\n2\n3\n")
    with pytest.raises(RockcliInputError, match=r"column"):
        read_record(tmp_path / "a.txt", units="g", dt=0.01, column=column)


def test_one_sample_is_not_a_record(tmp_path):
    (tmp_path / "a.txt").write_text("1\n")
    with pytest.raises(RockcliInputError, match=r"at least 2 are needed"):
        read_record(tmp_path / "a.txt", units="g", dt=0.01)


# ---------------------------------------------------------------- integration (PGV)

def test_integration_closed_form():
    """a = A sin(w t): v = A/w (1 - cos w t), trapezoid error O(dt^2)."""
    dt, w, A = 1e-3, 2 * np.pi, 3.0
    t = dt * np.arange(5001)
    rec = Record(A * np.sin(w * t), dt)
    vel, _ = integrate(rec, "none")
    np.testing.assert_allclose(vel, A / w * (1 - np.cos(w * t)), atol=A * w * dt ** 2)
    assert calc_peaks(rec).pgv_mps == pytest.approx(2 * A / w, rel=1e-5)


def test_linear_baseline_removes_offset_drift():
    dt = 0.01
    t = dt * np.arange(2001)
    clean = np.sin(2 * np.pi * t) * np.exp(-t)
    rec = Record(clean + 0.05, dt)  # a constant offset makes the velocity drift linearly
    p = calc_peaks(rec)
    assert p.pgv_mps > 0.9  # ~0.05 m/s^2 * 20 s of drift
    assert p.pgv_linear_mps < 0.2


def test_cumtrapz_matches_scipy():
    from scipy.integrate import cumulative_trapezoid

    y = np.random.default_rng(5).normal(size=101)
    np.testing.assert_allclose(cumtrapz(y, 0.02), np.r_[0, cumulative_trapezoid(y, dx=0.02)], rtol=1e-12, atol=1e-14)


def test_units_table_words():
    assert accel_factor("cm/sec^2") == 0.01 and accel_factor("G") == G and accel_factor("mm/s/s") == 1e-3
