"""``rockcli bench``: the SciPy reference in the package, work-precision convergence, stability checks
that can fail (planted failures), the CLI's files and exit codes, and ``assess column --check-tolerance``."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli import bench
from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Rigid, column
from rockcli.pulses import make_pulse
from rockcli.reference import (METHODS, ReferenceTimeout, impact_map_linear_system, reference_simulate,
                               state_scales)
from rockcli.io.units import G

BASSAE = column("bassae")
RICKER = make_pulse("ricker-sym", 0.5 * G, 1.2)


# ------------------------------------------------------------------------------------------
# the reference in the package
# ------------------------------------------------------------------------------------------
def test_reference_module_never_imports_numba_or_the_kernels():
    code = ("import sys, rockcli.reference as r; from rockcli.models import column; from rockcli.pulses import make_pulse;"
            "r.reference_simulate(column('bassae'), None, make_pulse('ricker-sym', 4.9, 1.2), rtol=1e-6);"
            "print('numba' in sys.modules, 'rockcli.kernels' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         cwd=Path(__file__).resolve().parents[1]).stdout.split()
    assert out == ["False", "False"]


def test_naive_and_naive_sliding_are_thin_reexports_of_the_reference():
    import naive
    import rockcli.reference as ref

    assert naive.reference_simulate is ref.reference_simulate
    assert naive.impact_map_linear_system is ref.impact_map_linear_system
    import naive_sliding

    assert naive_sliding.reference_sliding is ref.reference_sliding and naive_sliding.Bearing is ref.Bearing


@pytest.mark.parametrize("method", METHODS)
def test_every_scipy_method_converges_to_the_kernel_on_a_pulse(method):
    """All five solve_ivp methods, with the kernel's mixed error test (atol=None), reach the kernel's
    converged peak and rest time; the work is counted."""
    from rockcli.solve import simulate

    truth = simulate(BASSAE, Rigid(), RICKER, rtol=1e-13, history=True, tail=40.0)
    res = reference_simulate(BASSAE, Rigid(), RICKER, rtol=1e-8, atol=None, method=method)
    assert res.verdict == truth.verdict == "rocked"
    assert res.theta_max / BASSAE.alpha == pytest.approx(truth.theta_max_over_alpha, abs=1e-6)
    assert res.t_rest == pytest.approx(bench.history_rest_time(truth.history), abs=0.05)
    assert res.steps > 10 and res.nfev > res.steps and res.wall_s > 0 and res.method == method
    if method in ("Radau", "BDF"):
        assert res.njev > 0 and res.nlu > 0


def test_reference_wall_budget_and_bad_method():
    with pytest.raises(ReferenceTimeout):
        reference_simulate(BASSAE, Rigid(), RICKER, rtol=1e-12, atol=None, method="Radau", deadline_s=0.0)
    with pytest.raises(ValueError, match="unknown SciPy method"):
        reference_simulate(BASSAE, Rigid(), RICKER, method="Euler")


def test_state_scales_match_the_kernels_error_test():
    f = LinearIsolation(2.0)
    sc = state_scales(BASSAE, f, 4)
    w = max(f.omega_b, BASSAE.p)
    assert sc == pytest.approx([BASSAE.alpha, BASSAE.p * BASSAE.alpha, G * math.tan(BASSAE.alpha) / w ** 2,
                                G * math.tan(BASSAE.alpha) / w])


def test_aligned_steps_agree_with_the_kernel_on_a_record():
    """Per-sample alignment (no step across a kink of the record) brings DOP853 to the kernel's answer."""
    from rockcli.records import Record
    from rockcli.solve import simulate

    dt = 0.01
    t = np.arange(0.0, 6.0, dt)
    rec = Record(np.asarray(RICKER.acceleration(t)), dt, "sampled")
    truth = simulate(BASSAE, Rigid(), rec, rtol=1e-13).theta_max_over_alpha
    aligned = reference_simulate(BASSAE, Rigid(), rec, rtol=1e-12, atol=None, align=True)
    assert aligned.theta_max / BASSAE.alpha == pytest.approx(truth, abs=1e-9)


