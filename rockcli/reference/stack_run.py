"""The run of the slow stack reference (:func:`rockcli.reference.stack.reference_stack`): its result
(:class:`StackRefResult`) and the chain of phases (``_Run``: at rest, rocking, the impacts and the rest rules, the
isolated base on linear bearings; :mod:`rockcli.reference.stack_hysteretic` derives the hysteretic bearings' run
from it). The rules it applies are listed in :mod:`rockcli.reference.stack`'s notes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rockcli.io.units import G
from rockcli.reference.equations import ground_function
from rockcli.reference.ivp import Work
from rockcli.reference.stack_impact import choose_post


@dataclass
class StackRefResult:
    """Outcome of :func:`reference_stack` (SI). Per interface ``i`` (0 the ground, ``n - 1`` under the top block):
    ``peak`` max ``|psi_i|`` [rad] (the block above it relative to the one below), ``t_uplift`` its first
    opening, ``n_impacts`` while the ground moves, ``friction`` the peak continuous ``|T|/N``, ``friction_impulsive``
    the peak of impulses; per block ``theta_peak`` its peak absolute tilt. ``toppled``: the interface that reached
    ``pi/2`` (the blocks above it fall), or -1."""

    verdict: str
    toppled: int
    peak: list
    theta_peak: list
    t_uplift: list
    t_overturn: float
    n_impacts: list
    friction: list
    friction_impulsive: list
    n_jumps: int = 0
    n_inconsistent: int = 0
    settled: bool = True
    t_end: float = math.nan
    impacts: list = field(default_factory=list)
    patterns: list = field(default_factory=list)
    steps: int = 0
    nfev: int = 0
    wall_s: float = math.nan
    base_disp_max: float = math.nan


class _Run:
    def __init__(self, model, excitation, rtol, atol, horizon, rest_tol, restitution, method, align, demand_points,
                 record_impacts, deadline_s, tol):
        self.M, n = model, model.n
        self.ag, self.t_exc_end, self.scan_step, self.max_step = ground_function(excitation)
        self.t_max_end = self.t_exc_end + horizon
        self.rest_tol, self.E, self.npts, self.rec, self.tol = rest_tol, restitution, demand_points, record_impacts, tol
        p = np.sqrt(0.75 * G / np.hypot(model.b, model.h))  # each block's frequency parameter: a state scale
        self.pmax = float(np.max(p))
        self.scale = np.concatenate([[model.alpha[i], p[i] * model.alpha[i]] for i in range(n)])
        self.wb = 0.0
        self.xb, self.xscale = np.zeros(0), np.zeros(0)  # the bearings' own states (hysteretic ones) and scales
        if model.nb:  # the base's scales as the single block's: g tan(alpha)/w^2, g tan(alpha)/w, w = max(w_b, p)
            self._init_base()
            w = max(self.wb, self.pmax)
            thr = G * math.tan(float(np.min(model.alpha)))
            self.scale = np.concatenate([self.scale, [thr / w ** 2, thr / w], self.xscale])
        self.work = Work(method, rtol, atol, lambda k: self.scale[self.cols], deadline_s)
        if align and hasattr(excitation, "acc"):
            self.work.breaks = float(excitation.dt) * np.arange(1, np.asarray(excitation.acc).size)
        self.t, self.st, self.q, self.qd = 0.0, [0] * n, np.zeros(n), np.zeros(n)
        self.u = self.ud = self.u_max = 0.0
        self.done = False
        self.peak, self.theta_peak = [0.0] * n, [0.0] * n
        self.t_uplift, self.n_imp = [math.nan] * n, [0] * n
        self.fric, self.fric_imp = [0.0] * n, [0.0] * n
        self.fric_in = [0.0] * n  # the demand read while every block is inside its slenderness (a toppled run's)
        self.toppled, self.t_over = -1, math.nan
        self.n_jumps = self.n_incons = 0
        self.impacts, self.patterns = [], [(0.0, tuple(self.st))]
        self.cols = np.arange(0)

    # ---- bookkeeping ----------------------------------------------------------------------------------------
    def _set(self, st):
        self.st = [int(s) for s in st]
        self.patterns.append((self.t, tuple(self.st)))

    def _open(self, i, sigma):
        self.st[i] = sigma
        self.q[i] = self.qd[i] = 0.0
        self.patterns.append((self.t, tuple(self.st)))
        if math.isnan(self.t_uplift[i]):
            self.t_uplift[i] = self.t

    def _demand(self, forces, inside=True):
        """Note ``|T|/N`` of every interface (``N > 0``); ``inside``: every pivot inside its slenderness there,
        ``|psi_i| <= alpha_i`` (the reading a run that topples reports, docs/plinth.md "Friction")."""
        for i, (N, T, _, _) in enumerate(forces):
            if N > 0:
                self.fric[i] = max(self.fric[i], abs(T) / N)
                if inside:
                    self.fric_in[i] = max(self.fric_in[i], abs(T) / N)

    def _rest_demand(self, a):
        """At rest every interface carries the support's acceleration: the demand ``a = |ag|/g`` at each."""
        self.fric = [max(f, a) for f in self.fric]
        self.fric_in = [max(f, a) for f in self.fric_in]

    def _jump_demand(self, a0, a1):
        """A jump out of rest (docs/plinth.md, "Friction"): the stack, at rest up to its threshold ``a0`` (signed),
        has entered the pattern ``self.st`` under ``a1`` past it. The limit of a ramp from ``a0`` to ``a1``: at zero
        state the forces are linear in ``ag``; follow the patterns the stack passes through (a face opening about its
        other corner where a corner force reaches 0), reading the demand where each face stops holding and at
        ``a1``."""
        M, z = self.M, np.zeros(self.M.n)
        st, a = list(self.st), a0
        for _ in range(2 * M.n):
            fa = M.dynamics(st, z, z, a)[1]
            fb = M.dynamics(st, z, z, a1)[1]
            best, which = 1.0, None
            for i in range(M.n):
                if st[i] != 0:
                    continue
                for c, sigma in ((2, -1), (3, +1)):  # the right corner unloads: pivot left; the left: right
                    if fb[i][c] < 0.0 < fa[i][c] and fa[i][c] / (fa[i][c] - fb[i][c]) < best:
                        best, which = fa[i][c] / (fa[i][c] - fb[i][c]), (i, sigma)
            if which is None:
                self._demand(fb)
                return
            a = a + best * (a1 - a)
            self._demand(M.dynamics(st, z, z, a)[1])
            st[which[0]] = which[1]

    def _peaks(self, q):
        th = np.cumsum(q)
        for i in range(self.M.n):
            self.peak[i] = max(self.peak[i], abs(q[i]))
            self.theta_peak[i] = max(self.theta_peak[i], abs(th[i]))

    # ---- one phase -------------------------------------------------------------------------------------------
    def phase(self) -> bool:
        if self.t >= self.t_max_end - 1e-12 or self.toppled >= 0 or self.done:
            return False
        if all(s == 0 for s in self.st):
            if self.M.nb:
                if self.t >= self.t_exc_end and self._base_settled(self.u, self.ud):
                    return False
                return self._rock()
            return self._rest()
        return self._rock()

    # ---- the isolated base (linear bearings; rockcli.reference.stack_hysteretic overrides these for the others) --
    def _init_base(self):
        """``wb``, ``zeta`` of the linear bearings (the base's parameters ``(m_b, k_b, c_b)``)."""
        mb, kb, cb = self.M.base
        total = mb + float(np.sum(self.M.m))
        self.wb, self.zeta = math.sqrt(kb / total), cb / (2.0 * math.sqrt(kb * total))

    def _Fb(self, u, ud, xb):
        """The bearings' force on the base, or None: the linear ``-k_b u - c_b u'`` of the model."""
        return None

    def _xrates(self, u, ud, xb):
        """The rates of the bearings' own states (none on linear bearings)."""
        return []

    def _bearing(self, u, ud) -> float:
        """The bearing's force per unit moving mass [m/s^2]: the absolute acceleration of a stack at rest on it."""
        return -self.wb * self.wb * u - 2.0 * self.zeta * self.wb * ud

    def _free_bound(self, u, ud, xb) -> float:
        """A bound of every later ``|F|`` of the free base (the stack at rest on it, the ground still): its energy
        ``(u'^2 + w^2 u^2)/2`` never grows and bounds ``|F|`` by ``w sqrt(1 + 4 xi^2)`` times its square root."""
        return self.wb * math.hypot(1.0, 2.0 * self.zeta) * math.hypot(ud, self.wb * u)

    def _rest_thresholds(self):
        """The absolute accelerations ``(lo < 0 < up)`` of its support that lift the stack at rest (the face
        forces at rest are linear in it)."""
        G_ = self.M.ground
        z = np.zeros(self.M.n)
        f0 = G_.dynamics([0] * self.M.n, z, z, 0.0)[1]
        f1 = G_.dynamics([0] * self.M.n, z, z, 1.0)[1]
        up, lo = math.inf, -math.inf
        for i in range(self.M.n):
            for c in (2, 3):
                P0, P1 = f0[i][c], f1[i][c] - f0[i][c]
                if P1 != 0.0:
                    a = -P0 / P1
                    up, lo = (min(up, a), lo) if a > 0 else (up, max(lo, a))
        return lo, up

    def _base_settled(self, u, ud) -> bool:
        """After the excitation, the stack at rest on the free base stays at rest for ever: the free base's energy
        ``(u'^2 + w^2 u^2)/2`` never grows and bounds its acceleration by ``w sqrt(1 + 4 xi^2)`` times its square
        root (the single block's rule), which stays inside both rest thresholds."""
        lo, up = self._rest_thresholds()
        return self._free_bound(u, ud, self.xb) < min(up, -lo)

    def _base_tail(self):
        """The free base's later peak ``|u|`` after the run ends at rest (two periods of the free oscillator)."""
        from scipy.integrate import solve_ivp

        w, z = self.wb, self.zeta

        def f(t, y):
            return [y[1], -w * w * y[0] - 2 * z * w * y[1]]
        def turn(t, y):
            return y[1]
        sol = solve_ivp(f, (0.0, 4 * math.pi / w), [self.u, self.ud], rtol=1e-12, atol=1e-15, events=turn)
        for yy in sol.y_events[0]:
            self.u_max = max(self.u_max, abs(float(yy[0])))

    def _rest(self) -> bool:
        """At rest: the face forces are ``P0 + ag P1``; the first ``ag`` that brings a corner force to 0 opens it."""
        from scipy.optimize import brentq

        if self.t >= self.t_exc_end:
            return False
        z = np.zeros(self.M.n)
        f0 = self.M.dynamics(self.st, z, z, 0.0)[1]
        f1 = self.M.dynamics(self.st, z, z, 1.0)[1]
        up, lo, which_up, which_lo = math.inf, -math.inf, None, None
        for i in range(self.M.n):
            for c, sigma in ((2, -1), (3, +1)):  # the right corner unloads: pivot left (-1); the left: right (+1)
                P0, P1 = f0[i][c], f1[i][c] - f0[i][c]
                if P1 == 0.0:
                    continue
                a = -P0 / P1
                if a > 0 and a < up:
                    up, which_up = a, (i, sigma)
                elif a < 0 and a > lo:
                    lo, which_lo = a, (i, sigma)
        ag, t = self.ag, self.t
        grid = np.arange(t, self.t_exc_end + self.scan_step, self.scan_step / 4)
        grid = np.append(grid[grid < self.t_exc_end], self.t_exc_end)
        vals = np.array([ag(x) for x in grid])
        hit = np.nonzero((vals > up) | (vals < lo))[0]
        k = hit[0] if hit.size else grid.size
        if k:
            self._rest_demand(float(np.max(np.abs(vals[:k]))) / G)
        if not hit.size:
            self.t = self.t_exc_end
            return False
        above = vals[k] > up

        def excess(x):
            return ag(x) - up if above else lo - ag(x)

        self.t = grid[0] if k == 0 else brentq(excess, grid[k - 1], grid[k], xtol=1e-14)
        a1, lim = ag(self.t), (up if above else -lo)
        self._rest_demand(min(abs(a1), lim) / G)  # at rest the stack carries ag up to its threshold only
        self._open(*(which_up if above else which_lo))
        if abs(a1) > lim:  # a jump out of rest (k = 0: the ground acceleration already past it)
            self._jump_demand(math.copysign(lim, a1), a1)
        return True

    def _rhs_factory(self, piv):
        """The state ``y``: the pivots' ``(angle, rate)`` pairs, then on linear bearings the base's ``(u, u')``."""
        M, st, ag = self.M, list(self.st), self.ag
        npv = 2 * len(piv)

        def unpack(y):
            q, qd = np.zeros(M.n), np.zeros(M.n)
            q[piv], qd[piv] = y[0:npv:2], y[1:npv:2]
            return q, qd

        cache = {}

        def dyn(t, y):
            key = (t, y.tobytes())
            if key not in cache:
                cache.clear()
                q, qd = unpack(y)
                if M.nb:
                    u, ud, xb = y[npv], y[npv + 1], y[npv + 2:]
                    cache[key] = M.accelerations(st, q, qd, ag(t), u, ud, Fb=self._Fb(u, ud, xb))
                else:
                    cache[key] = M.dynamics(st, q, qd, ag(t))
            return cache[key]

        def rhs(t, y):
            d = dyn(t, y)
            out = np.empty_like(y)
            out[0:npv:2], out[1:npv:2] = y[1:npv:2], d[0][piv]
            if M.nb:
                out[npv], out[npv + 1] = y[npv + 1], d[2]
                out[npv + 2:] = self._xrates(y[npv], y[npv + 1], y[npv + 2:])
            return out

        return rhs, dyn, unpack

    def _rock(self) -> bool:
        M, st, t0 = self.M, list(self.st), self.t
        piv = [i for i in range(M.n) if st[i] != 0]
        faces = [i for i in range(M.n) if st[i] == 0]
        rhs, dyn, unpack = self._rhs_factory(piv)
        nb, npv = M.nb, 2 * len(piv)
        nx = self.xb.size
        self.cols = np.concatenate([[2 * i, 2 * i + 1] for i in piv]
                                   + [list(range(2 * M.n, 2 * M.n + 2 + nx))] * nb).astype(int)
        y0 = np.ravel(np.column_stack([self.q[piv], self.qd[piv]]))
        if nb:
            y0 = np.concatenate([y0, [self.u, self.ud], self.xb])
        # a face that cannot hold at the start opens now (its corner force is already negative)
        forces = dyn(t0, y0)[1]
        for f in faces:
            if min(forces[f][2], forces[f][3]) < -self.tol * M.weight[f]:
                self._open(f, +1 if forces[f][3] < forces[f][2] else -1)
                return True
        events, kinds = [], []
        for k, i in enumerate(piv):
            s = st[i]
            ev = (lambda tt, yy, k=k, s=s: s * yy[2 * k] if tt > t0 else 1.0)
            ev.terminal, ev.direction = True, -1
            events.append(ev), kinds.append(("impact", i))
            ev = (lambda tt, yy, k=k, s=s: s * yy[2 * k] - math.pi / 2)
            ev.terminal, ev.direction = True, 1
            events.append(ev), kinds.append(("topple", i))
            ev = (lambda tt, yy, k=k: yy[2 * k + 1])
            events.append(ev), kinds.append(("peak", i))
            ev = (lambda tt, yy, i=i: dyn(tt, yy)[1][i][0] / M.weight[i])
            ev.direction = -1
            events.append(ev), kinds.append(("jump", i))
        for i in range(M.n):  # turning points of each block's absolute tilt
            ks = [k for k, j in enumerate(piv) if j <= i]
            if ks:
                ev = (lambda tt, yy, ks=tuple(ks): sum(yy[2 * k + 1] for k in ks))
                events.append(ev), kinds.append(("tilt", i))
        for f in faces:
            ev = (lambda tt, yy, f=f: min(dyn(tt, yy)[1][f][2], dyn(tt, yy)[1][f][3]) / M.weight[f]
                  if tt > t0 else 1.0)
            ev.terminal, ev.direction = True, -1
            events.append(ev), kinds.append(("open", f))
        if nb:
            ev = (lambda tt, yy: yy[npv + 1])  # turning points of the base's displacement
            events.append(ev), kinds.append(("upeak", -1))
            if not piv and t0 >= self.t_exc_end:  # at rest on the free base: settled for ever (_base_settled)
                lo, up = self._rest_thresholds()
                lim = min(up, -lo)
                ev = (lambda tt, yy: self._free_bound(yy[0], yy[1], yy[2:]) - lim)
                ev.terminal, ev.direction = True, -1
                events.append(ev), kinds.append(("settled", -1))
        t_end = self.t_exc_end if t0 < self.t_exc_end else self.t_max_end
        # solve_ivp sees an event only as a sign change between two step ends: a face's corner force that dips
        # below 0 and comes back within one step would be missed (seen on random scenes with steps of 0.07 s).
        # While a face is watched, steps are kept below 0.02/p of the fastest block (60 or more per rocking cycle),
        # and on linear bearings below 0.1/w_b (60 or more per period of the base)
        max_step = min(self.max_step, 0.02 / self.pmax, 0.1 / self.wb if self.wb else math.inf) if faces \
            else self.max_step
        # an impact is seen only as a sign change of a pivot's angle between two step ends: in a chatter of the body
        # on the rocking plinth (impacts a millisecond apart) a dip below 0 and back inside one step was missed, so
        # on the bearings the steps stay below 0.02/p in every pattern (found on a random scene: 50 impacts instead
        # of the 149 the driver finds at every rtol, the count growing as the reference's rtol tightened)
        if M.nb:
            max_step = min(max_step, 0.02 / self.pmax)
        sol = self.work.ivp(rhs, (t0, t_end), y0, max_step=max_step, events=events, dense_output=True)
        for yy in sol.y.T:
            self._peaks(unpack(yy)[0])
        if nb:
            self.u_max = max(self.u_max, float(np.max(np.abs(sol.y[npv]))))
        for k, (kind, i) in enumerate(kinds):
            if kind in ("peak", "tilt") and sol.y_events[k].size:
                for yy in sol.y_events[k]:
                    self._peaks(unpack(yy)[0])
            if kind == "upeak" and sol.y_events[k].size:
                self.u_max = max(self.u_max, float(np.max(np.abs(sol.y_events[k][:, npv]))))
            if kind == "jump" and sol.t_events[k].size:
                self.n_jumps += int(sol.t_events[k].size)
        ts = np.union1d(sol.t, np.linspace(t0, sol.t[-1], self.npts))
        ts = np.union1d(ts, 0.5 * (ts[1:] + ts[:-1]))
        for tt in ts:
            yy = sol.sol(tt)
            self._demand(dyn(tt, yy)[1], inside=bool(np.all(np.abs(unpack(yy)[0]) <= M.alpha)))
        self.t = float(sol.t[-1])
        self.q, self.qd = unpack(sol.y[:, -1])
        if nb:
            self.u, self.ud = float(sol.y[npv, -1]), float(sol.y[npv + 1, -1])
            self.xb = np.array(sol.y[npv + 2:, -1], float)
        if sol.status != 1:
            return True
        for k, (kind, i) in enumerate(kinds):
            if sol.t_events[k].size and events[k].__dict__.get("terminal", False):
                if kind == "topple":
                    self.toppled, self.t_over = i, self.t
                    self.peak[i] = math.pi / 2
                    return False
                if kind == "impact":
                    self.q[i] = 0.0
                    self._impact(i)
                    return True
                if kind == "open":
                    f = dyn(self.t, sol.y[:, -1])[1][i]
                    self._open(i, +1 if f[3] < f[2] else -1)
                    return True
                if kind == "settled":
                    self.done = True
                    return False
        return True

    # ---- impacts -------------------------------------------------------------------------------------------
    def _impact(self, j):
        M, t = self.M, self.t
        v_minus = M.velocities(self.st, self.q, self.qd, self.ud)
        if t <= self.t_exc_end:
            self.n_imp[j] += 1
        c, v, imp, margin, pulls = choose_post(M, self.st, self.q, v_minus, j, self.E, self.tol)
        if margin < -self.tol:
            self.n_incons += 1
        self.n_jumps += pulls
        for i in range(M.n):
            if imp[i][0] > 0:
                self.fric_imp[i] = max(self.fric_imp[i], abs(imp[i][1]) / imp[i][0])
        if self.rec:
            self.impacts.append(dict(t=t, j=j, pre=tuple(self.st), post=tuple(c), q=self.q.copy(), v_minus=v_minus,
                                     v_plus=v, ke_minus=M.kinetic(v_minus), ke_plus=M.kinetic(v), impulses=imp))
        self._set(c)
        self.qd = np.where(np.array(c) != 0, M.rel_rates(v), 0.0)
        self.ud = M.base_velocity(v)
        if any(c) and not np.any(self.q) and self._stack_rests(v):
            self._set([0] * M.n)
            self.qd = np.zeros(M.n)
            if M.nb:  # a plastic rest: the stack and the base keep their horizontal momentum
                self.ud = M.base_velocity(M.impact([0] * M.n, self.q, v)[0])
        elif c[j] != 0:
            self._rest_rule(j, v)
        if M.nb and self.st[j] != 0:
            self._no_rate(j, float(np.max(np.abs(M.rel_rates(v_minus)))))

    def _no_rate(self, j, vscale):
        """On the bearings, a pivot that leaves an impact with no opening rate (the plastic impact took it all) goes
        where the accelerations take it: it stays if it opens, takes the other corner if that one opens, else the
        interface sticks (a plastic stick). Without this rule a plinth carrying a rocking body on a light base was
        seen to chatter between its corners at one instant, thousands of impacts with no rate either way."""
        M, st = self.M, list(self.st)
        if st[j] * self.qd[j] > self.tol * vscale:
            return
        ag = self.ag(self.t)
        qd = self.qd.copy()
        qd[j] = 0.0
        Fb = self._Fb(self.u, self.ud, self.xb)
        if st[j] * M.accelerations(st, self.q, qd, ag, self.u, self.ud, Fb=Fb)[0][j] > 0:
            self.qd = qd
            return
        flipped = list(st)
        flipped[j] = -st[j]
        if flipped[j] * M.accelerations(flipped, self.q, qd, ag, self.u, self.ud, Fb=Fb)[0][j] > 0:
            self._set(flipped)
            self.qd = qd
            return
        s0 = list(st)
        s0[j] = 0
        v0, _ = M.impact(s0, self.q, M.velocities(st, self.q, qd, self.ud))
        self._set(s0)
        self.qd = np.where(np.array(s0) != 0, M.rel_rates(v0), 0.0)
        self.ud = M.base_velocity(v0)

    def _stack_rests(self, v) -> bool:
        """The whole stack's rest rule, every angle at 0: nothing could lift it from rest (each face's restoring
        moment at rest, twice its half width times its smaller corner force, positive) and its kinetic energy is
        below ``rest_tol`` times the smallest ``alpha_j`` times that moment (for one block, the single block's
        rule)."""
        M = self.M
        z = np.zeros(M.n)
        f = M.ground.dynamics([0] * M.n, z, z, self._ride(v, [0] * M.n))[1]
        moment = np.array([2.0 * M.c[i] * min(f[i][2], f[i][3]) for i in range(M.n)])
        return bool(np.all(moment > 0) and M.kinetic_relative(v) < self.rest_tol * float(np.min(M.alpha * moment)))

    def _ride(self, v, st) -> float:
        """The acceleration a rest rule rides on: the ground's, or on linear bearings the bearing's force per unit
        moving mass with the base's velocity after a plastic rest into ``st`` (the single block's rule)."""
        if not self.M.nb:
            return self.ag(self.t)
        return self._bearing(self.u, self.M.base_velocity(self.M.impact(st, self.q, v)[0]))

    def _rest_rule(self, j, v):
        """Stick interface ``j`` again when nothing could open it and its reach is below ``rest_tol alpha_j``."""
        M, c = self.M, list(self.st)
        s0 = list(c)
        s0[j] = 0
        v0, _ = M.impact(s0, self.q, v)
        qd0 = np.where(np.array(s0) != 0, M.rel_rates(v0), 0.0)
        a_ride = self._ride(v, s0)
        restoring = math.inf
        for sigma in (1, -1):
            s1 = list(s0)
            s1[j] = sigma
            restoring = min(restoring, -sigma * M.ground.dynamics(s1, self.q, qd0, a_ride)[0][j])
        rate = M.rel_rates(v)[j]
        if restoring > 0 and rate * rate / (2 * restoring) < self.rest_tol * M.alpha[j]:
            self._set(s0)
            self.qd = qd0
            self.ud = M.base_velocity(v0)

    def result(self) -> StackRefResult:
        uplifted = any(not math.isnan(x) for x in self.t_uplift)
        verdict = "overturned" if self.toppled >= 0 else ("rocked" if uplifted else "no_uplift")
        settled = self.toppled >= 0 or all(s == 0 for s in self.st)
        if self.M.nb and settled and self.toppled < 0:
            settled = self.done or self._base_settled(self.u, self.ud)
            if settled:
                self._base_tail()
        fric = self.fric_in if self.toppled >= 0 else self.fric  # a run that topples: read while inside
        out = StackRefResult(verdict, self.toppled, list(self.peak), list(self.theta_peak), list(self.t_uplift),
                              self.t_over, list(self.n_imp), list(fric), list(self.fric_imp), self.n_jumps,
                              self.n_incons, settled, self.t, self.impacts, self.patterns, self.work.steps,
                              self.work.nfev)
        out.base_disp_max = self.u_max if self.M.nb else math.nan
        return out
