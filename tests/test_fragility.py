"""Fragility: the censored lognormal MLE against closed forms, the bootstrap, capacities from the margin
search, suites with bad files (error rows, exit 0, a warning), per-scene errors in simulate_many, the seam.

Synthetic records (sampled Ricker pulses written as text) keep these tests independent of
ROCKCLI_RECORDS.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner
from conftest import write_pulse_record
from scipy.optimize import minimize
from scipy.stats import norm

from rockcli.assess import (IMS, fit_lognormal, fragility_probability, intensity_measure, map_chunks,
                            overturn_scales_chunked, parse_column_spec, parse_configurations, resolve_excitations,
                            run_fragility)
from rockcli.assess.fragility import CENSORED_RIGHT, bootstrap_lognormal, empirical_points
from rockcli.assess.margin import MARGIN_GRID, find_overturn_scales
from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.pulses import make_pulse
from rockcli.records import read_record
from rockcli.records.motion import calc_peaks
from rockcli.records.record import Record
from rockcli.solve import VERDICT_ERROR, JobError, simulate, simulate_many
from rockcli.io.units import G

THETA, BETA = 0.45, 0.5


def _sample(n, seed):
    return np.exp(np.log(THETA) + BETA * np.random.default_rng(seed).standard_normal(n))


def _scipy_mle(x, codes):
    """The same likelihood maximised by Nelder-Mead in (ln theta, ln beta): a slow, obvious reference."""
    lx = np.log(x)

    def nll(p):
        mu, s = p[0], math.exp(p[1])
        return -(norm.logpdf(lx[codes == 0], mu, s).sum() + norm.logsf(lx[codes == 1], mu, s).sum()
                 + norm.logcdf(lx[codes == -1], mu, s).sum())

    r = minimize(nll, [lx.mean(), math.log(lx.std())], method="Nelder-Mead",
                 options={"xatol": 1e-10, "fatol": 1e-12, "maxiter": 5000})
    return math.exp(r.x[0]), math.exp(r.x[1])


# --------------------------------------------------------------------------------------------------
# maximum likelihood
# --------------------------------------------------------------------------------------------------

def test_mle_without_censoring_is_the_closed_form_and_recovers_the_lognormal():
    n = 400
    c = _sample(n, 1)
    median, beta = fit_lognormal(c)
    lc = np.log(c)
    assert median == pytest.approx(math.exp(lc.mean()), rel=1e-9)
    assert beta == pytest.approx(lc.std(ddof=0), rel=1e-9)  # MLE: divisor n
    # within sampling error: SE(ln median) = beta/sqrt(n), SE(beta) ~ beta/sqrt(2n); 4 SE
    assert abs(math.log(median / THETA)) < 4 * BETA / math.sqrt(n)
    assert abs(beta - BETA) < 4 * BETA / math.sqrt(2 * n)


@pytest.mark.parametrize("seed", [2, 3])
def test_mle_with_right_censoring_recovers_the_lognormal(seed):
    n = 600
    c = _sample(n, seed)
    rng = np.random.default_rng(seed + 100)
    bound = np.exp(np.log(THETA) + rng.uniform(-0.2, 1.2, n) * BETA)  # a bound per record ("4 x IM")
    censored = c > bound
    assert 0.2 < censored.mean() < 0.6
    obs = np.where(censored, bound, c)
    median, beta = fit_lognormal(obs, [CENSORED_RIGHT if k else "" for k in censored])
    assert abs(math.log(median / THETA)) < 4 * 1.3 * BETA / math.sqrt(n)
    assert abs(beta - BETA) < 4 * 1.5 * BETA / math.sqrt(2 * n)
    # treating the bounds as capacities biases both, which the censored likelihood avoids
    naive_median, naive_beta = fit_lognormal(obs)
    assert naive_median < median and naive_beta < beta
    ref = _scipy_mle(obs, censored.astype(int))
    assert (median, beta) == pytest.approx(ref, rel=1e-6)


def test_mle_with_left_and_right_censoring_matches_the_reference():
    c = _sample(80, 4)
    codes = np.where(c > 0.8, 1, np.where(c < 0.25, -1, 0))
    obs = np.where(codes == 1, 0.8, np.where(codes == -1, 0.25, c))
    labels = ["right" if k == 1 else ("left" if k == -1 else "") for k in codes]
    assert (codes == 1).any() and (codes == -1).any()
    assert fit_lognormal(obs, labels) == pytest.approx(_scipy_mle(obs, codes), rel=1e-6)


def test_no_fit_without_two_distinct_exact_capacities():
    assert all(math.isnan(v) for v in fit_lognormal([0.3, 0.5, 0.7], [True, True, True]))
    assert all(math.isnan(v) for v in fit_lognormal([0.3, 0.5, 0.7], ["", "right", "right"]))
    assert all(math.isnan(v) for v in fit_lognormal([0.3, 0.3, 0.7], ["", "", "right"]))
    with pytest.raises(RockcliInputError, match="positive"):
        fit_lognormal([0.3, -1.0])


def test_bootstrap_is_repeatable_and_its_interval_covers_the_truth():
    c = _sample(60, 5)
    cens = c > 0.9
    obs = np.where(cens, 0.9, c)
    m1, b1 = bootstrap_lognormal(obs, cens, n_boot=400, seed=7)
    m2, b2 = bootstrap_lognormal(obs, cens, n_boot=400, seed=7)
    np.testing.assert_array_equal(m1, m2)
    np.testing.assert_array_equal(b1, b2)
    # each resample's fit is the plain fit of that resample
    idx = np.random.default_rng(7).integers(0, obs.size, size=(400, obs.size))
    k = 17
    assert (m1[k], b1[k]) == pytest.approx(fit_lognormal(obs[idx[k]], cens[idx[k]]), rel=1e-9)
    lo, hi = np.percentile(m1, [2.5, 97.5])
    assert lo < THETA < hi
    lo, hi = np.percentile(b1, [2.5, 97.5])
    assert lo < BETA < hi


def test_probability_and_plotting_positions():
    assert fragility_probability(0.45, 0.45, 0.5) == pytest.approx(0.5)
    assert fragility_probability(0.45 * math.exp(0.5), 0.45, 0.5) == pytest.approx(norm.cdf(1.0))

    class R:
        def __init__(self, capacity, censored=""):
            self.capacity, self.censored, self.error = capacity, censored, ""

    pts = empirical_points([R(v) for v in (0.5, 0.2, 0.3, 0.4)])
    assert [p[0] for p in pts] == [0.2, 0.3, 0.4, 0.5]
    assert [p[1] for p in pts] == pytest.approx([0.125, 0.375, 0.625, 0.875])  # (i - 0.5)/n
    # a censored record leaves the risk set: the later steps are larger (Kaplan-Meier)
    pts = empirical_points([R(0.2), R(0.25, CENSORED_RIGHT), R(0.3), R(0.4)])
    assert pts[1] == (0.25, pytest.approx(0.25), CENSORED_RIGHT)
    assert pts[2][1] == pytest.approx(1 - 0.5 * (0.75 + 0.75 * 0.5))


# --------------------------------------------------------------------------------------------------
# intensity measures and capacities
# --------------------------------------------------------------------------------------------------

def test_intensity_measures(tmp_path):
    rec = read_record(write_pulse_record(tmp_path / "r.txt", 0.4, 0.8, "ricker-anti"))
    assert intensity_measure(rec, "pga") == pytest.approx(rec.pga_g)
    assert intensity_measure(rec, "pgv") == pytest.approx(calc_peaks(rec).pgv_mps)  # as 'records show'
    assert intensity_measure(rec, "ap") == pytest.approx(0.4, rel=1e-3)
    p = make_pulse("ricker-sym", 0.3 * G, 1.0)
    v = p.velocity(np.linspace(*p.support(), 20001))
    assert intensity_measure(p, "pgv") == pytest.approx(np.abs(v).max(), rel=1e-6)
    assert intensity_measure(p, "ap") == pytest.approx(0.3)
    with pytest.raises(RockcliInputError, match="not one of"):
        intensity_measure(rec, "sa")
    assert set(IMS) == {"pga", "pgv", "ap"}


@pytest.fixture()
def suite(tmp_path):
    """Four pulse records of different shapes and periods, and one corrupt file."""
    folder = tmp_path / "suite"
    folder.mkdir()
    for name, a, T, shape in (("a.txt", 0.30, 0.5, "ricker-sym"), ("b.txt", -0.35, 0.8, "ricker-anti"),
                              ("c.txt", 0.25, 1.2, "ricker-sym"), ("d.txt", 0.40, 0.35, "ricker-anti")):
        write_pulse_record(folder / name, a, T, shape, pad=2.0)
    (folder / "corrupt.AT2").write_text("PEER NGA STRONG MOTION DATABASE RECORD\nfoo\nACCELERATION TIME SERIES IN UNITS OF G\n"
                                         "NPTS=  100, DT= .0100 SEC\n0.1 0.2 nan-ish junk\n")
    return folder


def test_capacities_are_overturn_scale_times_im_and_bracket_the_boundary(suite):
    block = parse_column_spec("small:R=0.6,alpha=12")
    xs, _ = resolve_excitations([str(suite)], "record")
    confs = parse_configurations(["none", "linear:Tb=2"])
    fr = run_fragility([block], xs, confs, im="pga", n_boot=50)
    bad = [r for r in fr.rows if r.record == "corrupt.AT2"]
    assert len(bad) == 2 and all(r.error and math.isnan(r.capacity) for r in bad)
    good = [r for r in fr.rows if not r.error]
    assert len(good) == 8
    motions = {x.label: x.motion for x in xs}
    foundations = {c.header: c.foundation for c in confs}
    for r in good:
        rec = motions[r.record]
        assert r.im_value == pytest.approx(rec.pga_g)
        if r.censored == CENSORED_RIGHT:
            assert r.capacity == pytest.approx(MARGIN_GRID[-1] * rec.pga_g)
            continue
        assert r.capacity == pytest.approx(r.overturn_scale * rec.pga_g)
        f = foundations[r.configuration]
        assert simulate(block, f, rec.scaled(r.overturn_scale)).overturned
        assert not simulate(block, f, rec.scaled(r.overturn_scale_survives)).overturned
    for curve in fr.curves:
        rows = [r for r in good if r.configuration == curve.configuration.header]
        ref = fit_lognormal([r.capacity for r in rows], [r.censored for r in rows])
        assert (curve.median, curve.beta) == pytest.approx(ref, rel=1e-9)
        assert curve.n_records == 4 and curve.n_exact + curve.n_right + curve.n_left == 4
    iso = fr.curve("small", "Tb=2s")
    rigid = fr.curve("small", "none")
    assert iso.ratio_to_rigid == pytest.approx(iso.median / rigid.median)


def test_a_note_on_unproven_scaled_runs_keeps_the_censoring(suite, monkeypatch):
    """The margin search appends a note when scaled runs ended NOT PROVEN; the capacity's censoring
    must still be read from the note's start (it used to compare the whole note)."""
    import rockcli.assess.fragility as fr_mod
    from rockcli.assess.margin import NOTE_NO_OVERTURN, NOTE_OVERTURNS_AT_MIN

    lo_f, hi_f = float(MARGIN_GRID[0]), float(MARGIN_GRID[-1])
    extra = "; 2 scaled run(s) not proven at the solver's horizon, counted as surviving"
    notes = [(math.nan, hi_f, NOTE_NO_OVERTURN.format(hi_f) + extra),
             (lo_f, math.nan, NOTE_OVERTURNS_AT_MIN.format(lo_f) + extra), (1.5, 1.4, extra[2:]), (2.0, 1.9, "")]
    monkeypatch.setattr(fr_mod, "overturn_scales_chunked", lambda scenes, **kw: notes[:len(scenes)])
    block = parse_column_spec("small:R=0.6,alpha=12")
    xs, _ = resolve_excitations([str(suite)], "record")
    xs = [x for x in xs if not x.error][:4]
    fr = run_fragility([block], xs, parse_configurations(["none"]), im="pga", n_boot=20)
    rows = [r for r in fr.rows if not r.error]
    assert [r.censored for r in rows] == [CENSORED_RIGHT, fr_mod.CENSORED_LEFT, "", ""]
    assert rows[0].capacity == pytest.approx(hi_f * rows[0].im_value)
    assert rows[1].capacity == pytest.approx(lo_f * rows[1].im_value)
    assert rows[2].capacity == pytest.approx(1.5 * rows[2].im_value)