# ------------------------------------------------------------------------------------------
# work-precision
# ------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def tiny_wp():
    scenes = bench.select_scenes(["rigid-ricker"], bench.WP_SCENES)
    return bench.run_work_precision(scenes, kernel_rtols=(1e-4, 1e-6, 5e-9, 1e-10), scipy_rtols=(1e-4, 1e-6, 1e-8),
                                    methods=("RK45",), repeats=1)[0]


def test_work_precision_errors_fall_as_rtol_tightens(tiny_wp):
    ws = tiny_wp
    assert ws.ref_verdict == "rocked" and ws.event == "rest"
    # the reference solution is verified by an independent one
    assert ws.check_method == "DOP853" and ws.check_d_theta < 1e-9 and ws.check_d_t_event_s < 1e-6
    for method in (bench.KERNEL, bench.KERNEL_VERDICT, "RK45"):
        runs = sorted((r for r in ws.runs if r.method == method), key=lambda r: -r.rtol)
        errs = [r.err_theta_max_over_alpha for r in runs]
        assert all(r.verdict_ok for r in runs)
        assert all(b < a for a, b in zip(errs, errs[1:])), (method, errs)  # convergence
        assert errs[-1] < 1e-3 * errs[0]
        cost = [r.nfev for r in runs]
        assert all(b >= a for a, b in zip(cost, cost[1:]))
    kern = sorted((r for r in ws.runs if r.method == bench.KERNEL), key=lambda r: -r.rtol)
    assert kern[-1].err_t_event_s < kern[0].err_t_event_s  # rest time converges too
    # observed: error ~ rtol^1 (tolerance proportionality) and a high order against the work
    assert 0.7 < ws.tol_slope < 1.3 and ws.order > 3
    s = bench.summarise(ws)
    assert s is not None and s.comparator == "RK45" and s.verdicts_agree and s.time_ratio > 0
    # the reference's rounding noise is measured, and the floor is at least the check's disagreement
    assert 0.0 <= ws.noise_theta < 1e-10 and ws.noise_t_event_s < 1e-8
    assert ws.floor == max(ws.check_d_theta, ws.noise_theta) and s.floor == ws.floor


def test_ulp_perturbed_moves_each_number_by_one_ulp():
    from rockcli.records import Record

    rng = np.random.default_rng(3)
    acc = np.concatenate([np.linspace(-3.0, 3.0, 200), [0.0, 1.0, -2.0]])
    rec = Record(acc, 0.01, "r")
    moved = bench.ulp_perturbed(rec, rng).acc
    up, down = moved == np.nextafter(acc, np.inf), moved == np.nextafter(acc, -np.inf)
    assert np.all(up | down) and up.sum() > 50 and down.sum() > 50
    seen = set()
    for _ in range(20):
        p = bench.ulp_perturbed(RICKER, rng)
        assert p.a_p in (np.nextafter(RICKER.a_p, np.inf), np.nextafter(RICKER.a_p, -np.inf))
        assert p.t0 in (RICKER.t0, np.nextafter(RICKER.t0, np.inf)) and p.T_p == RICKER.T_p
        assert p.support()[0] >= 0.0
        seen.add((p.a_p > RICKER.a_p, p.t0 > RICKER.t0))
    assert len(seen) == 4


def _planted_summary(err_kernel, err_scipy, check, noise):
    scene = bench.select_scenes(["rigid-ricker"], bench.WP_SCENES)[0]
    ws = bench.WPScene(scene, event="rest", check_d_theta=check, noise_theta=noise)
    for method, rtol, err in ((bench.KERNEL, 5e-9, err_kernel), (bench.KERNEL_VERDICT, 5e-9, err_kernel),
                              ("RK45", 1e-8, err_scipy)):
        ws.runs.append(bench.WPRun(scene.name, method, rtol, verdict_ok=True, event="rest",
                                   err_theta_max_over_alpha=err, wall_s=1e-3))
    return bench.summarise(ws)


