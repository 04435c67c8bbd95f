"""One step of the stack driver on bearings (:mod:`rockcli.kernels.stack_linear`) and what is read along it.

States ``y = (psi, psi', theta2, theta2', u, u')`` in every pattern (the angles of a face stay 0), integrated by
Dormand-Prince 5(4) with its continuous extension (:func:`_dp5`, :func:`_dense`: the coefficients of SciPy's
``RK45``, those of :mod:`rockcli.kernels.dopri`), the error of each state kept below ``rtol max(|y|, scale)``. The
events are looked for on the continuous extension at 16 points and located by bisection (:func:`_first_fall`): a
pivot's angle back to 0 (an impact), at ``pi/2`` (its block topples), the watched face's smaller corner force down
to 0 (:func:`_face_value`; R: the bearing's force reaching the lower uplift threshold; B: the plinth's base; P: the
joint). A lift below the tolerance is recognised (:func:`_unresolved_fall`) and the lift a held face suppresses
bounded (:func:`_held_push`: docs/physics-plinth.md, "A lift below the tolerance"). At rest the bearing's force and
the base's displacement are bounded over a step (:func:`_rest_bounds`, :func:`_rest_bounds_hysteretic`); on a
hysteretic bearing a step ends where ``u`` reverses (:func:`_reversal`). :func:`_scan` reads the peaks, the first
exceedances and the friction demand over a step into the outputs ``z`` (the ``Z_*`` layout).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.bearings import z_sensitivity
from rockcli.kernels.dopri import _A, _C, _E, _P
from rockcli.kernels.ground import ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import FOUNDATION_LINEAR
from rockcli.kernels.polynomials import _first_down, _poly
from rockcli.kernels.stack_linear_physics import (L_AASM, L_RTOL, L_SC, L_THR1, L_THRA, L_WB, L_XI, accel, bearing,
                                                  force, rhs)
from rockcli.kernels.stack_physics import S_A1, S_G, S_M2, forces

# outputs ``z``
Z_STATUS, Z_TOPPLED, Z_T_OVER, Z_PEAK0, Z_PEAK1, Z_TILT, Z_UMAX = 0, 1, 2, 3, 4, 5, 6
Z_TUP0, Z_TUP1, Z_NIMP0, Z_NIMP1, Z_NIMPALL0, Z_NIMPALL1 = 7, 8, 9, 10, 11, 12
Z_FR0, Z_FR1, Z_FRI0, Z_FRI1, Z_JUMPS, Z_INCONS, Z_SETTLED = 13, 14, 15, 16, 17, 18, 19
Z_T_END, Z_STEPS, Z_REJ, Z_NRHS, Z_TEX0, Z_TEX1, Z_NPLASTIC, Z_T_SETTLED, Z_NRESTS = 20, 21, 22, 23, 24, 25, 26, 27, 28
Z_FR0_IN, Z_FR1_IN = 29, 30  # the friction demand read while both blocks are inside their slenderness (notes)
N_Z = 31

HALF_PI = 0.5 * math.pi
# the events of :func:`_value` (2 and above: a face, :func:`_face_kind`, which reads no column) and the pivots' angle
# columns of ``y`` (the body's psi, the plinth's theta2): int64 values, as the codes of rockcli.kernels.layout
V_IMPACT, V_OVERTURN = np.int64(0), np.int64(1)
C_BODY, C_PLINTH = np.int64(0), np.int64(2)


@kernel
def _dp5(s, k, sp, lp, bb, seg, epar, t, h, y, K, ynew):
    """One Dormand-Prince step from ``y`` (``K[0] = f(t, y)`` given) into ``ynew``, ``K[6] = f(t + h, ynew)``:
    the error norm (<= 1: accepted)."""
    yt = np.empty(6)
    for st in range(1, 6):
        for i in range(6):
            acc = 0.0
            for j in range(st):
                acc += _A[st][j] * K[j, i]
            yt[i] = y[i] + h * acc
        rhs(s, k, sp, lp, bb, yt, ground_at(t + _C[st] * h, seg, epar), K[st])
    for i in range(6):
        acc = 0.0
        for j in range(6):
            acc += _A[6][j] * K[j, i]  # the weights of the 5th-order solution
        ynew[i] = y[i] + h * acc
    rhs(s, k, sp, lp, bb, ynew, ground_at(t + h, seg, epar), K[6])
    err = 0.0
    rtol = lp[L_RTOL]
    # on a hysteretic bearing the error of u passes to its Bouc-Wen elements, |dz/du| <= gz: the tolerance of u is
    # rtol / (1/max(|u|, scale) + gz), as for the single block (rockcli.kernels.dopri)
    gz = 0.0 if bb[0] == FOUNDATION_LINEAR else z_sensitivity(bb[0], bb[1], bb[2])
    for i in range(6):
        e = 0.0
        for j in range(7):
            e += _E[j] * K[j, i]
        if i == 4 and gz > 0.0:
            sc = rtol / (1.0 / max(lp[L_SC + i], abs(y[i]), abs(ynew[i])) + gz)
        else:
            sc = rtol * max(lp[L_SC + i], abs(y[i]), abs(ynew[i]))
        err = max(err, abs(h * e) / sc)
    return err


@kernel(inline='always')
def _dense(y, K, h, sig, out):
    s2 = sig * sig
    w = np.empty(7)
    for j in range(7):
        w[j] = _P[j][0] * sig + _P[j][1] * s2 + _P[j][2] * s2 * sig + _P[j][3] * s2 * s2
    for i in range(6):
        acc = 0.0
        for j in range(7):
            acc += w[j] * K[j, i]
        out[i] = y[i] + h * acc


@kernel
def _value(kind, c, sgn, s, k, sp, lp, bb, seg, epar, t, h, y, K, sg, yy):
    """The value whose first fall to 0 is the event, at fraction ``sg`` of the step: ``kind`` 0 an impact of the
    pivot in column ``c`` on corner ``sgn``, 1 its block's overturn, 2 the watched face (:func:`_face_value`; 3 and
    4: at rest with the joint, the base held, :func:`_face_kind`)."""
    _dense(y, K, h, sg, yy)
    if kind == 0:
        return sgn * yy[c]
    if kind == 1:
        return HALF_PI - sgn * yy[c]
    return _face_value(s, k, sp, lp, bb, yy, ground_at(t + sg * h, seg, epar), kind)


@kernel
def _first_fall(kind, c, sgn, s, k, sp, lp, bb, seg, epar, t, h, y, K, sig_lim):
    """First fraction in ``(0, sig_lim]`` of the step where the event value is <= 0 (16 samples, bisection;
    the start counts as above 0), else 2."""
    yy = np.empty(6)
    lo = 0.0
    for m in range(1, 17):
        sg = sig_lim * m / 16.0
        if _value(kind, c, sgn, s, k, sp, lp, bb, seg, epar, t, h, y, K, sg, yy) <= 0.0:
            hi = sg
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if _value(kind, c, sgn, s, k, sp, lp, bb, seg, epar, t, h, y, K, mid, yy) <= 0.0:
                    hi = mid
                else:
                    lo = mid
            return hi
        lo = sg
    return 2.0


@kernel
def _face_value(s, k, sp, lp, bb, yy, ag, kind):
    """R: the lower uplift threshold less the bearing's force (``kind`` 3: the joint held, the plinth's threshold;
    4: the base held, the body's); B: the plinth's smaller base corner force over its load; P: the joint's over the
    body's weight."""
    if s == 0.0 and k == 0.0:
        thr = lp[L_THRA] if kind == 3 else (lp[L_THR1] if kind == 4 else min(lp[L_THR1], lp[L_THRA]))
        return thr - abs(force(lp, bb, yy[4], yy[5]))
    pdd, tdd, ab = accel(s, k, sp, lp, bb, yy, ag)
    f = forces(s, k, sp, yy[2], yy[0], yy[3], yy[1], tdd, pdd, ab)
    if s == 0.0:
        return min(f[2], f[3]) / ((1.0 + sp[S_M2]) * sp[S_G])
    return min(f[6], f[7]) / sp[S_G]


