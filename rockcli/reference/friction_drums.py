"""The slow reference of a column of drums with Coulomb friction at every contact (docs/physics-drums.md):
:func:`reference_drums`. SciPy ``solve_ivp`` with events for every change of pattern, phases chained in plain Python,
as the reference of one block and of a body on its plinth (:mod:`rockcli.reference.friction`), whose run it extends.

Written independently of :mod:`rockcli.kernels`: the mechanics are the separate drums' Newton-Euler equations with
one constraint per contact force (:mod:`rockcli.reference.drum_mechanics`, where the constraints of a face at the ends
of its overlap and of the pivots of kind A and B are derived); the pattern after an event is found among all the
patterns the event allows, by enumeration or by a mixed-integer problem over the contact conditions, and chosen by
the driver's rule (:mod:`rockcli.reference.drum_patterns`). What this module adds to the existing run:

* **Faces at the overlap.** A face's corner forces are its two constraints' multipliers at the ends of the overlap
  ``e_R = min(b, b_L - s)``, ``e_L = max(-b, -b_L - s)``; the face opens when the smaller reaches 0, the chain is at
  rest while both press (the band of ``ag``), and the rest rules' restoring moments are ``2 b min(N_R, N_L)``.
* **The switch of kind.** A sliding pivot whose corner reaches the edge of the top below (``c s + b = b_L``, either
  way) is a terminal event: positions are continuous (the slip is set past the switch by ``1e-12 b_L`` so that the
  chart of the other kind holds, as the driver), the velocities before (maximal, from the old chart) take a plastic
  impulse with Coulomb's law into the same pattern of the new chart (``M dv = J^T Lambda``, ``J v+ = 0``: energy
  never rises, recorded with ``record_energy``); where that stops or turns the slip, the contact law chooses again.
* **Failures.** A pivot's angle at ``pi/2``: the drums above that contact topple (``toppled`` its index). A slip at
  ``|s| = b + b_L`` (no overlap left): slid off. For a body on its plinth (a :class:`rockcli.models.Stack`) the
  plinth's own criterion (``|s| = b_L - b``) and no overlap, so that ``n = 2`` is the existing reference's model.

Everything else (the scan from rest, the events of the forces and slips, impacts by Moreau's law with Coulomb's,
the rest rules, the end of the run) is the existing reference's, read through these mechanics.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from rockcli.io.units import G
from rockcli.reference import drum_patterns as dp
from rockcli.reference.drum_mechanics import DrumChain
from rockcli.reference.equations import ground_function
from rockcli.reference.friction import FrictionRefResult, _all_stuck, _Run
from rockcli.reference.ivp import Work

#: events at one instant in a row before the best other candidate is forced (as the driver's MAX_STALL)
MAX_STALL = 64


@dataclass
class DrumRefResult(FrictionRefResult):
    """:class:`rockcli.reference.friction.FrictionRefResult` and: ``n_kind_switches`` (a sliding pivot past the edge
    of the top below), ``n_stall`` (choices forced after ``MAX_STALL`` events at one instant), ``how`` (how many pattern choices were made by enumeration and by the mixed-integer problem),
    ``residual_offsets`` (each drum's offset from the axis of the footprint at the end [m]); with ``flight=True``:
    ``n_flights`` (lift-offs), ``n_landings``, ``flight_time`` (per interface [s]), ``flight_path`` (with ``trace``:
    the flying phases sampled, ``(t, X, V, flying interfaces)``)."""

    n_kind_switches: int = 0
    n_stall: int = 0
    how: dict = field(default_factory=dict)
    residual_offsets: list = field(default_factory=list)
    trace: list = field(default_factory=list)
    n_flights: int = 0
    n_landings: int = 0
    flight_time: list = field(default_factory=list)
    flight_path: list = field(default_factory=list)


def chain_of(body, mu, foundation=None) -> DrumChain:
    """The mechanics of ``body`` (a DrumColumn, a Stack or a Block) with friction ``mu`` on ``foundation``."""
    from rockcli.models.drums import DrumColumn
    from rockcli.solve.slide import _blocks, _mus

    blocks, _ = _blocks(body)
    n = len(blocks)
    mus = _mus(mu, n)
    base = None
    if foundation is not None and getattr(foundation, "kind", 0) != 0:
        m = sum(x[2] for x in blocks)
        total = m / foundation.gamma
        w = foundation.omega_b
        base = (total - m, total * w * w, 2.0 * foundation.xi * w * total)
    if isinstance(body, DrumColumn):
        blow = [math.inf] + [blocks[j - 1][0] for j in range(1, n)]
        edge = [math.inf] + [blocks[j][0] + blocks[j - 1][0] for j in range(1, n)]
    else:  # a block, or a body on its plinth: the plinth's edge as a fall, no overlap
        blow = [math.inf] * n
        edge = [math.inf] + [blocks[j - 1][0] - blocks[j][0] for j in range(1, n)]
    return DrumChain(blocks, mus, base, blow, edge)


def reference_drums(body, excitation, mu, foundation=None, *, rtol=1e-10, horizon=600.0, rest_tol=1e-8,
                    method="DOP853", align=True, deadline_s=None, tol=1e-9, max_phases=200000,
                    record_energy=False, patterns="auto", trace=False, flight=False) -> DrumRefResult:
    """Run ``body`` (a :class:`rockcli.models.drums.DrumColumn`; a Block or a Stack run as one or two drums with
    their own criteria) under ``excitation`` with friction ``mu`` (one, or per contact bottom to top) on
    ``foundation`` (None, Rigid, or LinearIsolation with gamma > 0). ``patterns``: how the pattern after an event is
    found (``"enum"``, ``"milp"``, ``"auto"``: :func:`rockcli.reference.drum_patterns.candidates`);
    ``record_energy``: keep every impact's, switch's and rest projection's change of kinetic energy; ``trace``: keep
    ``(t, event, interface, pattern after)`` of every event (to find where two runs part). ``flight``: interfaces may
    lift off, fly and land (:mod:`rockcli.reference.drum_flight`); without it a pivot that pulls is kept as a hinge
    and counted (``n_jumps``), exactly as before."""
    t_wall = time.perf_counter()
    if flight:
        from rockcli.reference.drum_flight_run import FlightRun as cls
    else:
        cls = _DrumRun
    run = cls(chain_of(body, mu, foundation), excitation, rtol, horizon, rest_tol, method, align, deadline_s,
              tol, record_energy, patterns)
    run.trace = [] if trace else None
    if flight and trace:
        run.flight_path = []
    for _ in range(max_phases):
        if not run.phase():
            break
    return run.result(time.perf_counter() - t_wall)


class _DrumRun(_Run):
    def __init__(self, ch, excitation, rtol, horizon, rest_tol, method, align, deadline_s, tol, record_energy,
                 patterns):
        self.ch = ch
        self.patterns = patterns
        self.how = {}
        self.n_kind = 0
        self.trace = None
        self.rigid_ch = DrumChain(list(zip(ch.b, ch.h, ch.m)), ch.mu, None, ch.blow, ch.edge)
        self.ag, self.t_exc_end, self.scan_step, self.max_step = ground_function(excitation)
        self.t_max_end = self.t_exc_end + horizon
        self.rest_tol, self.tol = rest_tol, tol
        n = self.n = ch.n
        self.pat = [0.0] * (2 * n)
        self.q = np.zeros(1 + 2 * n)
        self.qd = np.zeros(1 + 2 * n)
        self.t = 0.0
        self.pmax = max(math.sqrt(0.75 * G / math.hypot(b, h)) for b, h in zip(ch.b, ch.h))
        self.wb = math.sqrt(ch.base[1] / (ch.base[0] + sum(ch.m))) if ch.base else 0.0
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
        u_sc = G * math.tan(min(ch.alpha)) / w ** 2
        self.pos_scale = np.array([u_sc] + [x for j in range(n) for x in (ch.b[j], ch.alpha[j])])
        self.rate_scale = np.array([u_sc * w] + [x * self.pmax for j in range(n) for x in (ch.b[j], ch.alpha[j])])
        self._phase_scales = None
        self.work = Work(method, rtol, None, lambda k: self._phase_scales, deadline_s)
        if align and hasattr(excitation, "acc"):
            self.work.breaks = excitation.dt * np.arange(np.asarray(excitation.acc).size)

    def _switch(self, new):
        super()._switch(new)
        if self.trace is not None:
            self.trace.append((self.t, self._event, tuple(new), self.q.copy(), self.qd.copy()))

    _event = ("start", -1)

    # ---- the contact law -----------------------------------------------------------------------------
    def _sol(self, pat, q, qd, ag, ch=None):
        return dp.pattern_solution(ch or self.ch, pat, q, qd, ag)

    def _choose(self, q, qd, ag, zero_psi, zero_s):
        # an event that returns at once to the same instant, again and again (no pattern meets the conditions and
        # the current one fails at once: the run would stall): after MAX_STALL, the best other candidate is forced
        # (the driver's MAX_STALL), counted as inconsistent
        self._stall = self._stall + 1 if abs(self.t - self._t_last) <= 1e-12 * max(1.0, self.t) else 0
        self._t_last = self.t
        force = self._stall > MAX_STALL
        if force:
            self.n_stall += 1
        best, m, _ = dp.choose(self.ch, self.pat, q, qd, ag, zero_psi, zero_s, self.patterns, self.how, force)
        if m < -self.tol:
            self.n_incons += 1
        return best

    _stall, _t_last, n_stall = 0, -math.inf, 0

    def _band(self, q):
        """The band of ``ag`` (on bearings: of the base's acceleration) in which the chain stays at rest."""
        ch = self.rigid_ch
        self._event = ("from rest", -1)
        pat = [0.0] * (2 * self.n)
        z = np.zeros_like(q)
        f0 = self._sol(pat, q, z, 0.0, ch)[3]
        f1 = self._sol(pat, q, z, 1.0, ch)[3] - f0
        lo, hi = -math.inf, math.inf
        for j in range(self.n):
            mu = ch.mu[j]
            (N0, T0, R0, L0), (N1, T1, R1, L1) = f0[j], f1[j]
            for c0, c1 in ((R0, R1), (L0, L1), (mu * N0 - T0, mu * N1 - T1), (mu * N0 + T0, mu * N1 + T1)):
                if c1 > 0:
                    lo = max(lo, -c0 / c1)
                elif c1 < 0:
                    hi = min(hi, -c0 / c1)
                elif c0 < 0:
                    lo = math.inf
        return lo, hi

    def _free_bound(self, u, ud) -> float:
        mb, kb, cb = self.ch.base
        M = mb + sum(self.ch.m)
        E = 0.5 * M * ud * ud + 0.5 * kb * u * u
        return (kb * math.sqrt(2 * E / kb) + cb * math.sqrt(2 * E / M)) / M

    # ---- a phase -----------------------------------------------------------------------------------------
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
                sol = self._sol(pat, q, qd, self.ag(t))
                cache[key] = (sol[4], sol[3])
            return cache[key]

        def rhs(t, y):
            return np.concatenate([y[nfr:], dyn(t, y)[0][free]])

        y0 = np.concatenate([self.q[free], self.qd[free]])
        self._phase_scales = np.concatenate([self.pos_scale[free], self.rate_scale[free]])
        events, kinds = [], []

        def add(f, kind, j, terminal=True, direction=-1, guard=True, at_start=1.0):
            g = (lambda tt, yy, f=f: f(tt, yy) if tt > t0 else at_start) if guard else f
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
                add(lambda tt, yy, j=j: min(dyn(tt, yy)[1][j][2], dyn(tt, yy)[1][j][3])
                    / max(abs(dyn(tt, yy)[1][j][0]), 1e-300), "open", j)
                watched = True
            if sl != 0.0:
                k = free.index(1 + 2 * j)
                add(lambda tt, yy, k=k, sl=sl: sl * yy[nfr + k], "stop", j)
                if math.isfinite(ch.edge[j]):
                    add(lambda tt, yy, k=k, e=ch.edge[j]: e - abs(yy[k]), "off", j, guard=False)
                add(lambda tt, yy, k=k: yy[nfr + k], "speak", j, terminal=False, direction=0, guard=False)
                if c != 0.0 and math.isfinite(ch.blow[j]):
                    kb = ch.kind_b(j, c, self.q[1 + 2 * j])
                    add(lambda tt, yy, k=k, c=c, j=j: c * yy[k] + ch.b[j] - ch.blow[j], "kind", j,
                        direction=-1 if kb else 1, at_start=1.0 if kb else -1.0)
            else:
                mu = ch.mu[j]
                add(lambda tt, yy, j=j, mu=mu: (mu * dyn(tt, yy)[1][j][0] - abs(dyn(tt, yy)[1][j][1]))
                    / max(abs(dyn(tt, yy)[1][j][0]), 1e-300) if (pat[2 * j] == 0.0 or dyn(tt, yy)[1][j][0] > 0)
                    else 1.0, "slip", j)
                watched = True
        if ch.nb:
            add(lambda tt, yy: yy[nfr], "upeak", -1, terminal=False, direction=0, guard=False)
            if _all_stuck(pat) and t0 >= self.t_exc_end:
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
            self._event = (kind, j)
            if kind == "topple":
                self.toppled, self.t_fail = j, self.t
                self.psi_max[j] = math.pi / 2
                self.done = True
                return False
            if kind == "settled":
                self.settled = self.done = True
                return False
            if kind == "off":
                self.slid_off, self.t_fail = j, self.t
                self.s_max[j] = max(self.s_max[j], abs(self.q[1 + 2 * j]))
                self.done = True
                return False
            if kind == "kind":
                self._kind_switch(j)
                return True
            zero_psi, zero_s = [False] * self.n, [False] * self.n
            if kind == "impact":
                k = free.index(2 + 2 * j)
                c = pat[2 * j]
                tt = np.linspace(t0, self.t, 65)
                if y0[k] == 0.0 and c * y0[nfr + k] <= 0.0 and max(c * sol.sol(x)[k] for x in tt[1:-1]) <= 0.0:
                    # entered at angle 0, it turned into the surface (the pattern could not hold): chosen again
                    self.t = t0
                    self.q, self.qd = unpack(y0)
                    self.q[2 + 2 * j] = 0.0
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

    # ---- impacts, the switch of kind, rest -------------------------------------------------------------
    def _velocity_step(self, pat_to, ch, V=None):
        """``(V-, V+, rates+)``: the velocities of the current state (or ``V``) into ``pat_to`` by a plastic
        impulse (``ch`` sets the friction: the frictionless chain for the rest projections)."""
        X, V0 = self.ch.maximal(self.pat, self.q, self.qd)
        V0 = V0 if V is None else V
        dv, _ = ch.solve(pat_to, self.q, X, V0, None, "v")
        Vp = V0 + dv
        return V0, Vp, ch.rates(pat_to, self.q, X, V0, Vp, "v")

    def _kind_switch(self, j):
        """Interface ``j``'s sliding pivot at the edge of the top below: the other kind from here (module notes)."""
        self.n_kind += 1
        ch, pat = self.ch, self.pat
        c = pat[2 * j]
        sw = c * (ch.blow[j] - ch.b[j])
        hair = (1e-12 if self.qd[1 + 2 * j] > 0.0 else -1e-12) * ch.blow[j]
        self.q[1 + 2 * j] = sw - hair
        _, V = ch.maximal(pat, self.q, self.qd)  # the velocities before, in the chart of the old kind
        self.q[1 + 2 * j] = sw + hair
        V0, Vp, rates = self._velocity_step(pat, ch, V)
        self._record_energy(V0, Vp)
        self._set_rates(pat, rates)
        if self.qd[1 + 2 * j] * pat[2 * j + 1] <= 0.0:  # the plastic map stopped the slip: stick or turn
            self.qd[1 + 2 * j] = 0.0
            zero_s = [i == j for i in range(self.n)]
            self._switch(self._choose(self.q, self.qd, self.ag(self.t), [False] * self.n, zero_s))

    def _impact(self, j):
        if self.t <= self.t_exc_end:
            self.n_imp[j] += 1
        best, m, pulls, V, Vp, rates, _ = dp.impact(self.ch, self.pat, self.q, self.qd, j, self.patterns, self.how)
        if m < -self.tol:
            self.n_incons += 1
        if pulls:
            self.n_jumps += 1
        self._record_energy(V, Vp)
        self._switch(best)
        self._set_rates(best, rates)
        self._rest_rules(j)

    def _project(self, pat_to):
        free = DrumChain(list(zip(self.ch.b, self.ch.h, self.ch.m)), [0.0] * self.n, self.ch.base, self.ch.blow,
                         self.ch.edge)
        V, Vp, rates = self._velocity_step(pat_to, free)
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
            fr = self._sol([0.0] * (2 * n), self.q, np.zeros_like(self.qd), ag, self.rigid_ch)[3]
            moments = [2 * ch.b[i] * min(fr[i][2], fr[i][3]) for i in range(n)]
            if all(m > 0 for m in moments):
                qd = self.qd.copy()
                qd[0] = 0.0
                qd[1::2] = 0.0
                _, V = ch.maximal(self.pat, self.q, qd)
                if ch.kinetic(V) < self.rest_tol * min(ch.alpha[i] * moments[i] for i in range(n)):
                    self._project([0.0 if k % 2 == 0 else self.pat[k] for k in range(2 * n)])
                    return
        if self.pat[2 * j] != 0.0:
            rest = math.inf
            q, qd = self.q.copy(), self.qd.copy()
            q[2 + 2 * j] = qd[2 + 2 * j] = 0.0
            for sg in (1.0, -1.0):
                cand = list(self.pat)
                cand[2 * j] = sg
                rest = min(rest, -sg * self._sol(cand, q, qd, ag)[4][2 + 2 * j])
            rate = self.qd[2 + 2 * j]
            if rest > 0 and rate * rate < 2 * rest * self.rest_tol * ch.alpha[j]:
                cand = list(self.pat)
                cand[2 * j] = 0.0
                self._project(cand)

    def result(self, wall) -> DrumRefResult:
        r = super().result(wall)
        d = dict(r.__dict__)
        offsets, x = [], 0.0
        for s in d["s_end"]:
            x += s
            offsets.append(x)
        return DrumRefResult(**d, n_kind_switches=self.n_kind, n_stall=self.n_stall, how=dict(self.how),
                             residual_offsets=offsets,
                             trace=self.trace or [], n_flights=getattr(self, "n_flights", 0),
                             n_landings=getattr(self, "n_landings", 0),
                             flight_time=list(getattr(self, "flight_time", [0.0] * self.n)),
                             flight_path=getattr(self, "flight_path", None) or [])