def test_summary_ranks_errors_only_above_the_reference_floor():
    s = _planted_summary(1e-9, 2e-9, 1e-13, 1e-14)
    assert s.as_accurate and not s.at_floor and s.floor == 1e-13
    # rigid-kobe before half-sample steps: rockcli 9.9e-14 against RK45 2.7e-14, floor 3.9e-14: NO
    s = _planted_summary(9.9e-14, 2.7e-14, 6.1e-15, 3.9e-14)
    assert not s.as_accurate and not s.at_floor
    # after: 1.2e-14 against 1.1e-14, both below the floor: they cannot be ranked
    s = _planted_summary(1.2e-14, 1.1e-14, 6.1e-15, 3.9e-14)
    assert s.as_accurate and s.at_floor
    # no floor measured: errors are ranked as they are
    s = _planted_summary(1.2e-14, 1.1e-14, math.nan, math.nan)
    assert not s.as_accurate and math.isnan(s.floor)


def test_unavailable_scenes_are_reported_not_run(monkeypatch):
    from rockcli.models import parse_isolation_spec

    try:
        parse_isolation_spec("scss:Tb=3,mu=0.05")
        sliding = True
    except RockcliInputError:
        sliding = False
    scss = bench.select_scenes(["scss-ricker"], bench.WP_SCENES)[0]
    if sliding:
        assert bench.resolve_scene(scss)[1] is not None
    else:
        with pytest.raises(bench.SceneUnavailable, match="pending: sliding bearings not available"):
            bench.resolve_scene(scss)
    with pytest.raises(bench.SceneUnavailable, match="refused"):
        bench.parse_foundation("linear:Tb=-1")
    monkeypatch.setenv("ROCKCLI_RECORDS", "/nonexistent")
    kobe = bench.select_scenes(["rigid-kobe"], bench.WP_SCENES)
    ws = bench.run_work_precision(kobe, methods=(), check=False)[0]
    assert not ws.available and ws.note.startswith("skipped: record") and not ws.runs
    with pytest.raises(RockcliInputError, match="unknown scene 'nope'"):
        bench.select_scenes(["nope"], bench.WP_SCENES)


# ------------------------------------------------------------------------------------------
# stability checks: each detects a planted failure
# ------------------------------------------------------------------------------------------
def _impact_history(block, gamma, thd1=-0.3, ud1=0.05, isolated=True):
    thd2, ud2 = impact_map_linear_system(block, gamma, thd1, ud1)
    t = np.array([0.0, 1.0, 1.0, 2.0])
    theta = np.array([0.01, 0.0, 0.0, -0.01])
    theta_dot = np.array([thd1, thd1, thd2, thd2])
    u_dot = np.array([ud1, ud1, ud2, ud2]) if isolated else np.zeros(4)
    return t, theta, theta_dot, u_dot


def test_momentum_check_holds_on_the_impact_map_and_catches_a_jump():
    kw = dict(R=BASSAE.R, alpha=BASSAE.alpha, gamma=0.1, isolated=True)
    t, th, thd, ud = _impact_history(BASSAE, 0.1)
    assert bench.check_momentum(t, th, thd, ud, **kw).ok
    bad = ud.copy()
    bad[2:] += 1e-3  # the base gains momentum at the impact
    c = bench.check_momentum(t, th, thd, bad, **kw)
    assert not c.ok and "momentum not kept" in c.detail
    bad = thd.copy()
    bad[2:] *= 1.01  # the block gains angular momentum
    assert not bench.check_momentum(t, th, bad, ud, **kw).ok
    # rigid base: the angular momentum about the new pivot alone (Housner)
    t, th, thd, ud = _impact_history(BASSAE, 0.0, isolated=False)
    rig = dict(R=BASSAE.R, alpha=BASSAE.alpha, gamma=0.0, isolated=False)
    assert bench.check_momentum(t, th, thd, ud, **rig).ok
    assert thd[2] / thd[1] == pytest.approx(BASSAE.housner_restitution)
    thd[2:] = -thd[1]  # a "bounce" that keeps the speed: energy and momentum created
    assert not bench.check_momentum(t, th, thd, ud, **rig).ok


