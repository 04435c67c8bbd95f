"""The friction driver's impacts (:func:`rockcli.kernels.chain_run.simulate_chain`, docs/physics-sliding.md): the
pattern and rates after an impact (Moreau's law with Coulomb friction, or a given restitution where its impulses
fit the cone), the rest rules, the check of the cone at the force level that follows, and the bookkeeping of every
change of pattern (:func:`switch`).

Rest rules after an impact (the rocking model's, for any chain): with every angle at 0, the chain is set on its
faces (a plastic impact into them, each contact sticking or sliding as the contact law says) when nothing could
lift it from rest under the current ``ag`` (each face's restoring moment at rest positive) and the kinetic energy
of its rocking (the rates of the slips and of the base left out) is below ``rest_tol`` times the smallest
``alpha_j M_j``; else the impacting interface is set on its face when both accelerations that would turn it back
are positive and the rotation it could still reach against the smaller is below ``rest_tol`` times its
slenderness. For one block on the ground both are the rocking driver's rule."""

from __future__ import annotations

import math

from rockcli.kernels.chain import CP_E, CP_N, CP_REST, CP_TOL, F_AREST, F_MU, col_psi, col_s, energy, fld
from rockcli.kernels.chain_out import (J_N_IMP, J_N_IMP_ALL, J_N_RESTS, J_N_SLIPS, J_T_SLIDE, J_T_UPLIFT, N_XG, NX_J,
                                       X_N_INCONS, X_N_JUMP, X_N_PLASTIC, X_N_SLIP_IMPACTS, X_N_SLIP_IN, X_N_SWITCH,
                                       X_T_FIRST)
from rockcli.kernels.contact import face_corners, project, rest_moments, restoring_rate, solve_pattern
from rockcli.kernels.contact_lcp import choose, impact_any
from rockcli.kernels.contact_restitution import restitution_impact
from rockcli.kernels.jit import kernel


@kernel
def switch(xo, pat, new, n, t, cp, y):
    """Enter the pattern ``new`` at the state ``y``: the bookkeeping of uplifts and slips (a slip that starts while
    every block leans less than its slenderness, ``|psi_j| <= alpha_j``, counted apart: not during a fall)."""
    inside = True
    for j in range(n):
        if abs(y[col_psi(j)]) > fld(cp, j, F_AREST):
            inside = False
    changed = False
    for j in range(n):
        o = N_XG + NX_J * j
        if pat[2 * j] == 0.0 and new[2 * j] != 0.0:
            if math.isnan(xo[o + J_T_UPLIFT]):
                xo[o + J_T_UPLIFT] = t
            if math.isnan(xo[X_T_FIRST]):
                xo[X_T_FIRST] = t
        if pat[2 * j + 1] == 0.0 and new[2 * j + 1] != 0.0:
            if math.isnan(xo[o + J_T_SLIDE]):
                xo[o + J_T_SLIDE] = t
            xo[o + J_N_SLIPS] += 1.0
            if inside:
                xo[X_N_SLIP_IN] += 1.0
            if math.isnan(xo[X_T_FIRST]):
                xo[X_T_FIRST] = t
        if pat[2 * j] != new[2 * j] or pat[2 * j + 1] != new[2 * j + 1]:
            changed = True
        pat[2 * j] = new[2 * j]
        pat[2 * j + 1] = new[2 * j + 1]
    if changed:
        xo[X_N_SWITCH] += 1.0


@kernel
def rocking_energy(cp, pat, y, ws, ytmp):
    """The kinetic energy of the chain's rocking: its rates with those of the slips and of the base set to 0."""
    n = int(cp[CP_N])
    for i in range(y.shape[0]):
        ytmp[i] = y[i]
    ytmp[1] = 0.0
    for j in range(n):
        ytmp[col_s(j) + 1] = 0.0
    T, _ = energy(cp, pat, ytmp, ws)
    return T


