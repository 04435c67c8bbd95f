"""Two horizontal components onto the rocking plane: projection, checks, ``--azimuth`` (issue 24 item 3)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.models import Block, Rigid
from rockcli.records.orientation import check_pair, cos_deg, project, read_pair, split_source, sweep_azimuths
from rockcli.records.record import Record
from rockcli.solve import simulate
from rockcli.io.units import G


def _component(acc, azimuth, name="pair", dt=0.01, station="ST"):
    return Record(acc=acc, dt=dt, name=name, meta={"azimuth_deg": azimuth, "vertical": False, "station": station,
                                                   "component": f"{azimuth:g}", "path": f"{name}-{azimuth:g}"})


def _rotated_pair(phi, n=2000, seed=3):
    """A random horizontal ground motion (north, east) seen by two perpendicular sensors at phi, phi + 90."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * 0.01
    north = rng.normal(size=n) * np.exp(-((t - 5) / 3) ** 2) * 3.0
    east = rng.normal(size=n) * np.exp(-((t - 6) / 2) ** 2) * 2.0

    def along(az):
        return north * math.cos(math.radians(az)) + east * math.sin(math.radians(az))

    return north, east, along, _component(along(phi), phi), _component(along(phi + 90.0), (phi + 90.0) % 360.0)


@pytest.mark.parametrize("phi", [0.0, 22.0, 140.0, 315.0])
def test_projection_recovers_the_rotated_motion(phi):
    north, east, along, a, b = _rotated_pair(phi)
    for theta in (0.0, 17.5, 90.0, 133.0, 200.0, phi):
        got = project(a, b, theta)
        np.testing.assert_allclose(got.acc, along(theta), rtol=0, atol=1e-12 * np.abs(north).max())
        np.testing.assert_array_equal(project(a, b, theta + 180.0).acc, -got.acc) if cos_deg(theta - phi) in (
            0.0, 1.0, -1.0) else np.testing.assert_allclose(project(a, b, theta + 180.0).acc, -got.acc, atol=1e-12)
    # onto a component's own azimuth: that component, sample for sample (and the other one's)
    np.testing.assert_array_equal(project(a, b, phi).acc, a.acc)
    np.testing.assert_array_equal(project(a, b, phi + 90.0).acc, b.acc)


def test_own_azimuth_reproduces_the_single_component_run_bit_for_bit():
    rng = np.random.default_rng(5)
    acc = np.convolve(rng.normal(size=3000), np.ones(60) / 60, "same")
    acc *= 0.3 * G / np.abs(acc).max()
    a = _component(acc, 140.0)
    b = _component(acc[::-1].copy(), 230.0)
    block = Block(R=1.0, alpha=math.radians(12))
    one = simulate(block, Rigid(), a)
    via = simulate(block, Rigid(), project(a, b, 140.0))
    assert one.summary() == via.summary()
    assert one.theta_max_over_alpha > 0.1  # it rocks: the comparison is not trivially 0 == 0


def test_pairs_are_checked():
    _, _, _, a, b = _rotated_pair(30.0)
    with pytest.raises(RockcliInputError, match="not perpendicular"):
        check_pair(a, _component(b.acc, 100.0))
    with pytest.raises(RockcliInputError, match="time steps differ"):
        check_pair(a, _component(b.acc, 120.0, dt=0.02))
    with pytest.raises(RockcliInputError, match="different stations"):
        check_pair(a, _component(b.acc, 120.0, station="OTHER"))
    with pytest.raises(RockcliInputError, match="orientation of the component is not stated; give it as"):
        check_pair(a, Record(acc=b.acc, dt=0.01, meta={"path": "x.txt"}))
    with pytest.raises(RockcliInputError, match="vertical"):
        check_pair(a, Record(acc=b.acc, dt=0.01, meta={"vertical": True, "path": "z"}))
    # components of different lengths: the shorter is padded with zeros (ground at rest after it ends)
    c = _component(b.acc[:1500], 120.0)
    got = project(a, c, 75.0)
    assert got.npts == a.npts
    np.testing.assert_allclose(got.acc[1500:], a.acc[1500:] * math.cos(math.radians(45.0)))


