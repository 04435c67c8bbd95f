"""Slow, obviously correct reference for rocking on sliding (hysteretic) bearings: SciPy ``solve_ivp``
(Radau by default) with z integrated as a state, straight from the paper's equations.

Written independently of :mod:`rockcli.kernels`: Eq (34) is typed literally (``z`` is an ODE state,
stiff for small ``u_y``, which is what an implicit method is for); Eq (36) for the rocking phase;
the double concave bearing in *rate form*: the massless slider keeps the two surface forces equal,
so their rates are equal, ``K1 u1' = K2 u2'`` with the tangent stiffnesses ``K_i = k_i + q_i Phi_i/u_yi``
(``Phi_i`` the bracket of Eq 34 for surface i), which gives ``u1' = u' K2/(K1 + K2)`` and the states
``u, u', u1, z1, z2`` (the kernels instead solve the force balance algebraically). The impact map is
the 2x2 momentum system of :func:`naive.impact_map_linear_system`. The same documented rules are
applied: uplift threshold, rest criterion with the base acceleration, overturning at |theta| = pi/2,
and the end of the run of a stuck block on a free base by the bound ``sqrt(F^2 + K u'^2) < g tan(alpha)``
(P3s), checked here as a terminal event.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from naive import RefResult, ground_function, impact_map_linear_system
from rockcli.models import Block, DoubleConcaveSliding, LeadRubber, SingleConcaveSliding
from rockcli.units import G


@dataclass
class Bearing:
    """The bearing typed again from the paper (per unit total mass)."""

    dcss: bool
    w2: float  # SCSS/LRB second slope omega_b^2 [1/s^2]
    Q: float  # SCSS/LRB strength [m/s^2]
    uy: float
    k1: float = 0.0
    k2: float = 0.0
    q1: float = 0.0
    q2: float = 0.0
    uy1: float = 0.0
    uy2: float = 0.0
    n: float = 2.0
    beta: float = 0.5
    gbw: float = 0.5

    @classmethod
    def of(cls, f):
        bw = dict(n=f.n, beta=f.beta, gbw=f.gamma_bw)
        if isinstance(f, DoubleConcaveSliding):
            return cls(True, G / (f.R1_eff + f.R2_eff), 0.0, f.u_y, G / f.R1_eff, G / f.R2_eff, f.mu1 * G,
                       f.mu2 * G, 0.5 * f.u_y, 0.5 * f.u_y, **bw)
        Q = f.mu * G if isinstance(f, SingleConcaveSliding) else f.Q_ratio * G
        assert isinstance(f, (SingleConcaveSliding, LeadRubber))
        return cls(False, (2 * math.pi / f.T_b) ** 2, Q, f.u_y, **bw)

    @property
    def nb(self):
        return 5 if self.dcss else 3  # base states: u, u', z  or  u, u', u1, z1, z2

    def bracket(self, ud, z):
        """Eq (34): u_y z' = u' * bracket."""
        return 1.0 - self.gbw * np.sign(ud * z) * abs(z) ** self.n - self.beta * abs(z) ** self.n

    def force(self, b):
        """F: force of the bearings on the base per unit total mass [m/s^2]."""
        if self.dcss:
            return -(self.k1 * b[2] + self.q1 * b[3])
        return -self.w2 * b[0] - self.Q * b[2]

    def rates(self, b):
        """d/dt of the hysteretic states given u' = b[1]."""
        ud = b[1]
        if not self.dcss:
            return [ud * self.bracket(ud, b[2]) / self.uy]
        K1 = self.k1 + self.q1 * self.bracket(ud, b[3]) / self.uy1
        K2 = self.k2 + self.q2 * self.bracket(ud, b[4]) / self.uy2
        u1d = ud * K2 / (K1 + K2)
        u2d = ud - u1d
        return [u1d, u1d * self.bracket(ud, b[3]) / self.uy1, u2d * self.bracket(ud, b[4]) / self.uy2]

    def stiffness(self, b, d):
        """Tangent stiffness -dF/du for motion in direction d."""
        if not self.dcss:
            return self.w2 + self.Q * self.bracket(d, b[2]) / self.uy
        K1 = self.k1 + self.q1 * self.bracket(d, b[3]) / self.uy1
        K2 = self.k2 + self.q2 * self.bracket(d, b[4]) / self.uy2
        return K1 * K2 / (K1 + K2)

    def free_bound(self, b):
        F = self.force(b)
        if b[1] == 0.0:
            return abs(F)
        return math.sqrt(F * F + self.stiffness(b, math.copysign(1.0, b[1])) * b[1] ** 2)


