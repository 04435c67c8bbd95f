"""Slow, obviously correct references for the compiled kernel: SciPy ``solve_ivp`` with events.

Written independently of :mod:`rockcli.kernels` (never imports it, nor numba): the equations are
typed again from the paper (Eq 3; Eqs 7-11 with the reading-notes corrections; Eqs 33-38 for
sliding bearings), the impact map is obtained by solving the two momentum balances (Eqs 14 and 16)
as a 2x2 linear system instead of using the closed form, and the phases are chained in plain Python.
The same documented rules are applied: uplift threshold, rest criterion (with the base
acceleration), overturning at |theta| = pi/2. The end of the run takes no shortcut on a rigid
foundation: after the excitation the free rocking is followed until the block rests (the rest rule)
or overturns. On an isolated base a stuck block is followed until the free base provably cannot
lift it again (its oscillator energy bounds |a|), or the horizon.

Any of SciPy's methods (``RK45``, ``DOP853``, ``Radau``, ``LSODA``, ``BDF``) at any ``rtol``/``atol``
can integrate the phases; :class:`RefResult` also says how much work that took (steps, right-hand
sides, Jacobians, LU decompositions, wall time), which ``rockcli bench work-precision`` compares with
the kernel. SciPy is imported when a reference runs, not when this module is imported.

The test suite's ``tests/naive.py`` re-exports this module.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from rockcli.models import Block, LinearIsolation
from rockcli.units import G

#: The SciPy ``solve_ivp`` methods a reference can use.
METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF")
#: Implicit methods: their right-hand-side count includes the finite-difference Jacobian columns.
IMPLICIT = ("Radau", "BDF", "LSODA")


@dataclass
class RefResult:
    """Outcome of :func:`reference_simulate` (SI units).

    ``verdict``, peak ``theta_max`` [rad], ``t_uplift``, ``t_overturn`` [s] (NaN when it does not
    overturn), ``n_impacts`` (while the ground moves), peak base displacement ``u_max`` [m];
    ``t_rest`` [s], the last time the block was set at rest for good (NaN when it never rests or
    overturns); ``t_theta_max`` [s], when the peak was reached; the work: ``steps`` (accepted steps
    of every ``solve_ivp`` call), ``nfev`` (right-hand sides, including ``n_states`` per finite-difference Jacobian), ``njev``, ``nlu``
    and ``wall_s`` (the whole run); ``method``, ``rtol`` and ``atol`` as used.
    """

    verdict: str
    theta_max: float
    t_uplift: float
    t_overturn: float
    n_impacts: int
    u_max: float
    t_rest: float = math.nan
    t_theta_max: float = math.nan
    steps: int = 0
    nfev: int = 0
    njev: int = 0
    nlu: int = 0
    wall_s: float = math.nan
    method: str = "DOP853"
    rtol: float = math.nan
    atol: object = None
    n_rests: int = 0


class ReferenceTimeout(RuntimeError):
    """A reference run passed its wall-time budget (``deadline_s``)."""


class ReferenceFailure(RuntimeError):
    """``solve_ivp`` gave up (e.g. the step size fell below its minimum)."""


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


def is_hysteretic(foundation) -> bool:
    """A sliding or lead-rubber bearing (a Bouc-Wen element): recognised by its fields, so that this
    module needs no bearing class (they live in :mod:`rockcli.models` once sliding bearings exist)."""
    return hasattr(foundation, "u_y") and (hasattr(foundation, "mu1") or hasattr(foundation, "mu")
                                          or hasattr(foundation, "Q_ratio"))


def state_scales(block: Block, foundation, n_states: int) -> np.ndarray:
    """Scales of the states (theta, theta_dot, u, u_dot, hysteretic...) for a mixed error test.

    The kernel keeps the error on each state below ``rtol * max(|y|, scale)``; ``atol = rtol * scale``
    gives SciPy the same test: alpha, p alpha, ``g tan(alpha)/max(omega_b, p)^2`` and
    ``g tan(alpha)/max(omega_b, p)`` for the base, 1 for a Bouc-Wen ``z`` (|z| <= 1) and the
    displacement scale for a DCSS surface displacement.
    """
    p, alpha = block.p, block.alpha
    sc = [alpha, p * alpha]
    if n_states > 2:
        thr = G * math.tan(alpha)
        w = getattr(foundation, "omega_b", p)
        w = max(w, p)
        sc += [thr / w ** 2, thr / w]
        if n_states > 4:
            extra = n_states - 4
            sc += [1.0] * extra if extra == 1 else [thr / w ** 2] + [1.0] * (extra - 1)
    return np.asarray(sc[:n_states], dtype=float)


class _Work:
    """Counts the work of the ``solve_ivp`` calls of one reference run; enforces the wall budget."""

    def __init__(self, method: str, rtol: float, atol, scales_of, deadline_s: float | None):
        from scipy.integrate import solve_ivp

        if method not in METHODS:
            raise ValueError(f"unknown SciPy method {method!r} (use one of {', '.join(METHODS)})")
        self.solve_ivp = solve_ivp
        self.method, self.rtol, self.atol, self.scales_of = method, float(rtol), atol, scales_of
        self.steps = self.nfev = self.njev = self.nlu = 0
        self.calls = 0
        self.breaks = None  # sorted break points [s] (a record's sample times) when aligned
        self.deadline = None if deadline_s is None else time.perf_counter() + float(deadline_s)

    def _atol(self, n):
        if self.atol is None:
            return self.rtol * self.scales_of(n)
        return self.atol

    def _wrap(self, fun):
        if self.deadline is None:
            return fun
        deadline = self.deadline

        def timed(t, y):
            self.calls += 1
            if self.calls % 256 == 0 and time.perf_counter() > deadline:
                raise ReferenceTimeout(f"{self.method} at rtol {self.rtol:g}: over the wall-time budget")
            return fun(t, y)

        return timed

    def ivp(self, fun, span, y0, **kw):
        """``solve_ivp`` over ``span``; with break points (a record's samples), one call per interval
        between them, chained (no step straddles a kink of the piecewise-linear ground motion)."""
        if self.breaks is not None:
            lo = np.searchsorted(self.breaks, span[0], side="right")
            hi = np.searchsorted(self.breaks, span[1], side="left")
            if hi > lo:
                kw["max_step"] = np.inf
                edges = [span[0], *self.breaks[lo:hi], span[1]]
                pieces = []
                y = np.asarray(y0, dtype=float)
                for a, b in zip(edges[:-1], edges[1:]):
                    if b <= a:
                        continue
                    sol = self._ivp1(fun, (a, b), y, **kw)
                    pieces.append(sol)
                    y = sol.y[:, -1]
                    if sol.status == 1:
                        break
                return _Chain(pieces)
        return self._ivp1(fun, span, y0, **kw)

    def _ivp1(self, fun, span, y0, **kw):
        n = len(y0)
        try:
            sol = self.solve_ivp(self._wrap(fun), span, y0, method=self.method, rtol=self.rtol, atol=self._atol(n),
                                 **kw)
        except ValueError as exc:  # e.g. brentq in SciPy's event location: the interpolant disagrees at a step end
            raise ReferenceFailure(f"{self.method} at rtol {self.rtol:g}: solve_ivp failed ({exc})") from None
        self.steps += max(0, len(sol.t) - 1)
        self.nfev += int(sol.nfev) + n * int(sol.njev)
        self.njev += int(sol.njev)
        self.nlu += int(sol.nlu)
        if sol.status == -1:
            raise ReferenceFailure(f"{self.method} at rtol {self.rtol:g}: {sol.message}")
        if not np.all(np.isfinite(sol.y)):  # e.g. an explicit method on a stiff Bouc-Wen element
            raise ReferenceFailure(f"{self.method} at rtol {self.rtol:g}: diverged (non-finite states)")
        return sol


class _Chain:
    """Successive ``solve_ivp`` results read as one: states, events and a piecewise dense output."""

    def __init__(self, pieces):
        self.pieces = pieces
        self.t = np.concatenate([pieces[0].t] + [p.t[1:] for p in pieces[1:]])
        self.y = np.concatenate([pieces[0].y] + [p.y[:, 1:] for p in pieces[1:]], axis=1)
        self.status = pieces[-1].status
        n_ev = len(pieces[0].t_events) if pieces[0].t_events is not None else 0
        self.t_events = [np.concatenate([p.t_events[i] for p in pieces]) for i in range(n_ev)] if n_ev else None
        self.y_events = ([np.concatenate([p.y_events[i].reshape(-1, self.y.shape[0]) for p in pieces])
                          for i in range(n_ev)] if n_ev else None)
        self._ends = np.array([p.t[-1] for p in pieces])

    def sol(self, t):
        if np.ndim(t) == 0:
            k = min(int(np.searchsorted(self._ends, t, side="left")), len(self.pieces) - 1)
            return self.pieces[k].sol(t)
        t = np.asarray(t, dtype=float)
        order = None if t.size < 2 or np.all(t[1:] >= t[:-1]) else np.argsort(t, kind="stable")
        ts = t if order is None else t[order]
        out = np.empty((self.y.shape[0], t.size))
        cuts = np.searchsorted(ts, self._ends, side="right")
        cuts[-1] = ts.size
        lo = 0
        for k, hi in enumerate(cuts):
            if hi > lo:
                out[:, lo:hi] = self.pieces[k].sol(ts[lo:hi])
            lo = max(lo, hi)
        if order is not None:
            back = np.empty_like(out)
            back[:, order] = out
            out = back
        return out


def reference_simulate(block: Block, foundation, excitation, *, rtol=1e-10, atol=1e-13, horizon=600.0,
                       rest_tol=1e-8, max_phases=200000, method="DOP853", deadline_s=None,
                       align=False) -> RefResult:
    """Chain stuck and rocking phases with ``solve_ivp`` and terminal events.

    Parameters
    ----------
    block, foundation, excitation
        As for :func:`rockcli.solve.simulate` (rigid, linear, or a hysteretic bearing).
    rtol : float
        Relative tolerance of ``solve_ivp``.
    atol : float, array or None
        Absolute tolerance; ``None`` gives ``rtol`` times the state scales of :func:`state_scales`
        (the kernel's mixed error test). For hysteretic bearings a float is multiplied by those scales.
    method : str
        One of :data:`METHODS`. Hysteretic bearings (a stiff ``z`` for small ``u_y``) call for ``Radau``.
    deadline_s : float, optional
        Wall-time budget [s]; past it the run raises :class:`ReferenceTimeout`.
    align : bool
        Records only: integrate each sample interval by its own ``solve_ivp`` call, so that no step
        straddles a kink of the piecewise-linear ground motion (as the kernel does). Otherwise the
        steps are only limited to one sample interval, and the error of the steps across kinks
        limits the accuracy (about 1e-7 in theta_max/alpha on Kobe Takarazuka at any rtol).

    Returns
    -------
    RefResult
        Verdict, peaks and the work done. Raises :class:`ReferenceFailure` when ``solve_ivp`` fails.
    """
    import scipy.integrate  # noqa: F401  (imported before the clock starts)
    import scipy.optimize  # noqa: F401

    t_wall = time.perf_counter()
    if is_hysteretic(foundation):
        n_total = 2 + Bearing.of(foundation).nb
    else:
        n_total = 4 if isinstance(foundation, LinearIsolation) else 2
    full = state_scales(block, foundation, n_total)
    # rocking integrates every state; a stuck block only the base states (the last ones)
    work = _Work(method, rtol, atol, lambda n: full[-n:], deadline_s)
    if align and hasattr(excitation, "acc"):
        work.breaks = float(excitation.dt) * np.arange(1, np.asarray(excitation.acc).size)
    run = _reference_hysteretic if is_hysteretic(foundation) else _reference_linear
    with np.errstate(all="ignore"):  # a diverging method is reported (ReferenceFailure), not warned about
        out = run(block, foundation, excitation, work, horizon=horizon, rest_tol=rest_tol, max_phases=max_phases)
    out.steps, out.nfev, out.njev, out.nlu = work.steps, work.nfev, work.njev, work.nlu
    out.wall_s = time.perf_counter() - t_wall
    out.method, out.rtol, out.atol = method, float(rtol), atol
    return out


def _reference_linear(block, foundation, excitation, work, *, horizon, rest_tol, max_phases) -> RefResult:
    """Rigid foundation (Eq 3) or linear bearings (Eqs 7-11)."""
    from scipy.optimize import brentq, minimize_scalar

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
    t_rest, n_rests, t_theta_max = math.nan, 0, math.nan
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
                    sol = work.ivp(stuck_rhs, (t, t_end), y[2:4], max_step=max_step,
                                   events=(ev_settle,) if after else None, dense_output=True)
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
                    inner = absa[1:-1]
                    cand = np.nonzero((inner >= absa[:-2]) & (inner >= absa[2:]) & (inner > 0.99 * thr))[0] + 1
                    for k in cand[cand < k_over]:
                        def neg(x):
                            z = sol.sol(x)
                            return -abs(F(z[0], z[1]))
                        m = minimize_scalar(neg, bounds=(grid[k - 1], grid[k + 1]), method="bounded",
                                            options={"xatol": 1e-14})
                        if -m.fun > thr:
                            hit = (grid[k - 1], m.x)
                            break
                    if hit is None and k_over < grid.size:
                        hit = (grid[k_over - 1], grid[k_over])
                    if hit is None:
                        u_max = max(u_max, float(np.max(np.abs(yy[0]))))
                        y[2:4] = sol.y[:, -1]
                        t = T
                        if after:
                            # settled (P3) or at the horizon; the free base may still reach a larger |u|
                            if T < t_max_end - 1e-12:
                                tail_sol = work.ivp(stuck_rhs, (T, T + 4 * math.pi / wb), y[2:4], dense_output=True)
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
            t_rest = math.nan
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
        sol = work.ivp(rock_rhs(s), (t, t_end), y[:n], max_step=max_step, events=(ev_imp, ev_ot, ev_pk),
                       dense_output=True)
        k_top = int(np.argmax(np.abs(sol.y[0])))
        if abs(sol.y[0][k_top]) > theta_max:
            theta_max, t_theta_max = float(abs(sol.y[0][k_top])), float(sol.t[k_top])
        if sol.y_events[2].size:
            k_top = int(np.argmax(np.abs(sol.y_events[2][:, 0])))
            if abs(sol.y_events[2][k_top, 0]) > theta_max:
                theta_max, t_theta_max = float(abs(sol.y_events[2][k_top, 0])), float(sol.t_events[2][k_top])
        if isolated:
            ts_ = np.linspace(t, sol.t[-1], 4000)
            u_max = max(u_max, float(np.max(np.abs(sol.sol(ts_)[2]))))
        y[:n] = sol.y[:, -1]
        t = sol.t[-1]
        if sol.status == 1 and sol.t_events[1].size:
            t_overturn = t
            theta_max = math.pi / 2
            t_theta_max = t
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
                t_rest = t
                n_rests += 1
            continue
        if t >= t_max_end - 1e-12:
            break
    verdict = "overturned" if not math.isnan(t_overturn) else ("rocked" if uplifted else "no_uplift")
    if phase != "stuck":
        t_rest = math.nan
    return RefResult(verdict, float(theta_max), float(t_uplift), float(t_overturn), n_imp, float(u_max),
                     t_rest=float(t_rest), n_rests=n_rests, t_theta_max=float(t_theta_max))


# ------------------------------------------------------------------------------------------------
# Hysteretic bearings (sliding, lead-rubber): typed from the paper, z as an ODE state
# ------------------------------------------------------------------------------------------------
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
        return 1.0 - self.gbw * np.sign(ud * z) * abs(z) ** self.n - self.beta * abs(z) ** self.n

    def force(self, b):
        if self.dcss:
            return -(self.k1 * b[2] + self.q1 * b[3])
        return -self.w2 * b[0] - self.Q * b[2]

    def rates(self, b):
        ud = b[1]
        if not self.dcss:
            return [ud * self.bracket(ud, b[2]) / self.uy]
        K1 = self.k1 + self.q1 * self.bracket(ud, b[3]) / self.uy1
        K2 = self.k2 + self.q2 * self.bracket(ud, b[4]) / self.uy2
        u1d = ud * K2 / (K1 + K2)
        u2d = ud - u1d
        return [u1d, u1d * self.bracket(ud, b[3]) / self.uy1, u2d * self.bracket(ud, b[4]) / self.uy2]

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


def _reference_hysteretic(block, foundation, excitation, work, *, horizon, rest_tol, max_phases) -> RefResult:
    ag, t_exc_end, _, max_step = ground_function(excitation)
    if not hasattr(excitation, "acc"):
        max_step = excitation.T_p / 20.0
    brg = Bearing.of(foundation)
    nb = brg.nb
    g, p2, alpha, R = G, block.p ** 2, block.alpha, block.R
    thr = g * math.tan(alpha)
    gamma = foundation.gamma
    t_max_end = t_exc_end + horizon
    def stuck_rhs(t, b):
        return [b[1], brg.force(b) - ag(t), *brg.rates(b)]

    def rock_rhs(s):
        def f(t, y):
            th, thd, b = y[0], y[1], y[2:]
            A = alpha * s - th
            num = brg.force(b) - gamma * R * thd ** 2 * math.sin(A) + gamma * R * p2 * math.cos(A) * math.sin(A)
            a_abs = num / (1 - gamma * R * p2 * math.cos(A) ** 2 / g)
            thdd = -p2 * (math.sin(A) + math.cos(A) * num / (g - gamma * R * p2 * math.cos(A) ** 2))
            return [thd, thdd, b[1], a_abs - ag(t), *brg.rates(b)]
        return f

    t = 0.0
    y = np.zeros(2 + nb)
    phase, s = "stuck", 0.0
    theta_max, t_uplift, t_overturn, n_imp, u_max = 0.0, math.nan, math.nan, 0, 0.0
    t_rest, n_rests, t_theta_max = math.nan, 0, math.nan
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
                sol = work.ivp(stuck_rhs, (t, t_end), b, max_step=max_step, events=events, dense_output=True)
                tt = np.linspace(t, sol.t[-1], 2000)
                u_max = max(u_max, float(np.max(np.abs(sol.sol(tt)[0]))), float(np.max(np.abs(sol.y[0]))))
                y[2:] = sol.y[:, -1]
                t = sol.t[-1]
                hit_up = sol.status == 1 and (sol.t_events[0].size or sol.t_events[1].size)
                if not hit_up:
                    if after:
                        if t < t_max_end - 1e-12:
                            T = 2 * math.pi / math.sqrt(brg.w2)
                            tail = work.ivp(stuck_rhs, (t, t + T), y[2:], dense_output=True)
                            u_max = max(u_max, float(np.max(np.abs(tail.sol(np.linspace(t, tail.t[-1], 2000))[0]))))
                        break
                    continue
                s = -1.0 if sol.t_events[0].size else 1.0
            phase = "rock"
            t_rest = math.nan
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
        sol = work.ivp(rock_rhs(s), (t, t_end), y, max_step=max_step, events=(ev_imp, ev_ot, ev_pk), dense_output=True)
        k_top = int(np.argmax(np.abs(sol.y[0])))
        if abs(sol.y[0][k_top]) > theta_max:
            theta_max, t_theta_max = float(abs(sol.y[0][k_top])), float(sol.t[k_top])
        if sol.y_events[2].size:
            k_top = int(np.argmax(np.abs(sol.y_events[2][:, 0])))
            if abs(sol.y_events[2][k_top, 0]) > theta_max:
                theta_max, t_theta_max = float(abs(sol.y_events[2][k_top, 0])), float(sol.t_events[2][k_top])
        tt = np.linspace(t, sol.t[-1], 2000)
        u_max = max(u_max, float(np.max(np.abs(sol.sol(tt)[2]))))
        y = sol.y[:, -1].copy()
        t = sol.t[-1]
        if sol.status == 1 and sol.t_events[1].size:
            t_overturn = t
            theta_max = math.pi / 2
            t_theta_max = t
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
                t_rest = t
                n_rests += 1
            continue
    verdict = "overturned" if not math.isnan(t_overturn) else ("rocked" if uplifted else "no_uplift")
    if phase != "stuck":
        t_rest = math.nan
    return RefResult(verdict, float(theta_max), float(t_uplift), float(t_overturn), n_imp, float(u_max),
                     t_rest=float(t_rest), n_rests=n_rests, t_theta_max=float(t_theta_max))