@kernel(inline='always')
def _face_kind(s, k, held):
    """The face the driver watches in pattern ``(s, k)`` with interface ``held`` held shut (-1: none): -1 none, 2 the
    pattern's own (R: the lower threshold), 3 at rest with the joint held (the plinth's threshold), 4 with the base
    held (the body's)."""
    if s != 0.0 and k != 0.0:
        return -1
    if held < 0:
        return 2
    if s == 0.0 and k == 0.0:
        return 3 if held == 1 else 4
    return -1  # P or B: its only face is the held one


@kernel
def _unresolved_fall(c, sgn, lp, y, K, h, sig):
    """The hair-lift test (docs/physics-plinth.md, "A lift below the tolerance"): the pivot in column ``c`` (corner
    ``sgn``) started the step just opened (angle and rate exactly 0), and its angle, back at 0 at fraction ``sig``,
    never rose above its error floor ``rtol scale`` on ``[0, sig]`` (17 samples of the continuous extension), its
    rate there below its own floor: the lift is below what the integration resolves."""
    if y[c] != 0.0 or y[c + 1] != 0.0:
        return False
    eps = lp[L_RTOL] * lp[L_SC + c]
    yy = np.empty(6)
    for m in range(17):
        _dense(y, K, h, sig * m / 16.0, yy)
        if sgn * yy[c] > eps:
            return False
    return abs(yy[c + 1]) <= lp[L_RTOL] * lp[L_SC + c + 1]