def test_energy_check_catches_energy_created_in_free_rocking():
    p, a = BASSAE.p, BASSAE.alpha
    t = np.linspace(0, 10, 101)
    th = 0.4 * a * np.abs(np.sin(t))
    E = p * p * math.cos(0.5 * a)  # free rocking at constant energy, peaks at alpha/2
    thd = np.sqrt(2 * (E - p * p * np.cos(a - th)))
    kw = dict(p=p, alpha=a, t_exc_end=2.0, rtol=1e-8)
    assert bench.check_energy(t, th, thd, **kw).ok
    grow = thd * (1 + 1e-3 * (t > 6))  # a kick after the excitation
    c = bench.check_energy(t, th, grow, **kw)
    assert not c.ok and "energy created" in c.detail
    assert not bench.check_energy(t, th, np.where(t > 6, np.nan, thd), **kw).ok
    early = thd * (1 + 1e-3 * (t < 1.5))  # during the excitation the ground may add energy: not judged
    assert bench.check_energy(t, th, early, **kw).ok


def test_finite_budget_steps_and_tolerance_checks_fail_when_they_should():
    assert bench.check_finite(t=[0, 1], theta=[0, 0.1]).ok
    assert not bench.check_finite(t=[0, 1], theta=[0, np.nan]).ok
    assert bench.check_budget(0.1, 30, 0, 100, 1000).ok
    assert not bench.check_budget(31.0, 30, 0, 100, 1000).ok
    assert not bench.check_budget(0.1, 30, -1, 1000, 1000).ok  # step cap: a hang stopped by the budget
    t = np.concatenate([np.linspace(0, 1, 50), 1 + 1e-12 * np.arange(1, 80), [2.0]])
    c = bench.check_steps(t, steps=130, rejected=3)
    assert not c.ok and "collapsed" in c.detail
    assert bench.check_steps(np.linspace(0, 1, 50), steps=49, rejected=2).ok
    assert not bench.check_steps(np.linspace(0, 1, 50), steps=49, rejected=40).ok
    assert bench.check_tolerance("rocked", "rocked", 0.5, 0.5 + 1e-5).ok
    assert not bench.check_tolerance("rocked", "overturned", 0.5, 8.5).ok
    assert not bench.check_tolerance("rocked", "rocked", 0.5, 0.51).ok
    assert bench.check_tolerance("overturned", "overturned", 8.5, 8.5, 3.0, 3.0 + 1e-6).ok
    assert not bench.check_tolerance("overturned", "overturned", 8.5, 8.5, 3.0, 3.1).ok


def test_dissipation_check_accepts_a_hysteretic_loop_and_catches_created_energy():
    uy, Q = 1e-3, 0.5
    u = 0.01 * np.sin(np.linspace(0, 4 * np.pi, 2001))
    z = np.zeros_like(u)  # the elastic-perfectly-plastic limit of Bouc-Wen: |z| <= 1, elastic on reversal
    for i in range(1, u.size):
        z[i] = np.clip(z[i - 1] + (u[i] - u[i - 1]) / uy, -1, 1)
    assert bench.check_dissipation(u, z, Q=Q, u_y=uy).ok
    c = bench.check_dissipation(u, -z, Q=Q, u_y=uy)  # a force that pushes with the motion
    assert not c.ok and "created" in c.detail


def test_history_rest_time():
    h = SimpleNamespace(t=np.array([0, 1, 1, 2, 3, 3, 4.0]), theta=np.array([0, 0, 0, 0.1, 0, 0, 0]),
                        theta_dot=np.array([0, -1, 0.5, 0, -0.1, 0, 0]))
    assert bench.history_rest_time(h) == 3.0
    h.theta_dot[5] = 0.05  # the last impact is not a rest
    assert math.isnan(bench.history_rest_time(h))


def test_stability_scenes_pass_and_state_the_undamped_base():
    scenes = bench.select_scenes(["alpha-at-end", "xi-0", "spike-10g-linear"], bench.STABILITY_SCENES)
    res = {r.scene.name: r for r in bench.run_stability(scenes)}
    at_end = res["alpha-at-end"]
    assert at_end.status == "pass", at_end.reason
    assert {c.name for c in at_end.checks} >= {"finite @1e-06", "budget @1e-10", "steps @1e-10", "momentum @1e-10",
                                               "energy @1e-10", "tolerance", "expected"}
    # the record ends exactly when the block reaches alpha (the scene's construction)
    blk, _, rec = bench._passes_alpha_at_end()
    from rockcli.solve import simulate

    r = simulate(blk, Rigid(), rec, rtol=1e-12)
    assert r.t_exceed_alpha_s == pytest.approx(bench.excitation_end(rec), abs=1e-9)
    assert r.verdict == "overturned"
    xi0 = res["xi-0"]
    assert xi0.status == "stated" and "NOT PROVEN" in xi0.reason and xi0.passed
    assert not any(d["settled"] for d in xi0.runs.values())
    spike = res["spike-10g-linear"]
    assert spike.status == "pass" and any(c.name.startswith("momentum") and "impacts" in c.detail for c in spike.checks)


