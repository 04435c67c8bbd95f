"""The contact law, written once for every body rockcli stands on another (docs/physics-sliding.md): each
interface is a face or a pivot on either corner, and each sticks or slides either way, under unilateral normal
contact and Coulomb's law with one coefficient ``mu`` (static = kinetic). Used by the friction driver
(:mod:`rockcli.kernels.chain_run`) with the chain's mechanics (:mod:`rockcli.kernels.chain`).

Conditions of a pattern (forces ``N, T`` of the block below on everything above, couple ``Mc`` about the contact
point; the same with impulses at an impact):

* a face presses on both corners: ``P_right = N/2 - Mc/(2 b) >= 0`` and ``P_left = N/2 + Mc/(2 b) >= 0``;
* a pivot presses: ``N >= 0`` (a pivot that would pull is kept, bilateral, and counted as a jump: the rocking
  model's assumption "no flight" fails there, as it is said without friction);
* a contact that sticks stays inside Coulomb's cone: ``|T| <= mu N``;
* a contact that slides in direction ``sl`` has ``T = -mu sl N`` (built into the equations) and keeps sliding that
  way: ``sl s' >= 0``, and, starting from ``s' = 0``, ``sl s'' >= 0``;
* a pivot that starts (its angle and rate at 0) opens: ``c psi'' >= 0`` (at an impact ``c psi'+ >= 0``).

The pattern that follows an event is the one whose forces (impulses) meet every condition: candidates are the
patterns the event allows (the interfaces whose angle is at 0 may be a face or either pivot, those at rest
relative to the surface below may stick or slide either way), each checked by one solve of the chain's
equations; the one with the largest smallest margin is taken (exactly one is consistent in every case we met but
ties at a threshold; the margins are relative). A contact whose normal force is negative in every candidate is
kept and counted (``n_jumps``).

Impacts (Moreau's plastic impact with Coulomb's law): the impulses act at the contacts of the pattern after the
impact; every contact that sticks has no relative velocity after it, every contact that slides has its tangential
impulse at ``mu`` times its normal one, against the slip after it. The candidate where every contact sticks is the
rocking model's plastic law (Housner's for one block on the ground); it is taken whenever its impulses fit the
cone, so that an impact without slip is the rocking model's impact. Energy never rises: the impulses' work is
``P . v+ - |P|^2_{M^-1}/2 <= 0`` when every normal impulse is at a contact with no normal velocity after and every
tangential one opposes the slip after.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.chain import (BASE_RIGID, overlap_ends, CP_BASE, CP_BLK, CP_N, CP_TOL, F_B, F_M, F_MU, NF_BLK, assemble, col_psi, col_s, solve_level,
                                   contact_forces, fld, impulses, kinematics, solve_small)
from rockcli.kernels.jit import hot, kernel


@kernel(inline='always')
def face_corners(cp, j, s, N, Mc):
    """``(P_right, P_left)``: the normal force ``N`` and couple ``Mc`` (clockwise on the block above, about the centre
    of its base) of interface ``j``'s face, at the slip ``s``, as the forces at the two ends of the contact: the
    block's corners, or where a corner overhangs the top below (a drum slid past the one under it), that top's
    corner (:func:`rockcli.kernels.chain.overlap_ends`). ``e_R P_right + e_L P_left = -Mc``."""
    b = fld(cp, j, F_B)
    e_r, e_l = overlap_ends(cp, j, s)
    if e_r == b and e_l == -b:
        return 0.5 * N - 0.5 * Mc / b, 0.5 * N + 0.5 * Mc / b
    w = e_r - e_l
    if w <= 1e-12 * b:  # no overlap left (the slip at the edge, where the run ends as slid off): a point contact
        return 0.5 * N, 0.5 * N
    return (-Mc - N * e_l) / w, (N * e_r + Mc) / w


@hot
def pattern_margin(cp, pat, y, ws, frc, nf, zero_psi, zero_s, level_v, y_before):
    """How well the pattern's solution (``ws``'s ``x[:nf]`` after a solve; ``frc`` its forces or impulses per
    interface) meets the contact conditions: the smallest relative margin (negative: a condition fails), and
    the number of pivots that pull. ``zero_psi[j]``: interface ``j``'s angle is at 0 (a face or a pivot starting:
    its corner and its opening are checked); ``zero_s[j]``: its slip rate is at 0 (a slide starting: its direction is
    checked on ``s''``). At an impact (``level_v``) the opening and the slip are checked on the rates after it."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    worst = math.inf
    pulls = 0
    # scales: the largest normal force (impulse) of the chain, and the largest rate
    fs = 0.0
    for j in range(n):
        fs = max(fs, abs(frc[j, 0]), abs(frc[j, 1]))
    fs = max(fs, 1e-300)
    vs = 1e-300
    for k in range(nf):
        vs = max(vs, abs(x[k]))
    for j in range(n):
        c = pat[2 * j]
        sl = pat[2 * j + 1]
        N = frc[j, 0]
        T = frc[j, 1]
        b = fld(cp, j, F_B)
        if c == 0.0:
            pr, pl = face_corners(cp, j, y[col_s(j)], N, frc[j, 2])
            worst = min(worst, pr / fs, pl / fs)
        else:
            if zero_psi[j]:
                worst = min(worst, N / fs)
                # the pivot opens: c psi'' (its rate after an impact) >= 0
                rate = _rate_of(free, x, nf, col_psi(j))
                worst = min(worst, c * rate / vs)
            elif N < 0.0:
                pulls += 1
        mu = fld(cp, j, F_MU)
        if sl == 0.0:
            if N > 0.0 or c == 0.0 or zero_psi[j]:
                worst = min(worst, (mu * max(N, 0.0) - abs(T)) / fs)
        else:
            if mo[j] != 0.0:  # solved without friction because it pulled: it must pull still
                worst = min(worst, -N / fs)
            if zero_s[j] or level_v:
                rate = _rate_of(free, x, nf, col_s(j))
                worst = min(worst, sl * rate / vs)
    return worst, pulls


