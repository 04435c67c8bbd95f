"""The slow reference of rocking and sliding (a block, or a body on its plinth, with Coulomb friction at every
contact; docs/physics-sliding.md): SciPy ``solve_ivp`` with events for every change of pattern, phases chained in
plain Python.

Written independently of :mod:`rockcli.kernels`: the mechanics are the separate bodies' Newton-Euler equations
with constraint multipliers (:class:`rockcli.reference.friction_mechanics.FrictionChain`); the rules are those of
the note, each written here again:

* At rest on the rigid ground (every face sticking) the forces are affine in ``ag``: the ground motion is scanned
  (a grid, then ``brentq``) for the first ``ag`` outside the band where every corner force presses and every
  contact is inside Coulomb's cone; there the pattern that meets every condition starts.
* In a pattern the free relative coordinates (the pivots' angles, the slips, the base's ``u``) are integrated;
  terminal events: a pivot's angle back to 0 (an impact) or at ``pi/2`` (a topple), a slip rate back to 0, a slip
  at the edge of the surface below (sliding off), a face's corner force down to 0, a sticking contact at Coulomb's
  cone. While a face or a sticking contact is watched, steps stay below ``0.02/p`` of the fastest block, so that a
  short dip is not stepped over.
* After an event the candidates (the interfaces at angle 0 a face or either pivot; those at slip rate 0 sticking
  or sliding either way) are solved and checked (corner forces pressing, pivots pressing and opening, the cone, the
  slip's direction); the largest smallest relative margin is taken. Impacts: Moreau's plastic impact with
  Coulomb's law (velocity level), the candidates where every contact sticks first.
* Rest rules after an impact (every angle at 0: the whole chain onto its faces when nothing can lift it and its
  rocking energy is below ``rest_tol`` times the smallest ``alpha_j M_j``; else the impacting interface onto its
  face when both accelerations that turn it back are positive and its rate is small), each a projection of the
  velocities in the energy metric (no friction impulse).
* The run ends when a block topples or slides off, at rest after the excitation (on bearings: when the free base
  can no longer open a face or start a slip), or ``horizon`` after the excitation.
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass

import numpy as np

from rockcli.io.units import G
from rockcli.reference.equations import ground_function
from rockcli.reference.friction_mechanics import FrictionChain
from rockcli.reference.ivp import Work


@dataclass
class FrictionRefResult:
    """Per interface (0 the base): ``psi_max`` [rad], ``s_max``, ``s_end`` [m], ``t_slide``, ``n_slips``,
    ``n_impacts`` (while the ground moves), ``t_uplift``; ``verdict`` as :class:`rockcli.solve.slide.SlideResponse`."""

    verdict: str
    toppled: int
    slid_off: int
    t_fail: float
    psi_max: list
    s_max: list
    s_end: list
    t_slide: list
    n_slips: list
    n_impacts: list
    t_uplift: list
    n_jumps: int
    n_inconsistent: int
    settled: bool
    t_end: float
    u_max: float
    steps: int
    nfev: int
    wall_s: float
    energy_rises: list


def reference_friction(body, excitation, mu, foundation=None, *, rtol=1e-10, horizon=600.0, rest_tol=1e-8,
                       method="DOP853", align=True, deadline_s=None, tol=1e-9, max_phases=200000,
                       record_energy=False) -> FrictionRefResult:
    """Run ``body`` (a :class:`rockcli.models.Block` or :class:`rockcli.models.Stack`) under ``excitation`` with
    friction ``mu`` (one, or per contact) on ``foundation`` (None, Rigid, or LinearIsolation with gamma > 0).
    ``record_energy``: keep, for every impact and rest projection, the kinetic energy after minus before (the
    tests' check that it never rises)."""
    from rockcli.solve.slide import _blocks, _mus, chain_parameters

    t_wall = time.perf_counter()
    blocks, _ = _blocks(body)
    n = len(blocks)
    mus = _mus(mu, n)
    base = None
    if foundation is not None and getattr(foundation, "kind", 0) != 0:
        cp = chain_parameters(body, mus, foundation)
        from rockcli.kernels import chain as ch  # the base's numbers only (no numba is called)

        base = (float(cp[ch.CP_MB]), float(cp[ch.CP_KB]), float(cp[ch.CP_CB]))
    run = _Run(FrictionChain(blocks, mus, base), excitation, rtol, horizon, rest_tol, method, align, deadline_s, tol,
               record_energy)
    for _ in range(max_phases):
        if not run.phase():
            break
    return run.result(time.perf_counter() - t_wall)


def _all_stuck(pat):
    return all(p == 0.0 for p in pat)


class _Run:
    def __init__(self, ch, excitation, rtol, horizon, rest_tol, method, align, deadline_s, tol, record_energy):
        self.ch = ch
        self.free_ch = FrictionChain([(b, h, m) for b, h, m in zip(ch.b, ch.h, ch.m)], [0.0] * ch.n, ch.base)
        self.ag, self.t_exc_end, self.scan_step, self.max_step = ground_function(excitation)
        self.t_max_end = self.t_exc_end + horizon
        self.rest_tol, self.tol = rest_tol, tol
        n = ch.n
        self.n = n
        self.pat = [0.0] * (2 * n)
        self.q = np.zeros(1 + 2 * n)  # u, then (s_j, psi_j)
        self.qd = np.zeros(1 + 2 * n)
        self.t = 0.0
        self.pmax = max(math.sqrt(0.75 * G / math.hypot(b, h)) for b, h in zip(ch.b, ch.h))
        self.wb = math.sqrt(ch.base[1] / (ch.base[0] + ch.m.sum())) if ch.base else 0.0
        self.psi_max = [0.0] * n
        self.s_max = [0.0] * n
        self.t_slide = [math.nan] * n
        self.t_uplift = [math.nan] * n
        self.n_slips = [0] * n
        self.n_imp = [0] * n
        self.n_jumps = self.n_incons = 0
        self.u_max = 0.0
        self.toppled = self.slid_off = -1
        self.t_fail = math.nan
        self.settled = False
        self.done = False
        self.energy_rises = [] if record_energy else None
        w = max(self.wb, self.pmax)
        u_sc = G * math.tan(float(np.min(ch.alpha))) / w ** 2
        self.pos_scale = np.array([u_sc] + [x for j in range(n) for x in (ch.b[j], ch.alpha[j])])
        self.rate_scale = np.array([u_sc * w] + [x * self.pmax for j in range(n) for x in (ch.b[j], ch.alpha[j])])
        self._phase_scales = None
        self.work = Work(method, rtol, None, lambda k: self._phase_scales, deadline_s)
        if align and hasattr(excitation, "acc"):
            self.work.breaks = excitation.dt * np.arange(np.asarray(excitation.acc).size)

    # ---- patterns --------------------------------------------------------------------------------------
    def _free(self, pat):
        """Indices into ``q`` of the pattern's free coordinates."""
        out = [0] if self.ch.nb else []
        for j in range(self.n):
            if pat[2 * j + 1] != 0.0:
                out.append(1 + 2 * j)
            if pat[2 * j] != 0.0:
                out.append(2 + 2 * j)
        return out

    def _qvec(self, q):
        """The mechanics' ``q`` (u, s_j, psi_j) from ours (the same)."""
        return q

    def _solve(self, pat, q, qd, ag, ch=None):
        ch = ch or self.ch
        X, V = ch.maximal(pat, q, qd)
        A, lam, kinds = ch.solve(pat, X, V, ch.loads(X, V, ag))
        return X, V, A, ch.forces(pat, lam, kinds)

    def _margin(self, pat, forces, rates, zero_psi, zero_s, level_v):
        """The smallest relative margin of the contact conditions (module notes), and the pulling pivots."""
        fs = max(1e-300, float(np.max(np.abs(forces[:, :2]))))
        free = self._free(pat)
        vs = max([1e-300] + [abs(rates[i]) for i in free])
        worst, pulls = math.inf, 0
        for j in range(self.n):
            c, sl = pat[2 * j], pat[2 * j + 1]
            N, T, Mc = forces[j]
            b = self.ch.b[j]
            if c == 0.0:
                worst = min(worst, (N / 2 - Mc / (2 * b)) / fs, (N / 2 + Mc / (2 * b)) / fs)
            elif zero_psi[j]:
                worst = min(worst, N / fs, c * rates[2 + 2 * j] / vs)
            elif N < 0.0:
                pulls += 1
            if sl == 0.0:
                if N > 0.0 or c == 0.0 or zero_psi[j]:
                    worst = min(worst, (self.ch.mu[j] * max(N, 0.0) - abs(T)) / fs)
            else:
                if j in self.ch.last_off:  # solved without friction because it pulled: it must pull still
                    worst = min(worst, -N / fs)
                if zero_s[j] or level_v:
                    worst = min(worst, sl * rates[1 + 2 * j] / vs)
        return worst, pulls

    def _choose(self, q, qd, ag, zero_psi, zero_s):
        """The pattern that continues the motion (no impact): the largest smallest margin among the candidates."""
        opts = []
        for j in range(self.n):
            opts.append((-1.0, 0.0, 1.0) if zero_psi[j] else (self.pat[2 * j],))
            opts.append((-1.0, 0.0, 1.0) if zero_s[j] else (self.pat[2 * j + 1],))
        best, best_m, best_p = None, -math.inf, 0
        for cand in itertools.product(*opts):
            cand = list(cand)
            if cand == list(self.pat):  # the pattern whose condition failed: only as a last resort (a tangency)
                continue
            try:
                X, V, A, forces = self._solve(cand, q, qd, ag)
            except np.linalg.LinAlgError:
                continue
            rates = self.ch.relative_rates(cand, X, V, A)
            m, p = self._margin(cand, forces, rates, zero_psi, zero_s, False)
            if m > best_m:
                best, best_m, best_p = cand, m, p
        if best_m < -self.tol:
            X, V, A, forces = self._solve(list(self.pat), q, qd, ag)
            rates = self.ch.relative_rates(list(self.pat), X, V, A)
            best_m = self._margin(list(self.pat), forces, rates, zero_psi, zero_s, False)[0]
            best = list(self.pat)
        if best_m < -self.tol:
            self.n_incons += 1
        return best

    def _switch(self, new):
        for j in range(self.n):
            if self.pat[2 * j] == 0.0 and new[2 * j] != 0.0 and math.isnan(self.t_uplift[j]):
                self.t_uplift[j] = self.t
            if self.pat[2 * j + 1] == 0.0 and new[2 * j + 1] != 0.0:
                self.n_slips[j] += 1
                if math.isnan(self.t_slide[j]):
                    self.t_slide[j] = self.t
        self.pat = list(new)

    # ---- the run ---------------------------------------------------------------------------------------
    def phase(self) -> bool:
        if self.done:
            return False
        if self.t >= self.t_exc_end and _all_stuck(self.pat):
            if self.ch.nb == 0 or self._base_settled():
                self.settled = True
                return False
        if self.t >= self.t_max_end:
            return False
        if self.ch.nb == 0 and _all_stuck(self.pat):
            return self._rest()
        return self._move()

    def _band(self, q):
        """The band of ``ag`` (on bearings: of the base's acceleration) in which the chain stays at rest."""
        rigid = FrictionChain([(b, h, m) for b, h, m in zip(self.ch.b, self.ch.h, self.ch.m)], self.ch.mu)
        pat = [0.0] * (2 * self.n)
        z = np.zeros_like(q)
        f0 = self._solve(pat, q, z, 0.0, rigid)[3]
        f1 = self._solve(pat, q, z, 1.0, rigid)[3] - f0
        lo, hi = -math.inf, math.inf
        for j in range(self.n):
            b, mu = self.ch.b[j], self.ch.mu[j]
            (N0, T0, M0), (N1, T1, M1) = f0[j], f1[j]
            for c0, c1 in ((N0 / 2 - M0 / (2 * b), N1 / 2 - M1 / (2 * b)), (N0 / 2 + M0 / (2 * b), N1 / 2 + M1 / (2 * b)),
                           (mu * N0 - T0, mu * N1 - T1), (mu * N0 + T0, mu * N1 + T1)):
                if c1 > 0:
                    lo = max(lo, -c0 / c1)
                elif c1 < 0:
                    hi = min(hi, -c0 / c1)
        return lo, hi

    def _rest(self) -> bool:
        from scipy.optimize import brentq

        if self.t >= self.t_exc_end:
            return False
        lo, hi = self._band(self.q)
        ag, t = self.ag, self.t
        grid = np.arange(t, self.t_exc_end + self.scan_step, self.scan_step / 4)
        grid = np.append(grid[grid < self.t_exc_end], self.t_exc_end)
        vals = np.array([ag(x) for x in grid])
        hit = np.nonzero((vals > hi) | (vals < lo))[0]
        if not hit.size:
            self.t = self.t_exc_end
            return True
        k = hit[0]
        above = vals[k] > hi

        def excess(x):
            return ag(x) - hi if above else lo - ag(x)

        self.t = grid[0] if k == 0 else brentq(excess, grid[k - 1], grid[k], xtol=1e-14)
        a = (hi + 1e-9 * abs(hi)) if above else (lo - 1e-9 * abs(lo))
        new = self._choose(self.q, self.qd, a, [True] * self.n, [True] * self.n)
        self._switch(new)
        if _all_stuck(self.pat):
            self.t += 1e-9 * max(1.0, self.t)
        return True

    def _free_bound(self, u, ud) -> float:
        """The largest acceleration the free base can still reach (its energy never grows)."""
        mb, kb, cb = self.ch.base
        M = mb + self.ch.m.sum()
        E = 0.5 * M * ud * ud + 0.5 * kb * u * u
        return (kb * math.sqrt(2 * E / kb) + cb * math.sqrt(2 * E / M)) / M

    def _base_settled(self) -> bool:
        amax = self._free_bound(self.q[0], self.qd[0])
        lo, hi = self._band(self.q)
        return -amax > lo and amax < hi

    def _move(self) -> bool:
        ch, pat, t0 = self.ch, list(self.pat), self.t
        free = self._free(pat)
        nfr = len(free)

        def unpack(y):
            q, qd = self.q.copy(), np.zeros_like(self.qd)
            q[free] = y[:nfr]
            qd[free] = y[nfr:]
            return q, qd

        cache = {}

        def dyn(t, y):
            key = (t, y.tobytes())
            if key not in cache:
                cache.clear()
                q, qd = unpack(y)
                X, V, A, forces = self._solve(pat, q, qd, self.ag(t))
                cache[key] = (ch.relative_rates(pat, X, V, A), forces)
            return cache[key]

        def rhs(t, y):
            rates = dyn(t, y)[0]
            return np.concatenate([y[nfr:], rates[free]])

        y0 = np.concatenate([self.q[free], self.qd[free]])
        self._phase_scales = np.concatenate([self.pos_scale[free], self.rate_scale[free]])
        events, kinds = [], []

        def add(f, kind, j, terminal=True, direction=-1, guard=True):
            if guard:
                g = (lambda tt, yy, f=f: f(tt, yy) if tt > t0 else 1.0)
            else:
                g = f
            g.terminal, g.direction = terminal, direction
            events.append(g)
            kinds.append((kind, j))

        watched = False
        for j in range(self.n):
            c, sl = pat[2 * j], pat[2 * j + 1]
            if c != 0.0:
                k = free.index(2 + 2 * j)
                add(lambda tt, yy, k=k, c=c: c * yy[k], "impact", j)
                add(lambda tt, yy, k=k, c=c: c * yy[k] - math.pi / 2, "topple", j, direction=1, guard=False)
                add(lambda tt, yy, k=k: yy[nfr + k], "peak", j, terminal=False, direction=0, guard=False)
                add(lambda tt, yy, j=j: dyn(tt, yy)[1][j][0], "jump", j, terminal=False, guard=False)
            else:
                b = ch.b[j]
                add(lambda tt, yy, j=j, b=b: min(dyn(tt, yy)[1][j][0] / 2 - dyn(tt, yy)[1][j][2] / (2 * b),
                                                 dyn(tt, yy)[1][j][0] / 2 + dyn(tt, yy)[1][j][2] / (2 * b))
                    / max(abs(dyn(tt, yy)[1][j][0]), 1e-300), "open", j)
                watched = True
            if sl != 0.0:
                k = free.index(1 + 2 * j)
                add(lambda tt, yy, k=k, sl=sl: sl * yy[nfr + k], "stop", j)
                if math.isfinite(ch.edge[j]):
                    add(lambda tt, yy, k=k, e=ch.edge[j]: e - abs(yy[k]), "off", j, guard=False)
                add(lambda tt, yy, k=k: yy[nfr + k], "speak", j, terminal=False, direction=0, guard=False)
            else:
                mu = ch.mu[j]
                add(lambda tt, yy, j=j, mu=mu: (mu * dyn(tt, yy)[1][j][0] - abs(dyn(tt, yy)[1][j][1]))
                    / max(abs(dyn(tt, yy)[1][j][0]), 1e-300) if (pat[2 * j] == 0.0 or dyn(tt, yy)[1][j][0] > 0)
                    else 1.0, "slip", j)
                watched = True
        if ch.nb:
            add(lambda tt, yy: yy[nfr], "upeak", -1, terminal=False, direction=0, guard=False)
            if _all_stuck(pat) and t0 >= self.t_exc_end:  # at rest on the free base: settled once it cannot move
                lo, hi = self._band(self.q)
                lim = min(-lo, hi)
                add(lambda tt, yy: self._free_bound(yy[0], yy[nfr]) - lim, "settled", -1, guard=False)
        t_end = self.t_exc_end if t0 < self.t_exc_end else self.t_max_end
        max_step = min(self.max_step, 0.02 / self.pmax) if (watched or ch.nb) else self.max_step
        sol = self.work.ivp(rhs, (t0, t_end), y0, max_step=max_step, events=events, dense_output=True)
        ts = np.union1d(sol.t, np.linspace(t0, sol.t[-1], 64))
        for tt in ts:
            self._peaks(unpack(sol.sol(tt))[0], pat)
        for k, (kind, j) in enumerate(kinds):
            if kind in ("peak", "speak", "upeak") and sol.y_events[k].size:
                for yy in sol.y_events[k]:
                    self._peaks(unpack(yy)[0], pat)
            if kind == "jump" and sol.t_events[k].size:
                self.n_jumps += int(sol.t_events[k].size)
        self.t = float(sol.t[-1])
        self.q, self.qd = unpack(sol.y[:, -1])
        if sol.status != 1:
            return True
        for k, (kind, j) in enumerate(kinds):
            if not (sol.t_events[k].size and events[k].terminal):
                continue
            if kind == "topple":
                self.toppled, self.t_fail = j, self.t
                self.psi_max[j] = math.pi / 2
                self.done = True
                return False
            if kind == "settled":
                self.settled = True
                self.done = True
                return False
            if kind == "off":
                self.slid_off, self.t_fail = j, self.t
                self.s_max[j] = max(self.s_max[j], abs(self.q[1 + 2 * j]))
                self.done = True
                return False
            zero_psi, zero_s = [False] * self.n, [False] * self.n
            if kind == "impact":
                k = free.index(2 + 2 * j)
                c = pat[2 * j]
                tt = np.linspace(t0, self.t, 65)
                if y0[k] == 0.0 and c * y0[nfr + k] <= 0.0 and max(c * sol.sol(x)[k] for x in tt[1:-1]) <= 0.0:
                    # entered at angle 0, it turned into the surface (the pattern could not hold): chosen again
                    self.q[2 + 2 * j] = 0.0
                    self.t = t0
                    self.q, self.qd = unpack(y0)
                    zero_psi[j] = True
                    zero_s[j] = pat[2 * j + 1] == 0.0
                    self._switch(self._choose(self.q, self.qd, self.ag(self.t), zero_psi, zero_s))
                    return True
                self.q[2 + 2 * j] = 0.0
                self._impact(j)
                return True
            if kind == "stop":
                self.qd[1 + 2 * j] = 0.0
                zero_s[j] = True
            elif kind == "open":
                zero_psi[j] = True
                zero_s[j] = pat[2 * j + 1] == 0.0
            else:  # the cone
                zero_s[j] = True
                zero_psi[j] = pat[2 * j] == 0.0
            for i in range(self.n):  # a pivot still at angle and rate 0 may turn either way, or close again
                if pat[2 * i] != 0.0 and self.q[2 + 2 * i] == 0.0 and self.qd[2 + 2 * i] == 0.0:
                    zero_psi[i] = True
            self._switch(self._choose(self.q, self.qd, self.ag(self.t), zero_psi, zero_s))
            return True
        return True

    def _peaks(self, q, pat):
        tilt = 0.0
        for j in range(self.n):
            self.psi_max[j] = max(self.psi_max[j], abs(q[2 + 2 * j]))
            self.s_max[j] = max(self.s_max[j], abs(q[1 + 2 * j]))
        if self.ch.nb:
            self.u_max = max(self.u_max, abs(q[0]))

    # ---- impacts and rest ------------------------------------------------------------------------------
    def _velocity_jump(self, pat_from, pat_to, ch=None):
        """``(V+, rates+, impulses)`` of the velocity-level solve into ``pat_to`` from the state in ``pat_from``."""
        ch = ch or self.ch
        X, V = self.ch.maximal(pat_from, self.q, self.qd)
        dV, lam, kinds = ch.solve(pat_to, X, V, None, level="v")
        Vp = V + dV
        rates = self._rates_of(pat_to, X, Vp)
        return V, Vp, rates, ch.forces(pat_to, lam, kinds)

    def _rates_of(self, pat, X, V):
        """The relative rates (u', s_j', psi_j') of the maximal velocities ``V`` in the chart of ``pat``."""
        out = np.zeros(1 + 2 * self.n)
        if self.ch.nb:
            out[0] = V[-1]
        for j in range(self.n):
            out[2 + 2 * j] = V[3 * j + 2] - (V[3 * (j - 1) + 2] if j > 0 else 0.0)
            Jt, _ = self.ch.tangent_row(j, pat[2 * j], X, V)
            out[1 + 2 * j] = float(Jt @ V)
        return out

    def _impact(self, j):
        n = self.n
        if self.t <= self.t_exc_end:
            self.n_imp[j] += 1
        zero_psi = [i == j or self.pat[2 * i] == 0.0 for i in range(n)]
        corner_opts = [(-1.0, 0.0, 1.0) if zero_psi[i] else (self.pat[2 * i],) for i in range(n)]
        best = None
        for stage in (0, 1):
            best, best_m, best_p, best_rates = None, -math.inf, 0, None
            slip_opts = [(0.0,)] * n if stage == 0 else [(-1.0, 0.0, 1.0)] * n
            for corners in itertools.product(*corner_opts):
                for slips in itertools.product(*slip_opts):
                    cand = [x for pair in zip(corners, slips) for x in pair]
                    try:
                        V, Vp, rates, imp = self._velocity_jump(self.pat, cand)
                    except np.linalg.LinAlgError:
                        continue
                    m, p = self._margin(cand, imp, rates, zero_psi, [False] * n, True)
                    if m > best_m:
                        best, best_m, best_p, best_rates, best_V = cand, m, p, rates, (V, Vp)
            if best_m >= -self.tol:
                break
        if best_m < -self.tol:
            self.n_incons += 1
        if best_p:
            self.n_jumps += 1
        self._record_energy(*best_V)
        self._switch(best)
        self._set_rates(best, best_rates)
        self._rest_rules(j)

    def _set_rates(self, pat, rates):
        self.qd = np.zeros_like(self.qd)
        for i in self._free(pat):
            self.qd[i] = rates[i]

    def _record_energy(self, V, Vp):
        if self.energy_rises is not None:
            M = self.ch.Mdiag
            self.energy_rises.append(0.5 * float(np.dot(M, Vp * Vp)) - 0.5 * float(np.dot(M, V * V)))

    def _project(self, pat_to):
        V, Vp, rates, _ = self._velocity_jump(self.pat, pat_to, self.free_ch)
        self._record_energy(V, Vp)
        new = list(pat_to)
        for i in range(self.n):
            if new[2 * i + 1] != 0.0:
                v = rates[1 + 2 * i]
                new[2 * i + 1] = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        self._switch(new)
        self._set_rates(new, rates)

    def _rest_rules(self, j):
        n, ch = self.n, self.ch
        ag = self.ag(self.t)
        if all(self.q[2 + 2 * i] == 0.0 for i in range(n)):
            rigid = FrictionChain([(b, h, m) for b, h, m in zip(ch.b, ch.h, ch.m)], ch.mu)
            pat0 = [0.0] * (2 * n)
            forces = self._solve(pat0, self.q, np.zeros_like(self.qd), ag, rigid)[3]
            moments = [2 * ch.b[i] * min(forces[i][0] / 2 - forces[i][2] / (2 * ch.b[i]),
                                         forces[i][0] / 2 + forces[i][2] / (2 * ch.b[i])) for i in range(n)]
            if all(m > 0 for m in moments):
                qd = self.qd.copy()
                qd[0] = 0.0
                qd[1::2] = 0.0
                X, V = ch.maximal(self.pat, self.q, qd)
                energy = 0.5 * float(np.dot(ch.Mdiag, V * V))
                if energy < self.rest_tol * min(ch.alpha[i] * moments[i] for i in range(n)):
                    self._project([0.0 if k % 2 == 0 else self.pat[k] for k in range(2 * n)])
                    return
        if self.pat[2 * j] != 0.0:
            rest = math.inf
            q = self.q.copy()
            qd = self.qd.copy()
            q[2 + 2 * j] = qd[2 + 2 * j] = 0.0
            for sg in (1.0, -1.0):
                cand = list(self.pat)
                cand[2 * j] = sg
                X, V, A, _ = self._solve(cand, q, qd, ag)
                rest = min(rest, -sg * ch.relative_rates(cand, X, V, A)[2 + 2 * j])
            rate = self.qd[2 + 2 * j]
            if rest > 0 and rate * rate < 2 * rest * self.rest_tol * ch.alpha[j]:
                cand = list(self.pat)
                cand[2 * j] = 0.0
                self._project(cand)

    def result(self, wall) -> FrictionRefResult:
        n = self.n
        if self.toppled >= 0:
            verdict = "overturned"
        elif self.slid_off >= 0:
            verdict = "slid off"
        elif any(math.isfinite(t) for t in self.t_uplift) or any(self.n_slips):
            verdict = "survives"
        else:
            verdict = "no motion"
        return FrictionRefResult(
            verdict=verdict, toppled=self.toppled, slid_off=self.slid_off, t_fail=self.t_fail,
            psi_max=list(self.psi_max), s_max=list(self.s_max), s_end=[float(self.q[1 + 2 * j]) for j in range(n)],
            t_slide=list(self.t_slide), n_slips=list(self.n_slips), n_impacts=list(self.n_imp),
            t_uplift=list(self.t_uplift), n_jumps=self.n_jumps, n_inconsistent=self.n_incons, settled=self.settled,
            t_end=self.t, u_max=self.u_max, steps=self.work.steps, nfev=self.work.nfev, wall_s=wall,
            energy_rises=self.energy_rises or [])