def test_conditioning_separates_a_chaotic_long_record_from_a_pulse():
    # a pulse: one ulp of a_p (and of t0) moves the peak by rounding only
    spread, verdicts = bench.measure_conditioning(BASSAE, Rigid(), RICKER, rtol=1e-10)
    assert verdicts == ("rocked", "rocked") and spread < 1e-12
    # Bassae under 100 s of band-limited motion (596 impacts): one ulp of the record moves the peak,
    # reached after 56 s, by 0.33 alpha; the scene is reported ill-conditioned, and still passes
    res = bench.run_stability(bench.select_scenes(["record-100s", "chatter-pulse"], bench.STABILITY_SCENES))
    chaotic, calm = res
    assert chaotic.status == "pass" and chaotic.ill_conditioned and chaotic.ulp_spread > 0.1
    assert chaotic.ulp_verdicts == ("rocked", "rocked")
    assert calm.status == "pass" and not calm.ill_conditioned and calm.ulp_spread < 1e-12


def test_a_changed_verdict_or_unknown_time_stays_in_the_running_spread():
    from rockcli.conditioning import answer_change, widest

    run = SimpleNamespace
    base = run(verdict="rocked", theta_max_over_alpha=0.5, t_overturn_s=math.nan)
    assert answer_change(base, run(verdict="rocked", theta_max_over_alpha=0.52, t_overturn_s=math.nan)) == \
        pytest.approx(0.02)
    assert math.isnan(answer_change(base, run(verdict="overturned", theta_max_over_alpha=9.0, t_overturn_s=3.0)))
    fell = run(verdict="overturned", theta_max_over_alpha=9.0, t_overturn_s=3.0)
    assert answer_change(fell, run(verdict="overturned", theta_max_over_alpha=9.1, t_overturn_s=3.5)) == 0.5
    spread = 0.0
    for change in (1e-3, math.nan, 0.5, 1e-9):  # a NaN once seen is kept, whatever follows
        spread = widest(spread, change)
    assert math.isnan(spread)
    assert widest(widest(0.0, 0.3), 0.1) == 0.3


def test_ill_conditioned_reads_the_verdicts_and_the_spread():
    sc = bench.select_scenes(["alpha-45deg"], bench.STABILITY_SCENES)[0]

    def planted(verdict, spread, verdicts):
        r = bench.StabilityResult(sc, runs={1e-10: {"verdict": verdict}}, ulp_spread=spread, ulp_verdicts=verdicts)
        return r.ill_conditioned

    assert not planted("rocked", 5e-4, ("rocked", "rocked"))
    assert planted("rocked", 2e-3, ("rocked", "rocked"))
    assert planted("rocked", math.nan, ("rocked", "overturned"))
    assert not planted("overturned", 5e-4, ("overturned",))  # seconds, against T_OVERTURN_TOL
    assert planted("overturned", 0.5, ("overturned",))
    assert not planted("rocked", math.nan, ())  # not measured


def test_a_failing_check_fails_the_scene(monkeypatch):
    """Plant a failure in a real run: a tolerance on the peak no run can meet fails the scene."""
    monkeypatch.setattr(bench.check_tolerance, "__kwdefaults__", {"peak_tol": 0.0, "t_tol": 0.0})
    res = bench.run_stability(bench.select_scenes(["gamma-0"], bench.STABILITY_SCENES))[0]
    assert res.status == "FAIL" and "tolerance" in res.reason and not res.passed


