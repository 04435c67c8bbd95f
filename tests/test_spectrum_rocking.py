"""``rockcli spectrum rocking``: a record's rocking spectrum (issue 27 item 5).

Every point must be the single-scene run of its block (:func:`rockcli.solve.simulate`, no history,
``early=False``): the spectrum's batch calls the same compiled driver with the same arguments, so the
comparison is exact (bit for bit), not to a tolerance. A spectrum built from verdict-only early stops
(lower bounds of the peaks) would fail it.
"""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from conftest import write_pulse_record
from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.models import Block, Rigid, parse_isolation_spec
from rockcli.records import read_record
from rockcli.report.figures import NBSP, spec_text
from rockcli.report.rocking import ROCKING_COLUMNS
from rockcli.solve import simulate
from rockcli.spectra import Runner, rocking_spectrum, size_grid
from rockcli.io.units import G

#: Foundations the differential test draws from: rigid, linear (light and heavy base), a sliding bearing.
ISOLATIONS = ("none", "linear:Tb=2.5", "linear:Tb=4,xi=0.05,gamma=0.3", "scss:Tb=3,mu=0.1")


@pytest.fixture(scope="module")
def kobe(records_dirs):
    try:
        return read_record("kobe-1995-takarazuka-000")
    except RockcliInputError as exc:
        pytest.skip(str(exc))


@pytest.fixture()
def synthetic(tmp_path):
    """A short symmetric Ricker record (0.5 g, T_p = 0.6 s) that overturns small blocks and not large ones."""
    return write_pulse_record(tmp_path / "ricker.txt", a_p_g=0.5, T_p=0.6, pad=2.0)


def _same_as_simulate(curve, record, restitution=None, cap_ratio=0.0):
    for i, R in enumerate(curve.R):
        one = simulate(Block.from_degrees(float(R), curve.alpha_deg), curve.foundation, record,
                       restitution=restitution, cap_ratio=cap_ratio)
        assert curve.theta_max_over_alpha[i] == one.theta_max_over_alpha, (curve.alpha_deg, curve.isolation, R)
        assert bool(curve.overturned[i]) == one.overturned
        assert bool(curve.uplifted[i]) == (one.verdict != "no_uplift")
        assert bool(curve.settled[i]) == one.settled
        assert bool(curve.peak_final[i]) and one.peak_final


def test_each_point_is_the_simulate_run_of_its_block_100_random_points(kobe):
    rng = np.random.default_rng(27_5)
    foundations = [parse_isolation_spec(s) for s in ISOLATIONS]
    kinds = []
    for _ in range(100):
        R = float(np.exp(rng.uniform(math.log(0.2), math.log(20.0))))
        alpha = float(rng.uniform(3.0, 20.0))
        f = foundations[rng.integers(len(foundations))]
        (curve,) = rocking_spectrum(kobe, [alpha], [f], [R])
        _same_as_simulate(curve, kobe)
        kinds.append((f.label, bool(curve.overturned[0]), bool(curve.uplifted[0])))
    # the draw covers every foundation and all three outcomes (else the test would prove little)
    assert {k[0] for k in kinds} == {f.label for f in foundations}
    assert any(o for _, o, _ in kinds) and any(u and not o for _, o, u in kinds) and not all(u for *_, u in kinds)


def test_a_grid_of_curves_keeps_each_point_in_its_place(kobe):
    """alpha x foundation x R in one batch (shuffled across threads inside): every curve is its blocks' runs."""
    foundations = [Rigid(), parse_isolation_spec("linear:Tb=2.5")]
    curves = rocking_spectrum(kobe, [8.0, 13.0], foundations, size_grid("0.3:12:7"), runner=Runner())
    assert [(c.alpha_deg, c.isolation) for c in curves] == [(a, f.label) for a in (8.0, 13.0) for f in foundations]
    for c in curves:
        _same_as_simulate(c, kobe)


@pytest.mark.parametrize("isolated", [False, True])
def test_restitution_and_cap_ratio_reach_every_point(kobe, isolated):
    """On the rigid ground and (a capped colonnade on an isolated base) on linear bearings."""
    found = [parse_isolation_spec("linear:Tb=2.5") if isolated else Rigid()]
    runner = Runner(restitution=0.8, cap_ratio=0.5)
    (curve,) = rocking_spectrum(kobe, [10.0], found, size_grid("0.5:10:5"), runner=runner)
    _same_as_simulate(curve, kobe, restitution=0.8, cap_ratio=0.5)
    (plain,) = rocking_spectrum(kobe, [10.0], found, size_grid("0.5:10:5"))
    assert not np.array_equal(plain.theta_max_over_alpha, curve.theta_max_over_alpha)


