"""``rockcli.kernels.lcp``: Lemke's method against brute-force enumeration of the ``2^m`` complementary bases on
thousands of random LCPs (P-matrices: the unique solution; copositive-plus matrices: a solution whenever one exists,
a ray only when a linear program finds the LCP infeasible; Pfeiffer-Glocker friction LCPs: a solution whenever
enumeration finds one, and Coulomb's law in it), degenerate problems (no cycling), the trivial and infeasible cases,
scaling, the workspace and the status codes."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from scipy.optimize import linprog

from rockcli.kernels.lcp import (LCP_MAXITER, LCP_NONFINITE, LCP_OK, LCP_RAY, lcp_pivots, lcp_residual,
                                 lcp_workspace, lemke)

RES_TOL = 1e-10  # lcp_residual of an accepted solution (dimensionless; a few 1e-16 when all is well)


# ------------------------------------------------------------------------------------------
# helpers: the solver from Python, brute force, problem generators
# ------------------------------------------------------------------------------------------
def solve(M, q, ws=None, max_iter=-1):
    m = len(q)
    ws = lcp_workspace(m) if ws is None else ws
    z, w = np.zeros(m), np.zeros(m)
    status = lemke(np.ascontiguousarray(M, dtype=float), np.ascontiguousarray(q, dtype=float), z, w, ws, max_iter)
    return status, z, w


def brute_force(Ms, qs, tol=1e-9):
    """Every complementary basic solution of each LCP(qs[n], Ms[n]) (all of the same size ``m``), by solving
    ``M_aa z_a = -q_a`` for each of the ``2^m`` index sets ``a`` (pseudo-inverse: singular blocks too) and keeping
    the ``z >= 0`` with ``w >= 0``: a list of arrays ``(n_solutions, m)``."""
    N, m, _ = Ms.shape
    found = [[] for _ in range(N)]
    for k in range(m + 1):
        for a in itertools.combinations(range(m), k):
            a = list(a)
            z = np.zeros((N, m))
            if k:
                sub = Ms[:, a][:, :, a]
                z[:, a] = -np.einsum("nij,nj->ni", np.linalg.pinv(sub), qs[:, a])
            w = np.einsum("nij,nj->ni", Ms, z) + qs
            zs = np.maximum(np.abs(z).max(axis=1), 1.0)
            ws = np.abs(qs).max(axis=1) + np.einsum("nij,nj->ni", np.abs(Ms), np.abs(z)).max(axis=1)
            ok = ((z.min(axis=1) >= -tol * zs) & (w.min(axis=1) >= -tol * ws)
                  & (np.abs(w[:, a]).max(axis=1, initial=0.0) <= tol * ws))
            for n in np.flatnonzero(ok):
                found[n].append(z[n])
    return [np.array(f).reshape(-1, m) for f in found]


def distinct(sols, tol=1e-7):
    """The solutions of ``sols`` that differ (relative ``tol``)."""
    out = []
    for s in sols:
        if not any(np.abs(s - o).max() <= tol * max(1.0, np.abs(o).max()) for o in out):
            out.append(s)
    return out


def feasible(M, q):
    """Whether some ``z >= 0`` has ``M z + q >= 0`` (a linear program, HiGHS)."""
    m = len(q)
    res = linprog(np.zeros(m), A_ub=-M, b_ub=q, bounds=[(0, None)] * m, method="highs")
    assert res.status in (0, 2), res.message
    return res.status == 0


def p_matrices(rng, m, n):
    """``n`` random P-matrices of size ``m``: symmetric positive definite, non-symmetric positive definite, and
    diagonally dominant with a positive diagonal, in turn."""
    out = []
    for i in range(n):
        A = rng.normal(size=(m, m))
        kind = i % 3
        if kind == 0:
            M = A @ A.T + np.diag(rng.uniform(0.1, 1.0, m))
        elif kind == 1:
            S = rng.normal(size=(m, m))
            M = A @ A.T / m + (S - S.T) + np.diag(rng.uniform(0.1, 1.0, m))
        else:
            M = A.copy()
            np.fill_diagonal(M, 0.0)
            M += np.diag(np.abs(M).sum(axis=1) + rng.uniform(0.1, 1.0, m))
        out.append(M)
    return np.array(out)


def copositive_plus(rng, m, n):
    """``n`` random copositive-plus matrices of size ``m``: rank-deficient ``A A^T``, the LP/QP form ``[[P, B],
    [-B^T, Q]]`` (``P``, ``Q`` positive semidefinite, possibly zero), positive semidefinite plus skew-symmetric, and
    strictly copositive (non-negative entries, positive diagonal), in turn."""
    out = []
    for i in range(n):
        kind = i % 4
        if kind == 0:
            A = rng.normal(size=(m, rng.integers(0, m)))
            M = A @ A.T
        elif kind == 1:
            p = int(rng.integers(1, m)) if m > 1 else 1
            B = rng.normal(size=(p, m - p))
            Ap, Aq = rng.normal(size=(p, p // 2)), rng.normal(size=(m - p, (m - p) // 2))
            M = np.block([[Ap @ Ap.T, B], [-B.T, Aq @ Aq.T]])
        elif kind == 2:
            A, S = rng.normal(size=(m, max(m - 2, 0))), rng.normal(size=(m, m))
            M = A @ A.T + (S - S.T)
        else:
            M = rng.uniform(0.0, 1.0, (m, m)) * (rng.uniform(size=(m, m)) < 0.5)
            M += np.diag(rng.uniform(0.1, 1.0, m))
        out.append(M)
    return np.array(out)


def friction_lcp(G, mu, b):
    """The Pfeiffer-Glocker planar friction LCP of ``k`` contacts: ``G`` the Delassus matrix (``2k x 2k``, rows and
    columns normal, tangential per contact), ``mu`` the friction coefficients, ``b`` the bias accelerations ``(gN,
    gT)`` at zero force. Per contact ``z = (lambda_N, sdd_plus, lambda_L)``, ``lambda_T = mu lambda_N - lambda_L``,
    ``w = (gN_dd, 2 mu lambda_N - lambda_L, sdd_plus - gT_dd)`` with ``(gN_dd, gT_dd) = G (lambda_N, lambda_T) +
    b``."""
    k = len(mu)
    M, q = np.zeros((3 * k, 3 * k)), np.zeros(3 * k)
    for i, j in itertools.product(range(k), range(k)):
        nn, nt = G[2 * i, 2 * j], G[2 * i, 2 * j + 1]
        tn, tt = G[2 * i + 1, 2 * j], G[2 * i + 1, 2 * j + 1]
        M[3 * i, 3 * j], M[3 * i, 3 * j + 2] = nn + mu[j] * nt, -nt
        M[3 * i + 2, 3 * j], M[3 * i + 2, 3 * j + 2] = -(tn + mu[j] * tt), tt
    for i in range(k):
        M[3 * i + 1, 3 * i], M[3 * i + 1, 3 * i + 2], M[3 * i + 2, 3 * i + 1] = 2 * mu[i], -1.0, 1.0
        q[3 * i], q[3 * i + 2] = b[2 * i], -b[2 * i + 1]
    return M, q


def random_friction(rng, k):
    """A random friction LCP of ``k`` contacts: ``(M, q, G, mu, b)``."""
    A = rng.normal(size=(2 * k, 2 * k + int(rng.integers(0, 3))))
    G = A @ A.T + np.diag(rng.uniform(0.05, 0.5, 2 * k))
    mu = rng.uniform(0.1, 1.0, k)
    b = rng.normal(size=2 * k) * 2.0
    return (*friction_lcp(G, mu, b), G, mu, b)


def forces(z, w, G, mu, b):
    """``(lambda_N, lambda_T, gN_dd, gT_dd)`` per contact from an LCP solution, and the same accelerations from
    ``G``: the tableau's ``w`` against the mechanics."""
    lam_n, lam_t = z[0::3], mu * z[0::3] - z[2::3]
    gn, gt = w[0::3], z[1::3] - w[2::3]
    lam = np.ravel(np.column_stack([lam_n, lam_t]))
    g = G @ lam + b
    return lam_n, lam_t, gn, gt, g[0::2], g[1::2]


