"""Raw counts are refused unless a gain is given (issue 24 item 2): ``--gain FACTOR --units UNITS``.

A file is in counts when ObsPy reads integer samples (MiniSEED, GSE2, ...; K-NET's stated scale factor
excepted) or a text file states ``units: counts``; a file that states no units is taken as counts when a
gain is given. The gain times the counts is in ``--units``.
"""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.io.units import G


def _counts(n=400, seed=5):
    rng = np.random.default_rng(seed)
    return np.round(rng.normal(0.0, 2.0e5, n)).astype(np.int32)


@pytest.fixture()
def mseed_counts(tmp_path):
    obspy = pytest.importorskip("obspy")
    data = _counts()
    tr = obspy.Trace(data=data, header={"delta": 0.01, "network": "XX", "station": "CNT", "channel": "HNE"})
    path = tmp_path / "counts.mseed"
    tr.write(str(path), format="MSEED", encoding="STEIM2")
    return path, data


def test_integer_samples_are_refused_without_a_gain(mseed_counts):
    path, _ = mseed_counts
    for kwargs in ({}, {"units": "m/s^2"}):  # --units alone is not a gain: counts are not m/s^2
        with pytest.raises(RockcliInputError, match=r"raw counts .*give --gain FACTOR with --units UNITS") as exc:
            read_record(path, **kwargs)
        assert "\n" not in str(exc.value)


@pytest.mark.parametrize("units,factor", [("m/s^2", 1.0), ("g", G), ("cm/s^2", 0.01)])
def test_gain_converts_counts_to_the_given_units(mseed_counts, units, factor):
    path, data = mseed_counts
    gain = 3.7e-6
    rec = read_record(path, gain=gain, units=units)
    np.testing.assert_array_equal(rec.acc, data.astype(np.float64) * (gain * factor))
    assert rec.meta["units"] == "counts" and rec.meta["gain"] == gain and rec.meta["gain_units"] == units
    assert rec.dt == 0.01 and "gain" in rec.meta["units_source"]
    # linear in the gain: twice the gain, twice the record (no other scaling on the way)
    np.testing.assert_allclose(read_record(path, gain=2 * gain, units=units).acc, 2 * rec.acc, rtol=1e-15)


def test_text_file_stating_counts(tmp_path):
    counts = _counts(300, seed=8)
    path = tmp_path / "c.txt"
    path.write_text("# units: counts\n# dt=0.005 sec\n" + "\n".join(str(int(v)) for v in counts) + "\n")
    with pytest.raises(RockcliInputError, match=r"raw counts"):
        read_record(path)
    rec = read_record(path, gain=1e-5, units="gal")
    np.testing.assert_array_equal(rec.acc, counts * (1e-5 * 0.01))
    assert rec.dt == 0.005


def test_headerless_file_with_a_gain_is_taken_as_counts(tmp_path):
    counts = _counts(200, seed=9)
    path = tmp_path / "raw.txt"
    path.write_text("\n".join(str(int(v)) for v in counts) + "\n")
    rec = read_record(path, gain=2e-6, units="m/s^2", dt=0.01)
    np.testing.assert_array_equal(rec.acc, counts * 2e-6)


def test_gain_refusals(tmp_path, mseed_counts, find_record):
    path, _ = mseed_counts
    with pytest.raises(RockcliInputError, match=r"--gain 1e-06 needs --units"):
        read_record(path, gain=1e-6)
    for bad in (0, -1e-6, "x", float("nan")):
        with pytest.raises(RockcliInputError, match=r"--gain"):
            read_record(path, gain=bad, units="g")
    at2 = find_record("RSN1119_KOBE_TAZ000.AT2")  # states units g
    with pytest.raises(RockcliInputError, match=r"(?i)states units 'g', not raw counts; --gain applies only"):
        read_record(at2, gain=1e-6, units="m/s^2")


def test_cli_gain_on_records_show_and_simulate(mseed_counts):
    path, data = mseed_counts
    runner = CliRunner()
    out = runner.invoke(main, ["records", "show", str(path)])
    assert out.exit_code == 2 and "raw counts" in out.output and "Traceback" not in out.output
    out = runner.invoke(main, ["records", "show", str(path), "--gain", "2e-6", "--units", "m/s^2"])
    assert out.exit_code == 0, out.output
    pga_g = float(np.max(np.abs(data))) * 2e-6 / G
    assert f"{pga_g:.4g}"[:4] in out.output
    out = runner.invoke(main, ["simulate", "--record", str(path), "--gain", "2e-6", "--units", "m/s^2",
                              "--R", "0.5", "--alpha", "10"])
    assert out.exit_code == 0, out.output


def test_suite_gain_fills_in_counts_only(tmp_path, mseed_counts, find_record):
    """In a suite, --gain (like --units/--dt) fills in: the counts file is scaled, an AT2 file is read as it
    states; a manifest row's gain does the same for its file."""
    from rockcli.assess import resolve_excitations

    path, data = mseed_counts
    at2 = find_record("RSN1119_KOBE_TAZ000.AT2")
    xs, _ = resolve_excitations([str(path), str(at2)], "record", units="m/s^2", gain=4e-6)
    assert not any(x.error for x in xs), [x.error for x in xs]
    np.testing.assert_array_equal(xs[0].motion.acc, data * 4e-6)
    np.testing.assert_array_equal(xs[1].motion.acc, read_record(at2).acc)
    manifest = tmp_path / "suite.csv"
    manifest.write_text(f"file,units,gain\n{path.name},g,1e-7\n")
    (x,), _ = resolve_excitations([str(manifest)], "record")
    np.testing.assert_array_equal(x.motion.acc, data * (1e-7 * G))
    manifest.write_text(f"file,gain\n{path.name},1e-7\n")
    with pytest.raises(RockcliInputError, match=r"line 2: the gain needs the units"):
        resolve_excitations([str(manifest)], "record")