def test_chunked_margin_search_equals_one_batch_through_any_runner(suite):
    block = Block.from_degrees(0.6, 12, "small")
    xs, _ = resolve_excitations([str(suite)], "record")
    scenes = [(block, f, x.motion) for x in xs if x.motion is not None for f in (Rigid(), LinearIsolation(2.5))]
    seen = []

    def runner(func, chunks):  # what a distributed runner does: map a function over the chunks
        seen.extend(len(c) for c in chunks)
        return list(map(func, chunks))

    assert overturn_scales_chunked(scenes, chunk_size=3, runner=runner) == find_overturn_scales(scenes)
    assert seen == [3, 3, 2]
    assert map_chunks(lambda c: [v * 2 for v in c], [1, 2, 3], chunk_size=2) == [2, 4, 6]
    with pytest.raises(RuntimeError, match="results for a chunk"):
        map_chunks(lambda c: c[:1], [1, 2, 3])


def test_fragility_on_a_dask_cluster_equals_the_local_run(suite):
    """--scheduler: the margin searches run as Dask tasks on two workers; identical capacities and fits."""
    distributed = pytest.importorskip("distributed")
    from rockcli.assess.fragility import run_fragility, run_fragility_distributed

    block = Block.from_degrees(0.6, 12, "small")
    xs, unavailable = resolve_excitations([str(suite)], "record")
    configs = parse_configurations(["none", "linear:Tb=2"])
    parts = []  # the progress of each run (issue 35): its parts, announced, and the steps told in each

    class Progress:
        def phase(self, name, steps, *, known, unit):
            parts.append([name, steps, known, unit, 0])

        def __call__(self, n):
            parts[-1][4] += n

    local = run_fragility([block], xs, configs, n_boot=50, unavailable=unavailable, progress=Progress())
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        remote = run_fragility_distributed(client, [block], xs, configs, n_boot=50, unavailable=unavailable,
                                           progress=Progress())
    n = len(local.rows) - sum(bool(r.error) for r in local.rows)
    assert parts[0] == ["margin search", n * MARGIN_GRID.size, False, None, n * MARGIN_GRID.size]
    assert parts[1][0].startswith("margin search on Dask (") and parts[1][1:] == [n, False, "scenes", n]
    key = [(r.record, r.configuration, r.capacity, r.censored, r.error) for r in local.rows]
    assert [(r.record, r.configuration, r.capacity, r.censored, r.error) for r in remote.rows] == key
    assert [(c.median, c.beta) for c in remote.curves] == [(c.median, c.beta) for c in local.curves]


