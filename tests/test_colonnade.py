"""``cap_ratio`` / ``--cap-ratio GAMMA_C``: a capped colonnade on a rigid foundation (rockcli.models.colonnade,
docs/physics-colonnade.md), against an independent reference that assembles the equation of motion from
the separate bodies (each column a rigid rectangle given by Gauss points, the beam a translating mass on
whichever top corners are highest), and the verdict-only shortcuts re-checked."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp

from rockcli.models.colonnade import colonnade_restitution, frequency_factor
from rockcli.errors import RockcliInputError
from rockcli.models import Block, Rigid
from rockcli.pulses import make_pulse
from rockcli.solve import simulate
from rockcli.io.units import G
from test_verdict_paths import _compare_modes, random_scenes

_GL = np.array([-1.0, 1.0]) / math.sqrt(3.0)  # 2-point Gauss-Legendre: exact for the quadratic mass moments


class Colonnade:
    """N columns (mass 1 each) and a beam of mass ``N gamma_c``, as separate bodies on one angle theta.

    Column points (Gauss points of the rectangle, equal weights) rotate about the pivot corner
    ``s b`` (s = sign(theta)); the beam rests on the highest top corner of each column and translates
    with it (found by comparing both top corners, not assumed). Lagrange with the generalized
    coordinate theta: ``M theta'' + M'/2 theta'^2 = -V' + Q`` with ``M = sum m |dr/dtheta|^2``.
    """

    def __init__(self, block: Block, gamma_c: float, N: int = 3):
        self.b, self.h, self.N, self.mb = block.b, block.h, N, N * gamma_c
        X, Y = np.meshgrid(self.b * _GL, self.h + self.h * _GL)
        self.pts = np.stack([X.ravel(), Y.ravel()], axis=1)  # column points at rest, base centre at 0
        self.w = np.full(self.pts.shape[0], 1.0 / self.pts.shape[0])
        self.pts_f = [tuple(map(float, q)) for q in self.pts]
        self.w_f = [float(v) for v in self.w]

    def _rotate(self, pts, theta):
        """Points of a column rotated by theta (clockwise, theta > 0 about the right corner) and d/dtheta."""
        s = 1.0 if theta >= 0 else -1.0
        c, sn = math.cos(theta), math.sin(theta)
        rel = pts - np.array([s * self.b, 0.0])
        x = s * self.b + rel[:, 0] * c + rel[:, 1] * sn
        y = -rel[:, 0] * sn + rel[:, 1] * c
        dx = -rel[:, 0] * sn + rel[:, 1] * c
        dy = -rel[:, 0] * c - rel[:, 1] * sn
        return x, y, dx, dy

    def _beam(self, theta):
        tops = np.array([[-self.b, 2 * self.h], [self.b, 2 * self.h]])
        x, y, dx, dy = self._rotate(tops, theta)
        k = 0 if y[0] > y[1] else 1 if y[1] > y[0] else (0 if theta >= 0 else 1)  # (a tie only at theta = 0)
        return x[k] - tops[k, 0], y[k] - 2 * self.h, dx[k], dy[k]  # beam displacement (from the contact corner)

    def terms(self, theta):
        """``(M, V', Q/ag)`` at theta (per column mass), summed over the bodies' points in plain floats."""
        s = 1.0 if theta >= 0 else -1.0
        c, sn = math.cos(theta), math.sin(theta)
        M = Vp = Qa = 0.0
        for (px, py), w in zip(self.pts_f, self.w_f):
            rx, ry = px - s * self.b, py
            dx, dy = -rx * sn + ry * c, -rx * c - ry * sn
            M += w * (dx * dx + dy * dy)
            Vp += w * dy
            Qa -= w * dx
        _, _, bdx, bdy = self._beam(theta)
        N = self.N
        return N * M + self.mb * (bdx * bdx + bdy * bdy), G * (N * Vp + self.mb * bdy), N * Qa - self.mb * bdx

    def rhs(self, ag):
        """theta'' of Lagrange's equation; M is constant (checked in the first test), so no M' term."""
        def f(t, y):
            th, thd = y
            M, Vp, Qa = self.terms(th)
            return [thd, (Qa * ag(t) - Vp) / M]
        return f


def test_between_impacts_it_is_the_column_with_a_slower_p():
    rng = np.random.default_rng(5)
    for _ in range(50):
        block = Block(rng.uniform(0.5, 10.0), math.radians(rng.uniform(3, 30)))
        gc = rng.uniform(0.0, 3.0)
        ref = Colonnade(block, gc)
        th = rng.uniform(-1.2, 1.2) * block.alpha
        ag = rng.normal() * G * math.tan(block.alpha)
        M, Vp, Qa = ref.terms(th)
        s = 1.0 if th >= 0 else -1.0
        A = s * block.alpha - th
        want = -block.p ** 2 * frequency_factor(gc) * (math.sin(A) + ag / G * math.cos(A))
        assert (Qa * ag - Vp) / M == pytest.approx(want, rel=1e-12, abs=1e-12 * block.p ** 2)
        # the inertia about the pivots does not depend on theta: (N 4/3 + 4 N gamma_c) R^2 per column mass
        assert M == pytest.approx(ref.terms(0.37 * th)[0], rel=1e-13)
        assert M == pytest.approx(ref.N * block.R ** 2 * (4 / 3 + 4 * gc), rel=1e-13)
    assert frequency_factor(0.5) == pytest.approx(2 / 2.5) and frequency_factor(1.0) == pytest.approx(3 / 4)


def test_200_random_free_flight_arcs_match_the_multibody_reference():
    """Random starts (tilt, velocity) under random sine pulses, up to the first impact: the kernel's
    history rows against the reference integrated by SciPy (DOP853, rtol 1e-11), within 1e-8 rad."""
    rng = np.random.default_rng(2013)
    worst = 0.0
    n = impacts = 0
    while n < 200:
        block = Block(rng.uniform(0.5, 8.0), math.radians(rng.uniform(4, 20)))
        gc = rng.uniform(0.05, 2.0)
        th0 = rng.uniform(0.2, 0.9) * block.alpha * rng.choice([-1.0, 1.0])
        thd0 = rng.normal() * 0.3 * block.p * block.alpha
        pulse = make_pulse("sine", rng.uniform(-1.0, 1.0) * G * math.tan(block.alpha), rng.uniform(0.3, 3.0))
        res = simulate(block, Rigid(), pulse, history=True, theta0=th0, theta_dot0=thd0, cap_ratio=gc, rtol=1e-10,
                       tail=0.0)
        h = res.history
        zero = np.flatnonzero(h.theta[1:] == 0.0)
        if zero.size == 0 or res.overturned:
            continue
        k = zero[0] + 1  # rows before the first impact
        ref = Colonnade(block, gc)

        def hit(t, y):
            return y[0]
        hit.terminal = True
        t_end = min(h.t[k], 1.0)  # the arc, or its first second
        sol = solve_ivp(ref.rhs(lambda t: float(pulse.acceleration(t))), (0.0, t_end * (1 + 1e-6) + 1e-9),
                        [th0, thd0], method="DOP853", rtol=1e-11, atol=1e-13, dense_output=True, events=hit)
        if t_end == h.t[k]:
            assert sol.t_events[0].size, "the reference must reach the impact"
            assert h.t[k] == pytest.approx(sol.t_events[0][0], abs=1e-8)
            impacts += 1
        rows = h.t[:k] <= sol.t[-1]
        worst = max(worst, float(np.max(np.abs(sol.sol(h.t[:k][rows])[0] - h.theta[:k][rows]))))
        n += 1
    assert worst < 1e-8
    assert impacts > 50  # many arcs end at their impact within the first second


@pytest.mark.parametrize("alpha", [0.1, 0.2, 0.3])
@pytest.mark.parametrize("gc", [0.0, 0.5, 1.0, 3.0])
def test_the_impact_map_keeps_the_generalized_momentum_of_the_new_mechanism(alpha, gc):
    """Before the impact the columns turn about their right corners and the beam rides on the top-left
    corners; after it, about the left corners with the beam on the top-right ones. The momentum
    conjugate to theta of the mechanism after the impact, sum m v . dr/dtheta (its virtual velocities), is
    kept: the impulses at the new pivots and at the new beam contacts do no virtual work in it."""
    block = Block(2.0, alpha)
    ref = Colonnade(block, gc)
    thd1 = -0.7
    eta = colonnade_restitution(alpha, gc)
    eps = 1e-300
    x1, y1, dx1, dy1 = ref._rotate(ref.pts, +eps)  # velocities before: d r/d theta (right pivot) times thd1
    _, _, bdx1, bdy1 = ref._beam(+eps)
    x2, y2, dx2, dy2 = ref._rotate(ref.pts, -eps)  # the new mechanism (left pivot)
    _, _, bdx2, bdy2 = ref._beam(-eps)
    assert (bdx1, bdy1) != (bdx2, bdy2)  # the beam's contact moves to the other top corners

    def momentum(thd, dx, dy, bdx, bdy):
        return thd * (ref.N * np.sum(ref.w * (dx * dx2 + dy * dy2)) + ref.mb * (bdx * bdx2 + bdy * bdy2))

    assert momentum(eta * thd1, dx2, dy2, bdx2, bdy2) == pytest.approx(momentum(thd1, dx1, dy1, bdx1, bdy1), rel=1e-12)
    published = math.sqrt(((1 - 1.5 * math.sin(alpha) ** 2 + 3 * gc * math.cos(2 * alpha)) / (1 + 3 * gc)) ** 2)
    assert eta == pytest.approx(published, rel=1e-14)
    if gc == 0.0:
        assert eta == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, rel=1e-14)
    # the kinetic energy falls
    T1 = thd1 ** 2 * (ref.N * np.sum(ref.w * (dx1 ** 2 + dy1 ** 2)) + ref.mb * (bdx1 ** 2 + bdy1 ** 2))
    T2 = (eta * thd1) ** 2 * (ref.N * np.sum(ref.w * (dx2 ** 2 + dy2 ** 2)) + ref.mb * (bdx2 ** 2 + bdy2 ** 2))
    assert T2 < T1


def test_runs_cap_ratio_zero_is_the_column_and_the_map_is_applied():
    block = Block.from_degrees(3.03, 10.56)
    pulse = make_pulse("ricker-sym", 2.0 * G * math.tan(block.alpha), 1.0)
    a = simulate(block, Rigid(), pulse, history=True)
    b = simulate(block, Rigid(), pulse, history=True, cap_ratio=0.0)
    assert a.summary() == b.summary() and np.array_equal(a.history.theta, b.history.theta)
    c = simulate(block, Rigid(), pulse, history=True, cap_ratio=1.0)
    h = c.history
    i = np.flatnonzero((h.t[1:] == h.t[:-1]) & (h.theta[1:] == 0.0))
    moving = h.theta_dot[i + 1] != 0.0
    assert i.size >= 2
    assert np.allclose(h.theta_dot[i + 1][moving], colonnade_restitution(block.alpha, 1.0) * h.theta_dot[i][moving],
                       rtol=1e-14)
    # the same uplift threshold as the column: just below and just above g tan(alpha)
    for f, lifted in ((0.999, False), (1.001, True)):
        p = make_pulse("sine", f * G * math.tan(block.alpha), 1.0)
        assert (simulate(block, Rigid(), p, cap_ratio=1.0).verdict != "no_uplift") == lifted
    # with a given restitution the colonnade is the solitary column whose p is the colonnade's
    gc, E = 0.5, 0.9
    twin = Block(block.R / frequency_factor(gc), block.alpha)
    r1 = simulate(block, Rigid(), pulse, cap_ratio=gc, restitution=E)
    r2 = simulate(twin, Rigid(), pulse, restitution=E)
    assert r1.verdict == r2.verdict and r1.theta_max == pytest.approx(r2.theta_max, rel=1e-7)


def test_cap_ratio_is_checked():
    block, pulse = Block(1.0, 0.2), make_pulse("sine", 3.0, 1.0)
    for bad in (-0.1, math.nan, 1e3):
        with pytest.raises(RockcliInputError, match="cap_ratio"):
            simulate(block, Rigid(), pulse, cap_ratio=bad)
    from rockcli.cli import main

    out = CliRunner().invoke(main, ["simulate", "--R", "1", "--alpha", "12", "--pulse", "sine:ap=0.3,Tp=1",
                                    "--cap-ratio", "-0.5"])
    assert out.exit_code == 2 and "--cap-ratio must lie between 0 and 100" in out.output
    assert "Traceback" not in out.output
    ok = CliRunner().invoke(main, ["simulate", "--R", "1", "--alpha", "12", "--pulse", "sine:ap=0.3,Tp=1",
                                   "--cap-ratio", "0.5", "--json"])
    got = json.loads(ok.output)
    assert got["cap_ratio"] == 0.5 and got["p_colonnade_radps"] == pytest.approx(got["p_radps"] * math.sqrt(0.8))


def test_verdict_only_equals_full_history_for_random_colonnades():
    jobs = [j for j in random_scenes(3000, 2013) if isinstance(j[1], Rigid)]
    rng = np.random.default_rng(2013)
    caps = [float(rng.choice([0.0, rng.uniform(0.0, 3.0)])) for _ in jobs]
    early, verdict_only, mismatches = _compare_modes(jobs, cap_ratio=caps)
    assert mismatches == []
    verdicts = [r.verdict for r in verdict_only]
    assert min(verdicts.count(v) for v in ("rocked", "overturned")) > 300 and verdicts.count("no_uplift") > 20
    assert sum(not r.peak_final for r in early) > 50


def test_cli_spectrum_and_assess_run_colonnades(tmp_path):
    import csv

    from rockcli.cli import main
    from rockcli.spectra import Family, parse_isolation

    runner = CliRunner()
    path = tmp_path / "map.csv"
    out = runner.invoke(main, ["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "2:6:3", "--ap", "2:6:3",
                               "--csv", str(path), "--full-peaks", "--cap-ratio", "0.5"])
    assert out.exit_code == 0, out.output
    assert "gamma_c = 0.5" in out.output
    fam = Family(math.radians(10.0), "ricker-sym", parse_isolation("none"))
    for row in csv.DictReader(path.open()):
        assert float(row["cap_ratio"]) == 0.5
        r = simulate(*fam.scene(float(row["wp_over_p"]), float(row["ap_over_g_tan_alpha"])), cap_ratio=0.5)
        assert float(row["theta_max_over_alpha"]) == pytest.approx(r.theta_max_over_alpha, rel=1e-5)
    path = tmp_path / "a.csv"
    out = runner.invoke(main, ["assess", "column", "nemea", "--records", "kobe-1995-takarazuka-000", "--excitation",
                               "pulse", "--isolation", "none", "--no-margin", "--cap-ratio", "1", "--csv", str(path)])
    assert out.exit_code == 0, out.output
    rows = list(csv.DictReader(path.open()))
    assert rows and all(float(r["cap_ratio"]) == 1.0 for r in rows)