@kernel(inline='always')
def _rate_of(free, x, nf, col):
    for k in range(nf):
        if free[k] == col:
            return x[k]
    return 0.0


@hot
def solve_pattern(cp, pat, y, ag, ws, frc):
    """The accelerations of the pattern at the state ``y`` (``ws``'s ``x``) and its contact forces ``frc``; the
    number of free coordinates, or -1 when its system is singular."""
    nf = kinematics(cp, pat, y, ws)
    if nf > 0:
        if not solve_level(cp, pat, y, ws, nf, ag, False):
            return -1
    contact_forces(cp, pat, ws, nf, ag, frc)
    return nf


@kernel
def choose_pattern(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best):
    """The pattern that continues the motion from the state ``y`` (no impact): the interfaces with ``zero_psi``
    (angle and rate at 0) may be a face or either pivot, those with ``zero_s`` (slip rate 0) may stick or slide
    either way; the others keep ``pat``'s. ``pat`` itself, whose condition has just failed (the event), is taken only
    when no other candidate meets the conditions (within the relative slack ``CP_TOL``): a tangency, where the force
    touches its threshold and turns back. At the threshold the pattern that starts has its new freedom at zero
    acceleration (the corner force is exactly 0 there), so its own margin is at rounding level; ``pat``'s is too,
    and only the direction of the motion after the event tells them apart: the failing one is left out. Writes the
    chosen pattern into ``best``; returns its margin (negative: none met every condition) and its pulling pivots."""
    n = int(cp[CP_N])
    nz = 0
    for j in range(n):
        if zero_psi[j]:
            nz += 1
        if zero_s[j]:
            nz += 1
    total = 3 ** nz
    cand = pat.copy()
    best_m = -math.inf
    best_pulls = 0
    for code in range(total):
        rest = code
        for j in range(n):
            if zero_psi[j]:
                cand[2 * j] = float(rest % 3 - 1) if rest % 3 != 1 else 0.0
                rest //= 3
            if zero_s[j]:
                cand[2 * j + 1] = float(rest % 3 - 1) if rest % 3 != 1 else 0.0
                rest //= 3
        same = True
        for i in range(2 * n):
            if cand[i] != pat[i]:
                same = False
        if same:  # the pattern whose condition just failed: only if no other meets the conditions (a tangency)
            continue
        nf = solve_pattern(cp, cand, y, ag, ws, frc)
        if nf < 0:
            continue
        m, pulls = pattern_margin(cp, cand, y, ws, frc, nf, zero_psi, zero_s, False, y)
        if m > best_m:
            best_m = m
            best_pulls = pulls
            for i in range(2 * n):
                best[i] = cand[i]
    if best_m < -cp[CP_TOL]:
        for i in range(2 * n):
            best[i] = pat[i]
        nf = solve_pattern(cp, pat, y, ag, ws, frc)
        best_m, best_pulls = pattern_margin(cp, pat, y, ws, frc, nf, zero_psi, zero_s, False, y)
    return best_m, best_pulls