def test_fragility_scheduler_option_is_checked_before_any_work(suite, tmp_path):
    out = _invoke("bassae", "--records", suite, "--scheduler", "ftp://nowhere", "--csv", tmp_path / "f.csv")
    assert out.exit_code == 2 and "--scheduler" in out.output and "Traceback" not in out.output
    assert not (tmp_path / "f.csv").exists()


# --------------------------------------------------------------------------------------------------
# per-scene errors in simulate_many
# --------------------------------------------------------------------------------------------------

def test_simulate_many_turns_a_bad_job_into_an_error_result():
    block = Block.from_degrees(1.0, 12, "b")
    pulse = make_pulse("ricker-sym", 0.4 * G, 0.6)
    good_rec = Record(np.sin(np.linspace(0, 20, 500)) * 3.0, 0.01, "ok")
    nan_rec = Record(np.array([0.0, np.nan, 1.0]), 0.01, "nan")
    jobs = [(block, Rigid(), good_rec, 1.5), (block, Rigid(), nan_rec), (block, Rigid(), pulse, 2.0),
            ("not a block", Rigid(), pulse), (block, "springs", pulse), (block, LinearIsolation(2.0), pulse),
            (block, Rigid(), good_rec, 2.0)]
    res = simulate_many(jobs)
    assert [r.verdict == VERDICT_ERROR for r in res] == [False, True, False, True, True, False, False]
    assert isinstance(res[1], JobError) and "NaN" in res[1].error and not res[1].overturned
    assert "Block" in res[3].error
    # a scale factor multiplies a pulse's a_p (the same run as the scaled pulse)
    assert res[2].summary() == simulate(block, Rigid(), pulse.scaled(2.0)).summary()
    # and a record's samples as it goes: the same run as the scaled record, bit for bit when the scaling
    # is exact (a power of 2), else to rounding (1.5 x a sample is not always a double)
    assert res[6].summary() == simulate(block, Rigid(), good_rec.scaled(2.0)).summary()
    one, other = res[0].summary(), simulate(block, Rigid(), good_rec.scaled(1.5)).summary()
    assert one.keys() == other.keys() and one["verdict"] == other["verdict"] == "overturned"
    for key, v in one.items():
        assert v == (pytest.approx(other[key], rel=1e-12) if isinstance(v, float) else other[key]), key
    assert res[5].summary() == simulate(block, LinearIsolation(2.0), pulse).summary()
    with pytest.raises(RockcliInputError, match="rtol"):
        simulate_many(jobs, rtol=-1.0)  # a bad option concerns every job