@kernel
def _held_push(held, hc, s, k, sp, lp, bb, seg, epar, t, h, y, K):
    """The largest opening acceleration the held interface would have over the step (17 samples): its pivot on
    corner ``hc`` at angle 0 with no rate, the rest of the stack as it is."""
    yy = np.empty(6)
    amax = 0.0
    s1 = hc if held == 0 else s
    k1 = hc if held == 1 else k
    for m in range(17):
        sg = m / 16.0
        _dense(y, K, h, sg, yy)
        pdd, tdd, _ = accel(s1, k1, sp, lp, bb, yy, ground_at(t + sg * h, seg, epar))
        amax = max(amax, hc * (pdd if held == 1 else tdd))
    return amax


@kernel
def _rest_bounds(lp, y, K, h):
    """At rest (pattern R): bounds over the step of ``|F|`` (the bearing's force) and of ``|u|``, from the
    continuous extension's quartics ``sum_m c_m sigma^m`` (``|p(sigma)| <= sum |c_m|`` on ``[0, 1]``)."""
    w = lp[L_WB]
    cf = 2.0 * lp[L_XI] * w
    fb = abs(bearing(lp, y[4], y[5]))
    ub = abs(y[4])
    for m in range(4):
        cu = 0.0
        cv = 0.0
        for j in range(7):
            cu += _P[j][m] * K[j, 4]
            cv += _P[j][m] * K[j, 5]
        fb += h * abs(w * w * cu + cf * cv)
        ub += h * abs(cu)
    return fb, ub


@kernel
def _coeffs(y, K, h, i):
    """The quartic ``sum_m c_m sigma^m`` of state ``i`` over the step (the continuous extension)."""
    c = [y[i], 0.0, 0.0, 0.0, 0.0]
    for m in range(4):
        acc = 0.0
        for j in range(7):
            acc += _P[j][m] * K[j, i]
        c[m + 1] = h * acc
    return (c[0], c[1], c[2], c[3], c[4])


@kernel
def _rest_bounds_hysteretic(lp, bb, y, K, h):
    """:func:`_rest_bounds` on a hysteretic bearing: ``|u(sigma) - u(0)| <= span = sum_m>0 |c_m|``, and on the
    step's branch (the step ends at a reversal of u) ``F`` is a decreasing function of ``u`` alone, so ``|F| <=
    max(|F(u0 - span)|, |F(u0 + span)|)`` over the step (the single block's quick test,
    :func:`rockcli.kernels.events.hysteretic_uplift`)."""
    c = _coeffs(y, K, h, np.int64(4))
    span = abs(c[1]) + abs(c[2]) + abs(c[3]) + abs(c[4])
    fb = max(abs(force(lp, bb, y[4] - span, 0.0)), abs(force(lp, bb, y[4] + span, 0.0)))
    return fb, abs(y[4]) + span


@kernel
def _reversal(y, K, h, d, tol):
    """Did the base keep moving in direction ``d`` through the step (a hysteretic bearing's elements follow ``u``
    exactly only while it moves one way)? ``(code, sigma)``, as the single block's
    :func:`rockcli.kernels.events.reversal_check`: 1 ``d u'`` falls to 0 at ``sigma`` after the base moved forward by
    more than ``tol`` (the step is cut there); 2 the base moved back by more than ``tol`` before moving forward (a
    start at ``u' = 0`` whose direction was guessed wrong: retake the step on the other branch); else 0."""
    cv = _coeffs(y, K, h, np.int64(5))
    cu = _coeffs(y, K, h, np.int64(4))
    cv = (d * cv[0], d * cv[1], d * cv[2], d * cv[3], d * cv[4])
    cu = (d * cu[0], d * cu[1], d * cu[2], d * cu[3], d * cu[4])
    sr = _first_down(cv, 0.0, 0.0, 1.0)
    if sr >= 0.0 and _poly(cu, sr) - cu[0] > tol:
        return 1, sr
    for m in range(1, 17):
        D = _poly(cu, m / 16.0) - cu[0]
        if D < -tol:
            return 2, 0.0
        if D > tol:
            break
    return 0, 1.0


