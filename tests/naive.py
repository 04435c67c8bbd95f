"""Slow, obviously correct references for the compiled kernel (SciPy ``solve_ivp`` with events).

Written independently of :mod:`rockcli.kernels`: the equations are typed again from the paper
(Eq 3; Eqs 7-11 with the reading-notes corrections), the impact map is obtained by solving the
two momentum balances (Eqs 14 and 16) as a 2x2 linear system instead of using the closed form,
and the phases are chained in plain Python. The same documented rules are applied: uplift
threshold, rest criterion (with the base acceleration), overturning at |theta| = pi/2. The end of
the run takes no shortcut on a rigid foundation: after the excitation the free rocking is followed
until the block rests (the rest rule) or overturns. On an isolated base a stuck block is followed
until the free base provably cannot lift it again (its oscillator energy bounds |a|), or the horizon.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar

from rockcli.models import Block, LinearIsolation
from rockcli.units import G


@dataclass
class RefResult:
    verdict: str
    theta_max: float
    t_uplift: float
    t_overturn: float
    n_impacts: int
    u_max: float


def ground_function(excitation):
    """``(ag(t) [m/s^2], end of the excitation [s], scan grid step [s], max_step for solve_ivp [s])``.

    Records: solve_ivp steps at most one sample interval (piecewise-linear input); pulses are smooth
    and leave the step size to the error control.
    """
    if hasattr(excitation, "acc"):
        acc = np.asarray(excitation.acc, float)
        tt = excitation.dt * np.arange(acc.size)

        def ag(t):
            if t > tt[-1] or t < 0:
                return 0.0
            return float(np.interp(t, tt, acc))

        return ag, float(tt[-1]), float(excitation.dt), float(excitation.dt)

    def ag(t):
        return float(excitation.acceleration(t))

    ts, te = excitation.support()
    return ag, float(te), excitation.T_p / 200.0, np.inf


def impact_map_linear_system(block: Block, gamma: float, thd1: float, ud1: float):
    """Velocities after an impact from Eq (14) (angular momentum about the new pivot) and Eq (16)
    (horizontal momentum of block + base), per unit block mass, solved as a linear system."""
    R, b, h = block.R, block.b, block.h
    Io = 4.0 / 3.0 * R * R  # per unit mass
    mb_over_m = (1.0 - gamma) / gamma if gamma > 0 else np.inf
    if not np.isfinite(mb_over_m):
        return thd1 * (Io - 2 * b * b) / Io, ud1
    # unknowns (thd2, ud2):   Io thd2 + h ud2 = (Io - 2 b^2) thd1 + h ud1
    #                      h thd2 + (1 + mb/m) ud2 = h thd1 + (1 + mb/m) ud1
    M = np.array([[Io, h], [h, 1.0 + mb_over_m]])
    rhs = np.array([(Io - 2 * b * b) * thd1 + h * ud1, h * thd1 + (1.0 + mb_over_m) * ud1])
    thd2, ud2 = np.linalg.solve(M, rhs)
    return float(thd2), float(ud2)


def reference_simulate(block: Block, foundation, excitation, *, rtol=1e-10, atol=1e-13, horizon=600.0,
                       rest_tol=1e-8, max_phases=200000) -> RefResult:
    """Chain stuck and rocking phases with ``solve_ivp`` (DOP853) and terminal events."""
    ag, t_exc_end, scan_step, max_step = ground_function(excitation)
    g = G
    p2 = block.p ** 2
    alpha = block.alpha
    R = block.R
    thr = g * math.tan(alpha)
    isolated = isinstance(foundation, LinearIsolation)
    gamma = foundation.gamma if isolated else 0.0
    wb = foundation.omega_b if isolated else 0.0
    xi = foundation.xi if isolated else 0.0
    t_max_end = t_exc_end + horizon

    def F(u, ud):
        return -wb * wb * u - 2 * xi * wb * ud

    def base_cannot_lift(u, ud):
        # free base: (ud^2 + wb^2 u^2)/2 never grows and |a| <= wb sqrt(1 + 4 xi^2) sqrt(ud^2 + wb^2 u^2)
        return wb * math.hypot(1.0, 2.0 * xi) * math.hypot(ud, wb * u) < thr

    def rock_rhs(s):
        def f(t, y):
            th, thd = y[0], y[1]
            A = alpha * s - th
            if not isolated:
                return [thd, -p2 * (math.sin(A) + ag(t) / g * math.cos(A))]
            u, ud = y[2], y[3]
            num = F(u, ud) - gamma * R * thd ** 2 * math.sin(A) + gamma * R * p2 * math.cos(A) * math.sin(A)
            a_abs = num / (1 - gamma * R * p2 * math.cos(A) ** 2 / g)  # Eq (10) + ug_ddot
            thdd = -p2 * (math.sin(A) + math.cos(A) * num / (g - gamma * R * p2 * math.cos(A) ** 2))  # Eq (11)
            return [thd, thdd, ud, a_abs - ag(t)]
        return f

    def stuck_rhs(t, y):
        return [y[1], F(y[0], y[1]) - ag(t)]

    t = 0.0
    y = np.zeros(4)
    phase, s = "stuck", 0.0
    theta_max, t_uplift, t_overturn, n_imp, u_max = 0.0, math.nan, math.nan, 0, 0.0
    uplifted = False
    for _ in range(max_phases):
        if t >= t_max_end - 1e-12:
            break
        if phase == "stuck":
            if t >= t_exc_end and (not isolated or base_cannot_lift(y[2], y[3])):
                break
            if not isolated:
                # scan the ground motion on a fine grid, bracket and solve |ag| = thr
                t_end = t_exc_end
                grid = np.arange(t, t_end + scan_step, scan_step / 4)
                grid = grid[grid <= t_end]
                if grid.size == 0 or grid[-1] < t_end:
                    grid = np.append(grid, t_end)
                vals = np.array([abs(ag(x)) for x in grid]) - thr
                idx = np.nonzero(vals > 0)[0]
                if idx.size == 0:
                    t = t_exc_end
                    continue
                k = idx[0]
                tu = grid[0] if k == 0 else brentq(lambda x: abs(ag(x)) - thr, grid[k - 1], grid[k], xtol=1e-14)
                t = tu
                s = -math.copysign(1.0, ag(grid[k]))
            else:
                a_now = F(y[2], y[3])
                if abs(a_now) > thr:
                    s = -math.copysign(1.0, a_now)
                else:
                    # integrate the free base, then look for the first |a| > thr on the dense output:
                    # a fine grid, every sampled local maximum near thr refined by a bounded search
                    ev_settle = lambda tt, yy: (  # noqa: E731
                        wb * math.hypot(1.0, 2.0 * xi) * math.hypot(yy[1], wb * yy[0]) - thr)
                    ev_settle.terminal, ev_settle.direction = True, -1
                    after = t >= t_exc_end
                    t_end = t_max_end if after else t_exc_end
                    sol = solve_ivp(stuck_rhs, (t, t_end), y[2:4], method="DOP853", rtol=rtol, atol=atol,
                                    max_step=max_step, events=(ev_settle,) if after else None, dense_output=True)
                    T = sol.t[-1]
                    fine = min(2 * math.pi / wb, 4 * scan_step) / 2000.0
                    grid = np.union1d(np.linspace(t, T, max(3, int((T - t) / fine) + 1)), sol.t)
                    yy = sol.sol(grid)
                    absa = np.abs(F(yy[0], yy[1]))
                    hit = None
                    for k in range(1, grid.size):
                        if absa[k] > thr:
                            hit = (grid[k - 1], grid[k])
                            break
                        if k + 1 < grid.size and absa[k] >= absa[k - 1] and absa[k] >= absa[k + 1] \
                                and absa[k] > 0.99 * thr:
                            def neg(x):
                                z = sol.sol(x)
                                return -abs(F(z[0], z[1]))
                            m = minimize_scalar(neg, bounds=(grid[k - 1], grid[k + 1]), method="bounded",
                                                options={"xatol": 1e-14})
                            if -m.fun > thr:
                                hit = (grid[k - 1], m.x)
                                break
                    if hit is None:
                        u_max = max(u_max, float(np.max(np.abs(yy[0]))))
                        y[2:4] = sol.y[:, -1]
                        t = T
                        if after:
                            # settled (P3) or at the horizon; the free base may still reach a larger |u|
                            if T < t_max_end - 1e-12:
                                tail_sol = solve_ivp(stuck_rhs, (T, T + 4 * math.pi / wb), y[2:4], method="DOP853",
                                                     rtol=rtol, atol=atol, dense_output=True)
                                tt = np.linspace(T, tail_sol.t[-1], 4000)
                                u_max = max(u_max, float(np.max(np.abs(tail_sol.sol(tt)[0]))))
                            break
                        continue

                    def excess(x):
                        z = sol.sol(x)
                        return abs(F(z[0], z[1])) - thr

                    tu = brentq(excess, hit[0], hit[1], xtol=1e-15)
                    z = sol.sol(tu)
                    u_max = max(u_max, float(np.max(np.abs(sol.sol(np.linspace(t, tu, 200))[0]))))
                    y[2:4] = z
                    t = tu
                    s = -math.copysign(1.0, F(z[0], z[1]))
            phase = "rock"
            if not uplifted:
                uplifted = True
                t_uplift = t
            continue

        # rocking about corner s
        n = 4 if isolated else 2
        ev_imp = lambda tt, yy: s * yy[0] if tt > t0 else 1.0  # noqa: E731
        ev_imp.terminal, ev_imp.direction = True, -1
        ev_ot = lambda tt, yy: s * yy[0] - math.pi / 2  # noqa: E731
        ev_ot.terminal, ev_ot.direction = True, 1
        ev_pk = lambda tt, yy: yy[1]  # noqa: E731  (peaks of theta, not terminal)
        t0 = t
        t_end = t_exc_end if t < t_exc_end else t_max_end
        sol = solve_ivp(rock_rhs(s), (t, t_end), y[:n], method="DOP853", rtol=rtol, atol=atol, max_step=max_step,
                        events=(ev_imp, ev_ot, ev_pk), dense_output=True)
        theta_max = max(theta_max, float(np.max(np.abs(sol.y[0]))))
        if sol.y_events[2].size:
            theta_max = max(theta_max, float(np.max(np.abs(sol.y_events[2][:, 0]))))
        if isolated:
            ts_ = np.linspace(t, sol.t[-1], 4000)
            u_max = max(u_max, float(np.max(np.abs(sol.sol(ts_)[2]))))
        y[:n] = sol.y[:, -1]
        t = sol.t[-1]
        if sol.status == 1 and sol.t_events[1].size:
            t_overturn = t
            theta_max = math.pi / 2
            break
        if sol.status == 1 and sol.t_events[0].size:
            y[0] = 0.0
            n_imp += 1 if t <= t_exc_end else 0
            thd2, ud2 = impact_map_linear_system(block, gamma, y[1], y[3])
            y[1] = thd2
            if isolated:
                y[3] = ud2
            s = -s
            # rest: the base acceleration the block would ride on cannot lift it, and the reach
            # against the restoring acceleration p^2 cos(alpha) (tan(alpha) - |a|/g) is below rest_tol alpha
            ud_rest = y[3] + gamma * block.h * thd2 if isolated else 0.0
            a_rest = F(y[2], ud_rest) if isolated else ag(t)
            restoring = p2 * math.cos(alpha) * (math.tan(alpha) - abs(a_rest) / g)
            if restoring > 0 and thd2 ** 2 / (2 * restoring) < rest_tol * alpha:
                if isolated:
                    y[3] = ud_rest  # plastic: keep the momentum
                y[0] = y[1] = 0.0
                phase = "stuck"
            continue
        if t >= t_max_end - 1e-12:
            break
    verdict = "overturned" if not math.isnan(t_overturn) else ("rocked" if uplifted else "no_uplift")
    return RefResult(verdict, theta_max, t_uplift, t_overturn, n_imp, u_max)
