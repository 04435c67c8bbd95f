"""An exact solver of the linear complementarity problem: Lemke's complementary pivoting with the lexicographic rule.

The problem LCP(q, M): find ``z >= 0`` with ``w = M z + q >= 0`` and ``z . w = 0`` (``M`` dense, ``m x m``, not
symmetric in general). It chooses which contacts of a stack open, stick or slide (the Pfeiffer-Glocker planar
friction LCP: per contact the normal force, the forward slip acceleration and the backward friction reserve), whose
``M`` is neither symmetric nor a P-matrix.

Method (Lemke 1965; Cottle, Pang & Stone, *The Linear Complementarity Problem*, 1992, sections 4.4 and 4.9). An
artificial variable ``z0`` and the covering vector ``e`` (all ones) give the augmented system ``w = q + e z0 + M
z``, kept as the tableau ``B^-1 [I, -M, -e, q]`` of the current basis ``B`` (columns: ``w`` 0..m-1, ``z`` m..2m-1,
``z0`` 2m, the basic values 2m+1). Unless ``q >= 0`` (then ``z = 0`` at once), ``z0`` enters first and replaces the
most negative ``w``; after that, the variable entering is always the complement of the one that just left, and the
one leaving is given by the minimum ratio test. The path ends when ``z0`` leaves (a solution: ``LCP_OK``) or when the
entering column has no positive entry (secondary ray termination: ``LCP_RAY``).

Degeneracy (a basic variable at zero: a force exactly at zero, a contact at its threshold). Ties in the ratio test
are broken by the lexicographic minimum ratio rule: among the tied rows, the one whose row of ``(B^-1 q, B^-1) /
c_i`` (``c`` the entering column; the ``w`` columns of the tableau are ``B^-1``) is lexicographically smallest. The
rows of ``B^-1`` are independent, so the choice is unique, the basis never repeats and Lemke cannot cycle. When
``z0`` is among the rows tied on the ratio itself it leaves at once (the path ends with a solution).

Tolerances (floating point; the rule above holds for exact ties). A row is eligible as pivot when its entry in the
entering column exceeds ``PIVOT_TOL = 1e-12`` times the largest magnitude in that column. Ratios of one component
within ``TIE_TOL = 1e-9`` of the smallest (relative to it; a zero ties only exactly) are tied: the basic values carry
the rounding of ``B^-1`` (about ``cond(B)`` times 1e-16), and a tie missed at the end would leave ``z0`` at 1e-16
instead of 0 and end on a ray. A row chosen among tied ones may lose up to ``TIE_TOL`` of its basic value; a basic
value of zero may come out as -1e-17 (its ratio is then the smallest, as it should be). These tests compare
quantities of one row and one column, so they do not change when ``M`` and ``q`` are scaled. At the end the basic
values get one step of iterative refinement against the original ``M`` and ``q``, ``z`` is clipped at zero and ``w =
M z + q`` is computed from ``z`` (not from the tableau): check it with :func:`lcp_residual`.

Termination guarantees. With the lexicographic rule Lemke always stops, within the finitely many bases. When ``M``
is a P-matrix (all principal minors positive: positive definite, diagonally dominant with a positive diagonal) it
ends with the unique solution. When ``M`` is copositive-plus (positive semidefinite, also non-symmetric; ``[[0, B],
[-B^T, 0]]``; strictly copositive) a ray means that no ``z >= 0`` has ``M z + q >= 0``: the LCP has no solution at
all. The friction LCP is neither: a ray says only that Lemke found no solution. In the tests, every friction LCP
with a positive definite Delassus matrix and ``mu <= 1`` was solved; with a singular one (two contacts, rank 2 or 3)
0.02 to 0.2 % of the solvable problems ended on a ray, with ``mu`` up to 5 (Painleve's paradox) 1.5 %.

What the caller must do on ``LCP_RAY``: not use ``z``, ``w`` (they are zeroed). If ``M`` is copositive-plus, the
LCP has no solution (for contacts: no consistent set of forces; an impact or another model is needed). Otherwise
first try Lemke with another covering vector ``d > 0``: it is Lemke on ``(D^-1 M, D^-1 q)``, ``D = diag(d)``, which
has the same ``z`` (and ``w = D w'``); in the tests, 20 random ``d`` solved 47 of 48 such cases. Then treat the
contact state as undecided. ``LCP_MAXITER`` (``max_iter`` pivots, default ``50 m``) should not happen with the
lexicographic rule; treat it as a ray. ``LCP_NONFINITE``: ``M`` or ``q`` holds a NaN or an infinity, or the tableau
overflowed. Arrays of the wrong size raise ``ValueError``.

The workspace (:func:`lcp_workspace`) holds every array, so that :func:`lemke` never allocates (``@hot``); one
sized for ``m_max`` serves every ``m <= m_max``.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.jit import hot, kernel

LCP_OK = 0  #: a solution: z, w satisfy the conditions (to rounding)
LCP_RAY = 1  #: secondary ray termination: Lemke found no solution (for copositive-plus M: none exists)
LCP_MAXITER = 2  #: max_iter pivots without an end
LCP_NONFINITE = 3  #: NaN or infinity in M, q, or an overflow in the tableau

PIVOT_TOL = 1e-12  #: a pivot entry must exceed this times the entering column's largest magnitude
TIE_TOL = 1e-9  #: ratios this close (relative to the smallest) are tied and compared lexicographically
MAX_ITER_PER_ROW = 50  #: the default max_iter is this times m


@kernel
def lcp_workspace(m_max):
    """The arrays of :func:`lemke` for ``m <= m_max``: ``(T, basis, cand, info, r, nz)``. ``T`` the tableau (``m_max x
    (2 m_max + 2)``), ``basis[i]`` the variable basic in row ``i`` (``w_j``: ``j``, ``z_j``: ``m + j``, ``z0``:
    ``2m``), ``cand`` rows tied in the ratio test, ``info[0]`` the pivots of the last solve, ``r`` the residual of
    the refinement, ``nz`` the columns a pivot updates."""
    T = np.zeros((m_max, 2 * m_max + 2))
    basis = np.zeros(m_max, dtype=np.int64)
    cand = np.zeros(m_max, dtype=np.int64)
    info = np.zeros(2, dtype=np.int64)
    r = np.zeros(m_max)
    nz = np.zeros(2 * m_max + 2, dtype=np.int64)
    return T, basis, cand, info, r, nz


@kernel
def lcp_pivots(ws):
    """The number of pivots of the last :func:`lemke` solve with workspace ``ws``."""
    return ws[3][0]


@hot
def _setup(M, q, T, basis, m):
    """The starting tableau ``[I, -M, -e, q]`` with every ``w`` basic; False when ``M`` or ``q`` is not finite."""
    for i in range(m):
        if not math.isfinite(q[i]):
            return False
        for j in range(m):
            T[i, j] = 1.0 if i == j else 0.0
            if not math.isfinite(M[i, j]):
                return False
            T[i, m + j] = -M[i, j]
        T[i, 2 * m] = -1.0
        T[i, 2 * m + 1] = q[i]
        basis[i] = i
    return True


@hot
def _keep_ties(T, col, sgn, cand, n, k):
    """Keep, among the ``n`` rows ``cand[:n]``, those whose ratio ``T[i, k] / (sgn T[i, col])`` is within ``TIE_TOL``
    of the smallest (relative to it: a zero ties only exactly); returns their number."""
    lo = math.inf
    for a in range(n):
        i = cand[a]
        lo = min(lo, T[i, k] / (sgn * T[i, col]))
    band = TIE_TOL * abs(lo)
    kept = 0
    for a in range(n):
        i = cand[a]
        if T[i, k] / (sgn * T[i, col]) <= lo + band:
            cand[kept] = i
            kept += 1
    return kept


@hot
def _leaving(T, basis, cand, m, col, sgn):
    """The row leaving when column ``col`` enters: the lexicographic minimum ratio over the rows whose entry ``sgn
    T[i, col]`` is positive (``sgn = -1`` for the first pivot, on ``-e``); -1 when none is (a ray)."""
    cmax = 0.0
    for i in range(m):
        cmax = max(cmax, abs(T[i, col]))
    if not (cmax > 0.0 and math.isfinite(cmax)):
        return -1
    n = 0
    for i in range(m):
        if sgn * T[i, col] > PIVOT_TOL * cmax:
            cand[n] = i
            n += 1
    if n == 0:
        return -1
    n = _keep_ties(T, col, sgn, cand, n, 2 * m + 1)
    for a in range(n):  # z0 tied on the ratio itself: it leaves, the path ends
        if basis[cand[a]] == 2 * m:
            return cand[a]
    k = 0
    while n > 1 and k < m:  # the columns of B^-1, in order
        n = _keep_ties(T, col, sgn, cand, n, k)
        k += 1
    return cand[0]


@hot
def _pivot(T, nz, m, r, col):
    """Gauss-Jordan pivot on ``T[r, col]``, over the columns where row ``r`` is not zero (listed in ``nz``: the
    basic variables' columns are among the others)."""
    xc = 2 * m + 1
    p = 1.0 / T[r, col]
    n = 0
    for j in range(xc + 1):
        if T[r, j] != 0.0 and j != col:
            T[r, j] *= p
            nz[n] = j
            n += 1
    T[r, col] = 1.0
    for i in range(m):
        f = T[i, col]
        if i == r or f == 0.0:
            continue
        for t in range(n):
            T[i, nz[t]] -= f * T[r, nz[t]]
        T[i, col] = 0.0


@hot
def _refine(M, q, T, basis, rr, m):
    """One step of iterative refinement of the basic values ``x`` (``B x = q``, ``z0`` non-basic): ``x += B^-1 (q -
    B x)``, with ``B`` from the original ``M`` and ``B^-1`` the tableau's ``w`` columns."""
    xc = 2 * m + 1
    for k in range(m):
        rr[k] = q[k]
    for i in range(m):
        v = basis[i]
        if v < m:  # w_v: column e_v
            rr[v] -= T[i, xc]
        else:  # z_j: column -M[:, j]
            for k in range(m):
                rr[k] += M[k, v - m] * T[i, xc]
    for i in range(m):
        d = 0.0
        for k in range(m):
            d += T[i, k] * rr[k]
        T[i, xc] = max(T[i, xc] + d, 0.0)


@hot
def _extract(M, q, T, basis, z, w, m):
    """``z`` from the basic values, ``w = M z + q``; False when not finite."""
    for j in range(m):
        z[j] = 0.0
    for i in range(m):
        if m <= basis[i] < 2 * m:
            z[basis[i] - m] = T[i, 2 * m + 1]
    for i in range(m):
        s = q[i]
        for j in range(m):
            s += M[i, j] * z[j]
        w[i] = s
        if not (math.isfinite(s) and math.isfinite(z[i])):
            return False
    return True


@hot
def _path(T, basis, cand, info, nz, m, max_iter):
    """Lemke's complementary path from the first pivot (``z0`` in) to its end: a status."""
    z0 = 2 * m
    r = _leaving(T, basis, cand, m, z0, -1.0)
    _pivot(T, nz, m, r, z0)
    leave = basis[r]
    basis[r] = z0
    info[0] = 1
    while True:
        enter = leave + m if leave < m else leave - m
        if info[0] >= max_iter:
            return LCP_MAXITER
        r = _leaving(T, basis, cand, m, enter, 1.0)
        if r < 0:
            return LCP_RAY
        _pivot(T, nz, m, r, enter)
        leave = basis[r]
        basis[r] = enter
        info[0] += 1
        if leave == z0:
            return LCP_OK


@hot
def lemke(M, q, z, w, ws, max_iter=-1):
    """Solve LCP(q, M) (``m = len(q)``) into ``z``, ``w`` with the workspace ``ws`` (:func:`lcp_workspace`, for ``m``
    or more): a status, ``LCP_OK``, ``LCP_RAY``, ``LCP_MAXITER`` or ``LCP_NONFINITE``. ``max_iter`` caps the pivots
    (``-1``: ``50 m``). On any status but ``LCP_OK``, ``z`` and ``w`` are zeroed. Never allocates."""
    T, basis, cand, info, rr, nz = ws
    m = q.shape[0]
    if M.shape[0] != m or M.shape[1] != m or z.shape[0] < m or w.shape[0] < m or T.shape[0] < m:
        raise ValueError("lemke: M must be m x m, z and w of m, the workspace for m or more")
    info[0] = 0
    cap = max_iter if max_iter >= 0 else MAX_ITER_PER_ROW * m
    status = LCP_OK
    if not _setup(M, q, T, basis, m):
        status = LCP_NONFINITE
    else:
        qmin = 0.0
        for i in range(m):
            qmin = min(qmin, q[i])
        if qmin < 0.0:  # else z = 0 solves it
            status = _path(T, basis, cand, info, nz, m, cap)
            if status == LCP_OK:
                _refine(M, q, T, basis, rr, m)
    if status == LCP_OK and not _extract(M, q, T, basis, z, w, m):
        status = LCP_NONFINITE
    if status != LCP_OK:
        for i in range(m):
            z[i] = 0.0
            w[i] = 0.0
    return status


@hot
def lcp_residual(M, q, z, w):
    """How far ``z``, ``w`` are from solving LCP(q, M), dimensionless: the largest of ``-min(z) / max|z|``,
    ``-min(w) / W``, ``max|w - M z - q| / W`` and ``max|z_i w_i| / (max|z| W)``, where ``W = max_i (|q_i| + sum_j
    |M_ij z_j|)`` is the size of the terms that make ``w`` (a zero scale counts as one). A few 1e-16 for a solution
    of :func:`lemke`."""
    m = q.shape[0]
    zs = 0.0
    ws_ = 0.0
    for i in range(m):
        zs = max(zs, abs(z[i]))
        s = abs(q[i])
        for j in range(m):
            s += abs(M[i, j] * z[j])
        ws_ = max(ws_, s)
    zs = zs if zs > 0.0 else 1.0
    ws_ = ws_ if ws_ > 0.0 else 1.0
    res = 0.0
    for i in range(m):
        s = q[i]
        for j in range(m):
            s += M[i, j] * z[j]
        res = max(res, -z[i] / zs, -w[i] / ws_, abs(w[i] - s) / ws_, abs(z[i] * w[i]) / (zs * ws_))
    return res