@kernel(inline='always')
def _may_cross(c, a0, r0, a1, r1, kind):
    """Whether a pivot's angle (corner ``c``, from ``a0``, rate ``r0`` to ``a1``, ``r1`` over the step) may reach
    0 (``kind`` 0) or pi/2 (1) inside the step: its end is there, or the angle turned inside it (a minimum, or a
    maximum above 1 rad), or the pivot has just started from 0 (a fresh uplift that may fall straight back)."""
    if kind == 0:
        return c * a1 <= 0.0 or (c * r0 < 0.0 and c * r1 > 0.0) or a0 == 0.0
    return c * a1 >= HALF_PI or (c * r0 > 0.0 and c * r1 < 0.0 and max(c * a0, c * a1) > 1.0)


@kernel
def _scan(s, k, sp, lp, bb, seg, epar, t, h, y, K, sig_end, z):
    """Peaks, first exceedances and the friction demand over ``[0, sig_end]`` of the step (17 samples, the
    largest of each peak refined by golden section; the demand also where both blocks are inside their
    slenderness, ``Z_FR*_IN``: the reading of a run that topples); counts a step where a pivot's normal force is
    below 0."""
    yy = np.empty(6)
    best = np.zeros(4)
    arg = np.zeros(4, dtype=np.int64)
    jump = False
    for m in range(17):
        sg = sig_end * m / 16.0
        _dense(y, K, h, sg, yy)
        vals = (abs(yy[2]), abs(yy[0]), abs(yy[0] + yy[2]), abs(yy[4]))
        for q in range(4):
            if vals[q] > best[q]:
                best[q] = vals[q]
                arg[q] = m
        if s == 0.0 and k == 0.0:  # at rest: both interfaces carry the weight and |a_b| of it sideways
            fr = abs(force(lp, bb, yy[4], yy[5])) / sp[S_G]
            for i in (Z_FR0, Z_FR1, Z_FR0_IN, Z_FR1_IN):
                z[i] = max(z[i], fr)
            continue
        ag = ground_at(t + sg * h, seg, epar)
        pdd, tdd, ab = accel(s, k, sp, lp, bb, yy, ag)
        f = forces(s, k, sp, yy[2], yy[0], yy[3], yy[1], tdd, pdd, ab)
        inside = abs(yy[0]) <= sp[S_A1] and abs(yy[2]) <= lp[L_AASM]  # both blocks inside their slenderness
        if f[0] > 0.0 and (s != 0.0 or min(f[2], f[3]) > 0.0):
            z[Z_FR0] = max(z[Z_FR0], abs(f[1]) / f[0])
            if inside:
                z[Z_FR0_IN] = max(z[Z_FR0_IN], abs(f[1]) / f[0])
        if f[4] > 0.0 and (k != 0.0 or min(f[6], f[7]) > 0.0):
            z[Z_FR1] = max(z[Z_FR1], abs(f[5]) / f[4])
            if inside:
                z[Z_FR1_IN] = max(z[Z_FR1_IN], abs(f[5]) / f[4])
        if (s != 0.0 and f[0] < 0.0) or (k != 0.0 and f[4] < 0.0):
            jump = True
        if math.isnan(z[Z_TEX0]) and abs(yy[2]) >= lp[L_AASM]:
            z[Z_TEX0] = t + sg * h
        if math.isnan(z[Z_TEX1]) and abs(yy[0]) >= sp[S_A1]:
            z[Z_TEX1] = t + sg * h
    cols = (2, 0, -1, 4)
    record = (z[Z_PEAK0], z[Z_PEAK1], z[Z_TILT], z[Z_UMAX])
    for q in range(4):
        m = arg[q]
        if best[q] == 0.0 or best[q] < 0.9 * record[q]:
            # a sampled maximum below 0.9 of the peak so far cannot raise it (between samples 1/16 of a step apart,
            # a smooth maximum exceeds the samples by (w dt)^2/8 relatively: below 2e-3 with the steps' caps)
            continue
        a = sig_end * max(m - 1, 0) / 16.0
        b = sig_end * min(m + 1, 16) / 16.0
        gr = 0.5 * (math.sqrt(5.0) - 1.0)
        for _ in range(40):
            x1 = b - gr * (b - a)
            x2 = a + gr * (b - a)
            _dense(y, K, h, x1, yy)
            f1 = abs(yy[0] + yy[2]) if cols[q] < 0 else abs(yy[cols[q]])
            _dense(y, K, h, x2, yy)
            f2 = abs(yy[0] + yy[2]) if cols[q] < 0 else abs(yy[cols[q]])
            best[q] = max(best[q], f1, f2)
            if f1 > f2:
                b = x2
            else:
                a = x1
    z[Z_PEAK0] = max(z[Z_PEAK0], best[0])
    z[Z_PEAK1] = max(z[Z_PEAK1], best[1])
    z[Z_TILT] = max(z[Z_TILT], best[2])
    z[Z_UMAX] = max(z[Z_UMAX], best[3])
    if jump:
        z[Z_JUMPS] += 1.0
