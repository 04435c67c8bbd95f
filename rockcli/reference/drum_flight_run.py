"""The run of the slow reference of a column of drums with flight (``reference_drums(..., flight=True)``): the phases
of :class:`rockcli.reference.friction_drums._DrumRun` with flying interfaces (their lift integrated, their ends'
gaps, angle and overlap watched), a pivot's normal force at 0 a terminal event (lift-off), landings as impacts, and
the contact law of :mod:`rockcli.reference.drum_flight` at every event. Counts: lift-offs, landings, the time each
interface spent flying; with ``trace``, the flying phases sampled (``flight_path``: ``(t, X, V)``, the maximal
positions and velocities) for the tests' free-flight check."""

from __future__ import annotations

import math

import numpy as np

from rockcli.reference import drum_flight as df
from rockcli.reference.friction_drums import _DrumRun


class FlightRun(_DrumRun):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        n, ch = self.n, self.ch
        self.q = np.zeros(1 + 3 * n)
        self.qd = np.zeros(1 + 3 * n)
        self.pos_scale = np.concatenate([self.pos_scale, [ch.b[j] * ch.alpha[j] for j in range(n)]])
        self.rate_scale = np.concatenate([self.rate_scale, [ch.b[j] * ch.alpha[j] * self.pmax for j in range(n)]])
        self.n_flights = self.n_landings = 0
        self.flight_time = [0.0] * n
        self.flight_path = None
        self._fly, self._fly_only = (), False

    def _free(self, pat):
        from rockcli.reference.drum_patterns import free_of

        return free_of(self.ch, pat)

    def _switch(self, new):
        for j in range(self.n):
            was, now = df.flying(self.pat[2 * j]), df.flying(new[2 * j])
            if now and not was:
                self.n_flights += 1
            elif was and not now:
                self.n_landings += 1
                self.q[1 + 2 * self.n + j] = 0.0
        super()._switch(new)

    # ---- the contact law with flight ----------------------------------------------------------------
    def _choose(self, q, qd, ag, zero_psi, zero_s):
        from rockcli.reference.friction_drums import MAX_STALL

        self._stall = self._stall + 1 if abs(self.t - self._t_last) <= 1e-12 * max(1.0, self.t) else 0
        self._t_last = self.t
        force = self._stall > MAX_STALL
        if force:
            self.n_stall += 1
        best, m, pulling = df.choose(self.ch, self.pat, q, qd, ag, zero_psi, zero_s, self.patterns, self.how, force,
                                     self._fly, self._fly_only)
        self._fly, self._fly_only = (), False
        if m < -self.tol:
            self.n_incons += 1
        if pulling:
            self.n_jumps += 1
        return best

    def _do_impact(self, pat_in, zero_psi, V0, j):
        best, m, pulling, Vp, rates = df.impact(self.ch, pat_in, self.q, V0, zero_psi, self.patterns, self.how)
        if m < -self.tol:
            self.n_incons += 1
        if pulling:
            self.n_jumps += 1
        self._record_energy(V0, Vp)
        self._switch(best)
        self._set_rates(best, rates)
        if not any(df.flying(best[2 * i]) for i in range(self.n)):
            self._rest_rules(j)

    def _impact(self, j):
        """A pivot's angle back to 0 (the existing impact, with flight)."""
        if self.t <= self.t_exc_end:
            self.n_imp[j] += 1
        _, V0 = self.ch.maximal(self.pat, self.q, self.qd)
        zero_psi = [i == j or self.pat[2 * i] == 0.0 for i in range(self.n)]
        self._do_impact(list(self.pat), zero_psi, V0, j)

    def _landing(self, j, side):
        """Interface ``j``'s end ``side`` back on the top below (module notes of drum_flight)."""
        ch, n = self.ch, self.n
        if self.t <= self.t_exc_end:
            self.n_imp[j] += 1
        X, V0 = ch.maximal(self.pat, self.q, self.qd)
        gaps = df.end_gaps(ch, j, X)
        kb = gaps[side][1]
        q = self.q.copy()
        q[1 + 2 * n + j] = 0.0
        pat = list(self.pat)
        face = abs(gaps[-side][0]) <= 1e-9 * (ch.b[j] + ch.h[j])
        if face:  # both ends at once: a face
            q[1 + 2 * j] = df.q_slip(ch, pat, X, j)
            q[2 + 2 * j] = 0.0
            pat[2 * j] = 0.0
        else:
            q[1 + 2 * j] = ch.rows(j, side * (3.0 if kb else 2.0), 0.0, X, V0)["t"][0]
            pat[2 * j] = side
        pat[2 * j + 1] = 0.0
        self.q = q
        zero_psi = [(i == j and face) or pat[2 * i] == 0.0 for i in range(n)]
        self._do_impact(pat, zero_psi, V0, j)

    def _rest_rules(self, j):
        if any(df.flying(self.pat[2 * i]) for i in range(self.n)):
            return
        super()._rest_rules(j)

    # ---- a phase -------------------------------------------------------------------------------------
    def _move(self) -> bool:
        ch, pat, t0 = self.ch, list(self.pat), self.t
        n = self.n
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
                cache[key] = (sol[4], sol[3], sol[0])
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
        flying_now = [j for j in range(n) if df.flying(pat[2 * j])]
        for j in range(n):
            c, sl = pat[2 * j], pat[2 * j + 1]
            if df.flying(c):
                k = free.index(2 + 2 * j)
                for side in (1.0, -1.0):
                    add(lambda tt, yy, j=j, side=side: df.end_gaps(ch, j, dyn(tt, yy)[2])[side][0], "land", (j, side))
                for cc in (1.0, -1.0):
                    add(lambda tt, yy, k=k, cc=cc: cc * yy[k] - math.pi / 2, "topple", j, direction=1, guard=False)
                add(lambda tt, yy, k=k: yy[nfr + k], "peak", j, terminal=False, direction=0, guard=False)
                if math.isfinite(ch.blow[j]):
                    add(lambda tt, yy, j=j: df.overlap(ch, j, dyn(tt, yy)[2]), "off", j, guard=False)
                watched = True
                continue
            if c != 0.0:
                k = free.index(2 + 2 * j)
                add(lambda tt, yy, k=k, c=c: c * yy[k], "impact", j)
                add(lambda tt, yy, k=k, c=c: c * yy[k] - math.pi / 2, "topple", j, direction=1, guard=False)
                add(lambda tt, yy, k=k: yy[nfr + k], "peak", j, terminal=False, direction=0, guard=False)
                add(lambda tt, yy, j=j: dyn(tt, yy)[1][j][0] / max(float(np.max(np.abs(dyn(tt, yy)[1][:, :2]))),
                                                                   1e-300), "lift", j)
                watched = True
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
            from rockcli.reference.friction import _all_stuck

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
        if flying_now:
            for j in flying_now:
                self.flight_time[j] += float(sol.t[-1]) - t0
            if self.flight_path is not None:
                for tt in ts:
                    X, V = ch.maximal(pat, *unpack(sol.sol(tt)))
                    self.flight_path.append((float(tt), X, V, tuple(flying_now)))
        for k, (kind, j) in enumerate(kinds):
            if kind in ("peak", "speak", "upeak") and sol.y_events[k].size:
                for yy in sol.y_events[k]:
                    self._peaks(unpack(yy)[0], pat)
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
            if kind == "land":
                self._landing(*j)
                return True
            if kind == "kind":
                self._kind_switch(j)
                return True
            zero_psi, zero_s = [False] * n, [False] * n
            if kind == "impact":
                k = free.index(2 + 2 * j)
                c = pat[2 * j]
                tt = np.linspace(t0, self.t, 65)
                if y0[k] == 0.0 and c * y0[nfr + k] <= 0.0 and max(c * sol.sol(x)[k] for x in tt[1:-1]) <= 0.0:
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
                self._fly = (j,)
            elif kind == "lift":
                zero_s[j] = pat[2 * j + 1] == 0.0
                self._fly, self._fly_only = (j,), True
            else:  # the cone
                zero_s[j] = True
                zero_psi[j] = pat[2 * j] == 0.0
            for i in range(n):
                if pat[2 * i] in (1.0, -1.0) and self.q[2 + 2 * i] == 0.0 and self.qd[2 + 2 * i] == 0.0:
                    zero_psi[i] = True
            self._switch(self._choose(self.q, self.qd, self.ag(self.t), zero_psi, zero_s))
            return True
        return True