@kernel
def after_impact(cp, pat, y, j, t, t_exc_end, ag, xo, ws, frc, best, v0, w0, ynew, zero_psi, free_corner, ytmp, sp):
    """The impact of interface ``j`` (its angle at 0 in ``y``): the pattern and rates after it (Moreau with Coulomb),
    then the rest rules (module notes). Writes the state after into ``y`` and the pattern into ``pat``."""
    n = int(cp[CP_N])
    tol = cp[CP_TOL]
    o = N_XG + NX_J * j
    xo[o + J_N_IMP_ALL] += 1.0
    if t <= t_exc_end:
        xo[o + J_N_IMP] += 1.0
    for i in range(n):
        zero_psi[i] = i == j or pat[2 * i] == 0.0
        free_corner[i] = zero_psi[i]
    pat_to = pat.copy()
    restituted = False
    if cp[CP_E] >= 0.0:  # a coefficient of restitution: the energetic rule where its impulses fit the cone
        restituted = restitution_impact(cp, pat, zero_psi, y, ws, frc, j, cp[CP_E], v0, w0, best, ynew, ytmp,
                                        y.copy())
        if restituted:
            m, pulls, slipped = 0.0, 0, False
        else:
            xo[X_N_PLASTIC] += 1.0
    if not restituted:
        m, pulls, slipped = impact_any(cp, pat, pat_to, y, ws, frc, zero_psi, free_corner, best, v0, w0, ynew, sp)
    if m < -tol:
        xo[X_N_INCONS] += 1.0
    if pulls > 0:
        xo[X_N_JUMP] += 1.0
    if slipped:
        xo[X_N_SLIP_IMPACTS] += 1.0
    for i in range(y.shape[0]):
        y[i] = ynew[i]
    switch(xo, pat, best, n, t, cp, y)
    # rest rules
    all_zero = True
    for i in range(n):
        if y[col_psi(i)] != 0.0:
            all_zero = False
    rested = False
    if all_zero:
        scratch = pat.copy()
        rest_moments(cp, scratch, y, ag, ws, frc)
        lim = math.inf
        for i in range(n):
            if not frc[i, 0] > 0.0:
                lim = -1.0
                break
            lim = min(lim, fld(cp, i, F_AREST) * frc[i, 0])
        if lim > 0.0 and rocking_energy(cp, pat, y, ws, ytmp) < cp[CP_REST] * lim:
            for i in range(n):
                pat_to[2 * i] = 0.0
                pat_to[2 * i + 1] = pat[2 * i + 1]
            rested = True
    if not rested and pat[2 * j] != 0.0:
        rest = restoring_rate(cp, pat, y, ag, ws, frc, j)
        rate = y[col_psi(j) + 1]
        if rest > 0.0 and rate * rate < 2.0 * rest * cp[CP_REST] * fld(cp, j, F_AREST):
            for i in range(2 * n):
                pat_to[i] = pat[i]
            pat_to[2 * j] = 0.0
            rested = True
    if rested:
        for i in range(n):
            if pat_to[2 * i] == 0.0 and pat[2 * i] != 0.0:
                xo[N_XG + NX_J * i + J_N_RESTS] += 1.0
        project(cp, pat, pat_to, y, ws, v0, w0, ynew)
        for i in range(y.shape[0]):
            y[i] = ynew[i]
        switch(xo, pat, pat_to, n, t, cp, y)



@kernel
def cone_after_impact(cp, pat, y, t, ag, xo, ws, frc, best, zero_psi, zero_s, sp):
    """After an impact and the rest rules, the force level of the pattern they chose: a contact left sticking whose
    friction force would need more than ``mu N`` (beyond the relative slack ``CP_TOL`` of the largest force) starts
    to slide now, the way the contact law chooses (:func:`rockcli.kernels.contact_lcp.choose`): every sticking
    contact's slip free to start either way (one that slides changes the others' demand), every pivot at angle and
    rate 0 free to turn or close, as after a force event. The impact law chooses from velocities; a contact it leaves sticking may already
    be outside its cone, and the step's force events take a condition that fails at the step's start as an event only
    once it has held (a tangency), so without this check such a contact would stick on for as long as its force stays
    outside: the reference (rockcli.reference.friction) lets it slide at once. Likewise a face left shut whose
    force at a corner would be negative (beyond the same slack) may open now (a column of drums: an impact at one
    joint can leave another's face pulling). Returns True when the pattern changed."""
    n = int(cp[CP_N])
    tol = cp[CP_TOL]
    if solve_pattern(cp, pat, y, ag, ws, frc) < 0:
        return False
    fs = 0.0
    for i in range(n):
        fs = max(fs, abs(frc[i, 0]), abs(frc[i, 1]))
    out = False
    for i in range(n):
        zero_psi[i] = False
        if pat[2 * i + 1] == 0.0 and frc[i, 0] > 0.0 and fld(cp, i, F_MU) * frc[i, 0] - abs(frc[i, 1]) < -tol * fs:
            out = True
        if pat[2 * i] == 0.0:
            pr, pl = face_corners(cp, i, y[col_s(i)], frc[i, 0], frc[i, 2])
            if min(pr, pl) < -tol * fs:  # a face that would pull at a corner: it may open now
                zero_psi[i] = True
                out = True
    if not out:
        return False
    for i in range(n):  # every sticking contact may start to slide (the others' demand changes with it)
        zero_s[i] = pat[2 * i + 1] == 0.0
        if pat[2 * i] != 0.0 and y[col_psi(i)] == 0.0 and y[col_psi(i) + 1] == 0.0:
            zero_psi[i] = True
    m, pulls = choose(cp, pat, y, ag, ws, frc, zero_psi, zero_s, best, sp)
    if m < -tol:
        xo[X_N_INCONS] += 1.0
    switch(xo, pat, best, n, t, cp, y)
    return True
