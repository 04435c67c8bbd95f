"""``cap_ratio`` on an isolated base: a capped colonnade on linear bearings (rockcli.models.colonnade,
docs/physics-colonnade.md) against an independent multi-body reference.

The reference takes the bodies one by one (each column a rigid rectangle given by Gauss points, the
beam a translating mass on whichever top corners are highest, the base a mass on the bearings) and
writes d'Alembert's principle for the two generalized coordinates ``u`` and theta: ``sum m r'' . dr/dq
= Q_q``. Its impact map keeps the whole system's horizontal momentum and the momentum conjugate to
theta of the mechanism after the impact, both summed from the bodies' velocity fields. The kernel runs
the colonnade as the solitary block of semi-diagonal ``R_eff`` and mass ratio ``gamma_eff``: these
tests are the proof that the two are the same.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import solve_ivp

from rockcli.models.colonnade import colonnade_restitution, effective_gamma, frequency_factor, impact_ratio_on_base
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.pulses import make_pulse
from rockcli.solve import simulate
from rockcli.io.units import G
from test_colonnade import Colonnade
from test_verdict_paths import _compare_modes, random_scenes


class IsolatedColonnade(Colonnade):
    """N columns (mass 1 each), a beam of mass ``N gamma_c`` and a base of mass ``m_b`` on linear bearings
    (``k_b = M omega_b^2``, ``c_b = 2 xi omega_b M``, ``M`` the whole moving mass), where ``gamma`` is
    the mass of columns and beam over ``M``."""

    def __init__(self, block, gamma_c, gamma, omega_b=0.0, xi=0.0, N=3):
        super().__init__(block, gamma_c, N)
        self.M = N * (1.0 + gamma_c) / gamma
        self.wb, self.xi = omega_b, xi
        self._arms = {}

    def points(self, theta, side=None):
        """Masses and ``(dx, dy, ddx, ddy)`` (first and second theta-derivatives of the positions) of every
        column point and of the beam's contact corner, rotating about the corners ``side`` (default
        sign(theta)); the beam sits on the highest top corner (on the side given, its diagonal)."""
        s = side if side is not None else (1.0 if theta >= 0 else -1.0)
        c, sn = math.cos(theta), math.sin(theta)
        tops = np.array([[-self.b, 2 * self.h], [self.b, 2 * self.h]])
        if side is None:
            ys = [-(p[0] - s * self.b) * sn + p[1] * c for p in tops]
            k = 0 if ys[0] > ys[1] else 1 if ys[1] > ys[0] else (0 if s > 0 else 1)
        else:
            k = 0 if s > 0 else 1  # at theta = 0: the corner diagonally opposite the pivot
        if (s, k) not in self._arms:  # the masses and their arms about the pivot depend on the pivot and corner only
            pts = np.vstack([self.pts, tops[k:k + 1]])
            self._arms[s, k] = (np.append(self.N * self.w, self.mb), pts[:, 0] - s * self.b, pts[:, 1])
        m, rx, ry = self._arms[s, k]
        dx, dy = -rx * sn + ry * c, -rx * c - ry * sn
        ddx, ddy = -rx * c - ry * sn, rx * sn - ry * c
        return m, dx, dy, ddx, ddy

    def rhs(self, ag, s):
        """(theta, theta', u, u')' while rocking on corner ``s``: the 2x2 system of d'Alembert's principle."""
        def f(t, y):
            th, thd, u, ud = y
            m, dx, dy, ddx, ddy = self.points(th, s)
            a = ag(t)
            Fb = -self.M * (self.wb ** 2 * u + 2 * self.xi * self.wb * ud)
            Muu, Mut, Mtt = self.M, np.sum(m * dx), np.sum(m * (dx * dx + dy * dy))
            qu = -self.M * a + Fb - np.sum(m * ddx) * thd ** 2
            qt = -np.sum(m * (G * dy + a * dx)) - np.sum(m * (dx * ddx + dy * ddy)) * thd ** 2
            det = Muu * Mtt - Mut * Mut
            return [thd, (Muu * qt - Mut * qu) / det, ud, (Mtt * qu - Mut * qt) / det]
        return f

    def impact(self, s_old, thd1, ud1, restitution=None):
        """``(theta_dot+, u_dot+)`` from the momenta of the bodies' velocity fields before the impact taken
        with the virtual velocities of the mechanism after it (pivots ``-s_old``). A given ``restitution``
        adds the impulsive couple that makes the ratio on the ground ``E``:
        ``C = (E J - K) theta_dot-`` with ``J``, ``K`` the theta-theta terms after/after and before/after."""
        m, dx1, dy1, _, _ = self.points(0.0, s_old)
        _, dx2, dy2, _, _ = self.points(0.0, -s_old)
        vx, vy = ud1 + dx1 * thd1, dy1 * thd1
        p_u = self.M * ud1 + np.sum(m * dx1) * thd1  # the base moves with ud1 and carries the rest of M
        p_t = np.sum(m * (vx * dx2 + vy * dy2))
        J, K = np.sum(m * (dx2 * dx2 + dy2 * dy2)), np.sum(m * (dx1 * dx2 + dy1 * dy2))
        if restitution is not None:
            p_t += (restitution * J - K) * thd1
        Mut = np.sum(m * dx2)
        ud2, thd2 = np.linalg.solve([[self.M, Mut], [Mut, J]], [p_u, p_t])
        return thd2, ud2


