"""The contact law's pattern choice by a complementarity solve, for chains too tall to enumerate (a column of drums:
``9^n`` patterns when every joint is closed). Same law and same answer as
:func:`rockcli.kernels.contact.choose_pattern`, which tries every pattern the event allows; here the pattern comes
from one linear complementarity problem (Lemke's method, :mod:`rockcli.kernels.lcp`) and is then checked by the
same conditions (:func:`rockcli.kernels.contact.pattern_margin`).

The problem (Pfeiffer & Glocker's planar contact with friction, at the acceleration level). Each closed interface
``j`` (angle, rate and slip rate 0: ``zero_psi`` and ``zero_s``) is *released* (``kernels.chain.RELEASED``): its slip
``s``, its rotation ``phi`` about the centre of its base and its lift ``z`` along the normal of the top below are all
free, each against its contact forces, the corner forces ``N_R``, ``N_L`` at the ends of the overlap ``e_R``, ``e_L``
and the friction ``T``. Their generalised forces are ``Q_z = N_R + N_L``, ``Q_phi = -e_R N_R - e_L N_L``, ``Q_s =
T``. With every relative rate at 0, the corners' normal accelerations are ``g_R'' = z'' - e_R phi''``, ``g_L'' = z''
- e_L phi''`` and the slip's is ``s''``, exactly (the velocity terms vanish). Kane's equations of the released chain
``A x = r + B lambda`` give ``x`` affine in the forces; the conditions are, per released interface,

    0 <= N_R  _|_  g_R'' >= 0,      0 <= N_L  _|_  g_L'' >= 0,
    0 <= sigma  _|_  mu N + T >= 0,   0 <= lambda_L  _|_  sigma - s'' >= 0,    T = mu N - lambda_L,  N = N_R + N_L,

(``sigma`` the forward part of ``s''``: sliding forwards makes ``T = -mu N``, backwards ``lambda_L = 0``, ``T = mu
N``). An interface closed whose slip already moves (``zero_psi`` only) keeps its direction ``sl``: ``T = -mu sl N``
is a row of ``A`` and only its corner forces are unknowns. An interface that pivots with its slip at rest
(``zero_s`` only) has a bilateral normal force that is not an unknown of the problem: its three choices (stick,
slide either way) are tried outside the solve, every combination for up to ``KC_MAX`` such pivots, beyond that
all sticking and each sliding alone (not exact there: a miss is counted).

From the solution: a corner whose force is 0 and whose gap accelerates open lifts (the interface pivots on the other
corner), a slip that accelerates slides. At a threshold (the event that called the choice) a force and its
acceleration are both 0: the interfaces with such a pair are tried in every way the event allows, and the choice
among those candidates follows :func:`rockcli.kernels.contact.choose_pattern`'s rule (the pattern whose condition
just failed only when no other meets every condition; the largest smallest margin). Where Lemke finds no solution
(a ray: Painleve's paradox with a large friction) or no candidate meets the conditions, the enumeration decides if
it is small enough (``ENUM_MAX``), else the best candidate found is taken and counted (the driver's
``n_inconsistent``).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.chain import (BASE_RIGID, CP_BASE, CP_G, CP_N, CP_TOL, F_MU, RELEASED, RELEASED_STUCK, assemble,
                                   impulses, solve_level, col_lift, col_psi, col_s, fld,
                                   kinematics, overlap_ends)
from rockcli.kernels.contact import choose_pattern, impact, pattern_margin, solve_pattern
from rockcli.kernels.jit import kernel
from rockcli.kernels.lcp import LCP_OK, lcp_workspace, lemke

#: enumerate instead when the solve fails and the event allows at most this many patterns
ENUM_MAX = 729
#: a force and its acceleration both below this (relative to the largest of each) make a degenerate pair
DEGENERATE = 1e-9
#: at most this many degenerate interfaces are tried in every way (9 patterns each)
MAX_DEGENERATE = 3
#: the slips of at most this many pivots resting on their slip are tried in every combination (3^KC_MAX solves)
KC_MAX = 4

# the unknowns of an interface
V_NR, V_NL, V_SIG, V_LAM = 0, 1, 2, 3


@kernel
def lcp_space(n):
    """The arrays of :func:`lcp_choose` for a chain of ``n`` blocks."""
    mm = 4 * n
    nf = 3 * n + 1
    return (lcp_workspace(mm), np.zeros((mm, mm)), np.zeros(mm), np.zeros(mm), np.zeros(mm),
            np.zeros((nf, mm + 1)), np.zeros((nf, nf)), np.zeros(nf, dtype=np.int64),
            np.zeros(mm, dtype=np.int64), np.zeros(mm, dtype=np.int64), np.zeros((n, 5), dtype=np.int64),
            np.zeros((n, 2)), np.zeros(2 * n), np.zeros(2 * n), np.zeros(2 * n), np.zeros(n, dtype=np.bool_),
            np.zeros(nf))


@kernel
def _lu(A, piv, nf):
    """LU factors of ``A[:nf, :nf]`` in place with partial pivoting; False when singular."""
    for k in range(nf):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, nf):
            if abs(A[i, k]) > big:
                big = abs(A[i, k])
                p = i
        if big == 0.0 or not math.isfinite(big):
            return False
        piv[k] = p
        if p != k:
            for jj in range(nf):
                A[k, jj], A[p, jj] = A[p, jj], A[k, jj]
        for i in range(k + 1, nf):
            A[i, k] /= A[k, k]
            f = A[i, k]
            if f != 0.0:
                for jj in range(k + 1, nf):
                    A[i, jj] -= f * A[k, jj]
    return True


@kernel
def _lu_solve(A, piv, X, nf, ncol):
    """``X[:nf, :ncol] = A^-1 X`` with the factors of :func:`_lu`."""
    for c in range(ncol):
        for k in range(nf):
            p = piv[k]
            if p != k:
                X[k, c], X[p, c] = X[p, c], X[k, c]
        for i in range(nf):
            acc = X[i, c]
            for jj in range(i):
                acc -= A[i, jj] * X[jj, c]
            X[i, c] = acc
        for i in range(nf - 1, -1, -1):
            acc = X[i, c]
            for jj in range(i + 1, nf):
                acc -= A[i, jj] * X[jj, c]
            X[i, c] = acc / A[i, i]


@kernel
def _index_of(free, nf, col):
    for k in range(nf):
        if free[k] == col:
            return k
    return -1


@kernel
def lcp_candidate(cp, pat, y, ag, ws, zero_psi, zero_s, sp, cand, degen, level_v, stuck, v0, w0, keep_mo):
    """The pattern of the complementarity solve from ``pat`` (the interfaces with ``zero_psi`` released; those with
    ``zero_s`` too with their friction unknown) into ``cand``; ``degen[j]`` True where interface ``j`` has a
    degenerate pair. False when the released system is singular or Lemke finds no solution. ``level_v``: an impact
    (the unknowns are impulses, the rates after it; ``v0``, ``w0`` the velocities before); ``stuck``: every released
    interface's slip held (the rocking model's impact), ``zero_s`` then unused. ``keep_mo``: the sliding contacts
    whose friction is off (``ws``'s ``mo``: they pull, :func:`rockcli.kernels.chain.solve_level`) as they are; else
    every sliding contact has its friction."""
    lws, Ml, ql, z, w, X, A, piv, var_j, var_t, rows, ends, rel, _c1, _c2, _d, xs = sp
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    for i in range(2 * n):
        rel[i] = pat[i]
        cand[i] = pat[i]
    for j in range(n):
        degen[j] = False
        if zero_psi[j]:
            if stuck:
                rel[2 * j] = RELEASED_STUCK
                rel[2 * j + 1] = 0.0
            else:
                rel[2 * j] = RELEASED
                if zero_s[j]:
                    rel[2 * j + 1] = 0.0
    nf = kinematics(cp, rel, y, ws)
    if not keep_mo:
        for j in range(n):
            mo[j] = 0.0
    if level_v:
        for i in range(n):
            vG[i, 0] = v0[i, 0]
            vG[i, 1] = v0[i, 1]
            om[i] = w0[i]
    assemble(cp, rel, y, ws, nf, ag, cp[CP_G], level_v)
    # the unknowns and the rows of the released coordinates
    m = 0
    for j in range(n):
        if not zero_psi[j]:
            continue
        rows[j, 0] = _index_of(free, nf, col_s(j))
        rows[j, 1] = _index_of(free, nf, col_psi(j))
        rows[j, 2] = _index_of(free, nf, col_lift(j))
        rows[j, 3] = m
        e_r, e_l = overlap_ends(cp, j, y[col_s(j)])
        ends[j, 0] = e_r
        ends[j, 1] = e_l
        nv = 4 if zero_s[j] and not stuck else 2
        for t in range(nv):
            var_j[m] = j
            var_t[m] = t
            m += 1
        rows[j, 4] = nv
    if m == 0:
        return False
    # A x = r + B lambda: the columns [r, B]
    for k in range(nf):
        X[k, 0] = r[k]
        for v in range(m):
            X[k, 1 + v] = 0.0
        for l in range(nf):
            A[k, l] = M[k, l]
    for v in range(m):
        j = var_j[v]
        t = var_t[v]
        ks, kp, kz = rows[j, 0], rows[j, 1], rows[j, 2]
        mu = fld(cp, j, F_MU)
        if t == V_NR or t == V_NL:
            e = ends[j, 0] if t == V_NR else ends[j, 1]
            X[kz, 1 + v] += 1.0
            X[kp, 1 + v] -= e
            if zero_s[j] and not stuck:
                X[ks, 1 + v] += mu  # T = mu N - lambda_L
        elif t == V_LAM:
            X[ks, 1 + v] -= 1.0
    if not _lu(A, piv, nf):
        return False
    _lu_solve(A, piv, X, nf, m + 1)
    # the complementarity rows: w = q + Ml z
    for i in range(m):
        j = var_j[i]
        t = var_t[i]
        ks, kp, kz = rows[j, 0], rows[j, 1], rows[j, 2]
        o = rows[j, 3]
        mu = fld(cp, j, F_MU)
        for v in range(m):
            Ml[i, v] = 0.0
        if t == V_NR or t == V_NL:
            e = ends[j, 0] if t == V_NR else ends[j, 1]
            ql[i] = X[kz, 0] - e * X[kp, 0]
            for v in range(m):
                Ml[i, v] = X[kz, 1 + v] - e * X[kp, 1 + v]
        elif t == V_SIG:
            ql[i] = 0.0
            Ml[i, o + V_NR] = 2.0 * mu
            Ml[i, o + V_NL] = 2.0 * mu
            Ml[i, o + V_LAM] = -1.0
        else:
            ql[i] = -X[ks, 0]
            for v in range(m):
                Ml[i, v] = -X[ks, 1 + v]
            Ml[i, o + V_SIG] += 1.0
    status = lemke(Ml[:m, :m], ql[:m], z[:m], w[:m], lws)
    if status != LCP_OK:
        return False
    # the pattern: scales of the forces and of the accelerations
    fs = 1e-300
    as_ = 1e-300
    for i in range(m):
        if var_t[i] == V_NR or var_t[i] == V_NL:
            fs = max(fs, abs(z[i]))
            as_ = max(as_, abs(w[i]))
    for k in range(nf):
        acc = X[k, 0]
        for v in range(m):
            acc += X[k, 1 + v] * z[v]
        xs[k] = acc
        as_ = max(as_, abs(acc))
    for j in range(n):
        if not zero_psi[j]:
            continue
        o = rows[j, 3]
        touch_r = z[o + V_NR] > DEGENERATE * fs or w[o + V_NR] <= DEGENERATE * as_
        touch_l = z[o + V_NL] > DEGENERATE * fs or w[o + V_NL] <= DEGENERATE * as_
        if (z[o + V_NR] <= DEGENERATE * fs and w[o + V_NR] <= DEGENERATE * as_) or \
                (z[o + V_NL] <= DEGENERATE * fs and w[o + V_NL] <= DEGENERATE * as_):
            degen[j] = True
        if touch_r and touch_l:
            cand[2 * j] = 0.0
        elif touch_r:
            cand[2 * j] = 1.0  # the left corner lifts: a pivot on the right corner
        elif touch_l:
            cand[2 * j] = -1.0
        else:  # both corners lift: a flight, which the model has not (the enumeration decides)
            cand[2 * j] = 0.0
            degen[j] = True
        if zero_s[j] and not stuck:
            sdd = xs[rows[j, 0]]
            if sdd > DEGENERATE * as_:
                cand[2 * j + 1] = 1.0
            elif sdd < -DEGENERATE * as_:
                cand[2 * j + 1] = -1.0
            else:
                cand[2 * j + 1] = 0.0
            N = z[o + V_NR] + z[o + V_NL]
            lam = z[o + V_LAM]
            mu = fld(cp, j, F_MU)
            if N > DEGENERATE * fs and (lam <= DEGENERATE * fs or 2.0 * mu * N - lam <= DEGENERATE * fs) and \
                    abs(sdd) <= DEGENERATE * as_:
                degen[j] = True  # at the edge of the cone, not sliding: a slip may be starting
    return True


@kernel
def _n_codes(kc):
    """How many slip choices of ``kc`` resting pivots are tried: all ``3^kc`` up to ``KC_MAX`` pivots; beyond, every
    pivot sticking and each one sliding alone either way (``1 + 2 kc``): not every combination, so a choice may miss
    the consistent pattern there; the driver then counts it (``n_inconsistent``)."""
    return 3 ** kc if kc <= KC_MAX else 1 + 2 * kc


@kernel
def _slip_choice(code, k, kc):
    """The slip (0, +1, -1) of the ``k``-th resting pivot in choice ``code`` of :func:`_n_codes`."""
    if kc <= KC_MAX:
        d = (code // 3 ** k) % 3
    else:
        d = 0 if code == 0 or (code - 1) // 2 != k else 1 + (code - 1) % 2
    return 0.0 if d == 0 else (1.0 if d == 1 else -1.0)


@kernel
def _pulls_off(cp, cand, y, ag, ws, sp):
    """Solve the candidate as the enumeration does (:func:`rockcli.kernels.chain.solve_level`): True when a sliding
    contact pulls there (its friction then off: ``ws``'s ``mo`` set, kept for the second solve)."""
    n = int(cp[CP_N])
    nf = kinematics(cp, cand, y, ws)
    if nf == 0 or not solve_level(cp, cand, y, ws, nf, ag, False):
        return False
    mo = ws[13]
    for j in range(n):
        if mo[j] != 0.0:
            return True
    return False


@kernel
def _pulls_off_v(cp, cand, y, ws, v0, w0):
    """:func:`_pulls_off` at an impact (the velocities before ``v0``, ``w0``)."""
    n = int(cp[CP_N])
    nf = kinematics(cp, cand, y, ws)
    vG = ws[6]
    om = ws[7]
    for i in range(n):
        vG[i, 0] = v0[i, 0]
        vG[i, 1] = v0[i, 1]
        om[i] = w0[i]
    if nf == 0 or not solve_level(cp, cand, y, ws, nf, 0.0, True):
        return False
    mo = ws[13]
    for j in range(n):
        if mo[j] != 0.0:
            return True
    return False


@kernel
def lcp_choose(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best, sp):
    """:func:`rockcli.kernels.contact.choose_pattern` by the complementarity solve: the same arguments and returns
    (the margin of the pattern written into ``best``, its pulling pivots), and ``sp`` (:func:`lcp_space`)."""
    n = int(cp[CP_N])
    tol = cp[CP_TOL]
    cand = sp[13]
    trial = sp[14]
    degen = sp[15]
    best_m = -math.inf
    best_pulls = 0
    # the pivots whose slip rests: their choices outside the solve, each tried (the largest margin wins, as in the
    # enumeration: with friction two patterns may both meet every condition)
    kc = 0
    for j in range(n):
        if zero_s[j] and not zero_psi[j]:
            kc += 1
    solved = False
    for code in range(_n_codes(kc)):
        for i in range(2 * n):
            trial[i] = pat[i]
        k = 0
        for j in range(n):
            if zero_s[j] and not zero_psi[j]:
                trial[2 * j + 1] = _slip_choice(code, k, kc)
                k += 1
        if not lcp_candidate(cp, trial, y, ag, ws, zero_psi, zero_s, sp, cand, degen, False, False, sp[11], sp[16],
                             False):
            continue
        if _pulls_off(cp, cand, y, ag, ws, sp):  # a sliding contact pulls there: solved again without its friction
            if not lcp_candidate(cp, trial, y, ag, ws, zero_psi, zero_s, sp, cand, degen, False, False, sp[11],
                                 sp[16], True):
                continue
        solved = True
        # the candidate, and the interfaces with a degenerate pair in every way the event allows
        total = 1
        for j in range(n):
            if degen[j]:
                total *= (3 if zero_psi[j] else 1) * (3 if zero_s[j] else 1)
        if total > 9 ** MAX_DEGENERATE:
            total = 1
            for j in range(n):
                degen[j] = False
        for dc in range(total):
            rest = dc
            for i in range(2 * n):
                trial[i] = cand[i]
            for j in range(n):
                if degen[j]:
                    if zero_psi[j]:
                        a = rest % 3
                        rest //= 3
                        trial[2 * j] = 0.0 if a == 0 else (1.0 if a == 1 else -1.0)
                    if zero_s[j]:
                        bb = rest % 3
                        rest //= 3
                        trial[2 * j + 1] = 0.0 if bb == 0 else (1.0 if bb == 1 else -1.0)
            same = True
            for i in range(2 * n):
                if trial[i] != pat[i]:
                    same = False
            if same:  # the pattern whose condition just failed: only if nothing else meets the conditions
                continue
            nf = solve_pattern(cp, trial, y, ag, ws, frc)
            if nf < 0:
                continue
            m, pulls = pattern_margin(cp, trial, y, ws, frc, nf, zero_psi, zero_s, False, y)
            if m > best_m:
                best_m = m
                best_pulls = pulls
                for i in range(2 * n):
                    best[i] = trial[i]
    if not solved or best_m < -tol:
        nz = 0
        for j in range(n):
            if zero_psi[j]:
                nz += 1
            if zero_s[j]:
                nz += 1
        if 3 ** nz <= ENUM_MAX:
            return choose_pattern(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best)
    if best_m < -tol:
        for i in range(2 * n):
            best[i] = pat[i]
    # leave the chosen pattern's solution in ws and frc, as choose_pattern does
    nf = solve_pattern(cp, best, y, ag, ws, frc)
    if nf >= 0:
        best_m, best_pulls = pattern_margin(cp, best, y, ws, frc, nf, zero_psi, zero_s, False, y)
    return best_m, best_pulls


@kernel
def _impact_try(cp, cand, y, ws, frc, zero_psi, no_s, v0, w0, best, ynew, best_m, best_pulls):
    """Check one pattern after an impact (:func:`rockcli.kernels.contact.impact`'s test); keep the better."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    nf = kinematics(cp, cand, y, ws)
    for i in range(n):
        vG[i, 0] = v0[i, 0]
        vG[i, 1] = v0[i, 1]
        om[i] = w0[i]
    if nf > 0:
        if not solve_level(cp, cand, y, ws, nf, 0.0, True):
            return best_m, best_pulls
    impulses(cp, cand, ws, nf, frc)
    m, pulls = pattern_margin(cp, cand, y, ws, frc, nf, zero_psi, no_s, True, y)
    if m > best_m:
        for i in range(2 * n):
            best[i] = cand[i]
        for i in range(y.shape[0]):
            ynew[i] = y[i]
        for i in range(n):
            ynew[col_s(i) + 1] = 0.0
            ynew[col_psi(i) + 1] = 0.0
        if cp[CP_BASE] != BASE_RIGID:
            ynew[1] = 0.0
        for k in range(nf):
            ynew[free[k] + 1] = x[k]
        return m, pulls
    return best_m, best_pulls


@kernel
def lcp_impact(cp, pat, pat_to, y, ws, frc, zero_psi, free_corner, best, v0, w0, ynew, sp, stick_only=False):
    """:func:`rockcli.kernels.contact.impact` by the complementarity solve (the same arguments, ``sp`` added, and the
    same returns ``(margin, pulls, slipped)``): first the impact whose contacts all stick (the interfaces with
    ``free_corner`` released, their slips held: the rocking model's law), taken when it meets every condition; else
    every contact may slide (the released interfaces' friction unknown; the slips of the pivots that stay are tried
    each way outside the solve). Each solution is checked as the enumeration checks its candidates."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    tol = cp[CP_TOL]
    cand = sp[13]
    trial = sp[14]
    degen = sp[15]
    kinematics(cp, pat, y, ws)
    for i in range(n):
        v0[i, 0] = vG[i, 0]
        v0[i, 1] = vG[i, 1]
        w0[i] = om[i]
    no_s = np.zeros(n, dtype=np.bool_)
    all_s = np.ones(n, dtype=np.bool_)
    best_m = -math.inf
    best_pulls = 0
    slipped = False
    for stage in range(2):
        if stage == 1:
            if best_m >= -tol or stick_only:
                break
            slipped = True
            best_m = -math.inf
        kc = 0
        if stage == 1:
            for j in range(n):
                if not free_corner[j]:
                    kc += 1
        for code in range(_n_codes(kc)):
            for i in range(2 * n):
                trial[i] = pat_to[i]
            k = 0
            for j in range(n):
                if stage == 0 or free_corner[j]:
                    trial[2 * j + 1] = 0.0
                else:
                    trial[2 * j + 1] = _slip_choice(code, k, kc)
                    k += 1
            if not lcp_candidate(cp, trial, y, 0.0, ws, free_corner, all_s, sp, cand, degen, True, stage == 0,
                                 v0, w0, False):
                continue
            if _pulls_off_v(cp, cand, y, ws, v0, w0):
                if not lcp_candidate(cp, trial, y, 0.0, ws, free_corner, all_s, sp, cand, degen, True, stage == 0,
                                     v0, w0, True):
                    continue
            total = 1
            for j in range(n):
                if degen[j]:
                    total *= 3 if stage == 0 else 9
            if total > 9 ** MAX_DEGENERATE:
                total = 1
                for j in range(n):
                    degen[j] = False
            for dc in range(total):
                rest = dc
                for i in range(2 * n):
                    trial[i] = cand[i]
                for j in range(n):
                    if degen[j]:
                        a = rest % 3
                        rest //= 3
                        trial[2 * j] = 0.0 if a == 0 else (1.0 if a == 1 else -1.0)
                        if stage == 1:
                            bb = rest % 3
                            rest //= 3
                            trial[2 * j + 1] = 0.0 if bb == 0 else (1.0 if bb == 1 else -1.0)
                best_m, best_pulls = _impact_try(cp, trial, y, ws, frc, zero_psi, no_s, v0, w0, best, ynew, best_m,
                                                 best_pulls)
    return best_m, best_pulls, slipped


@kernel
def choose(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best, sp):
    """The friction driver's pattern choice: the enumeration for one block and a body on its plinth (the answers
    checked since; bit for bit), the complementarity solve for taller chains, where every closed face of the chain
    is released with the event's interfaces (a joint that stays shut is then a result, not an assumption), and, if
    no pattern meets the conditions, the pivots that stick too (their slips each way)."""
    n = int(cp[CP_N])
    if n <= 2:
        return choose_pattern(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best)
    for j in range(n):
        if pat[2 * j] == 0.0:
            zero_psi[j] = True
            if pat[2 * j + 1] == 0.0:
                zero_s[j] = True
    m, pulls = lcp_choose(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best, sp)
    if m >= -cp[CP_TOL]:
        return m, pulls
    more = False
    for j in range(n):
        if pat[2 * j] != 0.0 and pat[2 * j + 1] == 0.0 and not zero_s[j]:
            zero_s[j] = True
            more = True
    if not more:
        return m, pulls
    return lcp_choose(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best, sp)


@kernel
def impact_any(cp, pat, pat_to, y, ws, frc, zero_psi, free_corner, best, v0, w0, ynew, sp):
    """The friction driver's impact: the enumeration for one block and a body on its plinth, the complementarity
    solve for taller chains."""
    if int(cp[CP_N]) <= 2:
        return impact(cp, pat, pat_to, y, ws, frc, zero_psi, free_corner, best, v0, w0, ynew)
    return lcp_impact(cp, pat, pat_to, y, ws, frc, zero_psi, free_corner, best, v0, w0, ynew, sp)
