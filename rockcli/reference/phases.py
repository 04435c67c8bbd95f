"""The phase chain every reference run follows, whatever the base: stuck, rocking, impact, rest.

:class:`Phases` holds a run's state (time, states, the phase and the corner it rocks about) and what
is recorded on the way (peaks, uplift, overturn, impacts, rests). The rocking phase, the impact and
the rest rule are the same on every base and are typed here once; each base supplies its stuck phase,
its rocking right-hand side and the acceleration a block at rest would ride on
(:mod:`rockcli.reference.linear`, :mod:`rockcli.reference.hysteretic`).
"""

from __future__ import annotations

import math
from typing import Callable

import numpy as np

from rockcli.reference.equations import colonnade_masses, impact_map_linear_system
from rockcli.reference.result import RefResult
from rockcli.io.units import G


class Phases:
    """One reference run as its phases are chained.

    ``y`` holds theta, theta_dot, then the base states (u, u_dot and a bearing's hysteretic states;
    zeros on a rigid foundation). ``phase`` is ``"stuck"`` or ``"rock"``; ``s`` (+1 or -1) is the
    corner the block rocks about. A rocking phase integrates ``y[:n_rock]``; ``base_acc(t, y)`` is the
    absolute acceleration [m/s^2] of the base a block at rest with states ``y`` rides on (the rest
    rule); ``u_grid`` is the number of points of a rocking phase's dense output searched for the peak
    base displacement (0 on a rigid foundation). ``restitution`` (None: Housner's momentum rule) and
    ``cap_ratio`` (a capped colonnade) enter the impact map and the rest rule.
    """

    def __init__(self, block, gamma: float, n_states: int, *, t_exc_end: float, horizon: float, rest_tol: float,
                 n_rock: int, base_acc: Callable[[float, np.ndarray], float], u_grid: int,
                 gravity: Callable[[float], float] | None = None, restitution: float | None = None,
                 cap_ratio: float = 0.0):
        self.block, self.gamma = block, gamma
        self.restitution, self.cap_ratio = restitution, cap_ratio
        self.t_exc_end, self.t_max_end = t_exc_end, t_exc_end + horizon
        self.rest_tol, self.n_rock, self.base_acc, self.u_grid = rest_tol, n_rock, base_acc, u_grid
        self.gravity = gravity  # g + a_v(t) under a vertical motion (rest rule), None: g
        self.t = 0.0
        self.y = np.zeros(n_states)
        self.phase, self.s = "stuck", 0.0
        self.theta_max, self.t_theta_max, self.u_max = 0.0, math.nan, 0.0
        self.t_uplift = self.t_overturn = self.t_rest = math.nan
        self.n_imp = self.n_rests = 0
        self.uplifted = False

    def chain(self, stuck: Callable[["Phases"], bool], rock_rhs: Callable[[float], Callable], work, max_step: float,
              max_phases: int) -> RefResult:
        """Alternate ``stuck(self)`` (False: the run is over; it calls :meth:`lift` when the block lifts
        off) and rocking phases until the horizon, an overturn or the end of the run."""
        for _ in range(max_phases):
            if self.t >= self.t_max_end - 1e-12:
                break
            if self.phase == "stuck":
                if not stuck(self):
                    break
            elif not self.rock(work, rock_rhs(self.s), max_step):
                break
        return self.result()

    def lift(self, s: float) -> None:
        """The block lifts off about corner ``s`` at ``self.t``."""
        self.s = s
        self.phase = "rock"
        self.t_rest = math.nan
        if not self.uplifted:
            self.uplifted = True
            self.t_uplift = self.t

    def rock(self, work, rhs, max_step: float) -> bool:
        """One rocking phase, to the next impact (then :meth:`impact`), an overturn (returns False) or
        the end of the excitation or of the horizon."""
        s, t0, n = self.s, self.t, self.n_rock
        ev_imp = lambda tt, yy: s * yy[0] if tt > t0 else 1.0  # noqa: E731
        ev_imp.terminal, ev_imp.direction = True, -1
        ev_ot = lambda tt, yy: s * yy[0] - math.pi / 2  # noqa: E731
        ev_ot.terminal, ev_ot.direction = True, 1
        ev_pk = lambda tt, yy: yy[1]  # noqa: E731  (peaks of theta, not terminal)
        t_end = self.t_exc_end if t0 < self.t_exc_end else self.t_max_end
        sol = work.ivp(rhs, (t0, t_end), self.y[:n], max_step=max_step, events=(ev_imp, ev_ot, ev_pk),
                       dense_output=True)
        self._peak(sol.y[0], sol.t)
        if sol.y_events[2].size:
            self._peak(sol.y_events[2][:, 0], sol.t_events[2])
        if self.u_grid:
            ts = np.linspace(t0, sol.t[-1], self.u_grid)
            self.u_max = max(self.u_max, float(np.max(np.abs(sol.sol(ts)[2]))))
        self.y[:n] = sol.y[:, -1]
        self.t = sol.t[-1]
        if sol.status == 1 and sol.t_events[1].size:
            self.t_overturn = self.t
            self.theta_max = math.pi / 2
            self.t_theta_max = self.t
            return False
        if sol.status == 1 and sol.t_events[0].size:
            self.impact()
        return True

    def _peak(self, theta, t) -> None:
        k = int(np.argmax(np.abs(theta)))
        if abs(theta[k]) > self.theta_max:
            self.theta_max, self.t_theta_max = float(abs(theta[k])), float(t[k])

    def impact(self) -> None:
        """The impact map (the 2x2 momentum system), then the rest rule: the block stays at rest when the
        base acceleration it would ride on cannot lift it, and its reach against the restoring
        acceleration ``p^2 cos(alpha) (tan(alpha) - |a|/g)`` is below ``rest_tol`` alpha (a rest is
        plastic: block and base keep their total horizontal momentum; a colonnade's ``p`` and first
        moment in place of the block's)."""
        y, t, block = self.y, self.t, self.block
        y[0] = 0.0
        self.n_imp += 1 if t <= self.t_exc_end else 0
        thd2, ud2 = impact_map_linear_system(block, self.gamma, y[1], y[3], self.restitution, self.cap_ratio)
        y[1], y[3] = thd2, ud2  # the base displacement (and a bearing's hysteretic states) do not jump
        self.s = -self.s
        at_rest = y.copy()
        m = colonnade_masses(block, self.gamma, self.cap_ratio)
        at_rest[3] = y[3] + m.first * math.cos(block.alpha) / m.total * thd2  # S cos(alpha)/M (0: rigid)
        p2, alpha = m.p2, block.alpha
        if self.gravity is None:
            restoring = p2 * math.cos(alpha) * (math.tan(alpha) - abs(self.base_acc(t, at_rest)) / G)
        else:  # the uplift threshold (g + a_v) tan(alpha) in place of g tan(alpha)
            restoring = p2 * math.cos(alpha) * (self.gravity(t) * math.tan(alpha) - abs(self.base_acc(t, at_rest))) / G
        if restoring > 0 and thd2 ** 2 / (2 * restoring) < self.rest_tol * alpha:
            y[3] = at_rest[3]
            y[0] = y[1] = 0.0
            self.phase = "stuck"
            self.t_rest = t
            self.n_rests += 1

    def result(self) -> RefResult:
        verdict = "overturned" if not math.isnan(self.t_overturn) else ("rocked" if self.uplifted else "no_uplift")
        t_rest = self.t_rest if self.phase == "stuck" else math.nan
        return RefResult(verdict, float(self.theta_max), float(self.t_uplift), float(self.t_overturn), self.n_imp,
                         float(self.u_max), t_rest=float(t_rest), n_rests=self.n_rests,
                         t_theta_max=float(self.t_theta_max))