# --------------------------------------------------------------------------------------------------
# the command
# --------------------------------------------------------------------------------------------------

def _invoke(*args):
    return CliRunner().invoke(main, ["assess", "fragility", *map(str, args)])


def test_cli_folder_with_one_corrupt_file_one_error_row_exit_0_and_a_warning(suite, tmp_path):
    out, png = tmp_path / "f.csv", tmp_path / "f.png"
    res = _invoke("small:R=0.6,alpha=12", "--records", suite, "--isolation", "none", "--bootstrap", 100,
                  "--csv", out, "--plot", png)
    assert res.exit_code == 0, res.output
    assert "Warning: 1 of 5 records could not be read or run" in res.output
    assert "corrupt.AT2:" in res.output and png.stat().st_size > 10_000
    df = pd.read_csv(out, keep_default_na=False, na_values=[""])
    assert len(df) == 5 and (df.error.notna()).sum() == 1
    bad = df[df.record == "corrupt.AT2"].iloc[0]
    assert "corrupt.AT2" in bad.error and math.isnan(bad.capacity_g)
    ok = df[df.record != "corrupt.AT2"]
    assert ok.capacity_g.notna().all() and np.allclose(ok.capacity_g, ok.pga_g * ok.overturn_scale, rtol=2e-5)
    line = next(ln for ln in res.output.splitlines() if ln.startswith("small"))
    fields = line.split()
    assert fields[:5] == ["small", "none", "4", "4", "0"]
    assert float(fields[5]) == pytest.approx(df.median_g.iloc[0], rel=2e-3)
    assert float(fields[7]) == pytest.approx(df.beta.iloc[0], abs=6e-3)