def assert_solution(M, q, status, z, w):
    assert status == LCP_OK, status
    assert z.min() >= 0.0  # clipped at zero, exactly
    res = lcp_residual(M, q, z, w)
    assert res <= RES_TOL, res
    assert np.allclose(w, M @ z + q, rtol=0, atol=1e-12 * (np.abs(q).max() + np.abs(M).max() * np.abs(z).max()))


# ------------------------------------------------------------------------------------------
# random LCPs against brute force
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("m", range(1, 9))
def test_p_matrices_give_the_unique_solution_of_brute_force(m):
    rng = np.random.default_rng(100 + m)
    n = 300
    Ms, qs = p_matrices(rng, m, n), rng.normal(size=(n, m))
    qs[::5] = np.abs(qs[::5])  # some trivial ones
    sols = brute_force(Ms, qs)
    ws = lcp_workspace(m)
    for M, q, s in zip(Ms, qs, sols):
        unique = distinct(s)
        assert len(unique) == 1, (M, q, unique)  # the enumeration itself: a P-matrix has exactly one
        status, z, w = solve(M, q, ws)
        assert_solution(M, q, status, z, w)
        assert np.abs(z - unique[0]).max() <= 1e-9 * max(np.abs(unique[0]).max(), 1e-300), (M, q, z, unique)