def test_refused_and_pending_scenes_are_reported():
    def refused():
        raise RockcliInputError("alpha must be at least 1 deg")

    sc = bench.StabilityScene("refused-demo", "a scene validation refuses", refused)
    pend = bench.select_scenes(["bouc-wen-uy-0.01mm"], bench.STABILITY_SCENES)
    out = bench.run_stability([sc] + pend)
    assert out[0].status == "refused" and out[0].reason == "refused: alpha must be at least 1 deg"
    from rockcli.models import parse_isolation_spec

    try:
        parse_isolation_spec("scss:Tb=3,mu=0.05,uy=0.00001")
    except RockcliInputError:
        assert out[1].status == "pending" and out[1].reason == bench.PENDING_SLIDING


# ------------------------------------------------------------------------------------------
# CLI
# ------------------------------------------------------------------------------------------
def test_cli_work_precision_writes_csv_and_png_atomically(tmp_path):
    from rockcli.report.bench import WP_COLUMNS

    csv_path, png = tmp_path / "wp.csv", tmp_path / "wp.png"
    res = CliRunner().invoke(main, ["bench", "work-precision", "--scene", "rigid-sine-overturn", "--kernel-rtol",
                                    "1e-5,5e-9", "--methods", "RK45", "--scipy-rtol", "1e-6,1e-8", "--repeat", "1",
                                    "--csv", str(csv_path), "--plot", str(png)])
    assert res.exit_code == 0, res.output
    assert "t_overturn" in res.output and "rockcli at its default rtol (5e-9; 2e-9 on sliding bearings) against SciPy" in res.output
    lines = csv_path.read_text().splitlines()
    assert lines[0].split(",") == list(WP_COLUMNS) and len(lines) == 1 + 2 * 2 + 2
    assert "np." not in csv_path.read_text()
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size < 150_000
    assert sorted(p.name for p in tmp_path.iterdir()) == ["wp.csv", "wp.png"]  # no temporary file left


def test_cli_bad_inputs_exit_2_and_write_nothing(tmp_path):
    runner = CliRunner()
    res = runner.invoke(main, ["bench", "work-precision", "--scene", "nope", "--csv", str(tmp_path / "x.csv")])
    assert res.exit_code == 2 and "unknown scene 'nope'" in res.output
    res = runner.invoke(main, ["bench", "stability", "--scene", "nope"])
    assert res.exit_code == 2 and "unknown scene" in res.output
    res = runner.invoke(main, ["bench", "work-precision", "--scene", "rigid-ricker", "--kernel-rtol", "1e-20"])
    assert res.exit_code == 2 and "between 1e-14 and 1e-2" in res.output
    res = runner.invoke(main, ["bench", "work-precision", "--scene", "rigid-ricker", "--methods", "Euler"])
    assert res.exit_code == 2 and "unknown SciPy method" in res.output
    res = runner.invoke(main, ["bench", "work-precision", "--scene", "rigid-ricker", "--plot",
                               str(tmp_path / "missing" / "p.png")])
    assert res.exit_code == 2 and "does not exist" in res.output
    # an image format matplotlib cannot write, a folder as a file: refused before any run, nothing left behind
    res = runner.invoke(main, ["bench", "work-precision", "--scene", "rigid-sine-overturn", "--kernel-rtol", "1e-6",
                               "--methods", "none", "--no-check", "--plot", str(tmp_path / "p.xyz")])
    assert res.exit_code == 2 and "cannot draw a 'xyz' figure" in res.output and "reference" not in res.output
    res = runner.invoke(main, ["bench", "stability", "--scene", "alpha-45deg", "--csv", str(tmp_path)])
    assert res.exit_code == 2 and "is a folder" in res.output
    assert list(tmp_path.iterdir()) == []