def test_cli_says_when_capacities_rest_on_unproven_runs_and_horizon_follows_them(tmp_path):
    """A 4 deg stele on SCSS under a weak pulse: followed 20 s after the pulse, its scaled runs are still rocking,
    count as surviving and the notes say so; with the default horizon (600 s) they are proven, the note goes and
    the capacity is the same; a horizon out of range is refused. (A short horizon, not a more slender stele: the
    margin search follows hundreds of scaled runs, and each runs as long as the horizon lets it.)"""
    rec = write_pulse_record(tmp_path / "weak.txt", 6 * math.tan(math.radians(4)), 0.5, "ricker-sym", dt=0.005)
    args = ("stele:R=2,alpha=4", "--records", rec, "--isolation", "scss:Tb=3,mu=0.06", "--bootstrap", 0)
    res = _invoke(*args, "--horizon", 20, "--csv", tmp_path / "f.csv")
    assert res.exit_code == 0, res.output
    assert "1 capacities include scaled runs still moving at the solver's horizon" in res.output
    short = pd.read_csv(tmp_path / "f.csv")
    assert "not proven" in short.margin_note[0] and short.censored.isna()[0]
    res = _invoke(*args, "--csv", tmp_path / "g.csv")
    assert res.exit_code == 0 and "still moving" not in res.output, res.output
    proven = pd.read_csv(tmp_path / "g.csv")
    assert proven.margin_note.isna()[0] and proven.capacity_g[0] == short.capacity_g[0]
    res = _invoke(*args, "--horizon", 4000)
    assert res.exit_code == 2 and res.output.startswith("Error: horizon must be a time between 0 and 3600 s")


