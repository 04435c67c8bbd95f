"""The early stops of an isolated base during the excitation (P9 on linear bearings, P9s on sliding and
lead-rubber bearings, in :mod:`rockcli.kernels.driver_end`): a block at rest on its base that no
later base acceleration can lift ends a verdict-only ``early`` run.

Every shortcut is a theorem: the bounds are checked against the motion itself, and early, verdict-only and
full-history runs of thousands of random scenes (short synthetic records and pulses) must agree on the
verdict and on everything the proof declares final, with a sample confirmed by the slow reference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from naive import reference_simulate
from rockcli.models import Block, DoubleConcaveSliding, LeadRubber, LinearIsolation, SingleConcaveSliding
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.solve import simulate, simulate_many
from rockcli.io.units import G
from synthetic import synthetic_record

SHAPES = ("ricker-sym", "ricker-anti", "sine", "cosine")


def _kernel():
    from rockcli.kernels import linear_base  # the linear base's norm and record table (P9)

    return linear_base


# ------------------------------------------------------------------------------------------
# The bounds behind P9
# ------------------------------------------------------------------------------------------
def test_the_record_table_is_the_exact_linear_response():
    """``linear_base_table``: the base alone under a piecewise-linear record, step by step exact (against
    DOP853 at rtol 1e-13 on each sample interval), for light, heavy and over-critical damping."""
    from scipy.integrate import solve_ivp

    k = _kernel()
    acc = np.random.default_rng(3).normal(size=40)
    dt = 0.01
    for w, xi in ((2.5, 0.1), (40.0, 0.0), (3.0, 2.0)):
        tab = k.linear_base_table(acc, dt, w, xi)
        z, worst = np.zeros(2), 0.0
        for j in range(acc.size - 1):
            a0, a1 = acc[j], acc[j + 1]

            def f(t, y):
                return [y[1], -w * w * y[0] - 2 * xi * w * y[1] - (a0 + (a1 - a0) * t / dt)]

            z = solve_ivp(f, (0.0, dt), z, rtol=1e-13, atol=1e-16, method="DOP853").y[:, -1]
            worst = max(worst, float(np.max(np.abs(z - tab[j + 1, :2]) / np.max(np.abs(tab[:, :2]), axis=0))))
        assert worst < 1e-11
    # the step against a closed-form solution: under ag = a0 + s t the base can move as u = c0 + c1 t
    # (c1 = -s/w^2, c0 = -(a0 + 2 xi w c1)/w^2), up to w dt = 4
    for w, xi, h in ((2.5, 0.1, 0.01), (60.0, 0.0, 0.02), (200.0, 0.3, 0.02), (3.0, 2.0, 0.005)):
        cf = k.coefficients(w, xi, h)
        for a0, s in ((1.0, 0.0), (0.0, 1.0), (0.3, -2.0)):
            c1 = -s / w ** 2
            c0 = -(a0 + 2 * xi * w * c1) / w ** 2
            u1, v1 = k.advance(cf, c0, c1, a0, s)
            assert u1 == pytest.approx(c0 + c1 * h, rel=2e-12, abs=0.0)
            assert v1 == pytest.approx(c1, rel=2e-12, abs=2e-12 * w * abs(c0))  # (u, u'/w) to 2e-12


@pytest.mark.parametrize("xi", [0.0, 0.05, 0.3, 0.5, 0.8, 2.0])
def test_the_base_norm_bounds_the_acceleration_and_never_grows_when_free(xi):
    """``base_norm``: ``|w^2 u + 2 xi w u'| <= k_a w S`` and ``|u| <= k_u S/w`` with equality somewhere
    on the ellipse; along a free base S never grows, along a driven one ``dS/dt <= |ag|``."""
    k = _kernel()
    c, k_a, k_u = k.base_norm(xi)
    w = 2.0
    phi = np.linspace(0.0, 2 * math.pi, 20001)
    u, v = np.cos(phi) / w, np.sin(phi)
    S = np.array([k.base_norm_of(c, w, a, b) for a, b in zip(u, v)])
    a = np.abs(w * w * u + 2 * xi * w * v) / (w * S)
    assert a.max() <= k_a * (1 + 1e-12) and a.max() >= k_a * (1 - 1e-6)
    assert (np.abs(u) * w / S).max() <= k_u * (1 + 1e-12)
    # along the exact free and driven motion (the record table's steps)
    acc = np.random.default_rng(int(xi * 100)).normal(size=2000)
    dt = 0.01
    tab = k.linear_base_table(acc, dt, w, xi)
    S = np.array([k.base_norm_of(c, w, a, b) for a, b in tab[:, :2]])
    grow = np.diff(S) - 0.5 * dt * (np.abs(acc[1:]) + np.abs(acc[:-1]))
    assert grow.max() <= 1e-12 * S.max()
    free = k.linear_base_table(np.concatenate([acc[:300], np.zeros(1500)]), dt, w, xi)
    Sf = np.array([k.base_norm_of(c, w, a, b) for a, b in free[300:, :2]])
    assert np.all(np.diff(Sf) <= 1e-12 * Sf[0])
    # column 2 bounds every later S, also inside the sample intervals: the same record at 20 points per
    # interval (its linear interpolation is the same ground motion)
    fine = np.interp(np.arange(0.0, (acc.size - 1) * 20 + 1) / 20.0, np.arange(acc.size), acc)
    tf = k.linear_base_table(fine, dt / 20.0, w, xi)
    Sfine = np.array([k.base_norm_of(c, w, a, b) for a, b in tf[:, :2]])
    later = np.maximum.accumulate(Sfine[::-1])[::-1][::20]  # every later S from each sample on
    assert np.all(tab[:, 2] >= later * (1 - 1e-12))
    assert np.all(tab[:, 2] <= later + 0.5 * dt * 2 * np.abs(acc).max() + 1e-12)  # and not far above it


def test_the_bound_holds_along_stuck_stretches_of_real_runs():
    """P9's claim on history runs (linear bearings, synthetic records): from every step end where the block
    rests on its base and the bound is below g tan(alpha), the base acceleration of the rest of the run
    stays below it, and the block never lifts again."""
    k = _kernel()
    rng = np.random.default_rng(91)
    checked = 0
    for seed in range(6):
        rec = synthetic_record(300 + seed, duration=8.0, pga=0.4 * G)
        for _ in range(6):
            block = Block(math.exp(rng.uniform(math.log(0.5), math.log(10.0))), rng.uniform(0.08, 0.3))
            f = LinearIsolation(rng.uniform(0.8, 3.5), rng.uniform(0.0, 0.4), rng.uniform(0.0, 0.3))
            s = rng.uniform(0.5, 2.0)
            r = simulate(block, f, rec, history=True, _scale=s, tail=5.0)
            H = r.history
            w, xi = f.omega_b, f.xi
            c, k_a, _ = k.base_norm(xi)
            tab = k.linear_base_table(rec.acc, rec.dt, w, xi)
            thr = G * math.tan(block.alpha)
            a = np.abs(w * w * H.u + 2 * xi * w * H.u_dot)
            stuck = (H.theta == 0.0) & (H.theta_dot == 0.0)
            for i in np.flatnonzero(stuck):
                j = int(round(H.t[i] / rec.dt))
                if abs(j * rec.dt - H.t[i]) > 1e-12 or j >= rec.acc.size:
                    continue
                B = abs(s) * tab[j, 2] + k.base_norm_of(c, w, H.u[i] - s * tab[j, 0], H.u_dot[i] - s * tab[j, 1])
                if w * k_a * B < thr:
                    later = H.t > H.t[i]
                    assert a[later].max(initial=0.0) <= w * k_a * B * (1 + 1e-7)
                    assert np.all(stuck[later])
                    checked += 1
                    break
    assert checked > 15


# ------------------------------------------------------------------------------------------
# Early vs verdict-only vs full history
# ------------------------------------------------------------------------------------------
def _linear_scenes(n, seed):
    """Random scenes on linear bearings: short synthetic records (6-10 s, 4 in 5 scenes) and pulses;
    alpha 3-20 deg, R 0.3-20 m, T_b 0.5-4 s, xi 0-0.5 (a tenth 0.5-2), gamma 0-0.5, scale factors
    giving a PGA of 0.3-3 g tan(alpha)."""
    rng = np.random.default_rng(seed)
    recs = [synthetic_record(1000 + i, duration=float(rng.uniform(6.0, 10.0)), pga=G) for i in range(25)]
    jobs = []
    for i in range(n):
        alpha = math.radians(rng.uniform(3.0, 20.0))
        block = Block(math.exp(rng.uniform(math.log(0.3), math.log(20.0))), alpha)
        xi = rng.uniform(0.5, 2.0) if rng.random() < 0.1 else rng.uniform(0.0, 0.5)
        f = LinearIsolation(rng.uniform(0.5, 4.0), xi, rng.uniform(0.0, 0.5))
        y = rng.uniform(0.5, 5.0) * math.tan(alpha) * rng.choice([-1.0, 1.0])  # PGA / g
        if i % 5:
            jobs.append((block, f, recs[i % len(recs)], y))
        else:
            Tp = 2 * math.pi / (rng.uniform(0.5, 15.0) * block.p)
            jobs.append((block, f, make_pulse(SHAPES[(i // 5) % 4], y * G, Tp)))
    return jobs


def _sliding_scenes(n, seed):
    """Random scenes on SCSS, DCSS and lead-rubber bearings in turn under short synthetic records (6-10 s):
    alpha 3-20 deg, R 0.3-20 m, T_b 1-4 s, mu 2-12 %, u_y 0.05-1 mm (x20 lead-rubber), gamma 0-0.5."""
    rng = np.random.default_rng(seed)
    recs = [synthetic_record(2000 + i, duration=float(rng.uniform(6.0, 10.0)), pga=G) for i in range(10)]
    jobs = []
    for i in range(n):
        alpha = math.radians(rng.uniform(3.0, 20.0))
        block = Block(math.exp(rng.uniform(math.log(0.3), math.log(20.0))), alpha)
        Tb = rng.uniform(1.0, 4.0)
        uy = math.exp(rng.uniform(math.log(0.05e-3), math.log(1e-3)))
        gam = rng.uniform(0.0, 0.5)
        if i % 3 == 0:
            f = SingleConcaveSliding(Tb, rng.uniform(0.02, 0.12), uy, gam)
        elif i % 3 == 1:
            f = DoubleConcaveSliding.from_period(Tb, rng.uniform(0.02, 0.12), rng.uniform(0.02, 0.12),
                                                 ratio=math.exp(rng.uniform(math.log(0.5), math.log(2.0))), u_y=uy,
                                                 gamma=gam)
        else:
            f = LeadRubber(Tb, rng.uniform(0.03, 0.12), 20 * uy, gam)
        jobs.append((block, f, recs[i % len(recs)], rng.uniform(0.3, 3.0) * math.tan(alpha)))
    return jobs


def _t_exc_end(job):
    x = job[2]
    return (x.acc.size - 1) * x.dt if isinstance(x, Record) else x.support()[1]


def _same(a, b):
    return a == b or (math.isnan(a) and math.isnan(b))


def _history(job):
    return simulate(*job[:3], history=True, **({"_scale": job[3]} if len(job) > 3 else {}))


def _compare(jobs, history_every=1):
    """Early, verdict-only and (every ``history_every``-th scene) full-history runs of ``jobs``: returns
    the early runs, the mismatches and how many early runs P9/P9s proved during the excitation."""
    early = simulate_many(jobs, early=True)
    full = simulate_many(jobs)
    bad, during = [], 0
    for i, (e, f) in enumerate(zip(early, full)):
        runs = [f] + ([_history(jobs[i])] if i % history_every == 0 else [])
        same = e.settled and f.settled and e.peak_final and f.peak_final
        same = same and all(e.verdict == r.verdict and e.n_impacts == r.n_impacts and _same(e.t_uplift_s, r.t_uplift_s)
                            and e.theta_max == pytest.approx(r.theta_max, rel=1e-12, abs=0.0) for r in runs)
        if e.t_settled_s < _t_exc_end(jobs[i]) and not e.overturned:  # a proof during the excitation
            during += 1
            # the block never moves again: everything about it is final, bit for bit, and the full runs
            # end with it at rest
            same = same and e.steps < f.steps and all(
                e.theta_max == r.theta_max and e.n_uplifts == r.n_uplifts and e.n_rests == r.n_rests
                and e.n_impacts_total == r.n_impacts_total and _same(e.t_theta_max_s, r.t_theta_max_s)
                for r in runs)
            same = same and all(r.history.theta[-1] == 0.0 == r.history.theta_dot[-1] for r in runs[1:])
        # the base's peak: final and equal, or unknown (NaN), never a peak so far
        same = same and (math.isnan(e.base_disp_max_m)
                         or e.base_disp_max_m == pytest.approx(f.base_disp_max_m, rel=1e-7, abs=1e-12))
        if not same:
            bad.append((i, e.verdict, f.verdict, e.theta_max, f.theta_max, e.base_disp_max_m, f.base_disp_max_m))
    return early, bad, during


def test_linear_bearings_early_equals_verdict_only_and_history_on_3000_random_scenes():
    """P9: 3,000 random scenes on linear bearings (2,400 under synthetic records, 600 under pulses):
    early, verdict-only and (every tenth) full-history runs give the same verdict, impacts, uplift time and
    peak; where P9 proved the verdict during the excitation, also the same uplifts, rests and every impact
    bit for bit, and the block at rest at the end of the full runs; the base's peak is final or NaN.
    (20,000 more scenes of another seed, ``benchmarks/bench_early_isolated.py --linear``: 0 mismatches.)"""
    jobs = _linear_scenes(3000, 33)
    early, bad, during = _compare(jobs, history_every=10)
    assert bad == []
    verdicts = [r.verdict for r in early]
    assert min(verdicts.count(v) for v in ("no_uplift", "rocked", "overturned")) > 500
    # P9 does fire (measured: 1,669 proofs during the excitation, 132 of them after the block rocked), and
    # the base's peak is sometimes proven final with it (41), mostly unknown (NaN)
    assert during > 1200
    assert sum(r.verdict == "rocked" and r.t_settled_s < _t_exc_end(j) for r, j in zip(early, jobs)) > 80
    assert sum(math.isnan(r.base_disp_max_m) for r in early) > 1000
    assert sum(not math.isnan(r.base_disp_max_m) and r.t_settled_s < _t_exc_end(j) and not r.overturned
               for r, j in zip(early, jobs)) > 20


def test_sliding_bearings_early_equals_verdict_only_and_history_on_600_random_scenes():
    """P9s: 600 random SCSS / DCSS / lead-rubber scenes under synthetic records: the same comparison
    (full history for every eighth: a history run on sliding bearings costs about 0.1 s; 3,000 more
    offline, ``benchmarks/bench_early_isolated.py --sliding``: 0 mismatches)."""
    jobs = _sliding_scenes(600, 34)
    early, bad, during = _compare(jobs, history_every=8)
    assert bad == []
    verdicts = [r.verdict for r in early]
    assert min(verdicts.count(v) for v in ("no_uplift", "rocked", "overturned")) > 50
    assert during > 250  # measured: 404, 30 of them after the block rocked
    assert sum(r.verdict == "rocked" and r.t_settled_s < _t_exc_end(j) for r, j in zip(early, jobs)) > 15


def test_early_stops_agree_with_the_reference():
    """Linear bearings, scenes whose verdict P9 proved during the excitation: the slow SciPy reference,
    which takes no shortcut, gives the same verdict, two of each (record or pulse, no_uplift or rocked;
    a rocked block proven during a pulse is rare: none of these 40 pulses). Sliding bearings (P9s): the
    reference integrates the stiff Bouc-Wen element with Radau, 5-20 s of CPU a scene, too slow for the
    suite; ``benchmarks/bench_early_isolated.py --reference`` runs them (all agreed)."""
    jobs = _linear_scenes(200, 35)
    early = simulate_many(jobs, early=True)
    picked = {}
    for j, r in zip(jobs, early):
        if r.t_settled_s < _t_exc_end(j) and not r.overturned:
            key = (r.verdict, isinstance(j[2], Record))
            if len(picked.setdefault(key, [])) < 2:
                picked[key].append((j, r))
    assert {("no_uplift", True), ("no_uplift", False), ("rocked", True)} <= set(picked)
    for key, items in picked.items():
        for j, r in items:
            exc = j[2].scaled(j[3]) if len(j) > 3 else j[2]
            ref = reference_simulate(j[0], j[1], exc, align=isinstance(exc, Record))
            assert ref.verdict == r.verdict, (key, j)


def test_a_real_record_stops_after_the_strong_motion():
    """Kobe Takarazuka scaled to 0.5 under Bassae on T_b = 2 s bearings: the block rocks, rests, and P9
    ends the early run about 10 s into a 41 s record with the same verdict and peak (and, here, the
    base's peak proven final too)."""
    pytest.importorskip("obspy")
    from rockcli.assess import parse_column_spec
    from rockcli.records import read_record

    try:
        rec = read_record("kobe-1995-takarazuka-000")
    except Exception:
        pytest.skip("the Kobe record is not available (ROCKCLI_RECORDS)")
    b = parse_column_spec("bassae")
    f = LinearIsolation(2.0, 0.1)
    e, full = simulate(b, f, rec, early=True, _scale=0.5), simulate(b, f, rec, _scale=0.5)
    assert e.verdict == full.verdict == "rocked"
    assert e.theta_max == full.theta_max and e.n_impacts == full.n_impacts and e.n_uplifts == full.n_uplifts
    assert e.t_settled_s < 15.0 < 40.0 < full.t_end_s and e.steps < full.steps / 3
    assert e.base_disp_max_m == full.base_disp_max_m
