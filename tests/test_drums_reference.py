"""The slow reference of a column of drums (rockcli.reference.friction_drums, drum_mechanics, drum_patterns): its
mechanics against the existing reference's and the driver's, its pattern search (the mixed-integer problem against
the enumeration), one and two drums against the existing reference, energy across impacts and switches, the static
thresholds, and a handful of 3-5 drum scenes against the driver (benchmarks/bench_drums_reference.py runs many)."""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

from rockcli.io.units import G
from rockcli.models import Block, Plinth, Stack
from rockcli.models.drums import DrumColumn
from rockcli.pulses import OneSine, RickerSymmetric
from rockcli.records import Record
from rockcli.reference import drum_patterns as dp
from rockcli.reference.drum_mechanics import DrumChain
from rockcli.reference.friction_drums import chain_of, reference_drums

sys.path.insert(0, os.path.dirname(__file__))  # tests/synthetic.py, as the suite's other tests import it


def _random_chain(rng, n, base=False):
    drums = [(rng.uniform(0.3, 1.5), rng.uniform(0.3, 1.0)) for _ in range(n)]
    col = DrumColumn(tuple(drums))
    from rockcli.models import LinearIsolation

    iso = LinearIsolation(T_b=2.5, xi=0.1, gamma=0.3) if base else None
    return col, chain_of(col, tuple(float(x) for x in rng.uniform(0.3, 1.0, n)), iso)


def _random_state(rng, ch, closed_share=0.4):
    """A pattern and state: interfaces closed (angle and rate 0, resting or sliding) or open pivots of either kind;
    slips anywhere on the top below (some drums overhang)."""
    n = ch.n
    pat = [0.0] * (2 * n)
    q, qd = np.zeros(1 + 2 * n), np.zeros(1 + 2 * n)
    zero_psi, zero_s = [False] * n, [False] * n
    for j in range(n):
        q[1 + 2 * j] = rng.uniform(-0.7, 0.7) * (ch.b[j] + ch.blow[j]) if j else rng.normal() * 0.1
        if rng.random() < closed_share:
            zero_psi[j] = True
            if rng.random() < 0.5:
                zero_s[j] = True
            else:
                pat[2 * j + 1] = float(rng.choice([-1, 1]))
                qd[1 + 2 * j] = pat[2 * j + 1] * rng.uniform(0.01, 0.5)
        else:
            c = float(rng.choice([-1, 1]))
            pat[2 * j] = c
            q[2 + 2 * j] = c * rng.uniform(0.01, 0.3)
            qd[2 + 2 * j] = rng.normal() * 0.5
            pat[2 * j + 1] = float(rng.integers(-1, 2))
            if pat[2 * j + 1]:
                qd[1 + 2 * j] = pat[2 * j + 1] * rng.uniform(0.01, 0.5)
            else:
                zero_s[j] = rng.random() < 0.5
    if ch.nb:
        q[0], qd[0] = rng.normal() * 0.05, rng.normal() * 0.2
    return pat, q, qd, zero_psi, zero_s


# ---------------------------------------------------------------------------------------------
# the mechanics
# ---------------------------------------------------------------------------------------------
def test_mechanics_are_the_existing_references_where_no_drum_overhangs():
    """Without overlap (a body on its plinth, slips small), the point-on-line constraints give the existing
    reference's accelerations, rates after an impact and forces (its couple split into the corner forces)."""
    from rockcli.reference.friction_mechanics import FrictionChain

    rng = np.random.default_rng(2)
    for _ in range(150):
        n = int(rng.integers(1, 4))
        blocks = [(rng.uniform(0.15, 0.5), rng.uniform(0.15, 0.7), rng.uniform(0.5, 3)) for _ in range(n)]
        base = (2.0, 30.0, 1.0) if rng.random() < 0.5 else None
        mus = list(rng.uniform(0.2, 1, n))
        ch, fc = DrumChain(blocks, mus, base), FrictionChain(blocks, mus, base)
        pat = [float(rng.integers(-1, 2)) for _ in range(2 * n)]
        q, qd = np.zeros(1 + 2 * n), rng.normal(size=1 + 2 * n)
        for j in range(n):
            q[1 + 2 * j] = rng.uniform(-0.1, 0.1)
            q[2 + 2 * j] = rng.uniform(-0.3, 0.3) if pat[2 * j] else 0.0
            qd[2 + 2 * j] *= pat[2 * j] != 0.0
            qd[1 + 2 * j] *= pat[2 * j + 1] != 0.0
        qd[0] *= base is not None
        ag = rng.normal() * 3
        X, V = ch.maximal(pat, q, qd)
        assert np.allclose((X, V), fc.maximal(pat, q, qd), rtol=0, atol=1e-13)
        for level in ("a", "v"):
            F = ch.loads(X, V, ag) if level == "a" else None
            A, fr = ch.solve(pat, q, X, V, F, level)
            A2, lam, kinds = fc.solve(pat, X, V, F, level)
            fr2 = fc.forces(pat, lam, kinds)
            assert np.allclose(A, A2, rtol=1e-11, atol=1e-11)
            for j in range(n):
                N, T, Mc = fr2[j]
                assert fr[j, :2] == pytest.approx((N, T), rel=1e-10, abs=1e-11)
                if pat[2 * j] == 0.0:
                    b = blocks[j][0]
                    assert fr[j, 2:] == pytest.approx((N / 2 - Mc / (2 * b), N / 2 + Mc / (2 * b)), rel=1e-9,
                                                      abs=1e-11)