def _scene(rng):
    block = Block(rng.uniform(0.5, 8.0), math.radians(rng.uniform(4, 20)))
    gc = rng.uniform(0.05, 2.0)
    gamma = rng.uniform(0.05, 0.95)
    iso = LinearIsolation(rng.uniform(0.5, 4.0), rng.uniform(0.0, 0.3), gamma)
    return block, gc, iso


@pytest.mark.parametrize("restitution", [None, 0.8, 1.0])
def test_the_impact_map_is_the_isolated_map_of_the_effective_block(restitution):
    """At random states the bodies' momentum balance gives the kernel's map: ``theta_dot+ = eta theta_dot-``
    with ``eta`` the isolated map of E (the colonnade's ratio on the ground, or the given one) and
    ``gamma_eff``, and the base's jump ``gamma_eff h_eff (1 - eta) theta_dot-``."""
    rng = np.random.default_rng(31)
    for _ in range(100):
        block, gc, iso = _scene(rng)
        ref = IsolatedColonnade(block, gc, iso.gamma)
        s = rng.choice([-1.0, 1.0])
        thd1, ud1 = -s * rng.uniform(0.1, 2.0), rng.normal()
        thd2, ud2 = ref.impact(s, thd1, ud1, restitution)
        eta = impact_ratio_on_base(block.alpha, iso.gamma, gc, restitution)
        h_eff = block.h / frequency_factor(gc)
        assert eta > 0.0  # (none clamped in these ranges)
        assert thd2 == pytest.approx(eta * thd1, rel=1e-12)
        assert ud2 == pytest.approx(ud1 + effective_gamma(iso.gamma, gc) * h_eff * (1 - eta) * thd1, rel=1e-12,
                                    abs=1e-12 * abs(thd1) * block.R)
        # the kinetic energy never grows (sum of 1/2 m |v|^2 over the bodies and the base)
        m, dx1, dy1, _, _ = ref.points(0.0, s)
        _, dx2, dy2, _, _ = ref.points(0.0, -s)
        T1 = ref.M * ud1 ** 2 + 2 * np.sum(m * dx1) * ud1 * thd1 + np.sum(m * (dx1 ** 2 + dy1 ** 2)) * thd1 ** 2
        T2 = ref.M * ud2 ** 2 + 2 * np.sum(m * dx2) * ud2 * thd2 + np.sum(m * (dx2 ** 2 + dy2 ** 2)) * thd2 ** 2
        assert T2 <= T1 * (1 + 1e-12)
    # gamma -> 0 (an infinitely heavy base) gives the ratio on the ground, E = 1 no loss on any base
    a = math.radians(10)
    assert impact_ratio_on_base(a, 1e-14, 1.0, None) == pytest.approx(colonnade_restitution(a, 1.0), rel=1e-12)
    assert impact_ratio_on_base(a, 0.9, 1.0, 1.0) == 1.0