@pytest.mark.parametrize("m", range(1, 9))
def test_copositive_plus_solved_whenever_solvable_and_a_ray_only_when_infeasible(m):
    rng = np.random.default_rng(200 + m)
    n = 240
    Ms, qs = copositive_plus(rng, m, n), rng.normal(size=(n, m))
    sols = brute_force(Ms, qs)
    ws = lcp_workspace(m)
    solved = rays = 0
    for M, q, s in zip(Ms, qs, sols):
        status, z, w = solve(M, q, ws)
        if len(s):
            assert_solution(M, q, status, z, w)
            solved += 1
        elif status == LCP_OK:  # enumeration may miss a solution of a singular block: Lemke's is checked
            assert_solution(M, q, status, z, w)
        else:
            assert status == LCP_RAY, status
            assert not feasible(M, q), (M, q)  # copositive-plus: a ray proves infeasibility
            rays += 1
    assert solved >= n // 2 and (m == 1 or rays > 0), (solved, rays)  # both outcomes exercised


@pytest.mark.parametrize("k", [1, 2])
def test_friction_lcps_solved_whenever_brute_force_finds_a_solution_and_coulomb_holds(k):
    rng = np.random.default_rng(300 + k)
    n = 800
    probs = [random_friction(rng, k) for _ in range(n)]
    Ms, qs = np.array([p[0] for p in probs]), np.array([p[1] for p in probs])
    sols = brute_force(Ms, qs)
    ws = lcp_workspace(3 * k)
    slides = 0
    for (M, q, G, mu, b), s in zip(probs, sols):
        status, z, w = solve(M, q, ws)
        if not len(s) and status != LCP_OK:
            continue
        assert_solution(M, q, status, z, w)
        lam_n, lam_t, gn, gt, gn_g, gt_g = forces(z, w, G, mu, b)
        scale_f = max(np.abs(lam_n).max(), np.abs(b).max() / np.abs(G).max())  # forces: those of b at least
        scale_a = np.abs(b).max() + np.abs(G).max() * np.abs(z).max()
        assert np.allclose(gn, gn_g, atol=1e-10 * scale_a) and np.allclose(gt, gt_g, atol=1e-10 * scale_a)
        assert lam_n.min() >= 0 and gn.min() >= -1e-10 * scale_a
        assert np.all(np.abs(lam_t) <= mu * lam_n + 1e-10 * scale_f), (lam_t, mu * lam_n)
        moving = np.abs(gt) > 1e-9 * scale_a
        assert np.allclose(lam_t[moving], -mu[moving] * lam_n[moving] * np.sign(gt[moving]), atol=1e-10 * scale_f)
        slides += np.count_nonzero(moving & (lam_n > 1e-9 * scale_f))
    assert slides > n // 10  # sliding contacts exercised


