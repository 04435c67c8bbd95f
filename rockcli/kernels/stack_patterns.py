"""The stack driver's changes of pattern (:mod:`rockcli.kernels.stack`): entering a pattern (:func:`_set_pattern`),
the pattern after an impact (:func:`_after_impact`, from
:func:`rockcli.kernels.stack_physics.choose_after_impact`) and the rest rules: the single block's, with the body's or
the assembly's parameters, when one body rocks after the impact; the whole stack's (:func:`_stack_rests`); an
interface stuck again while the other pivots (:func:`_rest_check`).
"""

from __future__ import annotations

import math

from rockcli.kernels.events import _count_uplift, comes_to_rest
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (O_N_RESTS, O_UPLIFTED, PHASE_ROCKING, PHASE_STUCK, P_ALPHA, P_THR, RS_FRESH,
                                    RS_PHASE, RS_S, W_Y)
from rockcli.kernels.stack_physics import (S_A1REST, S_AAREST, S_B1, S_B2, S_G, S_H1, S_H2, S_M2, S_REST, _dot, bp_acc,
                                           choose_after_impact, fields, project)
from rockcli.kernels.stack_step import (PAT_B, PAT_BP, PAT_P, PAT_R, X_FRI_B, X_FRI_J, X_K, X_N_INCONS, X_N_JUMP,
                                        X_N_PLASTIC, X_N_SWITCH, X_PAT, X_PL_N_RESTS, X_PL_T_UPLIFT, X_S)


# ---------------------------------------------------------------------------------------------
# Changes of pattern
# ---------------------------------------------------------------------------------------------
@kernel
def _set_pattern(rs, W, xo, s, k, psi, psid, th2, thd2):
    """Enter the pattern of corners ``(s, k)`` (0: a face) with these states."""
    for i in range(4):
        W[W_Y, i] = 0.0
    if s == 0.0 and k == 0.0:
        pat = PAT_R
        rs[RS_PHASE] = PHASE_STUCK
        rs[RS_S] = 0.0
    elif s == 0.0:
        pat = PAT_B
        rs[RS_PHASE] = PHASE_ROCKING
        rs[RS_S] = k
        W[W_Y, 0] = psi
        W[W_Y, 1] = psid
    elif k == 0.0:
        pat = PAT_P
        rs[RS_PHASE] = PHASE_ROCKING
        rs[RS_S] = s
        W[W_Y, 0] = th2
        W[W_Y, 1] = thd2
    else:
        pat = PAT_BP
        rs[RS_PHASE] = PHASE_ROCKING
        rs[RS_S] = 2.0 * s + k
        W[W_Y, 0] = psi
        W[W_Y, 1] = psid
        W[W_Y, 2] = th2
        W[W_Y, 3] = thd2
    if pat != xo[X_PAT]:
        xo[X_N_SWITCH] += 1.0
    xo[X_PAT] = pat
    xo[X_S] = s
    xo[X_K] = k
    rs[RS_FRESH] = 1.0


@kernel
def _plinth_lifts(xo, t):
    if math.isnan(xo[X_PL_T_UPLIFT]):
        xo[X_PL_T_UPLIFT] = t


@kernel
def _rest_check(j, s, k, sp, th2, psi, V, ag):
    """The rest rule after an impact that leaves pivot ``j`` (0 base, 1 joint) of ``(s, k)`` turning: True (stick it,
    momentum kept along the rest) when the relative accelerations that pull it back on both corners are positive and
    the rotation it could still reach against the smaller is below ``rest_tol`` times its slenderness. Returns
    ``(stick, rates of the stuck pattern (theta2', psi'))``."""
    e2, e1 = fields(s if j == 1 else 0.0, k if j == 0 else 0.0, sp, th2, psi)
    q2, q1 = project(sp, e2, e1, V)
    ag_ = ag
    rest = math.inf
    for sg in (1.0, -1.0):
        if j == 1:
            pdd, _ = bp_acc(s, sg, sp, th2, 0.0, q2, 0.0, ag_)
            rest = min(rest, -sg * pdd)
        else:
            _, tdd = bp_acc(sg, k, sp, 0.0, psi, 0.0, q1, ag_)
            rest = min(rest, -sg * tdd)
    rate = V[5] - V[2] if j == 1 else V[2]
    alpha = sp[S_A1REST] if j == 1 else sp[S_AAREST]
    stick = rest > 0.0 and rate * rate < 2.0 * rest * sp[S_REST] * alpha
    return stick, q2, q1


