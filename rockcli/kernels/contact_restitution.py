"""A coefficient of restitution ``E`` with friction (docs/physics-sliding.md, "Restitution"): the rocking model's
energetic rule (docs/physics-plinth.md, "A coefficient of restitution"), taken when its impulses fit Coulomb's cone.

The rule, for an impact of interface ``j``: the pattern after it is the plastic law's where every contact sticks,
with interface ``j`` pivoting on its new corner; every motion that does not turn interface ``j`` gets the plastic
law (the projection ``P0 v-`` of the velocities before onto the motions with ``j`` stuck, in the kinetic-energy
metric), and ``j``'s own motion ``w`` (unit rate of ``psi_j``, orthogonal in that metric to those motions) gets the
rate ``E W`` on the new corner, ``W = |v- - P0 v-| / |w|``, the largest rate the kinetic energy allows. For one block
on the ground this is ``theta'+ = E theta'-``, rockcli's rule; the kinetic energy after is ``|P0 v-|^2/2 + E^2 (|v-|^2
- |P0 v-|^2)/2``, never more than before. Its impulses (the momentum jumps) must press at the new pivot and at every
face, and fit the cone at every contact (all stick): then it is the impact; otherwise the impact is the plastic one
with Coulomb's law (the restitution could not be carried: counted)."""

from __future__ import annotations

import math

from rockcli.kernels.chain import (BASE_RIGID, CP_BASE, CP_N, CP_TOL, F_B, F_MU, assemble, col_psi, col_s, fld,
                                   impulses, kinematics, solve_small)
from rockcli.kernels.contact import pattern_margin, project
from rockcli.kernels.jit import kernel


@kernel
def _energetic(cp, pat, pat_e, y, ws, frc, j, E, v0, w0, ynew, ytmp):
    """The energetic rule's velocities for the candidate ``pat_e`` (interface ``j`` on its new corner, every contact
    sticking) into ``ynew``, and their impulses against the velocities before in ``frc``; the candidate's number of
    free coordinates (its rates in ``ws``'s ``x``), or -1 when it cannot be formed."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    cb = pat[2 * j]
    stuck = pat_e.copy()
    stuck[2 * j] = 0.0
    project(cp, pat, stuck, y, ws, v0, w0, ytmp)  # P0 v- (rates in ytmp; v0, w0: the velocities before)
    e_minus = 0.0
    for i in range(n):  # |v-|^2 and |P0 v-|^2 in the energy metric
        e_minus += fld(cp, i, 2) * (v0[i, 0] ** 2 + v0[i, 1] ** 2) + fld(cp, i, 3) * w0[i] ** 2
    if cp[CP_BASE] != BASE_RIGID:
        e_minus += cp[6] * y[1] ** 2
    kinematics(cp, stuck, ytmp, ws)
    e_zero = 0.0
    for i in range(n):
        e_zero += fld(cp, i, 2) * (vG[i, 0] ** 2 + vG[i, 1] ** 2) + fld(cp, i, 3) * om[i] ** 2
    if cp[CP_BASE] != BASE_RIGID:
        e_zero += cp[6] * ytmp[1] ** 2
    nf = kinematics(cp, pat_e, y, ws)
    k = -1
    for q in range(nf):
        if free[q] == col_psi(j):
            k = q
    if k < 0:
        return -1
    assemble(cp, pat_e, y, ws, nf, 0.0, 0.0, True)  # the mass matrix (its right-hand side is not used)
    for q in range(nf):
        r[q] = 1.0 if q == k else 0.0
    if not solve_small(M, r, x, nf):
        return -1
    minv_kk = x[k]
    if not minv_kk > 0.0:
        return -1
    rate = E * math.sqrt(max(e_minus - e_zero, 0.0) * minv_kk)
    for i in range(y.shape[0]):
        ynew[i] = y[i]
    for i in range(n):
        ynew[col_s(i) + 1] = 0.0
        ynew[col_psi(i) + 1] = 0.0
    if cp[CP_BASE] != BASE_RIGID:
        ynew[1] = 0.0
    for q in range(nf):  # v+ = P0 v- (psi_j' = 0 there) + (E W / x_k) x along w = M^-1 e_k
        c = free[q]
        base = ytmp[c + 1] if c != col_psi(j) else 0.0
        ynew[c + 1] = base - cb * rate * x[q] / minv_kk
    kinematics(cp, pat_e, y, ws)
    for i in range(n):
        vG[i, 0] = v0[i, 0]
        vG[i, 1] = v0[i, 1]
        om[i] = w0[i]
    for q in range(nf):
        x[q] = ynew[free[q] + 1]
    impulses(cp, pat_e, ws, nf, frc)
    return nf


@kernel
def restitution_impact(cp, pat, zero_psi, y, ws, frc, j, E, v0, w0, best, ynew, ytmp, ycand):
    """The energetic rule's impact of interface ``j`` from ``pat`` at ``y`` (module notes): every candidate (the other
    interfaces at angle 0 a face or either pivot, interface ``j`` on its new corner, every contact sticking) gets the
    rule's velocities, and the one whose impulses meet every condition with the largest smallest margin is taken
    (as the rocking model chooses, docs/physics-plinth.md). Writes ``best`` and ``ynew``; True when one meets them."""
    n = int(cp[CP_N])
    cand = pat.copy()
    for i in range(n):
        cand[2 * i + 1] = 0.0
    cand[2 * j] = -pat[2 * j]
    nz = 0
    for i in range(n):
        if zero_psi[i] and i != j:
            nz += 1
    no_s = zero_psi.copy()
    for i in range(n):
        no_s[i] = False
    best_m = -math.inf
    for code in range(3 ** nz):
        rest = code
        for i in range(n):
            if zero_psi[i] and i != j:
                cand[2 * i] = float(rest % 3 - 1) if rest % 3 != 1 else 0.0
                rest //= 3
        nf = _energetic(cp, pat, cand, y, ws, frc, j, E, v0, w0, ycand, ytmp)
        if nf < 0:
            continue
        m, pulls = pattern_margin(cp, cand, y, ws, frc, nf, zero_psi, no_s, True, y)
        if m > best_m:
            best_m = m
            for i in range(2 * n):
                best[i] = cand[i]
            for i in range(y.shape[0]):
                ynew[i] = ycand[i]
    return best_m >= -cp[CP_TOL]