def test_split_source_and_sweep(tmp_path):
    assert split_source("TCU128-000@0") == ("TCU128-000", 0.0)
    assert split_source("x.AT2") == ("x.AT2", None)
    odd = tmp_path / "a@90"
    odd.write_text("1\n")
    assert split_source(str(odd)) == (str(odd), None)  # an existing file is never split
    assert list(sweep_azimuths(5.0)) == [5.0 * k for k in range(36)]
    assert list(sweep_azimuths(45)) == [0.0, 45.0, 90.0, 135.0]
    with pytest.raises(RockcliInputError, match="sweep_azimuths: step 0 must lie between 0.1 deg"):
        sweep_azimuths(0)


def _write(path, acc_g, dt=0.01):
    path.write_text(f"# dt={dt} sec\n# units: g\n" + "\n".join(f"{v:.12e}" for v in acc_g) + "\n")
    return path


@pytest.fixture()
def pair_files(tmp_path):
    """A pulse pair: the motion is along azimuth 60; sensors at 0 (N) and 90 (E)."""
    t = np.arange(0, 8, 0.01)
    motion = 0.32 * np.sin(2 * np.pi * t / 0.8) * (t < 0.8)  # one sine pulse [g] along azimuth 60
    north = _write(tmp_path / "n.txt", motion * math.cos(math.radians(60)))
    east = _write(tmp_path / "e.txt", motion * math.sin(math.radians(60)))
    return north, east


def test_simulate_azimuth_and_worst(pair_files):
    north, east = pair_files
    base = ["simulate", "--R", "0.8", "--alpha", "14", "--json", "--record", f"{north}@0", "--record-2", f"{east}@90"]
    res = CliRunner().invoke(main, [*base, "--azimuth", "worst", "--azimuth-step", "10"])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert out["azimuths_deg"] == [10.0 * k for k in range(18)]
    # the motion is along 60 deg: it rocks the block most there (a pulse just above uplift, tan 14 deg = 0.25 g,
    # well below overturning), and 150 deg (normal to it) feels nothing
    assert out["overturning_azimuths_deg"] == []
    assert out["worst_azimuth_deg"] == 60.0
    assert out["verdicts"][15] == "no_uplift"
    # each entry is the run at that one azimuth
    one = json.loads(CliRunner().invoke(main, [*base, "--azimuth", "60"]).output)
    assert out["worst_verdict"] == one["verdict"]
    if one["verdict"] != "overturned":
        assert out["theta_max_over_alpha"][6] == one["theta_max_over_alpha"]
    # --azimuth of a component's own orientation: the single-component run (as JSON, bar the label)
    own = json.loads(CliRunner().invoke(main, [*base, "--azimuth", "0"]).output)
    single = json.loads(CliRunner().invoke(main, ["simulate", "--R", "0.8", "--alpha", "14", "--json",
                                                  "--record", str(north)]).output)
    assert {k: v for k, v in own.items() if k != "excitation"} == {k: v for k, v in single.items() if k != "excitation"}


@pytest.mark.parametrize("extra, words", [
    (["--record-2", "{e}", "--azimuth", "30"], "orientation of the component is not stated; give it as n.txt@DEG"),
    (["--azimuth", "30"], "--azimuth needs two horizontal components: the file holds one"),
    (["--record-2", "{e}@90"], "--record-2 is the second horizontal component for --azimuth"),
    (["--record", "{n}@0", "--record-2", "{e}@80", "--azimuth", "3"], "not perpendicular"),
    (["--record", "{n}@0", "--record-2", "{e}@90", "--azimuth", "worst", "--plot", "{d}/x.png"],
     "need one --azimuth DEG"),
    (["--azimuth-step", "5"], "--azimuth-step applies to --azimuth worst"),
])
def test_simulate_azimuth_bad_input(pair_files, extra, words):
    north, east = pair_files
    extra = [e.format(e=east, n=north, d=east.parent) for e in extra]
    res = CliRunner().invoke(main, ["simulate", "--R", "0.8", "--alpha", "14", "--record", str(north), *extra])
    assert res.exit_code == 2 and words in res.output, res.output
    assert not (east.parent / "x.png").exists()
    res = CliRunner().invoke(main, ["simulate", "--R", "0.8", "--alpha", "14", "--pulse", "sine:ap=0.3,Tp=1",
                                    "--azimuth", "3"])
    assert res.exit_code == 2 and "apply to --record" in res.output