@kernel
def _stack_rests(sp, V, ag):
    """The rest rule of the whole stack, both angles at 0 after an impact: nothing could lift it from rest under
    ``ag`` (each interface's restoring moment ``M_j`` at rest positive: ``g b1 - |ag| h1`` for the body,
    ``(1 + m2)(g b2 - |ag| y_c)`` for the assembly, per unit body mass) and the kinetic energy is below
    ``rest_tol min_j alpha_j M_j``. For one block this is the single block's rule exactly (``J theta'^2/2 <
    rest_tol alpha m (g b - |a| h)`` is ``theta'^2/(2 p^2 cos(alpha)(tan(alpha) - |a|/g)) < rest_tol alpha``); it
    ends the cascades where each impact of the body kicks the plinth off its face by a little (the note)."""
    g = sp[S_G]
    b1, h1, b2, h2, m2 = sp[S_B1], sp[S_H1], sp[S_B2], sp[S_H2], sp[S_M2]
    yc = (m2 * h2 + 2.0 * h2 + h1) / (1.0 + m2)
    a = abs(ag)
    M1 = g * b1 - a * h1
    M0 = (1.0 + m2) * (g * b2 - a * yc)
    if M1 <= 0.0 or M0 <= 0.0:
        return False
    return 0.5 * _dot(sp, V, V) < sp[S_REST] * min(sp[S_A1REST] * M1, sp[S_AAREST] * M0)


@kernel
def _after_impact(j, s, k, sp, prm, prm_asm, th2, psi, V, rs, W, out, xo, t, ag):
    """The pattern after an impact at ``j`` from ``(s, k)`` (generic: any pattern may follow), and the rest rule
    (the single block's, with the body's or the assembly's parameters, when one body rocks after the impact)."""
    s1, k1, V1, margin, jump, db, dj, plastic = choose_after_impact(s, k, j, sp, th2, psi, V)
    if margin < -1e-9:
        xo[X_N_INCONS] += 1.0
    if plastic:
        xo[X_N_PLASTIC] += 1.0
    if jump:
        xo[X_N_JUMP] += 1.0
    xo[X_FRI_B] = max(xo[X_FRI_B], db)
    xo[X_FRI_J] = max(xo[X_FRI_J], dj)
    if s1 != 0.0 and th2 == 0.0:
        _plinth_lifts(xo, t)
    if k1 != 0.0 and k == 0.0 and out[O_UPLIFTED] == 0.0:
        _count_uplift(out, t)
    psid = V1[5] - V1[2]
    thd2 = V1[2]
    if th2 == 0.0 and psi == 0.0 and (s1 != 0.0 or k1 != 0.0) and _stack_rests(sp, V1, ag):
        _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        xo[X_PL_N_RESTS] += 1.0
        return
    if (j == 0 and s1 != 0.0) or (j == 1 and k1 != 0.0):
        if j == 1 and s1 == 0.0:  # the body alone rocks on the still plinth: its own rule
            if comes_to_rest(prm, ag, psid, prm[P_THR], prm[P_ALPHA]):
                _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
                out[O_N_RESTS] += 1.0
                return
        elif j == 0 and k1 == 0.0:  # the assembly rocks as one block
            if comes_to_rest(prm_asm, ag, thd2, prm_asm[P_THR], prm_asm[P_ALPHA]):
                _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
                xo[X_PL_N_RESTS] += 1.0
                return
        else:
            stick, q2, q1 = _rest_check(j, s1, k1, sp, th2, psi, V1, ag)
            if stick:
                if j == 0:
                    _set_pattern(rs, W, xo, 0.0, k1, psi, q1, 0.0, 0.0)
                    xo[X_PL_N_RESTS] += 1.0
                else:
                    _set_pattern(rs, W, xo, s1, 0.0, 0.0, 0.0, th2, q2)
                    out[O_N_RESTS] += 1.0
                return
    _set_pattern(rs, W, xo, s1, k1, psi, psid, th2, thd2)