def test_constraint_rows_are_the_derivatives_of_the_gaps_and_slips():
    """On random states of drums slid past each other (faces at the ends of the overlap, pivots of kind A and B):
    every held gap is 0 and every slip row reads ``s``; ``row . a + bias`` is the second derivative of the gap or slip
    along a motion (finite differences), and the slip's is the coordinate's own acceleration."""
    rng = np.random.default_rng(1)
    dt = 1e-4
    checked_b = 0
    for _ in range(120):
        n = int(rng.integers(2, 5))
        _, ch = _random_chain(rng, n, base=rng.random() < 0.5)
        pat = [float(rng.integers(-1, 2)) for _ in range(2 * n)]
        q, qd, qdd = np.zeros(1 + 2 * n), rng.normal(size=1 + 2 * n), rng.normal(size=1 + 2 * n)
        for j in range(n):
            q[1 + 2 * j] = rng.uniform(-0.7, 0.7) * (ch.b[j] + ch.blow[j]) if j else rng.normal() * 0.1
            q[2 + 2 * j] = rng.uniform(-0.3, 0.3) if pat[2 * j] else 0.0
            qd[2 + 2 * j] *= pat[2 * j] != 0.0
            qdd[2 + 2 * j] *= pat[2 * j] != 0.0
        if not ch.nb:
            q[0] = qd[0] = qdd[0] = 0.0
        near = any(pat[2 * j] and abs(pat[2 * j] * q[1 + 2 * j] + ch.b[j] - ch.blow[j]) < 1e-2 for j in range(n))
        if near:  # the kind would switch inside the finite-difference stencil
            continue

        def at(t):
            return ch.maximal(pat, q + qd * t + 0.5 * qdd * t * t, qd + qdd * t)

        X, V = at(0.0)
        Xp, Xm = at(dt)[0], at(-dt)[0]
        A = (Xp - 2 * X + Xm) / dt ** 2
        assert np.allclose((Xp - Xm) / (2 * dt), V, atol=1e-5)
        for j in range(n):
            checked_b += ch.kind_b(j, pat[2 * j], q[1 + 2 * j])
            rows = ch.rows(j, pat[2 * j], q[1 + 2 * j], X, V)
            for name, (val, row, bias) in rows.items():
                assert abs(val - (q[1 + 2 * j] if name == "t" else 0.0)) < 1e-12
                vals = [ch.rows(j, pat[2 * j], q[1 + 2 * j], *at(t))[name][0] for t in (-dt, dt)]
                fd = (vals[0] - 2 * val + vals[1]) / dt ** 2
                assert row @ A + bias == pytest.approx(fd, abs=2e-4 * (1 + abs(fd)))
                if name == "t":
                    assert fd == pytest.approx(qdd[1 + 2 * j], abs=2e-4 * (1 + abs(fd)))
    assert checked_b > 20