def test_cli_units_and_dt_for_headerless_files(suite, tmp_path):
    bare = tmp_path / "bare"
    bare.mkdir()
    rec = read_record(suite / "a.txt")
    np.savetxt(bare / "a_cms2.txt", rec.acc * 100.0)  # cm/s^2, no header
    np.savetxt(bare / "b_cms2.txt", read_record(suite / "b.txt").acc * 100.0)
    (bare / "states_g.txt").write_text((suite / "c.txt").read_text())  # states units: g
    res = _invoke("small:R=0.6,alpha=12", "--records", bare, "--isolation", "none", "--bootstrap", 0)
    assert res.exit_code == 0 and "does not state its units" in res.output
    res = _invoke("small:R=0.6,alpha=12", "--records", bare, "--isolation", "none", "--bootstrap", 0,
                  "--units", "cm/s^2", "--dt", 0.01, "--csv", tmp_path / "u.csv")
    assert res.exit_code == 0, res.output
    df = pd.read_csv(tmp_path / "u.csv", keep_default_na=False, na_values=[""])
    err = df.set_index("record").error
    assert pd.isna(err["a_cms2.txt"]) and pd.isna(err["b_cms2.txt"])
    # --units/--dt fill in only what a file does not state: a file that states g is read in g (issue 24)
    assert pd.isna(err["states_g.txt"])
    assert df.set_index("record").pga_g["states_g.txt"] == pytest.approx(read_record(suite / "c.txt").pga_g, rel=1e-12)
    assert df.set_index("record").pga_g["a_cms2.txt"] == pytest.approx(rec.pga_g, rel=1e-6)
    res = _invoke("small:R=0.6,alpha=12", "--records", bare, "--units", "furlongs")
    assert res.exit_code == 2 and "unknown acceleration unit" in res.output


@pytest.mark.parametrize("args, words", [
    (["bassae"], "give the record suite with --records"),
    (["bassae", "--records", "no/such/dir"], "no such file or folder"),
    (["bassae", "--records", "{suite}", "--csv", "no/such/dir/f.csv"], "does not exist"),
    (["bassae", "--records", "{suite}", "--plot", "{tmp}/f"], "suffix"),
    (["bassae", "--records", "{suite}", "--dt", "-1"], "positive"),
])
def test_cli_bad_input_exit_2_nothing_written(args, words, suite, tmp_path):
    args = [a.format(suite=suite, tmp=tmp_path) for a in args]
    res = _invoke(*args)
    assert res.exit_code == 2 and words in res.output and "Traceback" not in res.output
    assert not list(tmp_path.glob("f*"))