def test_assess_column_worst_azimuth(pair_files, tmp_path):
    north, east = pair_files
    res = CliRunner().invoke(main, ["assess", "column", "small:R=0.8,alpha=14", "--isolation", "none",
                                    "--records", f"{north}@0+{east}@90", "--azimuth", "worst",
                                    "--azimuth-step", "30", "--csv", str(tmp_path / "a.csv")])
    assert res.exit_code == 0, res.output
    import pandas as pd

    df = pd.read_csv(tmp_path / "a.csv")
    assert len(df) == 1 and df.azimuths_run[0] == 6 and df.azimuth_deg[0] == 60.0
    assert "@60" in res.output and "most adverse orientation" in res.output
    # the worst row is the run at that azimuth: its margin equals a fixed --azimuth 60 run's
    res60 = CliRunner().invoke(main, ["assess", "column", "small:R=0.8,alpha=14", "--isolation", "none",
                                      "--records", f"{north}@0+{east}@90", "--azimuth", "60",
                                      "--csv", str(tmp_path / "b.csv")])
    assert res60.exit_code == 0, res60.output
    one = pd.read_csv(tmp_path / "b.csv")
    assert one.overturn_scale[0] == df.overturn_scale[0] and one.verdict[0] == df.verdict[0]
    # an orientation no file states, in a pair: one sentence in the error row
    res = CliRunner().invoke(main, ["assess", "column", "small:R=0.8,alpha=14", "--isolation", "none",
                                    "--records", f"{north}+{east}@90", "--azimuth", "worst"])
    assert res.exit_code == 2 and "orientation of the component is not stated" in res.output


def test_read_pair_from_one_file(find_record):
    path = find_record("20161113_110259_WTMC_20.V2A")
    a, b = read_pair(str(path))
    assert (a.meta["azimuth_deg"], b.meta["azimuth_deg"]) == (332.0, 242.0)
    np.testing.assert_array_equal(project(a, b, 242.0).acc, b.acc)
    with pytest.raises(RockcliInputError, match="--component/--record-column do not apply with --azimuth"):
        read_pair(str(path), component="N28W")


def test_fragility_takes_one_azimuth(pair_files, tmp_path):
    north, east = pair_files
    args = ["assess", "fragility", "small:R=0.8,alpha=14", "--isolation", "none", "--bootstrap", "0",
            "--records", f"{north}@0+{east}@90"]
    res = CliRunner().invoke(main, [*args, "--azimuth", "60", "--csv", str(tmp_path / "f.csv")])
    assert res.exit_code == 0, res.output
    import pandas as pd

    df = pd.read_csv(tmp_path / "f.csv")
    # the motion along 60 deg is the 0.32 g pulse itself
    assert df.record[0] == "n.txt+e.txt@60" and df.pga_g[0] == pytest.approx(0.32, rel=1e-3)
    # --azimuth worst: every orientation (tests/test_fragility_azimuth.py); the worst is the motion's own, 60 deg
    res = CliRunner().invoke(main, [*args, "--azimuth", "worst", "--azimuth-step", "30",
                                    "--csv", str(tmp_path / "w.csv")])
    assert res.exit_code == 0, res.output
    w = pd.read_csv(tmp_path / "w.csv")
    worst = w[w.orientation == "worst"].iloc[0]
    assert worst.azimuth_deg == 60.0 and worst.overturn_scale == df.overturn_scale[0]


def test_catalogue_pair_id_with_azimuth(find_record):
    """A catalogue id naming two components takes --azimuth: onto its first component's own orientation the
    run is the id's single-component run (bar the label); --record-2 is not needed."""
    find_record("TCU128-090")
    base = ["simulate", "--body", "bassae", "--json", "--record", "chichi-1999-tcu128-n"]
    single = CliRunner().invoke(main, base)
    own = CliRunner().invoke(main, [*base, "--azimuth", "0"])
    assert single.exit_code == 0 and own.exit_code == 0, own.output
    one, via = json.loads(single.output), json.loads(own.output)
    assert {k: v for k, v in via.items() if k != "excitation"} == {k: v for k, v in one.items() if k != "excitation"}
    # the other component's orientation is the other file's run (--component E)
    east = json.loads(CliRunner().invoke(main, [*base, "--component", "E"]).output)
    via_e = json.loads(CliRunner().invoke(main, [*base, "--azimuth", "90"]).output)
    assert {k: v for k, v in via_e.items() if k != "excitation"} == {k: v for k, v in east.items() if k != "excitation"}
