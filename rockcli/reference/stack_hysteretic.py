"""The slow reference of a body on its plinth on hysteretic bearings (single and double concave sliding,
lead-rubber): :mod:`rockcli.reference.stack` with the bearings of the single block's reference.

The stack is the one of :mod:`rockcli.reference.stack` on linear bearings (the same separate bodies, the same base
coordinate ``u``, the same events, impacts, rest rules); only the bearings' force changes: the force law and the
extra states of :class:`rockcli.reference.hysteretic.Bearing` (typed from the paper for the single block, with the
Bouc-Wen variables as ODE states), per unit of the whole moving mass ``M = (m1 + m2)/gamma`` as for the single
block. The extra states are integrated with the others in every pattern (they follow ``u``); an impact leaves them
as they are (they are functions of the path of ``u``, which an impact does not move: docs/physics-plinth.md, "On
sliding and lead-rubber bearings"). The run ends at rest after the excitation once the free hysteretic base's
force bound (P3s of the single block, :meth:`Bearing.free_bound`) keeps every face shut; the base's later peak is
then read over two periods of the bearing's second slope.

Bouc-Wen variables with a small yield displacement are stiff: use an implicit method (``Radau``, the default of
:func:`reference_plinth` on these bearings), as for the single block's reference.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.reference.hysteretic import Bearing
from rockcli.reference.stack_run import _Run


def hysteretic_base(stack, isolation):
    """``((m_b, 0, 0), bearing)`` of a hysteretic ``isolation`` under ``stack`` (per unit body mass): the base's mass
    with ``gamma = (m1 + m2)/(m1 + m2 + m_b)`` as on linear bearings, and the bearing of the single block's reference
    (its force per unit of the whole moving mass)."""
    if not isolation.gamma > 0:
        raise ValueError("the stack reference needs a base of finite mass (gamma > 0)")
    m = 1.0 + stack.m2
    return (m / isolation.gamma - m, 0.0, 0.0), Bearing.of(isolation)


class HystRun(_Run):
    """:class:`rockcli.reference.stack_run._Run` on a hysteretic bearing ``brg`` (set before the run starts)."""

    brg: Bearing = None

    def _init_base(self):
        mb = self.M.base[0]
        self.total = mb + float(np.sum(self.M.m))
        self.wb, self.zeta = math.sqrt(self.brg.w2), 0.0
        nx = self.brg.nb - 2  # z, or u1, z1, z2 (double concave)
        self.xb = np.zeros(nx)
        thr = 9.80665 * math.tan(float(np.min(self.M.alpha)))
        w = max(self.wb, self.pmax)
        # scales of the error test: z (|z| <= 1) at 1, the slider's u1 as u
        self.xscale = np.array([thr / w ** 2, 1.0, 1.0]) if nx == 3 else np.ones(nx)

    def _full(self, u, ud, xb):
        return np.concatenate([[u, ud], np.asarray(xb, float)])

    def _Fb(self, u, ud, xb):
        return self.total * self.brg.force(self._full(u, ud, xb))

    def _xrates(self, u, ud, xb):
        return self.brg.rates(self._full(u, ud, xb))

    def _bearing(self, u, ud) -> float:
        return float(self.brg.force(self._full(u, ud, self.xb)))

    def _free_bound(self, u, ud, xb) -> float:
        """P3s of the single block: ``sqrt(F^2 + K u'^2)`` bounds every later ``|F|`` of the free base (the stack
        at rest on it moves with it, so the base is the single block's stuck base: ``u'' = F`` per unit moving
        mass)."""
        return self.brg.free_bound(self._full(u, ud, xb))

    def _free_disp_bound(self, y) -> float:
        """``sqrt(2 E)/w`` bounds every later ``|u|`` of the free base: ``E = u'^2/2 + sum (k_i u_i^2 + q_i u_yi
        z_i^2)/2`` never grows (P3s of the single block; ``k = w^2`` for one element, and for two in series
        ``|u1 + u2|^2 <= (1/k1 + 1/k2)(k1 u1^2 + k2 u2^2)`` with ``1/k1 + 1/k2 = 1/w^2``)."""
        b = self.brg
        if b.dcss:
            u, ud, u1, z1, z2 = y
            E2 = ud * ud + b.k1 * u1 * u1 + b.k2 * (u - u1) ** 2 + b.q1 * b.uy1 * z1 * z1 + b.q2 * b.uy2 * z2 * z2
        else:
            u, ud, z = y
            E2 = ud * ud + b.w2 * u * u + b.Q * b.uy * z * z
        return math.sqrt(E2 / b.w2)

    def _base_tail(self):
        """The free base's later peak ``|u|`` after the run ends at rest: its turning points until its energy bound
        of every later ``|u|`` is below the peak reached (exact), at most two periods of the second slope."""
        from scipy.integrate import solve_ivp

        brg = self.brg

        def f(t, y):
            return [y[1], brg.force(y), *brg.rates(y)]

        def turn(t, y):
            return y[1]

        def final(t, y):
            return self._free_disp_bound(y) - max(self.u_max, abs(y[0]))

        final.terminal, final.direction = True, -1
        y0 = self._full(self.u, self.ud, self.xb)
        if final(0.0, y0) <= 0.0:
            return
        sol = solve_ivp(f, (0.0, 4 * math.pi / self.wb), y0, method="Radau", rtol=1e-10, atol=1e-13,
                        events=[turn, final])
        for yy in sol.y_events[0]:
            self.u_max = max(self.u_max, abs(float(yy[0])))
        self.u_max = max(self.u_max, abs(float(sol.y[0, -1])))