def test_cli_stability_csv(tmp_path):
    from rockcli.report.bench import STAB_COLUMNS

    out = tmp_path / "stab.csv"
    res = CliRunner().invoke(main, ["bench", "stability", "--scene", "chatter-pulse", "--scene", "bouc-wen-uy-0.01mm",
                                    "--csv", str(out), "-v"])
    assert res.exit_code == 0, res.output
    assert "chatter-pulse" in res.output and "momentum @1e-10" in res.output
    lines = out.read_text().splitlines()
    assert lines[0].split(",") == list(STAB_COLUMNS) and len(lines) == 3
    import csv

    rows = list(csv.DictReader(lines))
    assert rows[0]["status"] == "pass" and rows[0]["verdict_rtol_1e-6"] == rows[0]["verdict_rtol_1e-10"] == "rocked"
    assert float(rows[0]["theta_max_over_alpha_rtol_1e-10"]) > 0 and int(rows[0]["steps_rtol_1e-10"]) > 0
    assert rows[1]["status"] in ("pending", "pass") and rows[0]["settled"] == "True"
    assert float(rows[0]["ulp_spread"]) < 1e-12 and rows[0]["ulp_verdicts"] == "rocked rocked"
    assert rows[0]["ill_conditioned"] in ("0", "False")


# ------------------------------------------------------------------------------------------
# assess column --check-tolerance
# ------------------------------------------------------------------------------------------
def test_assess_check_tolerance(pulse_records, tmp_path):
    from rockcli.report.tables import CHECK_COLUMNS, CSV_COLUMNS, read_assessment_csv

    out = tmp_path / "t.csv"
    res = CliRunner().invoke(main, ["assess", "column", "statue:R=1.2,alpha=14", "--records", str(pulse_records),
                                    "--isolation", "none", "--isolation", "linear:Tb=2", "--no-margin",
                                    "--check-tolerance", "--csv", str(out)])
    assert res.exit_code == 0, res.output
    df = read_assessment_csv(out)
    assert list(df.columns) == list(CSV_COLUMNS) + list(CHECK_COLUMNS) and len(df) == 4
    assert (df["tight_rtol_verdict"] == df["verdict"]).all() and (df["tight_rtol_peak_change"] < 1e-6).all()
    assert all(v.split() == [w, w] for v, w in zip(df["ulp_verdicts"], df["verdict"]))
    assert (df["ulp_peak_change"] < 1e-12).all() and not df["ill_conditioned"].any()
    res = CliRunner().invoke(main, ["assess", "column", "statue:R=1.2,alpha=14", "--records", str(pulse_records),
                                    "--isolation", "none", "--no-margin", "--csv", str(out)])
    assert res.exit_code == 0 and list(read_assessment_csv(out).columns) == list(CSV_COLUMNS)
    res = CliRunner().invoke(main, ["assess", "column", "statue:R=1.2,alpha=14", "--records", str(pulse_records),
                                    "--isolation", "none", "--isolation", "linear:Tb=2", "--no-margin",
                                    "--check-tolerance"])
    assert "Tolerance check: 4 scenes rerun at rtol 5e-11" in res.output and "no verdict changes" in res.output
    line = next(x for x in res.output.splitlines() if x.startswith("Conditioning check:"))
    assert "the 4 scenes rerun on 2 copies of their motion moved by one ulp" in line and "no verdict changes" in line


def test_assess_prints_the_ill_conditioned_scenes(pulse_records, monkeypatch):
    import rockcli.assess.table as table

    real = table.check_tolerance

    def planted(result, **kw):
        chk = real(result, **kw)
        a, b = result.rows[:2]
        return table.ToleranceCheck(chk.rtol, chk.base_rtol, chk.n_runs, [], 0.0, chk.base_rtols, 2,
                                    [(a, ("rocked", "rocked"), 0.25), (b, ("rocked", "overturned"), math.nan)], 0.25)

    monkeypatch.setattr(table, "check_tolerance", planted)
    res = CliRunner().invoke(main, ["assess", "column", "statue:R=1.2,alpha=14", "--records", str(pulse_records),
                                    "--isolation", "none", "--no-margin", "--check-tolerance"])
    assert res.exit_code == 0, res.output
    out = res.output.splitlines()
    k = next(i for i, x in enumerate(out) if x.startswith("Conditioning check:"))
    assert "2 ILL-CONDITIONED" in out[k]
    assert out[k + 1].endswith(": peak moves by 0.25 alpha")
    assert out[k + 2].endswith(" -> rocked, overturned")