@kernel
def impact(cp, pat, pat_to, y, ws, frc, zero_psi, free_corner, best, v0, w0, ynew, stick_only=False):
    """Moreau's plastic impact with Coulomb's law at the state ``y`` (the interfaces with ``zero_psi`` at angle 0,
    the impacting one among them) from the pattern ``pat`` before it. Candidates: the interfaces with
    ``free_corner`` a face or either pivot (the others keep the corner of ``pat_to``), every interface sticking or
    sliding either way; first the candidates where all stick (the rocking law), taken when one meets every
    condition; else all. Writes the pattern after into ``best`` and the state after into
    ``ynew`` (positions unchanged; the rates of the free coordinates; 0 for the others). Returns ``(margin, pulls,
    slipped)``: ``slipped`` True when the rocking law's impulses did not fit the cone. ``v0``, ``w0``: scratch for
    the velocities before (n x 2, n). ``stick_only``: the rocking law's candidates only (the best of them, whether or
    not it meets every condition)."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    kinematics(cp, pat, y, ws)
    for i in range(n):
        v0[i, 0] = vG[i, 0]
        v0[i, 1] = vG[i, 1]
        w0[i] = om[i]
    no_s = np.zeros(n, dtype=np.bool_)
    best_m = -math.inf
    best_pulls = 0
    slipped = False
    cand = pat_to.copy()
    nz = 0
    for j in range(n):
        if free_corner[j]:
            nz += 1
    for stage in range(2):  # 0: every contact sticks; 1: every tangential choice
        if stage == 1:
            if best_m >= -cp[CP_TOL] or stick_only:
                break
            slipped = True
            best_m = -math.inf
        total = 3 ** nz if stage == 0 else 3 ** (nz + n)
        for code in range(total):
            rest = code
            for j in range(n):
                if free_corner[j]:
                    cand[2 * j] = float(rest % 3 - 1) if rest % 3 != 1 else 0.0
                    rest //= 3
                if stage == 0:
                    cand[2 * j + 1] = 0.0
                else:
                    cand[2 * j + 1] = float(rest % 3 - 1) if rest % 3 != 1 else 0.0
                    rest //= 3
            nf = kinematics(cp, cand, y, ws)
            for i in range(n):
                vG[i, 0] = v0[i, 0]
                vG[i, 1] = v0[i, 1]
                om[i] = w0[i]
            if nf > 0:
                if not solve_level(cp, cand, y, ws, nf, 0.0, True):
                    continue
            impulses(cp, cand, ws, nf, frc)
            m, pulls = pattern_margin(cp, cand, y, ws, frc, nf, zero_psi, no_s, True, y)
            if m > best_m:
                best_m = m
                best_pulls = pulls
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
    return best_m, best_pulls, slipped


@kernel
def rest_moments(cp, pat, y, ag, ws, frc):
    """Each interface's restoring moment at rest under the ground acceleration ``ag`` (``2 b min(P_right, P_left)``
    of its face, everything above it standing still on it; ``M_j = m_above (g b - |ag| y_c)`` for a centred stack),
    into ``frc[:, 0]``: positive where nothing can lift it. ``pat`` is scratch (set to all faces sticking)."""
    n = int(cp[CP_N])
    for j in range(n):
        pat[2 * j] = 0.0
        pat[2 * j + 1] = 0.0
    solve_pattern(cp, pat, y, ag, ws, frc)
    for j in range(n):
        pr, pl = face_corners(cp, j, y[col_s(j)], frc[j, 0], frc[j, 2])
        frc[j, 0] = 2.0 * fld(cp, j, F_B) * min(pr, pl)


@kernel
def restoring_rate(cp, pat, y, ag, ws, frc, j):
    """The smaller of the two accelerations that turn interface ``j`` back to its face when it pivots from angle and
    rate 0 on either corner, the rest of the chain as in ``pat`` (its rates in ``y``): positive when the ground and
    the chain cannot open it (the rest rule's restoring acceleration; for one block on the ground ``p^2 cos(alpha)
    (tan(alpha) - |ag|/g)``)."""
    cand = pat.copy()
    yy = y.copy()
    yy[col_psi(j)] = 0.0
    yy[col_psi(j) + 1] = 0.0
    rest = math.inf
    for sg in (1.0, -1.0):
        cand[2 * j] = sg
        nf = solve_pattern(cp, cand, yy, ag, ws, frc)
        if nf < 0:
            return -math.inf
        free = ws[0]
        x = ws[12]
        acc = _rate_of(free, x, nf, col_psi(j))
        rest = min(rest, -sg * acc)
    return rest


@kernel
def project(cp, pat, pat_to, y, ws, v0, w0, ynew):
    """The rest rules' plastic step (the rocking model's "momentum kept along the rest"): the velocities of the
    state ``y`` in the pattern ``pat`` projected, in the kinetic-energy metric, onto the motions of ``pat_to`` (the
    velocity-level equations with no friction impulse: a contact that slides keeps its momentum along the slip, one
    that sticks is held). Energy never rises (a projection). Writes ``ynew``; the slip directions of ``pat_to`` are
    set from the rates after it (0: it sticks)."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    kinematics(cp, pat, y, ws)
    for i in range(n):
        v0[i, 0] = vG[i, 0]
        v0[i, 1] = vG[i, 1]
        w0[i] = om[i]
    cq = cp.copy()
    for j in range(n):
        cq[CP_BLK + NF_BLK * j + F_MU] = 0.0
    nf = kinematics(cq, pat_to, y, ws)
    for i in range(n):
        vG[i, 0] = v0[i, 0]
        vG[i, 1] = v0[i, 1]
        om[i] = w0[i]
    for i in range(y.shape[0]):
        ynew[i] = y[i]
    for i in range(n):
        ynew[col_s(i) + 1] = 0.0
        ynew[col_psi(i) + 1] = 0.0
    if cp[CP_BASE] != BASE_RIGID:
        ynew[1] = 0.0
    if nf > 0:
        assemble(cq, pat_to, y, ws, nf, 0.0, 0.0, True)
        if solve_small(M, r, x, nf):
            for k in range(nf):
                ynew[free[k] + 1] = x[k]
    for j in range(n):
        if pat_to[2 * j + 1] != 0.0:
            v = ynew[col_s(j) + 1]
            pat_to[2 * j + 1] = 1.0 if v > 0.0 else (-1.0 if v < 0.0 else 0.0)
