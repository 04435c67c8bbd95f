"""The rocking solver: physics (conservation, limits, symmetry, closed forms) and numerics
(convergence, agreement with the slow SciPy reference in tests/naive.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from naive import impact_map_linear_system, reference_simulate
from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Rigid, column, impact_coefficient, parse_isolation_spec
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.solve import simulate, simulate_many
from rockcli.io.units import G
from synthetic import synthetic_record

FIG1 = Block.from_dimensions(2.0, 0.5, "refrigerator")  # the paper's Figure 1 block


# ------------------------------------------------------------------------------------------
# Models
# ------------------------------------------------------------------------------------------
def test_column_presets_match_the_paper():
    b, n = column("bassae"), column("nemea")
    assert b.R == pytest.approx(3.03, abs=0.005) and b.alpha_deg == pytest.approx(10.56, abs=0.01)
    assert n.R == pytest.approx(5.22, abs=0.005) and n.alpha_deg == pytest.approx(8.37, abs=0.01)
    assert b.alpha == pytest.approx(0.1844, abs=1e-4) and n.alpha == pytest.approx(0.1461, abs=1e-4)
    assert FIG1.p == pytest.approx(2.67, abs=0.01)  # "p = 2.67 rad/s" in the paper
    assert math.tan(FIG1.alpha) == pytest.approx(0.25)


@pytest.mark.parametrize("bad", [
    lambda: Block(-1.0, 0.2), lambda: Block(1.0, 0.0), lambda: Block(1.0, math.pi / 2),
    lambda: Block(float("nan"), 0.2), lambda: Block.from_dimensions(-2, 1), lambda: Block.from_dimensions(2, 0),
    lambda: LinearIsolation(0.0), lambda: LinearIsolation(2.0, -0.1), lambda: LinearIsolation(2.0, 0.1, 1.0),
    lambda: LinearIsolation(2.0, 0.1, -0.1), lambda: column("parthenon"),
])
def test_invalid_parameters_raise_clear_errors(bad):
    with pytest.raises(RockcliInputError) as err:
        bad()
    assert len(str(err.value)) > 10 and "\n" not in str(err.value)


@pytest.mark.parametrize("spec, expected", [
    ("none", Rigid()),
    ("linear:Tb=2.5,xi=0.1,gamma=0.01", LinearIsolation(2.5, 0.1, 0.01)),
    ("linear:Tb=3", LinearIsolation(3.0, 0.1, 0.01)),
    ("LINEAR: Tb=2 , xi=0.05", LinearIsolation(2.0, 0.05, 0.01)),
])
def test_isolation_specs(spec, expected):
    assert parse_isolation_spec(spec) == expected


@pytest.mark.parametrize("spec, words", [
    ("rubber:Tb=2", "unknown isolation"), ("linear:xi=0.1", "needs Tb"), ("linear:Tb=abc", "must be a number"),
    ("linear:Tb=2,mu=0.1", "mu=0.1"), ("linear:Tb=-2", "must be positive"),
])
def test_bad_isolation_specs(spec, words):
    with pytest.raises(RockcliInputError, match=words):
        parse_isolation_spec(spec)


# ------------------------------------------------------------------------------------------
# Impact map
# ------------------------------------------------------------------------------------------
def angular_momentum_about(block, corner_x, thd, pivot_x, ud, nx=60, ny=200):
    """Angular momentum (per unit mass, z component) about the base corner ``corner_x`` of a block
    at theta = 0 rotating at ``thd`` about the corner ``pivot_x`` while its base moves at ``ud``,
    by integrating r x v over the rectangle (midpoint rule): no formula from the paper."""
    b, h = block.b, block.h
    xs = (np.arange(nx) + 0.5) / nx * 2 * b - b
    ys = (np.arange(ny) + 0.5) / ny * 2 * h
    X, Y = np.meshgrid(xs, ys)
    # theta > 0 is clockwise (centre of mass moves +x): omega_z = -thd
    rx, ry = X - pivot_x, Y
    vx = ud + (-thd) * (-ry)
    vy = (-thd) * rx
    qx, qy = X - corner_x, Y
    return float(np.mean(qx * vy - qy * vx))


@pytest.mark.parametrize("alpha", [0.1, 0.2, 0.35])
@pytest.mark.parametrize("gamma", [0.0, 0.01, 0.3, 0.8])
def test_impact_map_conserves_both_momenta(alpha, gamma):
    block = Block(2.0, alpha)
    b = block.b
    thd1, ud1 = -0.7, 0.13  # rocking on the right corner (theta > 0) coming back to theta = 0
    eta = impact_coefficient(alpha, gamma)
    k = (4 - 3 * gamma) / math.tan(alpha) ** 2
    thd2 = eta * thd1
    ud2 = ud1 + 6 * gamma * block.h * thd1 / (k + 4)
    # closed form == the linear system of Eqs (14), (16)
    ref = impact_map_linear_system(block, gamma, thd1, ud1)
    assert thd2 == pytest.approx(ref[0], rel=1e-12)
    assert ud2 == pytest.approx(ref[1], rel=1e-12, abs=1e-15)
    # total horizontal momentum per unit total mass: u_dot + gamma h theta_dot
    assert ud1 + gamma * block.h * thd1 == pytest.approx(ud2 + gamma * block.h * thd2, abs=1e-14)
    # angular momentum about the new pivot (the left corner) by direct integration over the block
    L1 = angular_momentum_about(block, -b, thd1, +b, ud1)
    L2 = angular_momentum_about(block, -b, thd2, -b, ud2)
    assert L1 == pytest.approx(L2, rel=1e-3)
    # kinetic energy never grows
    Io = 4 / 3 * block.R ** 2
    mb = (1 - gamma) / gamma if gamma else None
    if mb is not None:
        T1 = 0.5 * (1 + mb) * ud1 ** 2 + block.h * ud1 * thd1 + 0.5 * Io * thd1 ** 2
        T2 = 0.5 * (1 + mb) * ud2 ** 2 + block.h * ud2 * thd2 + 0.5 * Io * thd2 ** 2
        assert T2 < T1


def test_impact_coefficient_limits():
    for alpha in (0.05, 0.2, 0.4):
        assert impact_coefficient(alpha, 0.0) == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-14)
        # a heavier block on a lighter base loses more energy (paper's Figure 5)
        assert impact_coefficient(alpha, 0.5) < impact_coefficient(alpha, 0.1) < impact_coefficient(alpha, 0.0)
    assert impact_coefficient(1.2, 0.0) == 0.0  # too squat to rock: the first impact stops it


def test_history_impacts_conserve_momenta():
    block = column("bassae")
    iso = LinearIsolation(2.0, 0.1, 0.25)
    res = simulate(block, iso, make_pulse("ricker-sym", 0.55 * G, 1.2), history=True, tail=3.0)
    H = res.history
    pairs = np.nonzero(np.diff(H.t) == 0.0)[0]
    pairs = [i for i in pairs if H.theta[i] == 0.0 and H.theta_dot[i] != 0.0 and H.theta_dot[i + 1] != 0.0]
    assert len(pairs) >= 3
    g, h, b = iso.gamma, block.h, block.b
    for i in pairs:
        thd1, ud1, thd2, ud2 = H.theta_dot[i], H.u_dot[i], H.theta_dot[i + 1], H.u_dot[i + 1]
        assert np.sign(thd1) == np.sign(thd2)
        assert ud1 + g * h * thd1 == pytest.approx(ud2 + g * h * thd2, abs=1e-12)
        pivot_before = b if thd1 < 0 else -b  # coming back from theta > 0 pivots on the right corner
        L1 = angular_momentum_about(block, -pivot_before, thd1, pivot_before, ud1)
        L2 = angular_momentum_about(block, -pivot_before, thd2, -pivot_before, ud2)
        assert L1 == pytest.approx(L2, rel=2e-3)


# ------------------------------------------------------------------------------------------
# The paper's Figure 1 and uplift
# ------------------------------------------------------------------------------------------
def test_figure_1_size_frequency_effect():
    short = simulate(FIG1, Rigid(), make_pulse("sine", 0.50 * G, 0.5))
    long = simulate(FIG1, Rigid(), make_pulse("sine", 0.29 * G, 2.0))
    assert short.verdict == "rocked" and short.theta_max_over_alpha < 1.0
    assert long.verdict == "overturned" and long.t_overturn_s > long.t_exceed_alpha_s > long.t_uplift_s


@pytest.mark.parametrize("shape", ["sine", "cosine", "ricker-sym", "ricker-anti"])
def test_no_uplift_below_g_tan_alpha(shape):
    thr = G * math.tan(FIG1.alpha)
    below = simulate(FIG1, Rigid(), make_pulse(shape, 0.999 * thr, 1.0))
    above = simulate(FIG1, Rigid(), make_pulse(shape, 1.001 * thr, 1.0))
    assert below.verdict == "no_uplift" and below.theta_max == 0.0 and below.steps == 0
    assert above.verdict == "rocked"
    # the uplift instant is where |ag| first reaches g tan(alpha)
    p = make_pulse(shape, 1.001 * thr, 1.0)
    if shape == "cosine":  # jumps from 0 to a_p > g tan(alpha) at its start: uplift at once
        assert above.t_uplift_s == p.support()[0]
        return
    assert abs(p.acceleration(above.t_uplift_s)) == pytest.approx(thr, rel=1e-9)
    tt = np.linspace(p.support()[0], above.t_uplift_s, 20001)[:-1]
    assert np.all(np.abs(p.acceleration(tt)) < thr * (1 + 1e-12))


def _lobe_peaks(shape):
    """|ag| / a_p at every turn of the unit pulse (the heights a threshold can graze)."""
    from rockcli.kernels import _pulse_turns
    from rockcli.solve import _PULSE_CODES

    p = make_pulse(shape, 1.0, 1.0)
    return [abs(float(p.acceleration(p.t0 + c))) for c in _pulse_turns(_PULSE_CODES[shape]) if math.isfinite(c)]


def test_uplift_scan_agrees_with_a_dense_scan_on_random_pulses():
    """The stuck-phase scan cuts a pulse at its turns and bisects on the first monotone piece whose
    end exceeds the threshold. Against a brute-force scan on 100,001 points of each random window
    (1,200 windows; thresholds drawn near every lobe's height, from either side, and at random; windows starting
    anywhere in the support): an uplift is found exactly when a sampled |ag| exceeds the threshold
    by more than rounding, never after the first such sample, and never before a time where |ag|
    reaches the threshold."""
    from rockcli.kernels import _rigid_uplift
    from rockcli.solve import _excitation_arrays

    rng = np.random.default_rng(11)
    found = missed_checks = 0
    for trial in range(1200):
        shape = ["ricker-sym", "ricker-anti", "sine", "cosine"][trial % 4]
        a_p = float(rng.choice([-1.0, 1.0]) * rng.uniform(0.5, 20.0))
        T_p = float(rng.uniform(0.05, 5.0))
        pulse = make_pulse(shape, a_p, T_p)
        ekind, epar, *_ = _excitation_arrays(pulse)
        ts, te = pulse.support()
        kind = rng.integers(3)
        if kind == 0:
            peak = float(rng.choice(_lobe_peaks(shape)))
            thr = abs(a_p) * peak * (1.0 + float(rng.choice([-1.0, 1.0])) * 10.0 ** rng.uniform(-10, -2))
        else:
            thr = abs(a_p) * float(rng.uniform(0.01, 1.1))
        t = ts + (0.0 if kind == 2 else float(rng.uniform(0.0, 0.9)) * (te - ts))
        seg = (float(ekind), 0.0, 0.0, ts)
        tu, s = _rigid_uplift(seg, epar, thr, t, te)
        tt = np.linspace(t, te, 100001)
        a = pulse.acceleration(tt)
        over = np.flatnonzero(np.abs(a) > thr * (1.0 + 1e-9))
        if tu < 0.0:
            assert over.size == 0, (shape, a_p, T_p, thr, t)
            continue
        found += 1
        assert t <= tu <= te
        if over.size:
            assert tu <= tt[over[0]] * (1 + 1e-15), (shape, a_p, T_p, thr, t)
        before = tt[tt < tu]
        assert np.all(np.abs(pulse.acceleration(before)) <= thr * (1.0 + 1e-9)), (shape, a_p, T_p, thr, t)
        ag = float(pulse.acceleration(tu))
        if tu > t:
            assert abs(ag) == pytest.approx(thr, rel=1e-9)
            missed_checks += 1
        assert s == (-1.0 if ag > 0 else 1.0)
    assert found > 500 and missed_checks > 300


def test_uplift_on_a_record_is_located_between_samples():
    rec = synthetic_record(3)
    block = Block(1.0, 0.25)
    res = simulate(block, Rigid(), rec)
    thr = G * math.tan(block.alpha)
    k = int(np.nonzero(np.abs(rec.acc) > thr)[0][0])
    assert (k - 1) * rec.dt <= res.t_uplift_s <= k * rec.dt
    assert abs(np.interp(res.t_uplift_s, rec.times, rec.acc)) == pytest.approx(thr, rel=1e-12)


# ------------------------------------------------------------------------------------------
# Free rocking: Housner's decay and half-period, rest
# ------------------------------------------------------------------------------------------
def free_rocking_history(block, tail=20.0):
    """Kick the block with a short pulse, then let it rock freely; return the free part."""
    pulse = make_pulse("sine", 1.6 * G * math.tan(block.alpha), 0.3)
    res = simulate(block, Rigid(), pulse, history=True, tail=tail)
    H = res.history
    free = H.t > pulse.support()[1] + 1e-9
    return res, H, free


def test_free_rocking_amplitude_decay_follows_housner():
    block = Block(1.5, 0.2)
    res, H, free = free_rocking_history(block)
    th, thd = H.theta[free], H.theta_dot[free]
    # peaks from the dense history: theta_dot changes sign away from impacts
    idx = np.nonzero((thd[:-1] * thd[1:] < 0) & (th[:-1] != 0) & (np.abs(th[:-1]) > 1e-3 * block.alpha))[0]
    p2, a = block.p ** 2, block.alpha
    peaks = []
    for i in idx:  # energy is conserved between impacts: E = thd^2/2 + p^2 cos(alpha - |theta|)
        E = 0.5 * thd[i] ** 2 + p2 * math.cos(a - abs(th[i]))
        peaks.append(a - math.acos(E / p2))
    assert len(peaks) >= 5
    eta2 = (1 - 1.5 * math.sin(a) ** 2) ** 2
    for th_n, th_next in zip(peaks[:-1], peaks[1:]):
        predicted = a - math.acos(math.cos(a) + eta2 * (math.cos(a - th_n) - math.cos(a)))
        assert th_next == pytest.approx(predicted, rel=1e-6)
    # it ends at rest, in finite work, with every impact losing energy
    assert res.n_rests >= 1 and res.settled and res.steps < 50_000


def test_free_rocking_quarter_period_matches_exact_quadrature_and_housner():
    block = Block(1.0, 0.05)
    res, H, free = free_rocking_history(block)
    t, thd = H.t[free], H.theta_dot[free]
    imp = np.nonzero((np.diff(t) == 0.0))[0]
    assert imp.size >= 4
    p, a = block.p, block.alpha
    # between two consecutive impacts the block flies out and back: the flight lasts two quarter periods
    for i0, i1 in zip(imp[:-1], imp[1:]):
        thd0 = abs(thd[i0 + 1])
        E = 0.5 * thd0 ** 2 + p * p * math.cos(a)
        th0 = a - math.acos(E / (p * p))  # peak of this flight
        # t = int_0^th0 dtheta / theta_dot, theta_dot^2 = 2 p^2 (cos(a - th0) - cos(a - theta)):
        # an inverse-square-root singularity at th0, integrated with QUADPACK's algebraic weight
        def smooth(x):
            gap = 2.0 * math.sin(a - 0.5 * (x + th0)) * math.sin(0.5 * (th0 - x))
            return math.sqrt((th0 - x) / (2 * p * p * gap)) if th0 > x else 1.0 / math.sqrt(2 * p * p * math.sin(a - th0))

        quarter, _ = quad(smooth, 0, th0, weight="alg", wvar=(0, -0.5), epsabs=1e-14, epsrel=1e-12)
        assert t[i1] - t[i0] == pytest.approx(2 * quarter, rel=1e-6)
        # Housner (1963), slender-block approximation: T/4 = (1/p) acosh(1 / (1 - theta0/alpha))
        assert t[i1] - t[i0] == pytest.approx(2 / p * math.acosh(1 / (1 - th0 / a)), rel=2e-2)


def test_rest_threshold_is_respected_and_ends_chattering():
    block = Block(0.8, 0.15)
    for rest_tol in (1e-4, 1e-6, 1e-9):
        res = simulate(block, Rigid(), make_pulse("ricker-sym", 0.3 * G, 0.6), history=True, tail=30, rest_tol=rest_tol)
        assert res.settled and res.n_rests >= 1 and res.status == 0
        H = res.history
        last_impact = np.nonzero(np.diff(H.t) == 0.0)[0][-1]
        thd_before = abs(H.theta_dot[last_impact])
        eta = block.housner_restitution
        assert (eta * thd_before) ** 2 / (2 * block.p ** 2 * math.sin(block.alpha)) < rest_tol * block.alpha
        assert H.theta_dot[last_impact + 1] == 0.0


# ------------------------------------------------------------------------------------------
# Symmetry and limits
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("foundation", [Rigid(), LinearIsolation(2.0, 0.1, 0.2)])
def test_flipping_the_excitation_flips_theta(foundation):
    rec = synthetic_record(1, pga=0.5 * G)
    block = Block(1.2, 0.22)
    a = simulate(block, foundation, rec, history=True)
    b = simulate(block, foundation, rec.flipped(), history=True)
    assert a.history.t.shape == b.history.t.shape
    np.testing.assert_allclose(b.history.t, a.history.t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.history.theta, -a.history.theta, rtol=0, atol=1e-12 * block.alpha)
    np.testing.assert_allclose(b.history.u, -a.history.u, rtol=0, atol=1e-12)
    assert a.verdict == b.verdict and a.n_impacts == b.n_impacts


def test_gamma_to_zero_converges_and_tb_to_zero_recovers_the_rigid_foundation():
    block = Block(1.0, 0.2)
    pulse = make_pulse("ricker-sym", 0.35 * G, 0.8)
    rigid = simulate(block, Rigid(), pulse, rtol=1e-10)
    # a nearly rigid isolator (T_b -> 0) with gamma = 0 behaves like the rigid foundation
    stiff = simulate(block, LinearIsolation(0.005, 0.1, 0.0), pulse, rtol=1e-10)
    assert stiff.verdict == rigid.verdict == "rocked"
    assert stiff.theta_max == pytest.approx(rigid.theta_max, rel=2e-3)
    assert stiff.base_disp_max_m < 1e-4
    # gamma -> 0 converges
    iso = [simulate(block, LinearIsolation(1.5, 0.05, g), make_pulse("ricker-sym", 0.2 * G, 1.0), rtol=1e-10)
           for g in (1e-1, 1e-2, 1e-3, 1e-4, 0.0)]
    assert all(r.verdict == "rocked" for r in iso)
    d = [abs(r.theta_max - iso[-1].theta_max) for r in iso[:-1]]
    assert d[0] > d[1] > d[2] > d[3] and d[3] < 1e-3 * iso[-1].theta_max


def test_very_long_isolation_period_decouples_the_base():
    block = Block(1.0, 0.2)
    pulse = make_pulse("ricker-anti", 0.8 * G, 1.0)
    assert simulate(block, Rigid(), pulse).verdict == "overturned"
    res = simulate(block, LinearIsolation(1e6, 0.0, 0.01), pulse, history=True, tail=0.0)
    assert res.verdict == "no_uplift"
    # the base stays still in absolute terms: u = -u_g
    ug = pulse.displacement(res.history.t)
    np.testing.assert_allclose(res.history.u, -ug, atol=1e-6 * np.max(np.abs(ug)))


def test_isolation_period_is_the_base_period():
    block = Block(3.0, 0.2)
    Tb = 2.0
    pulse = make_pulse("cosine", 0.05 * G, 0.2)  # too weak to uplift: the base oscillates freely after it
    res = simulate(block, LinearIsolation(Tb, 0.0, 0.01), pulse, history=True, tail=10.0)
    assert res.verdict == "no_uplift"
    H = res.history
    after = H.t > 0.5
    t, u = H.t[after], H.u[after]
    i = np.nonzero((u[:-1] < 0) & (u[1:] >= 0))[0]
    zc = t[i] - u[i] * (t[i + 1] - t[i]) / (u[i + 1] - u[i])
    assert np.mean(np.diff(zc)) == pytest.approx(Tb, rel=2e-3)


# ------------------------------------------------------------------------------------------
# Numerics
# ------------------------------------------------------------------------------------------
def test_convergence_as_tolerance_tightens():
    """Global error on the peak rotation falls with the tolerance, in proportion to it."""
    block = Block(1.0, 0.2)
    scenes = [(Rigid(), make_pulse("ricker-sym", 0.32 * G, 1.0)),
              (LinearIsolation(2.0, 0.05, 0.1), make_pulse("ricker-anti", 0.6 * G, 0.8))]
    for foundation, pulse in scenes:
        best = simulate(block, foundation, pulse, rtol=1e-13, history=True)
        assert best.verdict == "rocked"
        rtols = (1e-4, 1e-7, 1e-10)
        runs = [simulate(block, foundation, pulse, rtol=rt, history=True) for rt in rtols]
        errs = [abs(r.theta_max - best.theta_max) / best.theta_max for r in runs]
        assert errs[0] > errs[1] > errs[2]
        assert errs[1] < 100 * rtols[1] and errs[2] < 100 * rtols[2]
        assert runs[0].steps < runs[1].steps < runs[2].steps


def test_verdict_only_and_history_runs_agree():
    rec = synthetic_record(2, pga=0.5 * G)
    for block, foundation in [(Block(1.0, 0.2), Rigid()), (Block(1.0, 0.2), LinearIsolation(2.5, 0.1, 0.01)),
                              (Block(0.5, 0.25), Rigid())]:
        a = simulate(block, foundation, rec)
        b = simulate(block, foundation, rec, history=True)
        assert a.verdict == b.verdict and a.n_impacts == b.n_impacts
        assert a.theta_max == pytest.approx(b.theta_max, rel=1e-9)
        assert a.steps <= b.steps
        if a.overturned:
            assert a.t_overturn_s == b.t_overturn_s


REF_SCENES = []
_rng = np.random.default_rng(2026)
for _i in range(10):
    _R = float(_rng.uniform(0.3, 4.0))
    _alpha = float(_rng.uniform(0.1, 0.35))
    _shape = ["ricker-sym", "ricker-anti", "sine"][_i % 3]
    _Tp = float(_rng.uniform(0.3, 2.0))
    _ap = float(_rng.uniform(1.2, 4.0)) * math.tan(_alpha) * G
    _found = Rigid() if _i % 2 == 0 else LinearIsolation(float(_rng.uniform(1.5, 3.5)), float(_rng.uniform(0, 0.2)),
                                                            float(_rng.choice([0.0, 0.01, 0.2])))
    REF_SCENES.append((Block(_R, _alpha), _found, make_pulse(_shape, _ap, _Tp)))


@pytest.mark.parametrize("block, foundation, pulse", REF_SCENES)
def test_agreement_with_slow_reference_on_pulses(block, foundation, pulse):
    fast = simulate(block, foundation, pulse, rtol=1e-10)
    slow = reference_simulate(block, foundation, pulse)
    assert fast.verdict == slow.verdict
    assert fast.theta_max == pytest.approx(slow.theta_max, rel=1e-6)
    assert fast.t_uplift_s == pytest.approx(slow.t_uplift, rel=1e-9, nan_ok=True)
    if fast.overturned:
        assert fast.t_overturn_s == pytest.approx(slow.t_overturn, rel=1e-6)
    assert fast.base_disp_max_m == pytest.approx(slow.u_max, rel=1e-5, abs=1e-9)


@pytest.mark.parametrize("seed, foundation", [(0, Rigid()), (1, LinearIsolation(2.0, 0.1, 0.01)),
                                              (4, LinearIsolation(3.0, 0.05, 0.3))])
def test_agreement_with_slow_reference_on_records(seed, foundation):
    rec = synthetic_record(seed, duration=8.0, pga=0.55 * G)
    block = Block(0.9, 0.21)
    fast = simulate(block, foundation, rec, rtol=1e-10)
    slow = reference_simulate(block, foundation, rec)
    assert fast.verdict == slow.verdict
    # the reference steps across the record's kinks (DOP853 with max_step = dt) and is itself only
    # good to ~1e-6 here; the compiled kernel never crosses a sample
    assert fast.theta_max == pytest.approx(slow.theta_max, rel=2e-5)
    assert fast.t_uplift_s == pytest.approx(slow.t_uplift, rel=1e-9, nan_ok=True)


def test_agreement_with_slow_reference_on_a_real_record(records_dir):
    from rockcli.records import read_record

    rec = read_record(records_dir / "RSN1119_KOBE_TAZ000.AT2")
    for block, foundation in [(column("bassae"), Rigid()), (column("nemea"), LinearIsolation(2.0))]:
        fast = simulate(block, foundation, rec)
        slow = reference_simulate(block, foundation, rec)
        assert fast.verdict == slow.verdict
        assert fast.theta_max == pytest.approx(slow.theta_max, rel=2e-5)


@pytest.mark.parametrize("block, foundation, pulse", [
    (Block(0.05, 0.3), Rigid(), make_pulse("ricker-sym", 2.0 * G, 0.05)),  # a small object, p = 12 rad/s
    (Block(30.0, 0.03), Rigid(), make_pulse("sine", 0.5 * G, 5.0)),  # a huge, very slender body
    (Block(1.0, 1.2), Rigid(), make_pulse("ricker-sym", 5.0 * G, 1.0)),  # squat: stops at its first impact
    (Block(1.0, 0.2), LinearIsolation(0.02, 0.5, 0.5), make_pulse("ricker-anti", 1.5 * G, 0.5)),  # stiff base
    (Block(1.0, 0.2), LinearIsolation(2.0, 3.0, 0.9), make_pulse("ricker-sym", 1.0 * G, 1.0)),  # overdamped, heavy block
    (Block(1.0, 0.2), Rigid(), make_pulse("cosine", 20.0 * G, 0.01)),  # violent and very short
])
def test_extreme_cases_finish_with_sane_results(block, foundation, pulse):
    res = simulate(block, foundation, pulse, history=True)
    assert res.status in (0, 1) and res.steps < 200_000
    assert 0.0 <= res.theta_max <= math.pi / 2 + 1e-12
    assert np.all(np.isfinite(res.history.theta)) and np.all(np.isfinite(res.history.u))
    assert np.all(np.abs(res.history.theta) <= math.pi / 2 + 1e-9)


def test_bad_arguments_to_simulate():
    with pytest.raises(RockcliInputError, match="rtol"):
        simulate(FIG1, Rigid(), make_pulse("sine", 1.0, 1.0), rtol=0.5)
    with pytest.raises(RockcliInputError, match="NaN"):
        simulate(FIG1, Rigid(), Record(np.array([0.0, np.nan, 1.0]), 0.01))
    with pytest.raises(RockcliInputError, match="tail"):
        simulate(FIG1, Rigid(), make_pulse("sine", 1.0, 1.0), tail=-1)


def test_a_sweep_stops_on_an_error_in_progress_and_the_next_one_runs():
    """simulate_many runs pieces on a thread pool: an exception raised by the progress callback
    (e.g. Ctrl-C) reaches the caller, the pieces not started are dropped, and the pool is left
    clean (a second sweep gives the results of a sweep without progress)."""
    jobs = [(Block(1.0, 0.2), Rigid(), make_pulse("ricker-sym", 3.0, 1.0), s) for s in np.linspace(0.5, 3.0, 2000)]
    calls = []

    def progress(k):
        calls.append(k)
        if len(calls) == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        simulate_many(jobs, progress=progress)
    assert len(calls) == 2 and calls[-1] < len(jobs)
    again = simulate_many(jobs, chunk=97)
    once = simulate_many(jobs)
    assert [r.verdict for r in again] == [r.verdict for r in once]
    assert [r.theta_max for r in again] == [r.theta_max for r in once]  # the pieces change no result