def test_rigid_foundation_uplift_does_not_depend_on_the_size(kobe):
    """On the rigid ground a block uplifts iff the record's PGA exceeds g tan(alpha), whatever its size."""
    R = size_grid("0.2:20:9")
    alphas = [20.0, 30.0, 40.0]  # tan(alpha) g = 0.36 g, 0.58 g, 0.84 g against Kobe's 0.697 g
    for c in rocking_spectrum(kobe, alphas, [Rigid()], R):
        expected = kobe.pga_g > math.tan(math.radians(c.alpha_deg))
        assert np.all(c.uplifted == expected), c.alpha_deg
        assert np.all(c.theta_max_over_alpha[~c.uplifted] == 0.0)


def test_reversed_record_mirrors_the_motion_same_peaks(kobe):
    R = size_grid("0.4:15:6")
    (a,) = rocking_spectrum(kobe, [11.0], [Rigid()], R)
    (b,) = rocking_spectrum(kobe.scaled(-1.0), [11.0], [Rigid()], R)
    assert np.array_equal(a.overturned, b.overturned)
    np.testing.assert_allclose(a.theta_max_over_alpha, b.theta_max_over_alpha, rtol=1e-9)


def test_size_grid_is_geometric_with_both_ends_exact():
    R = size_grid("0.2:20:3")
    assert R.tolist()[0] == 0.2 and R.tolist()[-1] == 20.0
    assert R[1] == pytest.approx(2.0, rel=1e-14)
    R = size_grid("0.1:20:200")
    ratios = R[1:] / R[:-1]
    np.testing.assert_allclose(ratios, ratios[0], rtol=1e-12)
    assert size_grid("1.5:1.5:1").tolist() == [1.5]


@pytest.mark.parametrize("text, words", [
    ("0:20:10", "start must be > 0"),
    ("0.2:20", "start:stop:count"),
    ("20:0.2:10", "stop must be larger than start"),
    ("0.2:1000:10", "between 0.01 m and 100 m"),
    ("a:b:c", "must be numbers"),
])
def test_size_grid_refuses_in_one_sentence(text, words):
    with pytest.raises(RockcliInputError, match=words) as exc:
        size_grid(text)
    assert "--R" in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.parametrize("args, words", [
    (["--alpha", "0"], "--alpha"),
    (["--alpha", "ten"], "--alpha"),
    (["--alpha", "0.5"], "below the supported 1 deg"),
    (["--alpha", "10", "--R", "0:20:5"], "--R"),
    (["--alpha", "10", "--isolation", "linear:TbTp=2"], "isolation 'linear:TbTp=2'"),
    (["--alpha", "10", "--isolation", "wobbly:Tb=2"], "unknown isolation"),
    (["--alpha", "10", "--scale", "0"], "--scale"),
    (["--alpha", "10", "--restitution", "1.5"], "--restitution"),
    (["--alpha", "10", "--horizon", "4000"], "horizon"),
])
def test_cli_bad_input_one_sentence_exit_2_nothing_written(tmp_path, synthetic, args, words):
    out, png = tmp_path / "s.csv", tmp_path / "s.png"
    r = CliRunner().invoke(main, ["spectrum", "rocking", str(synthetic), *args, "--csv", str(out), "--plot", str(png)])
    assert r.exit_code == 2, r.output
    assert r.output.startswith("Error:") and words in r.output and "Traceback" not in r.output
    assert r.output.strip().count("\n") == 0
    assert not out.exists() and not png.exists()


def test_cli_missing_record_is_one_sentence(tmp_path):
    r = CliRunner().invoke(main, ["spectrum", "rocking", str(tmp_path / "nope.AT2"), "--alpha", "10"])
    assert r.exit_code == 2 and "nope.AT2" in r.output and "Traceback" not in r.output