def test_outside_the_guarantee_a_ray_is_honest_and_another_covering_vector_may_solve_it():
    """Friction LCPs beyond the tests above: a singular Delassus matrix (rank 2 or 3 for two contacts) or mu up to 5
    (Painleve's paradox). ``M`` is not copositive-plus: Lemke may end on a ray although a solution exists. Every OK
    must be a solution; a ray on a solvable problem is solved again by Lemke on ``(D^-1 M, D^-1 q)`` (the covering
    vector ``d = D e``: the same ``z``) for some random positive ``d``, within 20 tries."""
    rng, rs = np.random.default_rng(800), np.random.default_rng(801)
    probs = []
    for t in range(3000):
        if t % 2:  # two contacts, G = A A^T of rank 2 or 3
            A = rng.normal(size=(4, 2 + t % 4 // 2))
            probs.append(friction_lcp(A @ A.T, rng.uniform(0.1, 1.0, 2), 2 * rng.normal(size=4)))
        else:  # one contact, mu up to 5
            A = rng.normal(size=(2, 2))
            probs.append(friction_lcp(A @ A.T + 0.05 * np.eye(2), rng.uniform(0.1, 5.0, 1), 2 * rng.normal(size=2)))
    rays = 0
    for k in (1, 2):
        sub = [p for p in probs if len(p[1]) == 3 * k]
        sols = brute_force(np.array([p[0] for p in sub]), np.array([p[1] for p in sub]))
        for (M, q), s in zip(sub, sols):
            status, z, w = solve(M, q)
            assert status in (LCP_OK, LCP_RAY)
            if status == LCP_OK:
                assert_solution(M, q, status, z, w)
            elif len(s):
                rays += 1
                for _ in range(20):
                    d = rs.uniform(0.1, 10.0, len(q))
                    status, z, _ = solve(M / d[:, None], q / d)
                    if status == LCP_OK:
                        break
                assert_solution(M, q, status, z, M @ z + q)
    assert rays > 0, rays  # the limitation is real (15 of these 3000)


def test_larger_friction_lcps_are_all_solved_and_obey_coulomb():
    """3 to 16 contacts (m = 9 to 48, beyond brute force): every one solved (in 20 000 such problems none ended on a
    ray), to rounding, with Coulomb's law. Ties at the end of the path (``z0`` reaching zero with other rows, to
    about 1e-10) are common here: a tie test too tight ends some of them on a ray."""
    rng = np.random.default_rng(850)
    for t in range(1200):
        M, q, G, mu, b = random_friction(rng, 3 + t % 14)
        status, z, w = solve(M, q)
        assert_solution(M, q, status, z, w)
        lam_n, lam_t, gn, gt, gn_g, gt_g = forces(z, w, G, mu, b)
        scale_f = max(np.abs(lam_n).max(), np.abs(b).max() / np.abs(G).max())
        assert np.all(np.abs(lam_t) <= mu * lam_n + 1e-10 * scale_f)


# ------------------------------------------------------------------------------------------
# degenerate problems: ties in the ratio test
# ------------------------------------------------------------------------------------------
def degenerate_problems(rng, n):
    """``n`` degenerate LCPs, ``(kind, M, q)``: kind 0 an integer P-matrix (diagonally dominant), 1 ``A A^T`` with
    repeated rows of ``A`` (duplicated rows and columns of ``M``, ``q`` repeated alike), 2 integer positive
    semidefinite plus skew-symmetric, all with entries of ``q`` in -2..2 (zeros and repeated values: ties in the
    ratios); 3 a friction LCP of one or two contacts with half its bias terms zero (contacts at their thresholds)."""
    out = []
    for trial in range(n):
        m, kind = int(rng.integers(2, 8)), trial % 4
        A = rng.integers(-2, 3, size=(m, m)).astype(float)
        q = rng.integers(-2, 3, size=m).astype(float)
        if kind == 0:
            M = A - np.diag(np.diag(A)) + np.diag(np.abs(A).sum(axis=1) + 1)
        elif kind == 1:
            dup = rng.integers(0, m // 2 + 1, size=m)
            M, q = A[dup] @ A[dup].T, q[dup]
        elif kind == 2:
            S = rng.integers(-2, 3, size=(m, m)).astype(float)
            M = A @ A.T + S - S.T
        else:
            M, q = random_friction(rng, 1 + trial % 8 // 4)[:2]
            q[rng.uniform(size=len(q)) < 0.5] = 0.0
        out.append((kind, M, q))
    return out


def test_degenerate_problems_with_zeros_duplicates_and_integer_ties_do_not_cycle():
    """2000 degenerate LCPs (:func:`degenerate_problems`): never the pivot cap; the P-matrices' unique solution; a
    solution whenever brute force finds one; a ray otherwise, for the copositive-plus kinds only when infeasible."""
    probs = degenerate_problems(np.random.default_rng(400), 2000)
    sols = {}
    for m in {len(q) for _, _, q in probs}:
        idx = [i for i, (_, _, q) in enumerate(probs) if len(q) == m]
        found = brute_force(np.array([probs[i][1] for i in idx]), np.array([probs[i][2] for i in idx]))
        sols.update(zip(idx, found))
    degenerate = 0
    for i, (kind, M, q) in enumerate(probs):
        status, z, w = solve(M, q)
        assert status != LCP_MAXITER, (M, q)
        if len(sols[i]):
            assert_solution(M, q, status, z, w)
            if kind == 0:
                unique = distinct(sols[i])
                assert len(unique) == 1 and np.abs(z - unique[0]).max() <= 1e-9 * max(np.abs(z).max(), 1.0)
        elif status == LCP_OK:
            assert_solution(M, q, status, z, w)
        else:
            assert status == LCP_RAY and (kind == 3 or not feasible(M, q)), (M, q, status)
        degenerate += status == LCP_OK and np.any((z == 0) & (np.abs(w) < 1e-12))
    assert degenerate > 300, degenerate  # solutions with a pair both at zero: the degenerate case exercised


def lowest_index_lemke_cycles(M, q, max_iter=500):
    """Lemke's method in plain numpy with the ratio ties broken by the lowest row instead of the lexicographic
    rule (``z0`` still leaves when tied): whether it comes back to a basis it has left."""
    m = len(q)
    T = np.hstack([np.eye(m), -M, -np.ones((m, 1)), q[:, None]])
    basis = list(range(m))

    def pivot(r, col):
        T[r] /= T[r, col]
        for i in range(m):
            if i != r:
                T[i] -= T[i, col] * T[r]
        leave, basis[r] = basis[r], col
        return leave

    leave, seen = pivot(int(np.argmin(q)), 2 * m), set()
    for _ in range(max_iter):
        col = leave + m if leave < m else leave - m
        c = T[:, col]
        rows = np.flatnonzero(c > 1e-12 * np.abs(c).max())
        if not len(rows):
            return False
        ratios = T[rows, -1] / c[rows]
        tied = rows[ratios <= ratios.min() * (1 + 1e-11) + 1e-15]
        z0 = [i for i in tied if basis[i] == 2 * m]
        if pivot(z0[0] if z0 else tied[0], col) == 2 * m:
            return False
        if tuple(sorted(basis)) in seen:
            return True
        seen.add(tuple(sorted(basis)))
    return True


# strictly copositive (a solution for every q), found by a random search of small integer problems
CYCLING = [
    ([[1, 2, 2, 2], [2, 1, 2, 0], [0, 0, 1, 2], [2, 0, 2, 3]], [-1, -1, -1, -1]),
    ([[3, 1, 1, 1, 0], [2, 1, 2, 2, 2], [2, 2, 1, 2, 0], [0, 1, 2, 3, 2], [2, 0, 2, 0, 1]], [1, -1, -1, 1, -1]),
    ([[1, 0, 0, 2, 2], [0, 3, 0, 1, 1], [1, 0, 2, 0, 1], [2, 1, 0, 2, 0], [0, 0, 2, 1, 3]], [-1, 0, 1, -1, -1]),
]


@pytest.mark.parametrize("M, q", CYCLING)
def test_problems_on_which_the_lowest_index_rule_cycles_are_solved(M, q):
    M, q = np.array(M, dtype=float), np.array(q, dtype=float)
    assert lowest_index_lemke_cycles(M, q)
    ws = lcp_workspace(len(q))
    status, z, w = solve(M, q, ws)
    assert_solution(M, q, status, z, w)
    assert lcp_pivots(ws) <= 2 * len(q)
    assert any(np.allclose(z, s) for s in brute_force(M[None], q[None])[0])


# ------------------------------------------------------------------------------------------
# special cases, scaling, workspace, codes
# ------------------------------------------------------------------------------------------
def test_non_negative_q_gives_zero_at_once():
    rng = np.random.default_rng(500)
    for m in range(1, 10):
        M, q = rng.normal(size=(m, m)), np.abs(rng.normal(size=m))
        q[0] = 0.0
        ws = lcp_workspace(m)
        status, z, w = solve(M, q, ws)
        assert status == LCP_OK and not z.any() and np.array_equal(w, q) and lcp_pivots(ws) == 0


def test_known_infeasible_lcps_end_on_a_ray():
    for M, q in [([[-1.0]], [-1.0]), ([[0.0]], [-1.0]), ([[1.0, -1.0], [-1.0, 1.0]], [-1.0, -1.0]),
                 ([[0.0, 1.0], [-1.0, 0.0]], [-1.0, -1.0])]:
        M, q = np.array(M), np.array(q)
        assert not feasible(M, q)
        status, z, w = solve(M, q)
        assert status == LCP_RAY and not z.any() and not w.any()


@pytest.mark.parametrize("s", [1e6, 1e-6])
def test_scaling_m_and_q_scales_the_solution_consistently(s):
    rng = np.random.default_rng(600)
    for trial in range(300):
        if trial % 2:
            M, q = random_friction(rng, int(rng.integers(1, 6)))[:2]
        else:
            m = int(rng.integers(1, 12))
            M, q = p_matrices(rng, m, 1)[0], rng.normal(size=m)
        status, z, w = solve(M, q)
        if status != LCP_OK:
            continue
        tol = 1e-9 * np.abs(z).max()
        for Ms, qs, zs in [(s * M, s * q, z), (M, s * q, s * z), (s * M, q, z / s)]:
            st, z2, w2 = solve(Ms, qs)
            assert st == LCP_OK and lcp_residual(Ms, qs, z2, w2) <= RES_TOL
            assert np.abs(z2 - zs).max() <= tol * (zs.max() / max(z.max(), 1e-300)), (trial, z2, zs)


def test_a_larger_workspace_serves_smaller_problems_and_is_reused():
    rng = np.random.default_rng(700)
    big = lcp_workspace(40)
    for trial in range(200):
        M, q = random_friction(rng, int(rng.integers(1, 14)))[:2]
        st1, z1, w1 = solve(M, q)
        st2, z2, w2 = solve(M, q, big)
        assert st1 == st2 and np.array_equal(z1, z2) and np.array_equal(w1, w2)


def test_the_pivot_cap_non_finite_data_sizes_and_no_allocations():
    M, q = np.array([[2.0, 1.0], [1.0, 2.0]]), np.array([-1.0, -1.0])
    ws = lcp_workspace(2)
    assert solve(M, q, ws)[0] == LCP_OK and lcp_pivots(ws) == 3
    st, z, w = solve(M, q, ws, max_iter=2)
    assert st == LCP_MAXITER and not z.any() and lcp_pivots(ws) == 2
    assert solve(M, np.array([np.nan, -1.0]))[0] == LCP_NONFINITE
    assert solve(np.array([[np.inf, 0.0], [0.0, 1.0]]), q)[0] == LCP_NONFINITE
    assert lemke.targetoptions.get("_nrt") is False  # @hot: it could not compile if it allocated
    for bad in [(np.eye(3), q), (M, np.ones(3))]:
        with pytest.raises(ValueError):
            solve(*bad, ws)


def test_refinement_keeps_the_residual_at_rounding_on_ill_conditioned_problems():
    """Positive semidefinite plus small skew ``M`` with eigenvalues down to 1e-8 to 1e-12: the refined basic values
    keep :func:`lcp_residual` at about 2e-16 (without the refinement step, 2e-15 to 6e-15 at worst)."""
    rng = np.random.default_rng(900)
    worst = 0.0
    for t in range(1500):
        m = int(rng.integers(3, 20))
        Q = np.linalg.qr(rng.normal(size=(m, m)))[0]
        S = 1e-3 * rng.normal(size=(m, m))
        M = Q @ np.diag(np.logspace(-int(rng.integers(8, 13)), 0, m)) @ Q.T + S - S.T
        q = rng.normal(size=m)
        status, z, w = solve(M, q)
        if status == LCP_OK:
            worst = max(worst, lcp_residual(M, q, z, w))
    assert worst < 1e-15, worst


def test_residual_sees_each_violation():
    M, q = np.array([[2.0, 1.0], [1.0, 2.0]]), np.array([-1.0, -1.0])
    st, z, w = solve(M, q)
    assert st == LCP_OK and lcp_residual(M, q, z, w) < 1e-15
    for dz, dw in [((-1e-6, 0), (0, 0)), ((0, 0), (-1e-6, 0)), ((0, 0), (1e-6, 0)), ((0.1, 0), (0, 0))]:
        z2, w2 = z + np.array(dz), w + np.array(dw)
        if dz[0] > 0:  # complementarity: a positive pair
            w2 = M @ z2 + q
        assert lcp_residual(M, q, z2, w2) > 1e-7
