"""A block on a rigid foundation (Eq 3) or on linear bearings (Eqs 7-11): the stuck phases.

On a rigid foundation the block lifts when ``|a_g| = g tan(alpha)``: the ground motion is scanned on a
fine grid and the crossing solved by ``brentq``; after the excitation it rests for good. On linear
bearings a stuck block rides the base oscillator: the free base is integrated (during a record one
window of about a second at a time) and its acceleration ``|F(u, u')|`` searched for the first crossing
of ``g tan(alpha)`` on the dense output; after the excitation the run ends once the oscillator's energy
bounds ``|F|`` below the threshold. The rocking phases, impacts and rests are those of
:class:`rockcli.reference.phases.Phases`.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.models import LinearIsolation
from rockcli.reference.equations import colonnade_masses, ground_function, interpolant, rocking_accelerations
from rockcli.reference.phases import Phases
from rockcli.reference.result import RefResult
from rockcli.io.units import G

#: Length of the free base's windows during a record [s] (rounded up to a sample): the search for the next
#: lift-off integrates one window at a time, not the rest of the record.
WINDOW_S = 1.0


def reference_linear(block, foundation, excitation, work, *, horizon, rest_tol, max_phases,
                     vertical=None, restitution=None, cap_ratio=0.0) -> RefResult:
    """Rigid foundation (``foundation`` not a LinearIsolation) or linear bearings; ``vertical``
    (``(acc, dt)``, rigid foundation only) a vertical ground acceleration: gravity ``g + a_v``;
    ``restitution`` and ``cap_ratio`` as for :class:`rockcli.reference.phases.Phases`."""
    from scipy.optimize import brentq, minimize_scalar

    ag, t_exc_end, scan_step, max_step = ground_function(excitation)
    record_dt = float(excitation.dt) if hasattr(excitation, "acc") else None
    g = G
    if vertical is None:
        def gv(t):
            return g
    else:
        vacc = np.asarray(vertical[0], float)
        vtt = float(vertical[1]) * np.arange(vacc.size)
        v_at = interpolant(vtt, vacc)

        def gv(t):  # gravity felt by the block: g + a_v(t), a_v zero outside the series
            return g + (v_at(t) if 0.0 <= t <= vtt[-1] else 0.0)

        t_exc_end = max(t_exc_end, float(vtt[-1]))
        scan_step = min(scan_step, float(vertical[1]))
        max_step = min(max_step, float(vertical[1]))
    alpha = block.alpha
    thr = g * math.tan(alpha)
    tan_a = math.tan(alpha)
    isolated = isinstance(foundation, LinearIsolation)
    gamma = foundation.gamma if isolated else 0.0
    wb = foundation.omega_b if isolated else 0.0
    xi = foundation.xi if isolated else 0.0
    t_max_end = t_exc_end + horizon
    p2 = colonnade_masses(block, gamma, cap_ratio).p2
    rocking = rocking_accelerations(block, gamma, cap_ratio)

    def F(u, ud):
        return -wb * wb * u - 2 * xi * wb * ud

    def free_bound(u, ud):
        # free base: (ud^2 + wb^2 u^2)/2 never grows and |a| <= wb sqrt(1 + 4 xi^2) sqrt(ud^2 + wb^2 u^2)
        return wb * math.hypot(1.0, 2.0 * xi) * math.hypot(ud, wb * u)

    def rock_rhs(s):
        def f(t, y):
            th, thd = y[0], y[1]
            if not isolated:
                A = alpha * s - th
                if vertical is None:
                    return [thd, -p2 * (math.sin(A) + ag(t) / g * math.cos(A))]  # Eq (3)
                return [thd, -p2 / g * (gv(t) * math.sin(A) + ag(t) * math.cos(A))]  # gravity g + a_v
            thdd, a_abs = rocking(th, thd, s, F(y[2], y[3]))
            return [thd, thdd, y[3], a_abs - ag(t)]
        return f

    def stuck_rhs(t, y):
        return [y[1], F(y[0], y[1]) - ag(t)]

    def ground_uplift(ph: Phases) -> bool:
        # scan the ground motion on a fine grid, bracket and solve |ag| = thr
        t = ph.t
        grid = np.arange(t, t_exc_end + scan_step, scan_step / 4)
        grid = grid[grid <= t_exc_end]
        if grid.size == 0 or grid[-1] < t_exc_end:
            grid = np.append(grid, t_exc_end)
        vals = np.array([abs(ag(x)) - (thr if vertical is None else gv(x) * tan_a) for x in grid])
        idx = np.nonzero(vals > 0)[0]
        if idx.size == 0:
            ph.t = t_exc_end
            return True
        k = idx[0]
        ph.t = grid[0] if k == 0 else brentq(lambda x: abs(ag(x)) - gv(x) * tan_a, grid[k - 1], grid[k],
                                                    xtol=1e-14)
        ph.lift(-math.copysign(1.0, ag(grid[k])))
        return True

    def base_uplift(ph: Phases) -> bool:
        t, y = ph.t, ph.y
        a_now = F(y[2], y[3])
        if abs(a_now) > thr:
            ph.lift(-math.copysign(1.0, a_now))
            return True
        if t >= t_exc_end:
            return free_base(ph, t_max_end, after=True)
        # during the excitation a window of about a second at a time (the chain calls this again from its end):
        # a record's windows end on its samples, where the solve_ivp calls of an aligned run are split anyway
        if record_dt is None:
            return free_base(ph, t_exc_end, after=False)
        return free_base(ph, min(t_exc_end, record_dt * math.ceil((t + WINDOW_S) / record_dt)), after=False)

    def free_base(ph: Phases, t_end: float, *, after: bool) -> bool:
        """Integrate the free base from ``ph.t`` to ``t_end`` (after the excitation: to where the oscillator
        can no longer lift the block, the horizon at most), then look for the first |a| > thr on the
        dense output: a fine grid, every sampled local maximum near thr refined by a bounded search (an end
        of the span by a one-sided one, so that a peak at a window's edge is seen). On a lift-off, or at
        the end of the span, returns True; False when the run is over (settled after the excitation, or
        at the horizon)."""
        t, y = ph.t, ph.y
        ev_settle = lambda tt, yy: free_bound(yy[0], yy[1]) - thr  # noqa: E731
        ev_settle.terminal, ev_settle.direction = True, -1
        sol = work.ivp(stuck_rhs, (t, t_end), y[2:4], max_step=max_step, events=(ev_settle,) if after else None,
                       dense_output=True)
        T = sol.t[-1]
        fine = min(2 * math.pi / wb, 4 * scan_step) / 2000.0
        grid = np.union1d(np.linspace(t, T, max(3, int((T - t) / fine) + 1)), sol.t)
        yy = sol.sol(grid)
        absa = np.abs(F(yy[0], yy[1]))
        # the first sample above thr, unless a sampled local maximum near thr before it
        # (checked in order) peaks above thr between the samples
        hit = None
        over = np.nonzero(absa[1:] > thr)[0]
        k_over = int(over[0]) + 1 if over.size else grid.size
        near = absa > 0.99 * thr
        peak = np.zeros(grid.size, bool)
        peak[1:-1] = (absa[1:-1] >= absa[:-2]) & (absa[1:-1] >= absa[2:])
        peak[0], peak[-1] = absa[0] >= absa[1], absa[-1] >= absa[-2]

        def neg(x):
            z = sol.sol(x)
            return -abs(F(z[0], z[1]))

        for k in np.nonzero(peak & near)[0]:
            if k >= k_over:
                break
            lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
            m = minimize_scalar(neg, bounds=(lo, hi), method="bounded", options={"xatol": 1e-14})
            if -m.fun > thr:
                hit = (lo, m.x)
                break
        if hit is None and k_over < grid.size:
            hit = (grid[k_over - 1], grid[k_over])
        if hit is None:
            ph.u_max = max(ph.u_max, float(np.max(np.abs(yy[0]))))
            y[2:4] = sol.y[:, -1]
            ph.t = T
            if not after:
                return True
            # settled (P3) or at the horizon; the free base may still reach a larger |u|
            if T < t_max_end - 1e-12:
                tail_sol = work.ivp(stuck_rhs, (T, T + 4 * math.pi / wb), y[2:4], dense_output=True)
                tt = np.linspace(T, tail_sol.t[-1], 4000)
                ph.u_max = max(ph.u_max, float(np.max(np.abs(tail_sol.sol(tt)[0]))))
            return False

        def excess(x):
            z = sol.sol(x)
            return abs(F(z[0], z[1])) - thr

        tu = brentq(excess, hit[0], hit[1], xtol=1e-15)
        z = sol.sol(tu)
        ph.u_max = max(ph.u_max, float(np.max(np.abs(sol.sol(np.linspace(t, tu, 200))[0]))))
        y[2:4] = z
        ph.t = tu
        ph.lift(-math.copysign(1.0, F(z[0], z[1])))
        return True

    def stuck(ph: Phases) -> bool:
        if ph.t >= t_exc_end and (not isolated or free_bound(ph.y[2], ph.y[3]) < thr):
            return False
        return base_uplift(ph) if isolated else ground_uplift(ph)

    base_acc = (lambda t, y: F(y[2], y[3])) if isolated else (lambda t, y: ag(t))
    ph = Phases(block, gamma, 4, t_exc_end=t_exc_end, horizon=horizon, rest_tol=rest_tol,
                n_rock=4 if isolated else 2, base_acc=base_acc, u_grid=4000 if isolated else 0,
                gravity=None if vertical is None else gv, restitution=restitution, cap_ratio=cap_ratio)
    return ph.chain(stuck, rock_rhs, work, max_step, max_phases)