def test_check_tolerance_flags_a_changed_verdict(pulse_records):
    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_assessment
    from rockcli.assess.table import check_tolerance

    xs, _ = resolve_excitations([str(pulse_records)], "auto")
    result = run_assessment([parse_column_spec("statue:R=1.2,alpha=14")], xs, parse_configurations(("none",)),
                            margin=False)
    chk = check_tolerance(result)
    assert chk.n_runs == 2 and not chk.changed and chk.rtol == pytest.approx(5e-11)
    # pulses are well conditioned: one ulp of a_p (and of t0) moves a peak by rounding only
    assert chk.ulp_draws == 2 and not chk.ill and chk.max_ulp_peak_change < 1e-12
    survivor = next(r for r in result.rows if r.verdict == "rocked")
    survivor.theta_max_over_alpha += 0.01  # as if the run had landed elsewhere in a chaotic spread
    chk = check_tolerance(result)
    assert [(row, v) for row, v, _ in chk.ill] == [(survivor, ("rocked", "rocked"))]
    assert chk.ill[0][2] == pytest.approx(0.01, rel=1e-6)
    survivor.theta_max_over_alpha -= 0.01
    planted = result.rows[0]
    planted.verdict = "overturned" if planted.verdict != "overturned" else "rocked"  # as if the loose run had erred
    chk = check_tolerance(result)
    assert [row for row, _ in chk.changed] == [planted]
    assert [row for row, _, _ in chk.ill] == [planted] and math.isnan(chk.ill[0][2])  # a verdict flip


def test_a_crash_is_a_failure_not_an_abort(monkeypatch):
    """A solver exception (e.g. the kernel's ZeroDivisionError) fails that scene; the others still run."""
    import rockcli.solve as solve

    real = solve.simulate

    def crashing(block, foundation=None, excitation=None, **kw):
        if kw.get("rtol") == 1e-10:
            raise ZeroDivisionError("division by zero")
        return real(block, foundation, excitation, **kw)

    monkeypatch.setattr(solve, "simulate", crashing)
    out = bench.run_stability(bench.select_scenes(["alpha-45deg", "chatter-pulse"], bench.STABILITY_SCENES))
    assert [r.status for r in out] == ["FAIL", "FAIL"]
    assert out[0].reason == "crash at rtol 1e-10: ZeroDivisionError: division by zero"
    assert any(c.name == "crash @1e-10" and not c.ok for c in out[0].checks)


def test_random_scenes_are_reproducible_and_checked():
    a, b = bench.random_scenes(30, seed=3), bench.random_scenes(30, seed=3)
    assert [s.title for s in a] == [s.title for s in b] and len({s.name for s in a}) == 30
    assert all(s.unproven_ok == ("xi=0," in s.title) for s in a)
    res = bench.run_stability(a[:12])
    assert all(r.status in ("pass", "stated", "FAIL") for r in res)
    assert sum(r.passed for r in res) >= 10  # extreme, but almost all hold every check


# ------------------------------------------------------------------------------------------
# what the stability study found in the solver (both fixed)
# ------------------------------------------------------------------------------------------
def test_momentum_kept_at_plastic_impacts_of_squat_blocks_on_light_bases():
    """Found by the stability study: with eta clamped to 0 (squat block on a light base) the base's velocity
    jump came from the unclamped ratio and lost 5 % of the horizontal momentum per impact; now
    P_DU = gamma h (1 - eta)."""
    from rockcli.solve import simulate

    block, f, exc = bench.STABILITY_SCENES[[s.name for s in bench.STABILITY_SCENES].index("alpha-45deg-gamma-0.9")].build()
    h = simulate(block, f, exc, history=True).history
    c = bench.check_momentum(h.t, h.theta, h.theta_dot, h.u_dot, R=block.R, alpha=block.alpha, gamma=f.gamma,
                             isolated=True)
    assert c.ok, c.detail


def test_micro_uplifts_with_subnormal_theta_do_not_crash():
    """Found by ``bench stability --random 5000 --seed 7``: a ZeroDivisionError in the kernel's regula falsi
    when theta is subnormal (fixed on main by the guard against 0/0 that came with the sliding merge)."""
    from rockcli.solve import simulate

    block, f, exc = bench._subnormal_uplift()
    assert simulate(block, f, exc, rtol=1e-6, history=True).verdict in ("rocked", "no_uplift")
