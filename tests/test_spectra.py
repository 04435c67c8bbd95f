"""Overturning spectra: cells against single runs, the minimum search against brute force, the
uplift boundary, the decoupled limit of a very flexible isolator, invariance in the block size,
Dask against local, and the CLI (bad input, CSV columns, Table I layout)."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.models import LinearIsolation, Rigid
from rockcli.pulses import make_pulse
from rockcli.solve import simulate
from rockcli.spectra import (Family, Grid, Isolation, PulseChoice, critical_R, critical_sizes, min_overturning_curves,
                             overturning_map, overturning_maps, parse_grid, parse_isolation, parse_pulse_choice,
                             run_cells_local, search_min_overturning)
from rockcli.io.units import G

LIN2 = "linear:TbTp=2,xi=0.05,gamma=0.01"


# ------------------------------------------------------------------------------------------
# Input parsing
# ------------------------------------------------------------------------------------------
def test_grid_includes_both_ends():
    g = parse_grid("0.5:12:24", "--wp-over-p", positive=True)
    assert g.values[0] == 0.5 and g.values[-1] == 12.0 and g.values.size == 24
    assert parse_grid("2:2:1").values.tolist() == [2.0]


@pytest.mark.parametrize("text", ["0.5:12", "a:1:3", "0:1:0", "1:0:5", "0:1:2.5", "-1:2:3", "0:inf:3", "1:2:1"])
def test_bad_grids_raise_one_sentence(text):
    with pytest.raises(RockcliInputError) as err:
        parse_grid(text, "--ap")
    assert "--ap" in str(err.value) and "\n" not in str(err.value)


def test_isolation_keeps_tb_over_tp_fixed_through_the_generic_spec_parser():
    iso = parse_isolation(LIN2)
    f = iso.foundation(0.7)
    assert isinstance(f, LinearIsolation) and f.T_b == pytest.approx(1.4) and f.xi == 0.05 and f.gamma == 0.01
    assert iso.label == "linear:TbTp=2,xi=0.05,gamma=0.01"
    assert parse_isolation("linear:TbTp=3").label == "linear:TbTp=3,xi=0.1,gamma=0.01"  # solver defaults, shown
    assert isinstance(parse_isolation("none").foundation(0.3), Rigid)
    assert iso.with_param("gamma", 0.3).foundation(1.0).gamma == 0.3
    for bad in ("linear:Tb=2", "linear:xi=0.05", "linear:TbTp=-1", "linear:TbTp=2,zeta=1", "scss:TbTp=2,mu=0.05x",
                "bouncy:TbTp=2"):
        with pytest.raises(RockcliInputError):
            parse_isolation(bad)


def test_pulse_choice():
    assert parse_pulse_choice("ricker-anti") == PulseChoice("ricker-anti", None)
    assert parse_pulse_choice("sine:Tp=0.5").T_p == 0.5
    for bad in ("ricker", "sine:ap=0.3", "cosine:Tp=-1"):
        with pytest.raises(RockcliInputError):
            parse_pulse_choice(bad)


# ------------------------------------------------------------------------------------------
# Cells, uplift boundary, invariance
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("shape, iso", [("ricker-sym", "none"), ("ricker-anti", "none"), ("sine", "none"),
                                        ("ricker-sym", LIN2), ("cosine", "linear:TbTp=3,xi=0.1,gamma=0.1")])
def test_a_cell_is_the_single_simulate_run(shape, iso):
    gx, gy = Grid(0.7, 8.0, 5), Grid(0.5, 6.0, 5)
    m = overturning_map(15.0, shape, iso, gx, gy)
    fam = Family(math.radians(15.0), shape, parse_isolation(iso))
    for i, y in enumerate(gy.values):
        for j, x in enumerate(gx.values):
            block, foundation, pulse = fam.scene(x, y)
            assert pulse.a_p == pytest.approx(y * G * math.tan(block.alpha), rel=1e-15)
            assert pulse.T_p == pytest.approx(2 * math.pi / (x * block.p), rel=1e-15)
            r = simulate(block, foundation, pulse)
            assert m.overturned[i, j] == r.overturned
            assert m.uplifted[i, j] == (r.verdict != "no_uplift")
            assert m.theta_max_over_alpha[i, j] == r.theta_max_over_alpha
    assert m.overturned.any() and (~m.overturned & m.uplifted).any()


@pytest.mark.parametrize("shape", ["ricker-sym", "ricker-anti", "sine", "cosine"])
def test_rigid_no_uplift_boundary_is_exactly_ap_equal_g_tan_alpha(shape):
    """Every shape peaks at |a_p| (the antisymmetric Ricker through beta), so the rigid-foundation
    uplift threshold is a_p = g tan(alpha) for all four: factor 1."""
    eps = 1e-6
    ys = np.array([0.3, 1.0 - eps, 1.0 + eps, 1.5])
    xs = np.array([0.5, 2.0, 6.0, 12.0])
    fam = Family(math.radians(12.0), shape, Isolation("none"))
    X, Y = np.meshgrid(xs, ys)
    res = run_cells_local([fam], np.zeros(X.size, np.int64), X.ravel(), Y.ravel())
    up = res.uplifted.reshape(X.shape)
    assert not up[:2].any() and up[2:].all()
    s = search_min_overturning([fam], [0, 0], [0.5, 2.0])
    assert np.all(s.ap_uplift == 1.0)


def test_dimensionless_map_does_not_depend_on_the_block_size():
    gx, gy = Grid(0.5, 10.0, 14), Grid(0.5, 8.0, 14)
    for iso in ("none", LIN2):
        small = overturning_map(10.0, "ricker-sym", iso, gx, gy, R=0.3)
        large = overturning_map(10.0, "ricker-sym", iso, gx, gy, R=5.0)
        assert np.array_equal(small.overturned, large.overturned)
        assert np.array_equal(small.uplifted, large.uplifted)
        np.testing.assert_allclose(small.theta_max_over_alpha, large.theta_max_over_alpha, rtol=1e-6)
        assert small.overturned.any() and not small.overturned.all()


# ------------------------------------------------------------------------------------------
# Minimum overturning search
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("shape, iso, x", [("ricker-sym", "none", 2.3), ("ricker-sym", "none", 4.0),
                                           ("ricker-anti", "none", 3.0), ("ricker-sym", LIN2, 3.0)])
def test_min_search_agrees_with_a_brute_force_fine_grid(shape, iso, x):
    fam = Family(math.radians(10.0), shape, parse_isolation(iso))
    s = search_min_overturning([fam], [0], [x], step=0.01, tol=1e-3)
    y_u, y_min, y_safe = s.ap_uplift[0], s.ap_min[0], s.ap_safe[0]
    assert y_safe < y_min <= y_safe * (1 + 1e-3) * (1 + 1e-12)
    # brute force: every 0.1 % from the uplift threshold to 2 % above the minimum found
    ys = y_u * 1.001 ** np.arange(1, int(math.log(1.02 * y_min / y_u) / math.log(1.001)) + 1)
    res = run_cells_local([fam], np.zeros(ys.size, np.int64), np.full(ys.size, x), ys)
    first = ys[np.argmax(res.overturned)]
    assert res.overturned.any()
    assert first == pytest.approx(y_min, rel=2.2e-3)  # one fine step + the search tolerance
    assert not res.overturned[ys < y_safe / 1.01].any()  # nothing overturns below the bracket
    one = run_cells_local([fam], [0, 0], [x, x], [y_safe, y_min])
    assert not one.overturned[0] and one.overturned[1]


def test_min_search_finds_overturning_below_a_safe_island():
    """Rigid, alpha = 10 deg, symmetric Ricker at omega_p/p = 2.3: the map has a safe gap above the
    first overturning band; the minimum is the band's lower edge, not the gap's upper edge."""
    fam = Family(math.radians(10.0), "ricker-sym", Isolation("none"))
    ys = np.linspace(1.0, 4.0, 301)
    res = run_cells_local([fam], np.zeros(ys.size, np.int64), np.full(ys.size, 2.3), ys)
    o = res.overturned
    first = int(np.argmax(o))
    assert o.any() and not o[first:].all()  # a safe island above the first overturning value
    s = search_min_overturning([fam], [0], [2.3])
    assert s.ap_min[0] <= ys[first] * 1.001


class _PlantedWindow:
    """A runner whose 'response' is synthetic: on a rigid foundation (uplift threshold 1) the block
    overturns in a narrow window ``[lo, hi]`` and from ``band`` on."""

    def __init__(self, lo, hi, band):
        self.lo, self.hi, self.band = lo, hi, band
        self.calls = []

    def __call__(self, families, fam, x, y, early=False):
        from rockcli.spectra import Cells

        y = np.asarray(y, dtype=float)
        self.calls.append(y.copy())
        over = ((y >= self.lo) & (y <= self.hi)) | (y >= self.band)
        n = y.size
        return Cells(over, y > 1.0, np.where(over, 1.5, 0.5), ~over, np.ones(n, bool), np.ones(n, np.int64))


def test_second_scan_finds_a_planted_window_the_first_scan_steps_over():
    """A 0.3 % window between two values of the 1 % scan, 2 % below the band where the scan first
    overturns: the scan alone (refine=0, the old search) reports the band's edge; the second scan
    (0.1 % steps over the 10 % below the scan's first overturning value) finds the window, to the
    bisection tolerance. A window further below is left to the first scan (the stated limit)."""
    fam = Family(math.radians(16.0), "ricker-sym", Isolation("none"))
    y20 = 1.01 ** 20
    lo, hi = y20 * 1.003, y20 * 1.006  # strictly between the scan values 1.01^20 and 1.01^21
    band = 1.01 ** 22 * 1.005
    old = search_min_overturning([fam], [0], [3.0], step=0.01, tol=1e-3, refine=0.0,
                                 runner=_PlantedWindow(lo, hi, band))
    assert old.ap_min[0] >= band and not old.refined.any()  # stepped over: 2 % too high
    planted = _PlantedWindow(lo, hi, band)
    new = search_min_overturning([fam], [0], [3.0], step=0.01, tol=1e-3, runner=planted)
    assert new.ap_safe[0] < lo <= new.ap_min[0] <= new.ap_safe[0] * (1 + 1e-3) * (1 + 1e-12)
    assert new.refined[0]
    tried = np.concatenate(planted.calls)
    # more than 10 % below the first overturning scan value 1.01^23: the first scan only
    assert not np.any((tried > 1.01 ** 12 * 1.0001) & (tried < 1.01 ** 12 * 1.0099))
    # the stated limit: a window further below than the band is left to the first scan
    far = _PlantedWindow(lo, hi, 1.01 ** 31 * 1.005)  # first scan overturns at 1.01^32: floor 1.01^22.4
    s = search_min_overturning([fam], [0], [3.0], step=0.01, tol=1e-3, runner=far)
    assert s.ap_min[0] >= 1.01 ** 31


@pytest.mark.parametrize("iso, x, stepped_over", [("dcss:TbTp=3,mu1=0.03,mu2=0.07,r=1", 2.0, True),
                                                  ("dcss:TbTp=2,mu1=0.03,mu2=0.06,r=2", 6.0, True),
                                                  ("scss:TbTp=3,mu=0.05", 1.0, False)])
def test_issue_28_sliding_cases_report_the_first_overturning_value(iso, x, stepped_over):
    """Figure 11 (alpha = 16 deg, symmetric Ricker): narrow overturning windows below the band the
    1 % scan finds (and, for SCSS, a ragged band edge on which the old bisection stopped 0.4 % too
    high). At the default settings the minimum is the first overturning value of a 0.1 % brute-force
    grid to within the bisection tolerance; the scan alone (refine=0) overstates it."""
    fam = Family(math.radians(16.0), "ricker-sym", parse_isolation(iso))
    new = search_min_overturning([fam], [0], [x])
    old = search_min_overturning([fam], [0], [x], refine=0.0)
    y_u = new.ap_uplift[0]
    ys = y_u * 1.001 ** np.arange(1, int(math.log(old.ap_min[0] / y_u) / math.log(1.001)) + 1)
    res = run_cells_local([fam], np.zeros(ys.size, np.int64), np.full(ys.size, x), ys, early=True)
    first = ys[np.argmax(res.overturned)]
    assert res.overturned.any()
    assert old.ap_min[0] > first * 1.003  # the window the issue reports is stepped over by the scan alone
    assert new.ap_min[0] <= first * (1 + 1e-3) and new.refined[0] == stepped_over
    one = run_cells_local([fam], [0, 0], [x, x], [new.ap_safe[0], new.ap_min[0]], early=True)
    assert not one.overturned[0] and one.overturned[1]


def test_isolated_uplift_threshold_approaches_the_decoupled_limit():
    """T_b/T_p -> large: the base barely moves in absolute terms during the pulse, so the block
    sees the bearing force only, a_base -> omega_b^2 u_g + 2 xi omega_b v_g (ground displacement
    and velocity); the uplift threshold tends to g tan(alpha) / max|that|, with an error O(T_p/T_b)."""
    alpha = math.radians(10.0)
    xi = 0.05
    errs = []
    for ratio in (8.0, 16.0, 32.0):
        iso = parse_isolation(f"linear:TbTp={ratio},xi={xi},gamma=0.01")
        fam = Family(alpha, "ricker-sym", iso)
        s = search_min_overturning([fam], [0], [2.0], ap_max=1e4)
        T_p = fam.T_p(2.0)
        wb = 2 * math.pi / (ratio * T_p)
        unit = make_pulse("ricker-sym", G * math.tan(alpha), T_p)  # y = 1
        t = np.linspace(*unit.support(), 20001)
        a_dec = np.max(np.abs(wb ** 2 * unit.displacement(t) + 2 * xi * wb * unit.velocity(t)))
        y_dec = G * math.tan(alpha) / a_dec
        errs.append(abs(s.ap_uplift[0] / y_dec - 1.0))
    assert errs[2] < 0.05 and errs[2] < errs[1] < errs[0]
    assert errs[0] / errs[2] > 2.5  # about O(T_p / T_b)


def test_gamma_below_0_1_hardly_matters_figure_8():
    curves = min_overturning_curves([12.0], [PulseChoice("ricker-sym")],
                                    [parse_isolation(f"linear:TbTp=2,xi=0.05,gamma={g}") for g in (0.01, 0.05)],
                                    [1.0, 2.5, 4.0])
    np.testing.assert_allclose(curves[0].ap_min, curves[1].ap_min, rtol=0.03)


# ------------------------------------------------------------------------------------------
# Critical size
# ------------------------------------------------------------------------------------------
def test_critical_size_is_where_the_curves_cross():
    res = critical_sizes([PulseChoice("ricker-sym", 0.6, "test")], [10.0], [parse_isolation(LIN2)],
                         wp_grid=Grid(1.0, 4.0, 7), xtol=2e-3, ap_max=20.0)
    row = res.rows[0]
    xc = row.wp_over_p_cross
    assert 1.0 < xc < 4.0
    assert row.R_critical_m == pytest.approx(3 * G / (4 * (2 * math.pi / (0.6 * xc)) ** 2))
    assert row.R_critical_m == pytest.approx(critical_R(0.6, xc)) and row.Tb_s == pytest.approx(1.2)
    rigid = Family(math.radians(10.0), "ricker-sym", Isolation("none"))
    lin = Family(math.radians(10.0), "ricker-sym", parse_isolation(LIN2))
    s = search_min_overturning([rigid, lin, rigid, lin], [0, 1, 2, 3], [xc * 0.99, xc * 0.99, xc * 1.01, xc * 1.01])
    assert s.ap_min[0] <= s.ap_min[1]  # below the crossing isolation is better
    assert s.ap_min[2] > s.ap_min[3]  # above it the rigid foundation is


# ------------------------------------------------------------------------------------------
# Dask
# ------------------------------------------------------------------------------------------
def test_dask_map_equals_the_local_map():
    distributed = pytest.importorskip("distributed")
    from rockcli.spectra import Runner

    gx, gy = Grid(0.5, 10.0, 16), Grid(0.0, 8.0, 16)
    isos = [parse_isolation("none"), parse_isolation(LIN2)]
    local = overturning_maps([10.0], [PulseChoice("ricker-sym")], isos, gx, gy)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        runner = Runner(client, chunk=97)
        with runner:
            remote = overturning_maps([10.0], [PulseChoice("ricker-sym")], isos, gx, gy, runner=runner)
        assert len(client.scheduler_info()["workers"]) == 2
    for a, b in zip(local, remote):
        assert np.array_equal(a.overturned, b.overturned) and np.array_equal(a.uplifted, b.uplifted)
        assert np.array_equal(a.theta_max_over_alpha, b.theta_max_over_alpha)
        assert np.array_equal(a.settled, b.settled)


# ------------------------------------------------------------------------------------------
# CLI
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("args, words", [
    (["overturning", "--alpha", "10", "--wp-over-p", "0.5:12"], "--wp-over-p"),
    (["overturning", "--alpha", "10", "--ap", "0:10:x"], "--ap"),
    (["overturning", "--alpha", "95"], "--alpha"),
    (["overturning", "--alpha", "10", "--isolation", "linear:Tb=2"], "TbTp"),
    (["overturning", "--alpha", "10", "--pulse", "ricker"], "unknown shape"),
    (["overturning", "--alpha", "10", "--scheduler", "http//x"], "--scheduler"),
    (["min-overturning", "--alpha", "10", "--gamma", "1.5"], "--gamma"),
    (["min-overturning", "--alpha", "10", "--step", "0"], "scan step"),
    (["critical-size", "--pulse", "ricker-sym"], "period"),
    (["critical-size", "--tbtp", "2,-1"], "--tbtp"),
    (["overturning", "--alpha", "10", "--horizon", "4000"], "horizon must be a time between 0 and 3600 s"),
    (["critical-size", "--horizon", "-1"], "horizon must be a time between 0 and 3600 s"),
])
def test_cli_bad_input_one_sentence_exit_2_nothing_written(tmp_path, args, words):
    out = tmp_path / "out.csv"
    r = CliRunner().invoke(main, ["spectrum", *args, "--csv", str(out)])
    assert r.exit_code == 2, r.output
    assert words in r.output and r.output.startswith("Error:") and "Traceback" not in r.output
    assert not out.exists()


def test_cli_overturning_csv_one_row_per_cell(tmp_path):
    out = tmp_path / "map.csv"
    png = tmp_path / "map.png"
    r = CliRunner().invoke(main, ["spectrum", "overturning", "--alpha", "20", "--pulse", "ricker-anti:Tp=0.9",
                                  "--wp-over-p", "1:6:6", "--ap", "0:3:5", "--csv", str(out), "--plot", str(png)])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 30
    assert list(rows[0]) == ["alpha_deg", "pulse", "isolation", "T_p_s", "R_m", "wp_over_p", "ap_over_g_tan_alpha",
                             "ap_g", "overturned", "theta_max_over_alpha", "uplift", "peak_final", "proven"]
    for row in rows:
        assert (row["uplift"] == "True") == (float(row["ap_over_g_tan_alpha"]) > 1.0)
        assert float(row["R_m"]) == pytest.approx(critical_R(0.9, float(row["wp_over_p"])))
        assert row["proven"] == "True"
    assert png.stat().st_size > 1000
    # early stops are the default: --full-peaks gives the same map with every peak final, and an
    # early peak is never above the final one
    full = tmp_path / "full.csv"
    r = CliRunner().invoke(main, ["spectrum", "overturning", "--alpha", "20", "--pulse", "ricker-anti:Tp=0.9",
                                  "--wp-over-p", "1:6:6", "--ap", "0:3:5", "--csv", str(full), "--full-peaks"])
    assert r.exit_code == 0, r.output
    frows = list(csv.DictReader(full.open()))
    assert any(row["peak_final"] == "False" for row in rows)
    for a, b in zip(rows, frows):
        assert (a["overturned"], a["uplift"]) == (b["overturned"], b["uplift"])
        assert b["peak_final"] == "True"
        assert float(a["theta_max_over_alpha"]) <= float(b["theta_max_over_alpha"]) * (1 + 1e-7) + 1e-12
        if a["peak_final"] == "True":
            assert float(a["theta_max_over_alpha"]) == pytest.approx(float(b["theta_max_over_alpha"]), rel=1e-7)


def test_cli_horizon_follows_unproven_cells_longer(tmp_path):
    """A 1.5 deg block on a gamma = 0 SCSS base: cells still rocking at a 30 s horizon count as surviving
    (proven 0, and the count is printed); at 600 s those two are proven, with the same verdicts."""
    args = ["spectrum", "overturning", "--alpha", "1.5", "--isolation", "scss:TbTp=2,mu=0.06,gamma=0",
            "--wp-over-p", "4.5:5:2", "--ap", "1:1:1"]
    rows = {}
    for h in ("30", "600"):
        out = tmp_path / f"h{h}.csv"
        r = CliRunner().invoke(main, [*args, "--horizon", h, "--csv", str(out)])
        assert r.exit_code == 0, r.output
        rows[h] = list(csv.DictReader(out.open()))
        assert ("2 NOT PROVEN" in r.output) == (h == "30"), r.output
    assert [row["proven"] for row in rows["30"]] == ["False", "False"]
    assert [row["proven"] for row in rows["600"]] == ["True", "True"]
    assert [row["overturned"] for row in rows["30"]] == [row["overturned"] for row in rows["600"]] == ["False", "False"]


def test_cli_critical_size_table_i_columns(tmp_path):
    out = tmp_path / "t1.csv"
    r = CliRunner().invoke(main, ["spectrum", "critical-size", "--alpha", "10", "--tbtp", "2",
                                  "--pulse", "ricker-sym:Tp=0.6", "--wp-over-p", "1:4:7", "--xtol", "0.01",
                                  "--ap-max", "15", "--csv", str(out)])
    assert r.exit_code == 0, r.output
    rows = list(csv.DictReader(out.open()))
    assert list(rows[0]) == ["source", "pulse", "T_p_s", "alpha_deg", "Tb_over_Tp", "Tb_s", "wp_over_p_cross",
                             "R_critical_m"]
    assert rows[0]["pulse"] == "ricker-sym" and float(rows[0]["Tb_s"]) == pytest.approx(1.2)
    assert float(rows[0]["R_critical_m"]) == pytest.approx(critical_R(0.6, float(rows[0]["wp_over_p_cross"])))


def test_cli_record_gives_shape_and_period(tmp_path, pulse_records):
    r = CliRunner().invoke(main, ["spectrum", "min-overturning", "--alpha", "20", "--record",
                                  str(pulse_records / "anti.txt"), "--isolation", "none", "--wp-over-p", "2:3:2"])
    assert r.exit_code == 0, r.output
    assert "fitted to record" in r.output and "ricker-anti" in r.output and "T_p = 0.500 s" in r.output


# ------------------------------------------------------------------------------------------
# solve helpers the sweeps use
# ------------------------------------------------------------------------------------------
def test_simulate_verdicts_are_simulate_many_as_arrays():
    from rockcli.models import Block
    from rockcli.solve import simulate_many, simulate_verdicts

    b = Block.from_degrees(1.0, 14.0)
    lin = LinearIsolation(1.0, 0.05, 0.01)
    jobs = [(b, f, make_pulse("ricker-anti", y * G * math.tan(b.alpha), 0.5)) for f in (Rigid(), lin)
            for y in (0.8, 1.4, 2.2, 3.1, 4.5)]
    for early in (False, True):
        many = simulate_many(jobs, early=early)
        v = simulate_verdicts(jobs, early=early)
        for i, (bb, f, p) in enumerate(jobs):
            single = simulate(bb, f, p, early=early)
            assert many[i].summary() == single.summary()
            assert v.overturned[i] == single.overturned and v.uplifted[i] == (single.verdict != "no_uplift")
            assert v.theta_max_over_alpha[i] == single.theta_max_over_alpha and v.nfev[i] == single.nfev
            assert v.settled[i] == single.settled and v.peak_final[i] == single.peak_final
        assert v.overturned.any() and not v.overturned.all()
    with pytest.raises(RockcliInputError, match="finite"):  # a sweep's bad job raises, no JobError
        simulate_verdicts([(b, Rigid(), jobs[0][2], float("nan"))])


def test_early_maps_have_the_same_verdicts():
    gx, gy = Grid(0.5, 10.0, 12), Grid(0.0, 8.0, 12)
    for iso in ("none", LIN2):
        full = overturning_map(10.0, "ricker-anti", iso, gx, gy)
        early = overturning_map(10.0, "ricker-anti", iso, gx, gy, early=True)
        assert np.array_equal(full.overturned, early.overturned) and np.array_equal(full.uplifted, early.uplifted)
        assert full.peak_final.all()
        assert np.all(early.theta_max_over_alpha <= full.theta_max_over_alpha + 1e-12)
        assert early.nfev <= full.nfev


def test_help_and_the_sweeps_library_import_nothing_heavy():
    import subprocess
    import sys

    code = ("import sys; from click.testing import CliRunner; from rockcli.cli import main\n"
            "for args in (['spectrum', '--help'], ['spectrum', 'overturning', '--help'],\n"
            "             ['spectrum', 'min-overturning', '--help'], ['spectrum', 'critical-size', '--help'],\n"
            "             ['spectrum', 'rocking', '--help']):\n"
            "    r = CliRunner().invoke(main, args); assert r.exit_code == 0, r.output\n"
            "import rockcli.spectra\n"
            "print(sorted(m for m in ('numba', 'pandas', 'matplotlib', 'obspy', 'scipy', 'dask', 'distributed')\n"
            "             if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"


def test_cli_search_defaults_are_the_library_defaults():
    """The CLI writes the search defaults out (``--help`` imports no numpy): they must not drift."""
    from rockcli.cli.spectrum import critical_size, min_overturning
    from rockcli.spectra import DEFAULT_REFINE, DEFAULT_REFINE_BAND, DEFAULT_STEP, DEFAULT_TOL

    want = {"step": DEFAULT_STEP, "tol": DEFAULT_TOL, "refine": DEFAULT_REFINE, "refine_band": DEFAULT_REFINE_BAND}
    for command in (min_overturning, critical_size):
        assert {p.name: p.default for p in command.params if p.name in want} == want


# --------------------------------------------------------------------------------------------------
# floors and caps: a search that cannot end, or a grid that cannot fit, is refused before any run
# --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("args, words", [
    (["min-overturning", "--alpha", "16", "--isolation", "none", "--wp-over-p", "2:2:1", "--tol", "1e-16"],
     "tolerance must lie in [1e-12, step]"),
    (["min-overturning", "--alpha", "16", "--isolation", "none", "--wp-over-p", "2:2:1", "--refine", "1e-17"],
     "refinement step must be 0"),
    (["min-overturning", "--alpha", "16", "--isolation", "none", "--wp-over-p", "2:2:1", "--step", "1e-18"],
     "scan step must lie in [0.0001, 0.5]"),
    (["critical-size", "--alpha", "10", "--tbtp", "2", "--pulse", "ricker-sym:Tp=0.6", "--wp-over-p", "0.5:12:6",
      "--xtol", "0"], "xtol must lie in [1e-12, 0.5]"),
    (["overturning", "--alpha", "10", "--wp-over-p", "1:8:100000", "--ap", "1:6:100000"],
     "the maps have 10,000,000,000 cells"),
])
def test_search_floors_and_grid_cap_refused_in_one_sentence(args, words, monkeypatch):
    """Before: --tol 1e-16 and --xtol 0 bisected forever (the midpoint of two neighbouring doubles is one of
    them), --refine 1e-17 divided by zero, and a 1e10-cell map tried to allocate 75 GiB. Now: refused before
    any run (the runner is never called), one sentence, exit 2."""
    from rockcli.spectra import runner as runner_mod

    def no_runs(*a, **k):
        raise AssertionError("a refused search must not run anything")

    monkeypatch.setattr(runner_mod.Runner, "__call__", no_runs)
    res = CliRunner().invoke(main, ["spectrum", *args])
    assert res.exit_code == 2, res.output
    assert words in res.output
    assert "Traceback" not in res.output and len(res.output.strip().splitlines()) == 1


def test_tolerance_at_its_floor_ends():
    """At the floor itself the bisection ends: 1e-12 relative is ~4,500 doubles wide, so every midpoint is new."""
    from rockcli.spectra import Family, parse_isolation, search_min_overturning

    fam = Family(math.radians(16.0), "ricker-sym", parse_isolation("none"))
    res = search_min_overturning([fam], np.array([0]), np.array([2.0]), tol=1e-12, refine=0.0)
    lo, hi = float(res.ap_safe[0]), float(res.ap_min[0])
    assert lo < hi and (hi - lo) <= 1e-12 * hi


# ------------------------------------------------------------------------------------------
# The 100 g limit of the minimum search (squat blocks)
# ------------------------------------------------------------------------------------------
class _Threshold:
    """A stand-in runner: uplift from ``y_up``, overturning from ``y_over`` (units of g tan alpha); records the
    largest a_p [g] asked for. The search's logic without the solver (its runs are what is checked here)."""

    def __init__(self, y_up, y_over):
        self.y_up, self.y_over, self.peak_g, self.runs = y_up, y_over, 0.0, 0

    def __call__(self, families, fam, x, y, early=False):
        from rockcli.spectra.runner import Cells

        y = np.asarray(y, float)
        tan = np.array([math.tan(families[f].alpha) for f in fam])
        self.peak_g = max(self.peak_g, float(np.max(y * tan, initial=0.0)))
        self.runs += y.size
        n = y.size
        return Cells(y >= self.y_over, y >= self.y_up, np.zeros(n), np.ones(n, bool), np.ones(n, bool),
                     np.zeros(n, np.int64))


@pytest.mark.parametrize("iso", ["none", LIN2])
def test_min_search_runs_no_pulse_past_100_g(iso):
    """alpha = 80 deg: ap_max = 20 g tan alpha is 113 g; the search ran pulses up to there (and the uplift bracket
    of an isolated base up to 2 ap_max, 227 g). Now it stops at 100 g, y = 17.63, and the curve says so."""
    from rockcli.spectra.minimum import capped_note, curves_of, y_limit

    cap = y_limit(math.radians(80.0))
    assert cap * math.tan(math.radians(80.0)) <= 100.0 and cap == pytest.approx(17.6327, rel=1e-5)
    families = [Family(math.radians(80.0), "ricker-sym", parse_isolation(iso))]
    beyond = _Threshold(1.0 if iso == "none" else 1.7, 19.0)  # overturns only past 100 g
    s = search_min_overturning(families, [0], [2.0], runner=beyond)
    assert beyond.peak_g <= 100.0 and math.isnan(s.ap_min[0]) and s.ap_cap[0] == cap
    curve, = curves_of(s, [(80.0, PulseChoice("ricker-sym"), parse_isolation(iso))], np.array([2.0]), ap_max=20.0,
                       step=0.01, tol=1e-3, refine=1e-3, refine_band=0.1)
    assert curve.capped and curve.ap_max == cap
    assert "about 17.63 at alpha = 80 deg" in capped_note([curve])
    # below the cap the search is the one of a block that is not capped (alpha = 10 deg): the same runs
    within, free = _Threshold(1.0 if iso == "none" else 1.7, 12.0), _Threshold(1.0 if iso == "none" else 1.7, 12.0)
    a = search_min_overturning(families, [0], [2.0], runner=within)
    b = search_min_overturning([Family(math.radians(10.0), "ricker-sym", parse_isolation(iso))], [0], [2.0],
                               runner=free)
    assert (a.ap_min[0], a.ap_safe[0], a.ap_uplift[0], a.runs) == (b.ap_min[0], b.ap_safe[0], b.ap_uplift[0], b.runs)
    assert within.peak_g <= 100.0 and 12.0 <= a.ap_min[0] < 12.0 * 1.001
    if iso != "none":  # the uplift bracket stops at the cap: a base that lifts the block off only past 100 g
        late = _Threshold(30.0, 40.0)
        s = search_min_overturning(families, [0], [2.0], runner=late)
        assert late.peak_g <= 100.0 and math.isnan(s.ap_uplift[0]) and math.isnan(s.ap_min[0])
