"""What the stack driver (:mod:`rockcli.kernels.stack`) reads along one step: its record ``xo`` (the ``X_*``
layout) and the patterns ``PAT_*``; the watched face of B and P (the base's corner forces in B: the plinth lifts when
one reaches 0; the joint's in P: the body lifts off the plinth), located on the step's dense output by sampling 16
sub-intervals and bisection (:func:`_face_opens`); an impact ahead; the peaks of a BP step; and the friction demand.

The friction demand is read where the contact forces are: in B and P at the samples of the face check, in BP at 17
points of every step and the vertex of the parabola through the largest (:func:`_bp_demand`), at rest ``|ag|/g``
(its largest on the interval, :func:`_max_abs_ag`). Two edges (docs/plinth.md, "Friction"):

* **A jump of the ground acceleration** (a one-cosine pulse starts at ``a_p``; a record whose first sample is not 0).
  At a jump the state does not move and the contact forces jump with ``ag``: the demand is the limit of the same
  excitation ramped in over a time that tends to 0, along which the stack passes through the forces of every ``ag``
  between the two sides at zero state (angles and rates 0). At rest it carries ``ag`` only up to its lower uplift
  threshold ``thr = g min(tan alpha1, tan alpha_asm)``: a jump out of rest (the stack at rest before it, past the
  threshold after it) is read ``thr/g`` at rest, not ``|ag|/g``, and the stack then moves in pattern B or P, whose
  forces at zero state are affine in ``ag``: each ratio ``|T|/N`` is monotone on every interval where ``N > 0``,
  so its largest over ``[thr, |ag|]`` is at an end: at ``thr`` it is the rest's, at the other end it is read by
  :func:`_jump_demand`: at the ``ag`` after the jump, or where the watched face stops holding before it (a corner
  force reaching 0, exactly, the forces being affine), where BP takes over with the same forces, BP's first step
  then reading the ``ag`` after the jump (sample 0 of :func:`_bp_demand`). On bearings ``ag`` does not enter the
  contact forces (the base's absolute acceleration, the bearings' force, does not jump): nothing to do there.
* **A run that topples.** As a block falls its contact unloads and ``|T|/N`` grows without bound: the demand of
  the fall says nothing (the topple is the answer). The demand is therefore also read where both blocks are
  inside their slenderness, ``|psi| <= alpha1`` (the body on the plinth) and ``|theta2| <= alpha_asm`` (the plinth
  carrying the body) (``X_FR_B_IN``, ``X_FR_J_IN``; at rest and at a jump out of rest always), and a run that
  topples reports that reading, as the single block reads its own while ``|theta| <= alpha`` only
  (:mod:`rockcli.solve.friction`). A run that survives reports every reading (a block past its slenderness that
  the shaking brought back was still carried by its contact). The impulsive demands are read at the impacts as
  before.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.dopri import _dense
from rockcli.kernels.ground import _pulse_turns, ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (E_T0, E_TP, O_T_EXCEED, O_T_THETA_MAX, P_ALPHA, P_G, P_P2, RS_T, RS_THMAX,
                                    SEG_LINEAR, W_Y, W_YNEW)
from rockcli.kernels.polynomials import _first_down, _golden_max, _poly
from rockcli.kernels.stack_physics import S_A1REST, S_AAREST, bp_acc, forces, forces_b, forces_p

PAT_R, PAT_B, PAT_P, PAT_BP = 0.0, 1.0, 2.0, 3.0

# the stack's own record and outputs ``xo``
X_PAT, X_S, X_K = 0, 1, 2  # the pattern, the base corner, the joint corner (0: a face)
X_PL_MAX, X_PL_T_MAX, X_PL_T_EXCEED = 3, 4, 5  # the plinth's peak |theta2|, when, first |theta2| >= alpha_asm
X_PL_T_UPLIFT, X_PL_N_IMP, X_PL_N_IMP_ALL = 6, 7, 8  # the plinth's first uplift, impacts while the ground moves, all
X_TILT_MAX = 9  # the body's peak absolute tilt |theta1|
X_TOPPLED = 10  # -1 none, 0 the plinth, 1 the body
X_FR_B, X_FR_J, X_FRI_B, X_FRI_J = 11, 12, 13, 14  # friction demand |T|/N: base, joint; at impacts: base, joint
X_N_JUMP, X_N_INCONS = 15, 16  # steps or impacts where a pivot would pull; impacts with no consistent pattern
X_N_SWITCH, X_STEPS_BP, X_P2S = 17, 18, 19  # pattern changes, steps of pattern BP, 1 when P2S ended the run
X_PL_N_RESTS = 20
X_N_PLASTIC = 21  # impacts where a given restitution could not be carried: the plastic law instead
X_FR_B_IN, X_FR_J_IN = 22, 23  # the friction demand read while both blocks are inside their slenderness (notes)
N_XO = 24

HALF_PI = 0.5 * math.pi
N_DEMAND = 16  # sub-intervals of a BP step at which the friction demand is read (as the faces of B and P are watched)


# ---------------------------------------------------------------------------------------------
# Friction demand and contact checks along a step
# ---------------------------------------------------------------------------------------------
@kernel
def _max_abs_ag(seg, epar, t0, t1):
    """The largest ``|ag|`` on ``[t0, t1]`` inside one segment (linear: its ends; a pulse: its ends and turns)."""
    a = max(abs(ground_at(t0, seg, epar)), abs(ground_at(t1, seg, epar)))
    if int(seg[0]) != SEG_LINEAR:
        turns = _pulse_turns(int(seg[0]))
        for i in range(4):
            tk = epar[E_T0] + turns[i] * epar[E_TP]
            if t0 < tk < t1:
                a = max(a, abs(ground_at(tk, seg, epar)))
    return a


@kernel(inline='always')
def _demand(xo, NB, TB, NJ, TJ, inside):
    """Note the demand ``|T|/N`` of both interfaces (where ``N > 0``); ``inside``: both blocks inside their
    slenderness there (the reading that counts for a run that topples, module notes)."""
    if NB > 0.0:
        xo[X_FR_B] = max(xo[X_FR_B], abs(TB) / NB)
        if inside:
            xo[X_FR_B_IN] = max(xo[X_FR_B_IN], abs(TB) / NB)
    if NJ > 0.0:
        xo[X_FR_J] = max(xo[X_FR_J], abs(TJ) / NJ)
        if inside:
            xo[X_FR_J_IN] = max(xo[X_FR_J_IN], abs(TJ) / NJ)


@kernel(inline='always')
def _rest_demand(xo, a):
    """At rest both interfaces carry the ground acceleration: the demand ``a = |ag|/g`` at both (inside)."""
    for i in (X_FR_B, X_FR_J, X_FR_B_IN, X_FR_J_IN):
        xo[i] = max(xo[i], a)


@kernel(inline='always')
def _zero_state(pat, s, k, sp, prm, ag):
    """The forces ``(NB, TB, NJ, TJ, PR, PL)`` of pattern B or P at zero state (angle and rate 0) under ``ag``
    (``PR``, ``PL``: the watched face's corners); affine in ``ag``."""
    A = prm[P_ALPHA] * (k if pat == PAT_B else s)
    add = -prm[P_P2] * (math.sin(A) + ag / prm[P_G] * math.cos(A))  # Eq (3) with the pattern's p, alpha
    if pat == PAT_B:
        NB, TB, PR, PL, NJ, TJ = forces_b(k, sp, 0.0, 0.0, add, ag)
    else:
        NB, TB, NJ, TJ, PR, PL = forces_p(s, sp, 0.0, 0.0, add, ag)
    return NB, TB, NJ, TJ, PR, PL


@kernel
def _jump_demand(pat, s, k, sp, prm, a_thr, a1, xo):
    """The demand of a jump out of rest (module notes, "A jump of the ground acceleration"): the stack has just
    entered pattern B or P at zero state, the ground acceleration past its threshold ``a_thr`` (signed) at ``a1``.
    Along ``a`` from ``a_thr`` to ``a1`` the forces are affine in ``a``: the demand is read where the watched face
    stops holding (a corner force reaching 0, found exactly; BP starts there with the same forces and its first
    step reads ``a1``), else at ``a1``."""
    NB, TB, NJ, TJ, PR0, PL0 = _zero_state(pat, s, k, sp, prm, a_thr)
    if min(PR0, PL0) <= 0.0:  # the face does not hold even at the threshold: the rest reading is all
        return
    NB, TB, NJ, TJ, PR1, PL1 = _zero_state(pat, s, k, sp, prm, a1)
    f = 1.0
    if PR1 <= 0.0:
        f = min(f, PR0 / (PR0 - PR1))
    if PL1 <= 0.0:
        f = min(f, PL0 / (PL0 - PL1))
    if f < 1.0:
        NB, TB, NJ, TJ, _, _ = _zero_state(pat, s, k, sp, prm, a_thr + f * (a1 - a_thr))
    _demand(xo, NB, TB, NJ, TJ, True)


@kernel(inline='always')
def _bp_forces(s, k, sp, q0, q1, q2, q3, sig, tt, seg, epar):
    """Normal and tangential forces ``(NB, TB, NJ, TJ)`` of pattern BP at the base and at the joint at fraction
    ``sig`` of the last step (``q0..q3`` its quartics of ``psi, psi', theta2, theta2'``, ``tt`` the time there)."""
    psi = _poly(q0, sig)
    psid = _poly(q1, sig)
    th2 = _poly(q2, sig)
    thd2 = _poly(q3, sig)
    ag = ground_at(tt, seg, epar)
    pdd, tdd = bp_acc(s, k, sp, th2, psi, thd2, psid, ag)
    NB, TB, _, _, NJ, TJ, _, _ = forces(s, k, sp, th2, psi, thd2, psid, tdd, pdd, ag)
    return NB, TB, NJ, TJ


@kernel(inline='always')
def _ratio(T, N):
    """The friction demand ``|T|/N``, or -1 where the normal force ``N`` is not positive."""
    return abs(T) / N if N > 0.0 else -1.0


@kernel(inline='always')
def _vertex(left, best, right, i):
    """Where the parabola through ``(i - 1, left), (i, best), (i + 1, right)`` peaks (in sample units), or -1 when
    the largest sample ``best`` is not interior or a neighbour has no demand (a normal force not positive)."""
    curv = left - 2.0 * best + right
    if left < 0.0 or right < 0.0 or not curv < 0.0:
        return -1.0
    return i + 0.5 * (left - right) / curv


@kernel(inline='always')
def _inside_bp(sp, q0, q2, sg):
    """Both blocks inside their slenderness at fraction ``sg`` of a BP step: ``|psi| <= alpha1`` (the body on the
    plinth), ``|theta2| <= alpha_asm`` (the plinth carrying the body)."""
    return abs(_poly(q0, sg)) <= sp[S_A1REST] and abs(_poly(q2, sg)) <= sp[S_AAREST]


@kernel
def _bp_demand(s, k, sp, W, hs, sig_end, t, seg, epar, xo):
    """The peak friction demand of the last BP step over ``[0, sig_end]`` (its dense output), at both interfaces:
    read at ``N_DEMAND + 1`` equally spaced fractions (both ends included), then at the vertex of the parabola
    through each interface's largest sample and the two beside it (the peak of a smooth demand between samples;
    the larger reading is kept, so the refinement never lowers the sampled peak); the readings where both blocks
    are inside their slenderness also go to ``X_FR_*_IN`` (module notes). Returns True when a pivot pulls (a normal
    force below 0) at the middle or the end of the step (samples ``N_DEMAND/2`` and ``N_DEMAND``)."""
    q0 = _dense(W, hs, np.int64(0), 1.0)
    q1 = _dense(W, hs, np.int64(1), 1.0)
    q2 = _dense(W, hs, np.int64(2), 1.0)
    q3 = _dense(W, hs, np.int64(3), 1.0)
    bb = bj = lb = lj = rb = rj = pb = pj = -1.0  # largest samples, their neighbours, the previous samples
    ib = ij = -2
    bb_in = bj_in = -1.0  # the largest readings with both blocks inside their slenderness
    pull = False
    for m in range(N_DEMAND + 1):
        sg = sig_end * m / N_DEMAND
        NB, TB, NJ, TJ = _bp_forces(s, k, sp, q0, q1, q2, q3, sg, t + sg * hs, seg, epar)
        db = _ratio(TB, NB)
        dj = _ratio(TJ, NJ)
        if _inside_bp(sp, q0, q2, sg):
            bb_in = max(bb_in, db)
            bj_in = max(bj_in, dj)
        if (m == N_DEMAND // 2 or m == N_DEMAND) and (NB < 0.0 or NJ < 0.0):
            pull = True
        if db > bb:
            bb, ib, lb, rb = db, m, pb, -1.0
        elif m == ib + 1:
            rb = db
        if dj > bj:
            bj, ij, lj, rj = dj, m, pj, -1.0
        elif m == ij + 1:
            rj = dj
        pb, pj = db, dj
    vb = _vertex(lb, bb, rb, ib)
    vj = _vertex(lj, bj, rj, ij)
    for v, which in ((vb, 0), (vj, 1)):
        if v >= 0.0:
            sg = sig_end * v / N_DEMAND
            NB, TB, NJ, TJ = _bp_forces(s, k, sp, q0, q1, q2, q3, sg, t + sg * hs, seg, epar)
            inside = _inside_bp(sp, q0, q2, sg)
            if which == 0:
                bb = max(bb, _ratio(TB, NB))
                if inside:
                    bb_in = max(bb_in, _ratio(TB, NB))
            else:
                bj = max(bj, _ratio(TJ, NJ))
                if inside:
                    bj_in = max(bj_in, _ratio(TJ, NJ))
    xo[X_FR_B] = max(xo[X_FR_B], bb)
    xo[X_FR_J] = max(xo[X_FR_J], bj)
    xo[X_FR_B_IN] = max(xo[X_FR_B_IN], bb_in)
    xo[X_FR_J_IN] = max(xo[X_FR_J_IN], bj_in)
    return pull


@kernel(inline='always')
def _one_forces(pat, s, k, sp, prm, c0, c1, sig, tt, seg, epar, xo):
    """B or P at fraction ``sig`` of the step (``c0``, ``c1`` its quartics of the angle and rate): the smaller corner
    force of the watched face (the base in B, the joint in P), the corner that keeps pressing, whether the pivot
    pulls; the friction demand is noted while the face holds (past its opening the pattern is not the motion)."""
    a = _poly(c0, sig)
    ad = _poly(c1, sig)
    ag = ground_at(tt, seg, epar)
    A = prm[P_ALPHA] * (k if pat == PAT_B else s) - a
    add = -prm[P_P2] * (math.sin(A) + ag / prm[P_G] * math.cos(A))  # Eq (3) with the pattern's p, alpha
    if pat == PAT_B:
        NB, TB, PR, PL, NJ, TJ = forces_b(k, sp, a, ad, add, ag)
        pull = NJ < 0.0
    else:
        NB, TB, NJ, TJ, PR, PL = forces_p(s, sp, a, ad, add, ag)
        pull = NB < 0.0
    f = min(PR, PL)
    if f > 0.0:
        _demand(xo, NB, TB, NJ, TJ, abs(a) <= prm[P_ALPHA])
    return f, (1.0 if PR > PL else -1.0), pull


@kernel
def _face_opens(pat, s, k, sp, prm, W, hs, t, seg, epar, xo, sig_lim):
    """First fraction in ``(0, sig_lim]`` of the last step of B or P at which the watched face's smaller corner
    force reaches 0 (16 samples, then bisection): ``(sigma, corner that keeps pressing)``, else ``(-1, 0)``. The
    friction demand is read at the samples."""
    c0 = _dense(W, hs, np.int64(0), 1.0)
    c1 = _dense(W, hs, np.int64(1), 1.0)
    jump = False
    for m in range(1, 17):
        sg = sig_lim * m / 16.0
        f, side, pull = _one_forces(pat, s, k, sp, prm, c0, c1, sg, t + sg * hs, seg, epar, xo)
        jump = jump or pull
        if f <= 0.0:
            lo = sig_lim * (m - 1) / 16.0
            hi = sg
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                fm, sd, _p = _one_forces(pat, s, k, sp, prm, c0, c1, mid, t + mid * hs, seg, epar, xo)
                if fm <= 0.0:
                    hi = mid
                    side = sd
                else:
                    lo = mid
            if jump:
                xo[X_N_JUMP] += 1.0
            return hi, side
    if jump:
        xo[X_N_JUMP] += 1.0
    return -1.0, 0.0


@kernel(inline='always')
def _impact_ahead(W, hs, col, c):
    """Fraction of the last step at which the angle in column ``col`` (corner ``c``) comes back to 0, else 1."""
    e1 = c * W[W_YNEW, col]
    d0 = c * W[W_Y, col + 1]
    d1 = c * W[W_YNEW, col + 1]
    if e1 <= 0.0 or (d0 < 0.0 and d1 > 0.0):
        sg = _first_down(_dense(W, hs, np.int64(col), c), 0.0, 0.0, 1.0)
        if sg >= 0.0:
            return sg
    return 1.0


@kernel
def _abs_max(c, sig_end):
    """The largest ``|poly(c)|`` on ``[0, sig_end]`` (17 samples, golden section about the largest)."""
    m = 0.0
    im = 0
    for i in range(17):
        v = abs(_poly(c, sig_end * i / 16.0))
        if v > m:
            m, im = v, i
    sg = 1.0 if _poly(c, sig_end * im / 16.0) > 0.0 else -1.0
    lo = sig_end * max(im - 1, 0) / 16.0
    hi = sig_end * min(im + 1, 16) / 16.0
    return max(m, abs(_poly(c, _golden_max(c, sg, lo, hi))))


@kernel
def _bp_peaks(rs, out, xo, sp, W, hs, sig_end):
    """Peaks of ``|psi|``, ``|theta2|`` and ``|theta1|`` over ``[0, sig_end]`` of the last BP step, and the first
    time ``|psi|`` reaches alpha1 and ``|theta2|`` alpha_asm."""
    t = rs[RS_T]
    for col in (0, 2):
        c = _dense(W, hs, np.int64(col), 1.0)
        v_end = abs(_poly(c, sig_end))
        best, sbest = v_end, sig_end
        d = _dense(W, hs, np.int64(col + 1), 1.0)
        for sgn in (1.0, -1.0):
            dd = (sgn * d[0], sgn * d[1], sgn * d[2], sgn * d[3], sgn * d[4])
            sp_ = _first_down(dd, 0.0, 0.0, sig_end)
            if sp_ >= 0.0 and abs(_poly(c, sp_)) > best:
                best, sbest = abs(_poly(c, sp_)), sp_
        if col == 0:
            if best > rs[RS_THMAX]:
                rs[RS_THMAX] = best
                out[O_T_THETA_MAX] = t + sbest * hs
            if math.isnan(out[O_T_EXCEED]) and rs[RS_THMAX] >= sp[S_A1REST]:
                out[O_T_EXCEED] = t + sbest * hs
        else:
            if best > xo[X_PL_MAX]:
                xo[X_PL_MAX] = best
                xo[X_PL_T_MAX] = t + sbest * hs
            if math.isnan(xo[X_PL_T_EXCEED]) and xo[X_PL_MAX] >= sp[S_AAREST]:
                xo[X_PL_T_EXCEED] = t + sbest * hs
    a = _dense(W, hs, np.int64(0), 1.0)
    b = _dense(W, hs, np.int64(2), 1.0)
    c1 = (a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3], a[4] + b[4])
    xo[X_TILT_MAX] = max(xo[X_TILT_MAX], _abs_max(c1, sig_end))
