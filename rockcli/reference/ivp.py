"""``solve_ivp`` as the references call it: the work counted, a wall budget, record samples as break points."""

from __future__ import annotations

import functools
import time

import numpy as np

from rockcli.reference.result import METHODS, ReferenceFailure, ReferenceTimeout


class Work:
    """Counts the work of the ``solve_ivp`` calls of one reference run; enforces the wall budget."""

    def __init__(self, method: str, rtol: float, atol, scales_of, deadline_s: float | None):
        from scipy.integrate import solve_ivp

        if method not in METHODS:
            raise ValueError(f"unknown SciPy method {method!r} (use one of {', '.join(METHODS)})")
        self.solve_ivp = solve_ivp
        self.solver = {"Radau": _radau_direct, "DOP853": _dop853_scalar_dense}.get(method, lambda: method)()
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
                return Chain(pieces)
        return self._ivp1(fun, span, y0, **kw)

    def _ivp1(self, fun, span, y0, **kw):
        n = len(y0)
        try:
            sol = self.solve_ivp(self._wrap(fun), span, y0, method=self.solver, rtol=self.rtol, atol=self._atol(n),
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


@functools.cache
def _radau_direct():
    """SciPy's ``Radau`` with its dense LU factorisation and solves called straight from LAPACK.

    ``Radau`` calls :func:`scipy.linalg.lu_factor` and :func:`scipy.linalg.lu_solve`, whose argument checks
    and batching wrappers cost some 50 us a call against a few us for ``getrf``/``getrs`` on a 4-7 state system:
    most of a hysteretic reference run. The subclass calls the same two LAPACK routines with the same arguments
    (so every number is the same), and keeps their checks: a non-finite matrix or right-hand side raises
    ``ValueError`` as ``check_finite`` does, a singular factor warns as ``lu_factor`` does.
    """
    import warnings

    from scipy.integrate import Radau
    from scipy.linalg import LinAlgWarning
    from scipy.linalg.lapack import get_lapack_funcs
    from scipy.sparse import issparse

    def factor(solver, A):
        solver.nlu += 1
        if not np.isfinite(A).all():
            raise ValueError("array must not contain infs or NaNs")
        getrf, = get_lapack_funcs(("getrf",), (A,))
        lu, piv, info = getrf(A, overwrite_a=True)
        if info < 0:
            raise ValueError(f"illegal value in {-info}th argument of internal getrf (lu_factor)")
        if info > 0:
            warnings.warn(f"Diagonal number {info} is exactly zero. Singular matrix.", LinAlgWarning,
                          stacklevel=2)
        return lu, piv, get_lapack_funcs(("getrs",), (lu,))[0]

    def solve(LU, b):
        lu, piv, getrs = LU
        if not np.isfinite(b).all():
            raise ValueError("array must not contain infs or NaNs")
        x, info = getrs(lu, piv, b, trans=0, overwrite_b=True)
        if info != 0:
            raise ValueError(f"illegal value in {-info}th argument of internal gesv|posv")
        return x

    class DirectRadau(Radau):
        def __init__(self, *args, **kw):
            super().__init__(*args, **kw)
            if not issparse(self.J):  # a dense Jacobian: LAPACK straight
                self.lu = lambda A: factor(self, A)
                self.solve_lu = solve

    return DirectRadau


@functools.cache
def _dop853_scalar_dense():
    """SciPy's ``DOP853`` whose dense output, at one time, sums its polynomial in plain Python floats.

    The event search (``brentq`` on each step's dense output) evaluates the interpolant at one time some ten times
    per event, and SciPy's numpy evaluation costs some 25 us a call on a 2-4 state system: the largest share of a
    rigid-foundation reference run, which is a chain of short rocking phases. The subclass evaluates the same
    Horner-like sum with the same operations in the same order (numpy's float64 arithmetic is Python's), so every
    number is the same; at several times it is SciPy's own.
    """
    from scipy.integrate import DOP853
    from scipy.integrate._ivp.rk import Dop853DenseOutput

    class ScalarDense(Dop853DenseOutput):
        def __init__(self, dense):
            super().__init__(dense.t_old, dense.t, dense.y_old, dense.F)
            self._rows = self.F[::-1].tolist()  # the sum starts from the highest power, as SciPy's
            self._y_old = self.y_old.tolist()

        def _call_impl(self, t):
            if t.ndim:
                return super()._call_impl(t)
            x = float((t - self.t_old) / self.h)
            x_1 = 1 - x
            out = []
            for j, y0 in enumerate(self._y_old):
                y = 0.0
                for i, f in enumerate(self._rows):
                    y += f[j]
                    y *= x if i % 2 == 0 else x_1
                out.append(y + y0)
            return np.array(out)

    class ScalarDenseDOP853(DOP853):
        def _dense_output_impl(self):
            return ScalarDense(super()._dense_output_impl())

    return ScalarDenseDOP853


class Chain:
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