def test_mechanics_are_the_drivers_on_drums_slid_past_each_other():
    """The same accelerations and corner forces as the driver's Kane equations (kernels/chain.py, another
    derivation) on random states with overhanging drums and pivots of kind B."""
    from rockcli.kernels import chain as kch
    from rockcli.kernels.contact import face_corners, solve_pattern
    from rockcli.solve.slide import chain_parameters

    rng = np.random.default_rng(3)
    for _ in range(80):
        n = int(rng.integers(2, 5))
        col, ch = _random_chain(rng, n)
        cp = chain_parameters(col, tuple(ch.mu))
        pat, q, qd, _, _ = _random_state(rng, ch, closed_share=0.3)
        for j in range(n):  # the driver's state carries a rate for every slip; a face has none of its angle
            qd[2 + 2 * j] *= pat[2 * j] != 0.0
        y = np.zeros(2 + 4 * n)
        for j in range(n):
            y[2 + 4 * j:6 + 4 * j] = q[1 + 2 * j], qd[1 + 2 * j], q[2 + 2 * j], qd[2 + 2 * j]
        ag = rng.normal() * 3
        ws, frc = kch.workspace(n), np.zeros((n, 3))
        nf = solve_pattern(cp, np.array(pat), y, ag, ws, frc)
        X, V, A, fr, rates, _ = dp.pattern_solution(ch, pat, q, qd, ag)
        for k in range(nf):
            col_ = int(ws[0][k])
            idx = 1 + 2 * ((col_ - 2) // 4) + (1 if (col_ - 2) % 4 == 2 else 0)
            assert rates[idx] == pytest.approx(ws[12][k], rel=1e-9, abs=1e-9)
        for j in range(n):
            assert fr[j, :2] == pytest.approx(frc[j, :2], rel=1e-9, abs=1e-9)
            if pat[2 * j] == 0.0:
                assert fr[j, 2:] == pytest.approx(face_corners(cp, j, q[1 + 2 * j], frc[j, 0], frc[j, 2]), rel=1e-8,
                                                  abs=1e-9)


# ---------------------------------------------------------------------------------------------
# the pattern search
# ---------------------------------------------------------------------------------------------
def _consistent(ch, pat, q, qd, ag, zero_psi, zero_s, level, V0, method):
    cands, _ = dp.candidates(ch, pat, q, qd, ag, zero_psi, zero_s, level, V0, method)
    ok = set()
    for c in cands:
        try:
            sol = dp.pattern_solution(ch, c, q, qd, ag, level, V0)
        except np.linalg.LinAlgError:
            continue
        if dp.margin(ch, c, sol[3], sol[4], zero_psi, zero_s, level == "v", sol[5])[0] >= -dp.TOL:
            ok.add(tuple(c))
    return ok


@pytest.mark.parametrize("level", ["a", "v"])
def test_the_mixed_integer_problem_finds_exactly_the_enumerations_patterns(level):
    """On random events of 2 and 3 drums, the patterns that meet every condition are the same whether every
    candidate is tried or the mixed-integer problem finds them."""
    rng = np.random.default_rng(5 if level == "a" else 6)
    sizes = []
    for _ in range(16):
        _, ch = _random_chain(rng, int(rng.integers(2, 4)), base=rng.random() < 0.3)
        pat, q, qd, zero_psi, zero_s = _random_state(rng, ch)
        V0 = None
        if level == "v":
            V0 = ch.maximal(pat, q, qd)[1] + rng.normal(size=ch.N) * 0.3
            zero_s = [True] * ch.n
        ag = rng.normal() * 5
        found = [_consistent(ch, pat, q, qd, ag, zero_psi, zero_s, level, V0, m) for m in ("enum", "milp")]
        assert found[0] == found[1]
        sizes.append(len(found[0]))
    assert 0 in sizes and sum(s >= 1 for s in sizes) >= 8


def test_both_searches_at_the_sliding_threshold_of_a_joint():
    """Three drums at rest, the ground a hair below and above the sliding threshold of the weakest joint (at rest
    ``T/N = ag/g`` at every contact): below, sticking is the only pattern; above, the drums above that joint sliding
    back; both searches find the same, and the contact law takes the slide."""
    col = DrumColumn(((1.0, 0.8), (0.9, 0.7), (0.8, 0.6)))
    ch = chain_of(col, (0.9, 0.25, 0.8))
    pat = [0.0] * 6
    q = qd = np.zeros(7)
    slide = (0.0, 0.0, 0.0, -1.0, 0.0, 0.0)
    for f, want in ((1 - 1e-6, {tuple(pat)}), (1 + 1e-6, {slide})):
        sets = [_consistent(ch, pat, q, qd, 0.25 * G * f, [True] * 3, [True] * 3, "a", None, m) for m in
                ("enum", "milp")]
        assert sets[0] == sets[1] == want
    best, m, _ = dp.choose(ch, pat, q, qd, 0.25 * G * (1 + 1e-6), [True] * 3, [True] * 3, method="milp")
    assert tuple(best) == slide and m >= -dp.TOL


def test_the_problem_that_crashed_highs_without_presolve_is_solved():
    """A mixed-integer problem of a 3-drum impact on which HiGHS (in SciPy) crashed the process with presolve off
    (scipy issue 22188): the reference keeps presolve on, and HiGHS answers it (infeasible), in a child process so
    that a crash fails this test instead of ending the session."""
    import subprocess
    import sys
    from pathlib import Path

    assert dp.PRESOLVE
    code = ("import numpy as np; from scipy.optimize import milp, LinearConstraint, Bounds; "
            f"d = np.load({str(Path(__file__).parent / 'data' / 'milp_crash.npz')!r}); "
            "r = milp(d['c'], constraints=LinearConstraint(d['A'], d['lb'], d['ub']), integrality=d['integ'], "
            "bounds=Bounds(d['lo'], d['hi']), options={'presolve': True}); print(r.status)")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and p.stdout.strip() == "2"


# ---------------------------------------------------------------------------------------------
# whole runs
# ---------------------------------------------------------------------------------------------
SCENES_12 = [
    (Block.from_dimensions(1.5, 0.5), RickerSymmetric(0.4 * G, 0.6), 0.6),
    (Block.from_dimensions(1.5, 0.5), OneSine(0.3 * G, 1.0), 0.25),
    (Stack(Block.from_dimensions(1.4, 0.45), Plinth(0.6, 0.8)), RickerSymmetric(0.5 * G, 0.8), (0.5, 0.7)),
    (Stack(Block.from_dimensions(1.0, 0.45), Plinth(0.6, 0.8)), OneSine(0.3 * G, 0.8), (0.3, 0.7)),
]


@pytest.mark.parametrize("k", range(len(SCENES_12)))
def test_one_drum_and_a_body_on_its_plinth_are_the_existing_reference(k):
    """A Block and a Stack run by the drums' reference: the existing reference's verdict, counts and peaks, to its
    tolerance (the same events and rules, other mechanics and another pattern search)."""
    from rockcli.reference.friction import reference_friction

    body, exc, mu = SCENES_12[k]
    a = reference_friction(body, exc, mu)
    b = reference_drums(body, exc, mu)
    assert a.verdict == b.verdict
    assert (a.n_slips, a.n_impacts, a.toppled, a.slid_off) == (b.n_slips, b.n_impacts, b.toppled, b.slid_off)
    assert b.psi_max == pytest.approx(a.psi_max, abs=1e-9)
    assert b.s_max == pytest.approx(a.s_max, abs=1e-10)
    assert b.s_end == pytest.approx(a.s_end, abs=1e-10)


def test_energy_never_rises_across_impacts():
    """Three drums, the base rocking (10 impacts, each with the joints above closed: impulses at every contact) and the
    top one sliding on a capital wider than the drum under it: every impact and rest projection takes energy out, to
    rounding."""
    col = DrumColumn(((0.6, 0.5), (0.5, 0.45), (0.45, 0.7)))
    q = reference_drums(col, RickerSymmetric(0.5 * G, 0.5), (0.8, 0.35, 0.3), record_energy=True)
    assert sum(q.n_impacts) >= 10 and q.n_slips[2] > 0 and len(q.energy_rises) >= sum(q.n_impacts)
    assert max(q.energy_rises) <= 1e-12 * G * sum(h * w for h, w in col.drums)


@pytest.mark.parametrize("drums,mu", [
    (((1.2, 0.8), (1.0, 0.7), (0.9, 0.6)), (0.9, 0.8, 0.9)),  # tapering: the base rocks first
    (((1.2, 0.8), (1.0, 0.7), (0.9, 0.6)), (0.9, 0.2, 0.9)),  # joint 1 slides first
    (((0.5, 1.0), (0.4, 0.9), (1.4, 0.35)), (0.9, 0.9, 0.9)),  # a slender top drum on squat ones: joint 2 rocks
    (((0.8, 0.6), (0.5, 0.9), (0.6, 0.5), (0.7, 0.5)), (0.7, 0.9, 0.9, 0.3)),  # a capital; the top slides
])
def test_static_thresholds_are_where_the_reference_first_moves(drums, mu):
    """Under a slow ramp of ground acceleration the column first moves at ``g min_j min(mu_j, tan alpha_j)``
    (DrumColumn.static_thresholds: everything above joint ``j`` as one body about the corner of its contact), at the
    joint that minimises it, opening where ``tan alpha_j`` is the smaller and sliding where ``mu_j`` is."""
    col = DrumColumn(drums)
    th = col.static_thresholds()
    lim = [min(m, t) for m, t in zip(mu, th)]
    j = int(np.argmin(lim))
    slope = 2.0  # m/s^3
    dt = 0.01
    t = np.arange(0.0, 1.2 * lim[j] * G / slope, dt)
    q = reference_drums(col, Record(slope * t, dt, "ramp"), mu, horizon=0.0)
    firsts = [min(a, b) for a, b in zip(np.nan_to_num(q.t_uplift, nan=np.inf), np.nan_to_num(q.t_slide, nan=np.inf))]
    assert int(np.argmin(firsts)) == j
    assert firsts[j] == pytest.approx(lim[j] * G / slope, rel=1e-9)
    opens = math.isfinite(q.t_uplift[j]) and q.t_uplift[j] == firsts[j]
    assert opens == (th[j] < mu[j])


@pytest.mark.parametrize("seed,n", [(3000004, 2), (3000001, 3), (3000006, 3), (3000009, 3), (3000000, 4)])
def test_the_driver_agrees_with_the_reference_on_columns(seed, n):
    """Random columns of 3 and 4 drums (tests/synthetic.py ``random_drum_scene``; benchmarks/bench_drums_reference.py
    runs many more): the same verdict and, where the column stands, the same slip and impact counts, peaks to 1e-8 of
    the slenderness and residual offsets to 1e-9 m (both at rtol 1e-10; found 1e-11 and 1e-15 m); where it falls, the
    same joint."""
    from synthetic import random_drum_scene

    from rockcli.solve.drums import DrumRun
    from rockcli.solve.slide import simulate_friction

    col, exc, mu, iso = random_drum_scene(seed, n)
    r = simulate_friction(col, exc, mu, iso, rtol=1e-10)
    q = reference_drums(col, exc, mu, iso, record_energy=True)
    assert r.verdict == q.verdict
    assert max(q.energy_rises, default=0.0) <= 1e-12 * G * sum(h * w for h, w in col.drums)
    if q.verdict == "overturned":
        assert r.toppled == col.joint_names()[q.toppled]
        return
    for j, p in enumerate(r.interfaces):
        assert (p.n_slips, p.n_impacts) == (q.n_slips[j], q.n_impacts[j])
        assert p.psi_max == pytest.approx(q.psi_max[j], abs=1e-8 * p.alpha)
    assert DrumRun(col, r, None).residual_offsets_m == pytest.approx(q.residual_offsets, abs=1e-9)


def test_the_drivers_friction_opposes_every_slip():
    """Along the driver's history every sliding contact that presses (``N > 0``, by the reference's mechanics at the
    driver's state) moves the way its friction opposes (``sl s' >= 0``): else friction does positive work. The
    scene: three drums under a Ricker pulse, where the reference stands and the driver had the top drum slide 0.5 m
    backwards, off its drum, at 3 m/s (t = 2.2-2.46 s), its friction pushing it: a slide entered at a slip rate of
    -2e-16 (after an impact) went on backwards, unseen by the slip-stop event; now such a slip stops at the start of
    the step and the contact law chooses again (kernels.chain_step.state_events), and the column stands."""
    from rockcli.solve.slide import simulate_friction

    col = DrumColumn(((1.0, 0.6), (0.8, 0.5), (0.7, 0.5)))
    exc = RickerSymmetric(0.4 * G, 0.6)
    r = simulate_friction(col, exc, 0.6, rtol=1e-10, history=True)
    ch = chain_of(col, 0.6)
    n = 3
    worst = 0.0
    for row in r.history:
        pat, y = [float(x) for x in row[3:3 + 2 * n]], row[3 + 2 * n:]
        wrong = [j for j in range(n) if pat[2 * j + 1] * y[3 + 4 * j] < -1e-9]
        if not wrong:
            continue
        q, qd = np.zeros(1 + 2 * n), np.zeros(1 + 2 * n)
        for j in range(n):
            q[1 + 2 * j], qd[1 + 2 * j], q[2 + 2 * j], qd[2 + 2 * j] = y[2 + 4 * j:6 + 4 * j]
        fr = dp.pattern_solution(ch, pat, q, qd, exc.acceleration(row[0]))[3]
        for j in wrong:
            if fr[j, 0] > 0.0:
                worst = min(worst, pat[2 * j + 1] * qd[1 + 2 * j])
    assert worst >= -1e-9
    assert r.verdict == "survives"
