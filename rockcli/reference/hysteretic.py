"""Rocking on hysteretic bearings (single and double concave sliding, lead-rubber), typed from the paper.

:class:`Bearing` is the bearing per unit total mass with Eq (34)'s ``z`` as an ODE state (stiff for
small ``u_y``, which is what an implicit method such as ``Radau`` is for); the double concave bearing in
rate form. A stuck block rides the bearing: uplift is a terminal event ``|F| = g tan(alpha)``, and after
the excitation the run ends by the bound ``sqrt(F^2 + K u'^2) < g tan(alpha)`` of the free base (P3s),
also an event. The rocking phases, impacts and rests are those of
:class:`rockcli.reference.phases.Phases`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockcli.reference.equations import ground_function, rocking_accelerations
from rockcli.reference.phases import Phases
from rockcli.reference.result import RefResult
from rockcli.io.units import G


def _sign(x):
    """``numpy.sign`` of one number, without its cost on a scalar."""
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else (0.0 if x == 0.0 else math.nan))


@dataclass
class Bearing:
    """A hysteretic bearing typed again from the paper, per unit total mass ``m + m_b``.

    Single concave sliding (Eqs 33-36): force ``-(omega_b^2 u + mu g z)`` with Eq (34)
    ``u_y z' = u' (1 - gamma_bw sign(u' z) |z|^n - beta |z|^n)``; lead-rubber: ``Q/(m + m_b)`` for
    ``mu g``. Double concave (Eqs 37-38): two such surfaces in series joined by a massless slider,
    written in rate form: the surface forces stay equal, so ``K1 u1' = K2 u2'`` with the tangent
    stiffnesses ``K_i = k_i + q_i Phi_i/u_yi`` (states ``u, u', u1, z1, z2``; each surface yields at
    ``u_y/2``).
    """

    dcss: bool
    w2: float
    Q: float
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
        bw = dict(n=getattr(f, "n", 2.0), beta=getattr(f, "beta", 0.5), gbw=getattr(f, "gamma_bw", 0.5))
        if hasattr(f, "R1_eff"):
            return cls(True, G / (f.R1_eff + f.R2_eff), 0.0, f.u_y, G / f.R1_eff, G / f.R2_eff, f.mu1 * G,
                       f.mu2 * G, 0.5 * f.u_y, 0.5 * f.u_y, **bw)
        Q = (f.Q_ratio if hasattr(f, "Q_ratio") else f.mu) * G
        return cls(False, (2 * math.pi / f.T_b) ** 2, Q, f.u_y, **bw)

    @property
    def nb(self) -> int:
        return 5 if self.dcss else 3

    def bracket(self, ud, z):
        zn = abs(z) ** self.n
        return 1.0 - self.gbw * _sign(ud * z) * zn - self.beta * zn

    def force(self, b):
        if self.dcss:
            return -(self.k1 * b[2] + self.q1 * b[3])
        return -self.w2 * b[0] - self.Q * b[2]

    def rates(self, b):
        ud = b[1]
        if not self.dcss:
            return [ud * self.bracket(ud, b[2]) / self.uy]
        br1, br2 = self.bracket(ud, b[3]), self.bracket(ud, b[4])
        K1 = self.k1 + self.q1 * br1 / self.uy1
        K2 = self.k2 + self.q2 * br2 / self.uy2
        u1d = ud * K2 / (K1 + K2)
        u2d = ud - u1d
        return [u1d, u1d * br1 / self.uy1, u2d * br2 / self.uy2]

    def stiffness(self, b, d):
        if not self.dcss:
            return self.w2 + self.Q * self.bracket(d, b[2]) / self.uy
        K1 = self.k1 + self.q1 * self.bracket(d, b[3]) / self.uy1
        K2 = self.k2 + self.q2 * self.bracket(d, b[4]) / self.uy2
        return K1 * K2 / (K1 + K2)

    def free_bound(self, b):
        """An upper bound of the later |force| of the free base (the end-of-run rule of a stuck block)."""
        F = self.force(b)
        if b[1] == 0.0:
            return abs(F)
        return math.sqrt(F * F + self.stiffness(b, math.copysign(1.0, b[1])) * b[1] ** 2)



def reference_hysteretic(block, foundation, excitation, work, *, horizon, rest_tol, max_phases, restitution=None,
                         cap_ratio=0.0) -> RefResult:
    """A block (or a capped colonnade, ``cap_ratio``) on a hysteretic bearing (``foundation`` with ``u_y``:
    SCSS, DCSS or lead-rubber); ``restitution`` None: Housner's momentum rule."""
    ag, t_exc_end, _, max_step = ground_function(excitation)
    if not hasattr(excitation, "acc"):
        max_step = excitation.T_p / 20.0
    brg = Bearing.of(foundation)
    thr = G * math.tan(block.alpha)
    gamma = foundation.gamma
    rocking = rocking_accelerations(block, gamma, cap_ratio)
    t_max_end = t_exc_end + horizon

    def stuck_rhs(t, b):
        return [b[1], brg.force(b) - ag(t), *brg.rates(b)]

    def rock_rhs(s):
        def f(t, y):
            th, thd, b = y[0], y[1], y[2:]
            thdd, a_abs = rocking(th, thd, s, brg.force(b))
            return [thd, thdd, b[1], a_abs - ag(t), *brg.rates(b)]
        return f

    def stuck(ph: Phases) -> bool:
        t, b = ph.t, ph.y[2:]
        after = t >= t_exc_end
        if after and brg.free_bound(b) < thr:
            return False
        a_now = brg.force(b)
        if abs(a_now) > thr:
            ph.lift(-math.copysign(1.0, a_now))
            return True
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
        sol = work.ivp(stuck_rhs, (t, t_end), b, max_step=max_step, events=events, dense_output=True)
        tt = np.linspace(t, sol.t[-1], 2000)
        ph.u_max = max(ph.u_max, float(np.max(np.abs(sol.sol(tt)[0]))), float(np.max(np.abs(sol.y[0]))))
        ph.y[2:] = sol.y[:, -1]
        ph.t = t = sol.t[-1]
        if sol.status == 1 and (sol.t_events[0].size or sol.t_events[1].size):
            ph.lift(-1.0 if sol.t_events[0].size else 1.0)
            return True
        if not after:
            return True
        if t < t_max_end - 1e-12:  # settled: the free base may still reach a larger |u|
            T = 2 * math.pi / math.sqrt(brg.w2)
            tail = work.ivp(stuck_rhs, (t, t + T), ph.y[2:], dense_output=True)
            ph.u_max = max(ph.u_max, float(np.max(np.abs(tail.sol(np.linspace(t, tail.t[-1], 2000))[0]))))
        return False

    ph = Phases(block, gamma, 2 + brg.nb, t_exc_end=t_exc_end, horizon=horizon, rest_tol=rest_tol, n_rock=2 + brg.nb,
                base_acc=lambda t, y: brg.force(y[2:]), u_grid=2000, restitution=restitution, cap_ratio=cap_ratio)
    return ph.chain(stuck, rock_rhs, work, max_step, max_phases)