def test_the_equations_of_motion_are_those_of_the_effective_block():
    """At random states the 2x2 system of the bodies equals the kernel's Eqs (10)-(11) with ``p_c``,
    ``R_eff`` and ``gamma_eff``: ``a = (F - g_e R_e thd^2 sin A + g_e R_e p_c^2 sin A cos A)/(1 - g_e R_e p_c^2
    cos^2 A / g)``, ``theta'' = -p_c^2 (sin A + a/g cos A)``."""
    rng = np.random.default_rng(13)
    for _ in range(200):
        block, gc, iso = _scene(rng)
        ref = IsolatedColonnade(block, gc, iso.gamma, iso.omega_b, iso.xi)
        th = rng.uniform(-1.3, 1.3) * block.alpha
        thd, u, ud, ag = rng.normal() * block.p * block.alpha, rng.normal() * 0.1, rng.normal() * 0.3, rng.normal() * 3
        s = 1.0 if th >= 0 else -1.0
        d = ref.rhs(lambda t: ag, s)(0.0, [th, thd, u, ud])
        p2 = block.p ** 2 * frequency_factor(gc)
        gR = effective_gamma(iso.gamma, gc) * block.R / frequency_factor(gc)
        F = -iso.omega_b ** 2 * u - 2 * iso.xi * iso.omega_b * ud
        A = s * block.alpha - th
        a = (F - gR * thd ** 2 * math.sin(A) + gR * p2 * math.sin(A) * math.cos(A)) / (1 - gR * p2 * math.cos(A) ** 2 / G)
        assert d[1] == pytest.approx(-p2 * (math.sin(A) + a / G * math.cos(A)), rel=1e-10, abs=1e-12 * p2)
        assert d[3] == pytest.approx(a - ag, rel=1e-10, abs=1e-12 * G)


def _reference_run(ref, block, pulse, th0, thd0, t_end, n_impacts, restitution=None):
    """The reference from (th0, thd0, 0, 0) through ``n_impacts`` impacts or to ``t_end``: ``(t, y)`` pieces."""
    ag = lambda t: float(pulse.acceleration(t))  # noqa: E731
    t, y = 0.0, np.array([th0, thd0, 0.0, 0.0])
    s = 1.0 if (th0 if th0 != 0 else thd0) > 0 else -1.0
    pieces, impacts = [], []
    for _ in range(n_impacts + 1):
        def hit(tt, yy, s=s, t0=t):
            return s * yy[0] if tt > t0 else 1.0
        hit.terminal, hit.direction = True, -1
        sol = solve_ivp(ref.rhs(ag, s), (t, t_end), y, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True,
                        events=hit)
        pieces.append((t, sol.t[-1], sol.sol))
        if sol.status != 1:
            break
        t, y = sol.t[-1], sol.y[:, -1].copy()
        impacts.append((t, y[1]))
        y[0] = 0.0
        y[1], y[3] = ref.impact(s, y[1], y[3], restitution)
        s = -s
    return pieces, impacts


@pytest.mark.parametrize("restitution", [None, 0.85])
def test_random_runs_through_impacts_match_the_multibody_reference(restitution):
    """40 random colonnades on linear bearings started from a tilt under a sine pulse, through their first
    three impacts: theta and u of the kernel's history rows (rtol 1e-11) against the reference (DOP853,
    rtol 1e-12): impact times within 1e-8 s, theta within 1e-9 alpha and u within 1e-9 R everywhere
    (measured: 6e-11)."""
    rng = np.random.default_rng(2027 if restitution is None else 2028)
    n = impacts_seen = 0
    worst = 0.0
    while n < 40:
        block, gc, iso = _scene(rng)
        th0 = rng.uniform(0.3, 0.9) * block.alpha * rng.choice([-1.0, 1.0])
        thd0 = rng.normal() * 0.2 * block.p * block.alpha
        pulse = make_pulse("sine", rng.uniform(-0.8, 0.8) * G * math.tan(block.alpha), rng.uniform(0.3, 2.0))
        res = simulate(block, iso, pulse, history=True, theta0=th0, theta_dot0=thd0, cap_ratio=gc, rtol=1e-11,
                       tail=2.0, restitution=restitution)
        h = res.history
        if res.overturned or "rest" in h.row_event:
            continue
        ref = IsolatedColonnade(block, gc, iso.gamma, iso.omega_b, iso.xi)
        ev = h.row_event
        kernel_impacts = [i for i in range(len(ev)) if ev[i] == "impact" and (i == 0 or ev[i - 1] != "impact"
                                                                             or h.t[i - 1] != h.t[i])][:3]
        t_end = h.t[kernel_impacts[-1]] if len(kernel_impacts) == 3 else min(h.t[-1], 3.0)
        pieces, ref_impacts = _reference_run(ref, block, pulse, th0, thd0, t_end * (1 + 1e-7) + 1e-9, 3, restitution)
        for k, (i, (t_ref, thd_ref)) in enumerate(zip(kernel_impacts, ref_impacts)):
            assert h.t[i] == pytest.approx(t_ref, abs=1e-8 * (k + 1))
            assert h.theta_dot[i] == pytest.approx(thd_ref, rel=1e-7, abs=1e-9)
            impacts_seen += 1
        for t0, t1, sol in pieces:
            rows = (h.t >= t0) & (h.t < t1) & np.isfinite(h.u)
            rows &= np.array([e != "impact" for e in ev])
            if rows.any():
                y = sol(h.t[rows])
                err = max(float(np.max(np.abs(y[0] - h.theta[rows]))) / block.alpha,
                          float(np.max(np.abs(y[2] - h.u[rows]))) / block.R)
                worst = max(worst, err)
        n += 1
    assert worst < 1e-9
    assert impacts_seen > 50