def reference_sliding(block: Block, foundation, excitation, *, rtol=1e-9, atol=1e-12, horizon=600.0,
                      rest_tol=1e-8, method="Radau", max_phases=20000, max_step=None, stats=None) -> RefResult:
    """Chain stuck and rocking phases with ``solve_ivp`` and terminal events (z as a state).

    ``stats`` (a dict), when given, accumulates ``steps``, ``nfev``, ``njev`` and ``nlu`` of the
    ``solve_ivp`` calls (the benchmark's cost figures)."""
    if stats is None:
        stats = {}
    for key in ("steps", "nfev", "njev", "nlu"):
        stats.setdefault(key, 0)

    def count(sol):
        stats["steps"] += max(0, sol.t.size - 1)
        for key in ("nfev", "njev", "nlu"):
            stats[key] += int(getattr(sol, key, 0) or 0)
        return sol

    ag, t_exc_end, _, max_step_rec = ground_function(excitation)
    if max_step is None:
        max_step = max_step_rec if hasattr(excitation, "acc") else excitation.T_p / 20.0
    brg = Bearing.of(foundation)
    nb = brg.nb
    g, p2, alpha, R = G, block.p ** 2, block.alpha, block.R
    thr = g * math.tan(alpha)
    gamma = foundation.gamma
    t_max_end = t_exc_end + horizon
    sc = np.concatenate([[alpha, block.p * alpha], [1.0, 1.0], np.ones(nb - 2)])

    def stuck_rhs(t, b):
        return [b[1], brg.force(b) - ag(t), *brg.rates(b)]

    def rock_rhs(s):
        def f(t, y):
            th, thd, b = y[0], y[1], y[2:]
            A = alpha * s - th
            num = brg.force(b) - gamma * R * thd ** 2 * math.sin(A) + gamma * R * p2 * math.cos(A) * math.sin(A)
            a_abs = num / (1 - gamma * R * p2 * math.cos(A) ** 2 / g)  # Eq (36), 2nd row + ug_ddot
            thdd = -p2 * (math.sin(A) + math.cos(A) * num / (g - gamma * R * p2 * math.cos(A) ** 2))
            return [thd, thdd, b[1], a_abs - ag(t), *brg.rates(b)]
        return f

    t = 0.0
    y = np.zeros(2 + nb)
    phase, s = "stuck", 0.0
    theta_max, t_uplift, t_overturn, n_imp, u_max = 0.0, math.nan, math.nan, 0, 0.0
    uplifted = False
    for _ in range(max_phases):
        if t >= t_max_end - 1e-12:
            break
        if phase == "stuck":
            b = y[2:]
            after = t >= t_exc_end
            if after and brg.free_bound(b) < thr:
                break
            a_now = brg.force(b)
            if abs(a_now) > thr:
                s = -math.copysign(1.0, a_now)
            else:
                up = lambda tt, bb: brg.force(bb) - thr  # noqa: E731
                up.terminal, up.direction = True, 1
                down = lambda tt, bb: brg.force(bb) + thr  # noqa: E731
                down.terminal, down.direction = True, -1
                events = [up, down]
                if after:
                    settle = lambda tt, bb: brg.free_bound(bb) - thr  # noqa: E731
                    settle.terminal, settle.direction = True, -1
                    events.append(settle)
                t_end = t_max_end if after else t_exc_end
                sol = count(solve_ivp(stuck_rhs, (t, t_end), b, method=method, rtol=rtol, atol=atol * sc[2:],
                                      max_step=max_step, events=events, dense_output=True))
                tt = np.linspace(t, sol.t[-1], 2000)
                u_max = max(u_max, float(np.max(np.abs(sol.sol(tt)[0]))), float(np.max(np.abs(sol.y[0]))))
                y[2:] = sol.y[:, -1]
                t = sol.t[-1]
                hit_up = sol.status == 1 and (sol.t_events[0].size or sol.t_events[1].size)
                if not hit_up:
                    if after:
                        if t < t_max_end - 1e-12:  # settled: the free base may still reach a larger |u|
                            T = 2 * math.pi / math.sqrt(brg.w2)
                            tail = count(solve_ivp(stuck_rhs, (t, t + T), y[2:], method=method, rtol=rtol,
                                                   atol=atol * sc[2:], dense_output=True))
                            u_max = max(u_max, float(np.max(np.abs(tail.sol(np.linspace(t, tail.t[-1], 2000))[0]))))
                        break
                    continue
                s = -1.0 if sol.t_events[0].size else 1.0
            phase = "rock"
            if not uplifted:
                uplifted = True
                t_uplift = t
            continue

        ev_imp = lambda tt, yy: s * yy[0] if tt > t0 else 1.0  # noqa: E731
        ev_imp.terminal, ev_imp.direction = True, -1
        ev_ot = lambda tt, yy: s * yy[0] - math.pi / 2  # noqa: E731
        ev_ot.terminal, ev_ot.direction = True, 1
        ev_pk = lambda tt, yy: yy[1]  # noqa: E731
        t0 = t
        t_end = t_exc_end if t < t_exc_end else t_max_end
        sol = count(solve_ivp(rock_rhs(s), (t, t_end), y, method=method, rtol=rtol, atol=atol * sc,
                              max_step=max_step, events=(ev_imp, ev_ot, ev_pk), dense_output=True))
        theta_max = max(theta_max, float(np.max(np.abs(sol.y[0]))))
        if sol.y_events[2].size:
            theta_max = max(theta_max, float(np.max(np.abs(sol.y_events[2][:, 0]))))
        tt = np.linspace(t, sol.t[-1], 2000)
        u_max = max(u_max, float(np.max(np.abs(sol.sol(tt)[2]))))
        y = sol.y[:, -1].copy()
        t = sol.t[-1]
        if sol.status == 1 and sol.t_events[1].size:
            t_overturn = t
            theta_max = math.pi / 2
            break
        if sol.status == 1 and sol.t_events[0].size:
            y[0] = 0.0
            n_imp += 1 if t <= t_exc_end else 0
            thd2, ud2 = impact_map_linear_system(block, gamma, y[1], y[3])
            y[1], y[3] = thd2, ud2  # z (and u1) do not jump: u does not
            s = -s
            ud_rest = y[3] + gamma * block.h * thd2
            b_rest = y[2:].copy()
            b_rest[1] = ud_rest
            a_rest = brg.force(b_rest)
            restoring = p2 * math.cos(alpha) * (math.tan(alpha) - abs(a_rest) / g)
            if restoring > 0 and thd2 ** 2 / (2 * restoring) < rest_tol * alpha:
                y[3] = ud_rest
                y[0] = y[1] = 0.0
                phase = "stuck"
            continue
    verdict = "overturned" if not math.isnan(t_overturn) else ("rocked" if uplifted else "no_uplift")
    return RefResult(verdict, theta_max, t_uplift, t_overturn, n_imp, u_max)