def test_cli_csv_and_json_columns(tmp_path, synthetic):
    out, png = tmp_path / "s.csv", tmp_path / "s.png"
    args = ["spectrum", "rocking", str(synthetic), "--alpha", "10,15", "--R", "0.1:20:12", "--isolation", "none",
            "--isolation", "linear:Tb=3,xi=0.05", "--scale", "1.2"]
    r = CliRunner().invoke(main, [*args, "--csv", str(out), "--plot", str(png)])
    assert r.exit_code == 0, r.output
    assert "isolation lowers the peak at R =" in r.output
    assert png.stat().st_size > 10_000
    lines = list(csv.reader(out.read_text().splitlines()))
    assert tuple(lines[0]) == ROCKING_COLUMNS
    rows = [dict(zip(ROCKING_COLUMNS, line)) for line in lines[1:]]
    assert len(rows) == 2 * 2 * 12
    assert [r_["alpha_deg"] for r_ in rows[::12]] == ["10.0", "10.0", "15.0", "15.0"]
    assert [r_["isolation"] for r_ in rows[::12]] == ["none", "linear:Tb=3,xi=0.05,gamma=0.01"] * 2
    over = [r_ for r_ in rows if r_["overturned"] == "True"]
    kept = [r_ for r_ in rows if r_["overturned"] == "False" and r_["uplift"] == "True"]
    assert over and kept  # the columns below are checked on both outcomes
    for r_ in rows:
        R = float(r_["R_m"])
        assert float(r_["p_radps"]) == pytest.approx(math.sqrt(0.75 * G / R), rel=1e-15)
        assert r_["record"] == "ricker.txt" and float(r_["scale"]) == 1.2 and r_["proven"] == "True"
        assert r_["peak_final"] == "True"
    for r_ in over:
        assert float(r_["theta_max_over_alpha"]) == pytest.approx(90.0 / float(r_["alpha_deg"]), rel=1e-12)
    for r_ in kept:
        assert 0.0 < float(r_["theta_max_over_alpha"]) < 90.0 / float(r_["alpha_deg"])

    r = CliRunner().invoke(main, [*args, "--json"])
    assert r.exit_code == 0, r.output
    data = json.loads(r.output)
    assert data["record"] == "ricker.txt" and data["scale"] == 1.2 and data["runs"] == 48
    assert len(data["curves"]) == 4
    for k, curve in enumerate(data["curves"]):
        assert set(curve) == {"alpha_deg", "isolation", *ROCKING_COLUMNS[4:]}
        part = rows[12 * k:12 * (k + 1)]
        assert curve["isolation"] == part[0]["isolation"]
        assert curve["R_m"] == [float(r_["R_m"]) for r_ in part]
        assert curve["theta_max_over_alpha"] == [float(r_["theta_max_over_alpha"]) for r_ in part]
        assert curve["overturned"] == [r_["overturned"] == "True" for r_ in part]


def test_cli_point_equals_cli_simulate(tmp_path, synthetic):
    """A CSV row's R_m (written exactly) given back to ``rockcli simulate`` reproduces its peak exactly."""
    out = tmp_path / "s.csv"
    r = CliRunner().invoke(main, ["spectrum", "rocking", str(synthetic), "--alpha", "12", "--R", "0.3:8:5",
                                  "--isolation", "linear:Tb=2", "--scale", "0.9", "--restitution", "0.85",
                                  "--csv", str(out)])
    assert r.exit_code == 0, r.output
    lines = list(csv.reader(out.read_text().splitlines()))
    assert lines[0] == [*ROCKING_COLUMNS, "restitution"]
    for line in lines[1:]:
        row = dict(zip(lines[0], line))
        assert row["restitution"] == "0.85"
        s = CliRunner().invoke(main, ["simulate", "--R", row["R_m"], "--alpha", "12", "--record", str(synthetic),
                                      "--isolation", "linear:Tb=2", "--scale", "0.9", "--restitution", "0.85",
                                      "--json"])
        assert s.exit_code == 0, s.output
        one = json.loads(s.output)
        assert (one["verdict"] == "overturned") == (row["overturned"] == "True")
        assert one["theta_max_over_alpha"] == float(row["theta_max_over_alpha"])


def test_legend_names_the_bearing_parameters():
    assert spec_text("none") == "rigid foundation"
    text = spec_text("linear:Tb=2.5,xi=0.05,gamma=0.01").replace(NBSP, " ")
    assert text.startswith("linear bearings") and "$T_b$ = 2.5 s" in text and r"$\xi$ = 0.05" in text
    assert r"$\gamma$ = 0.01" in text