def test_cap_ratio_zero_is_the_column_the_effective_block_and_the_same_uplift():
    block = Block.from_degrees(3.03, 10.56)
    pulse = make_pulse("ricker-sym", 2.0 * G * math.tan(block.alpha), 1.0)
    iso = LinearIsolation(2.5, 0.1, 0.3)
    a = simulate(block, iso, pulse, history=True)
    b = simulate(block, iso, pulse, history=True, cap_ratio=0.0)
    assert a.summary() == b.summary() and np.array_equal(a.history.theta, b.history.theta)
    # with a given restitution the colonnade is the solitary block of R_eff on the base of gamma_eff
    gc, E = 0.5, 0.9
    twin = Block(block.R / frequency_factor(gc), block.alpha)
    r1 = simulate(block, iso, pulse, cap_ratio=gc, restitution=E)
    r2 = simulate(twin, LinearIsolation(2.5, 0.1, effective_gamma(0.3, gc)), pulse, restitution=E)
    assert r1.verdict == r2.verdict and r1.theta_max == pytest.approx(r2.theta_max, rel=1e-7)
    assert r1.base_disp_max_m == pytest.approx(r2.base_disp_max_m, rel=1e-7)
    # the uplift threshold is g tan(alpha) on the base's acceleration, as for the solitary column: in the
    # multi-body reference at rest on the right corners theta'' > 0 once the bearings pull the base
    # with more than g tan(alpha) to the left ...
    ref = IsolatedColonnade(block, 1.0, 0.3, iso.omega_b, 0.0)
    for f in (0.999, 1.001):
        u = f * G * math.tan(block.alpha) / iso.omega_b ** 2  # F = -omega_b^2 u
        assert (ref.rhs(lambda t: 0.0, 1.0)(0.0, [0.0, 0.0, u, 0.0])[1] > 0.0) == (f > 1.0)
    # ... and the kernel lifts it at the same instant as the solitary column on the same base (to the
    # tolerance: the error scales of the base states follow p_c, so the steps differ)
    strong = make_pulse("sine", 6.0 * G * math.tan(block.alpha), 2.5)
    t_up = simulate(block, iso, strong).t_uplift_s
    assert t_up > 0 and simulate(block, iso, strong, cap_ratio=1.0).t_uplift_s == pytest.approx(t_up, rel=1e-9)
    assert effective_gamma(0.6, 0.0) == 0.6 and 0.6 < effective_gamma(0.6, 100.0) < 0.8


def test_verdict_only_equals_full_history_for_isolated_colonnades():
    """The end-of-run proofs on an isolated base (P3, P5, P8) hold for the effective block: 1,500 linear-base
    scenes of issue 9's set with random cap ratios (and restitutions in a third of them)."""
    jobs = [j for j in random_scenes(3000, 2030, gamma_max=0.9) if not isinstance(j[1], Rigid)]
    rng = np.random.default_rng(2030)
    caps = [float(rng.choice([0.0, rng.uniform(0.0, 3.0)])) for _ in jobs]
    Es = [float(rng.uniform(0.5, 1.0)) if rng.random() < 1 / 3 else None for _ in jobs]
    early, verdict_only, mismatches = _compare_modes(jobs, cap_ratio=caps, restitution=Es)
    assert mismatches == []
    verdicts = [r.verdict for r in verdict_only]
    assert min(verdicts.count(v) for v in ("no_uplift", "rocked", "overturned")) > 100


def test_cli_runs_isolated_colonnades():
    from rockcli.cli import main

    runner = CliRunner()
    out = runner.invoke(main, ["simulate", "--R", "1", "--alpha", "12", "--pulse", "sine:ap=0.3,Tp=1",
                               "--isolation", "linear:Tb=2,gamma=0.5", "--cap-ratio", "0.5", "--json"])
    assert out.exit_code == 0, out.output
    got = json.loads(out.output)
    assert got["cap_ratio"] == 0.5
    assert got["impact_ratio"] == pytest.approx(impact_ratio_on_base(math.radians(12), 0.5, 0.5, None), rel=1e-15)
    block = Block.from_degrees(1.0, 12.0)
    r = simulate(block, LinearIsolation(2.0, gamma=0.5), make_pulse("sine", 0.3 * G, 1.0), cap_ratio=0.5)
    assert got["theta_max"] == pytest.approx(r.theta_max, rel=1e-12)


def test_cli_spectrum_and_assess_run_isolated_colonnades(tmp_path):
    import csv

    from rockcli.cli import main
    from rockcli.spectra import Family, parse_isolation

    runner = CliRunner()
    path = tmp_path / "map.csv"
    out = runner.invoke(main, ["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "2:6:3", "--ap", "2:6:3",
                               "--isolation", "none", "--isolation", "linear:TbTp=2,gamma=0.5", "--csv", str(path),
                               "--full-peaks", "--cap-ratio", "0.5"])
    assert out.exit_code == 0, out.output
    rows = list(csv.DictReader(path.open()))
    iso_rows = [r for r in rows if r["isolation"].startswith("linear")]
    assert iso_rows and len(iso_rows) < len(rows)
    fam = Family(math.radians(10.0), "ricker-sym", parse_isolation("linear:TbTp=2,gamma=0.5"))
    for row in iso_rows:
        assert float(row["cap_ratio"]) == 0.5
        r = simulate(*fam.scene(float(row["wp_over_p"]), float(row["ap_over_g_tan_alpha"])), cap_ratio=0.5)
        assert float(row["theta_max_over_alpha"]) == pytest.approx(r.theta_max_over_alpha, rel=1e-5)
    path = tmp_path / "a.csv"
    out = runner.invoke(main, ["assess", "column", "nemea", "--records", "kobe-1995-takarazuka-000", "--excitation",
                               "pulse", "--isolation", "none", "--isolation", "linear:Tb=2.5", "--no-margin",
                               "--cap-ratio", "1", "--csv", str(path)])
    assert out.exit_code == 0, out.output
    rows = list(csv.DictReader(path.open()))
    assert len(rows) == 2 and all(float(r["cap_ratio"]) == 1.0 for r in rows)


@pytest.mark.parametrize("kind, wp, apr, gc, gamma", [("scss", 3, 2.0, 0.5, 0.3), ("lrb", 5, 1.8, 1.0, 0.5)])
def test_sliding_and_lead_rubber_bases_agree_with_the_radau_reference(kind, wp, apr, gc, gamma):
    """On hysteretic bearings the colonnade's moving mass carries the bearings' strength (mu M g): the kernel's
    effective block against the slow reference (Radau, the colonnade from its mass properties)."""
    from naive_sliding import reference_sliding
    from test_sliding import fig9

    b, f, e = fig9(wp, apr, 2, "ricker-anti", kind=kind, gamma=gamma)
    fast = simulate(b, f, e, rtol=1e-10, cap_ratio=gc)
    ref = reference_sliding(b, f, e, cap_ratio=gc)
    assert fast.verdict == ref.verdict == "rocked"
    assert fast.theta_max == pytest.approx(ref.theta_max, rel=1e-5)
    assert fast.base_disp_max_m == pytest.approx(ref.u_max, rel=1e-5)
    assert fast.theta_max != pytest.approx(simulate(b, f, e, rtol=1e-10).theta_max, rel=1e-2)  # the cap matters
