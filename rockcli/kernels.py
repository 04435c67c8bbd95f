"""Compiled kernels (numba): right-hand sides, the impact map and the event-driven integrator.

This is the only module that imports numba. All kernels that call each other live here, and
every constant is passed as an argument (numba's cache freezes globals).

The integrator
--------------
Dormand-Prince 5(4) with local extrapolation, PI-free classic step control and the quartic
dense output of Dormand & Prince / Shampine (the one SciPy's ``RK45`` uses). The time axis is cut
into *segments* on which the ground acceleration is smooth: for a record, each sample interval
(the record is piecewise linear between samples); for an analytic pulse, the pulse's support;
after the excitation, a zero-acceleration tail. A step never crosses a segment boundary, so the
error estimate always sees a smooth right-hand side.

Phases and states (``y = [theta, theta_dot, u, u_dot]``):

* *stuck*: the block moves with its base (theta = theta_dot = 0). On a rigid foundation nothing
  is integrated: the ground acceleration is scanned for the uplift condition. On an isolated base
  only the base states ``y[2:4]`` are integrated, block and base moving together.
* *rocking* about the corner ``s`` (+1 right, -1 left): ``y[0:2]`` on a rigid foundation,
  ``y[0:4]`` on an isolated base.

Events are located by root finding on the dense-output polynomial of the step (not on the step
grid): uplift (absolute base acceleration crossing ``-s g tan(alpha)``), impact (theta crossing 0),
the first ``|theta| = alpha``, overturning (``|theta| = pi/2``), and the extrema of theta and u for
the peaks.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

# ---------------------------------------------------------------------------------------------
# Codes shared with rockcli.solve
# ---------------------------------------------------------------------------------------------
FOUNDATION_RIGID = 0
FOUNDATION_LINEAR = 1

EXC_RECORD = 0
EXC_RICKER_SYM = 1
EXC_RICKER_ANTI = 2
EXC_SINE = 3
EXC_COSINE = 4

# layout of the parameter vector ``prm``
P_P2, P_G, P_ALPHA, P_R, P_GAMMA, P_W, P_XI, P_THR = 0, 1, 2, 3, 4, 5, 6, 7
P_SINA, P_COSA, P_H, P_ETA, P_DU, P_REST, P_RTOL = 8, 9, 10, 11, 12, 13, 14
P_SC0 = 15  # 4 state scales follow: theta, theta_dot, u, u_dot
N_PRM = 19

# layout of the excitation vector ``epar`` (pulses)
E_AP, E_TP, E_T0, E_TS, E_TE, E_BETA = 0, 1, 2, 3, 4, 5

# layout of the output vector
O_STATUS, O_UPLIFTED, O_T_UPLIFT, O_T_OVERTURN, O_THETA_MAX, O_T_THETA_MAX = 0, 1, 2, 3, 4, 5
O_T_EXCEED, O_N_IMPACTS, O_U_MAX, O_STEPS, O_REJECTED, O_NRHS, O_T_END = 6, 7, 8, 9, 10, 11, 12
O_N_RESTS, O_N_UPLIFTS, O_N_IMPACTS_ALL, O_SETTLED, O_THETA_END, O_U_END = 13, 14, 15, 16, 17, 18
O_PEAK_FINAL, O_T_SETTLED = 19, 20
N_OUT = 21

STATUS_DONE = 0
STATUS_OVERTURNED = 1
STATUS_MAX_STEPS = -1

# history columns
H_T, H_AG, H_TH, H_THD, H_U, H_UD = 0, 1, 2, 3, 4, 5
N_HIST = 6

# segment modes (how the RHS evaluates the ground acceleration)
SEG_LINEAR = 0  # ag = a0 + slope (t - ts); zero tails are linear with a0 = slope = 0

PHASE_STUCK = 0
PHASE_ROCKING = 1

# Dormand-Prince 5(4) tableau and its quartic dense output (Dormand & Prince 1980; Shampine 1986,
# the coefficients SciPy's RK45 uses). Module-level tuples: mathematical constants of the method,
# which numba compiles in as literals (they never change, so freezing them in the cache is safe).
_C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0)
_A = (
    (0.0, 0.0, 0.0, 0.0, 0.0),
    (1 / 5, 0.0, 0.0, 0.0, 0.0),
    (3 / 40, 9 / 40, 0.0, 0.0, 0.0),
    (44 / 45, -56 / 15, 32 / 9, 0.0, 0.0),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
)
_B = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84)
_E = (-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40)
_P = (
    (1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432),
    (0.0, 0.0, 0.0, 0.0),
    (0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799),
    (0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072),
    (0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632),
    (0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844),
    (0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423),
)

# rows of the work array W used by a step
W_Y = 7  # state at the start of the step
W_YNEW = 8  # state at the end of the step
W_TMP = 9  # stage state
N_W = 10


# ---------------------------------------------------------------------------------------------
# Ground motion
# ---------------------------------------------------------------------------------------------
@njit(cache=True, inline='always')
def pulse_acc(mode, epar, t):
    """Acceleration of an analytic pulse at time ``t`` [m/s^2] (zero outside its support)."""
    if t < epar[E_TS] or t > epar[E_TE]:
        return 0.0
    ap = epar[E_AP]
    tp = epar[E_TP]
    tau = t - epar[E_T0]
    if mode == EXC_RICKER_SYM:
        r = (math.pi * tau / tp) ** 2
        return ap * (1.0 - 2.0 * r) * math.exp(-r)
    if mode == EXC_RICKER_ANTI:
        x = 2.0 * math.pi * tau / (math.sqrt(3.0) * tp)
        return ap / epar[E_BETA] * (x * x - 3.0) * x * math.exp(-0.5 * x * x)
    if mode == EXC_SINE:
        return ap * math.sin(2.0 * math.pi * tau / tp)
    if mode == EXC_COSINE:
        return ap * math.cos(2.0 * math.pi * tau / tp)
    return 0.0


@njit(cache=True, inline='always')
def _ground(t, seg, epar):
    """Ground acceleration inside the current segment, ``seg = (mode, a0, slope, ts)``."""
    mode = int(seg[0])
    if mode == SEG_LINEAR:
        return seg[1] + seg[2] * (t - seg[3])
    return pulse_acc(mode, epar, t)


# ---------------------------------------------------------------------------------------------
# Right-hand sides (scalars in, scalars out: no array references in the hot path)
# ---------------------------------------------------------------------------------------------
@njit(cache=True, inline='always')
def _base_force(fkind, prm, u, ud):
    """Bearing force per unit total mass, ``-(k_b u + c_b u_dot)/(m + m_b)`` [m/s^2]."""
    w = prm[P_W]
    return -w * w * u - 2.0 * prm[P_XI] * w * ud


@njit(cache=True, inline='always')
def _rhs(fkind, phase, s, prm, seg, epar, t, th, thd, u, ud):
    """Derivatives ``(theta_dot, theta_ddot, u_dot, u_ddot)`` of the scene's states at ``t``.

    Rigid foundation, Eq (3): ``theta_ddot = -p^2 (sin A + ag/g cos A)``, ``A = s alpha - theta``.
    Isolated base, stuck: block and base move together, ``u_ddot = F - ag``. Isolated base,
    rocking: Eqs (10)-(11) with the corrected denominator (reading notes 1-2), written through the
    absolute base acceleration
    ``a = (F - gamma R thd^2 sin A + gamma R p^2 sin A cos A)/(1 - gamma R p^2 cos^2 A / g)``,
    ``theta_ddot = -p^2 (sin A + a/g cos A)``, ``u_ddot = a - ag``.
    """
    ag = _ground(t, seg, epar)
    if fkind == FOUNDATION_RIGID:
        A = s * prm[P_ALPHA] - th
        return thd, -prm[P_P2] * (math.sin(A) + ag / prm[P_G] * math.cos(A)), 0.0, 0.0
    F = _base_force(fkind, prm, u, ud)
    if phase == PHASE_STUCK:
        return 0.0, 0.0, ud, F - ag
    A = s * prm[P_ALPHA] - th
    sA = math.sin(A)
    cA = math.cos(A)
    gR = prm[P_GAMMA] * prm[P_R]
    a = (F - gR * thd * thd * sA + gR * prm[P_P2] * sA * cA) / (1.0 - gR * prm[P_P2] * cA * cA / prm[P_G])
    return thd, -prm[P_P2] * (sA + a / prm[P_G] * cA), ud, a - ag


@njit(cache=True, inline='always')
def _rhs_into(fkind, phase, s, prm, seg, epar, t, W, src, dst):
    d0, d1, d2, d3 = _rhs(fkind, phase, s, prm, seg, epar, t, W[src, 0], W[src, 1], W[src, 2], W[src, 3])
    W[dst, 0] = d0
    W[dst, 1] = d1
    W[dst, 2] = d2
    W[dst, 3] = d3


# ---------------------------------------------------------------------------------------------
# Dormand-Prince step and dense output
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _dp5_step(fkind, phase, s, prm, seg, epar, t, h, W, i0, i1):
    """One Dormand-Prince step of the active states ``i0:i1`` from ``(t, W[W_Y])``.

    Expects ``W[0] = f(t, y)``; fills the stage derivatives ``W[1:7]`` (``W[6] = f(t + h, ynew)``,
    first-same-as-last) and ``W[W_YNEW]``. Returns the RMS of the local error over the active
    states, each scaled by ``rtol * max(|y|, |ynew|, scale)`` (accept the step when <= 1).
    """
    for i in range(4):
        W[W_TMP, i] = W[W_Y, i]
    for st in range(1, 6):
        for i in range(i0, i1):
            acc = 0.0
            for j in range(st):
                acc += _A[st][j] * W[j, i]
            W[W_TMP, i] = W[W_Y, i] + h * acc
        _rhs_into(fkind, phase, s, prm, seg, epar, t + _C[st] * h, W, W_TMP, st)
    for i in range(4):
        W[W_YNEW, i] = W[W_Y, i]
    for i in range(i0, i1):
        acc = 0.0
        for j in range(6):
            acc += _B[j] * W[j, i]
        W[W_YNEW, i] = W[W_Y, i] + h * acc
    _rhs_into(fkind, phase, s, prm, seg, epar, t + h, W, W_YNEW, 6)
    rtol = prm[P_RTOL]
    tot = 0.0
    for i in range(i0, i1):
        err = 0.0
        for j in range(7):
            err += _E[j] * W[j, i]
        sc = max(abs(W[W_Y, i]), abs(W[W_YNEW, i]), prm[P_SC0 + i]) * rtol
        tot += (h * err / sc) ** 2
    return math.sqrt(tot / (i1 - i0))


@njit(cache=True)
def _dense(W, h, i, sign):
    """``sign *`` state ``i`` over the last step as a quartic in sigma = (t - t_step)/h: 5 coefficients."""
    c1 = 0.0
    c2 = 0.0
    c3 = 0.0
    c4 = 0.0
    for j in range(7):
        k = W[j, i]
        c1 += k * _P[j][0]
        c2 += k * _P[j][1]
        c3 += k * _P[j][2]
        c4 += k * _P[j][3]
    return (sign * W[W_Y, i], sign * h * c1, sign * h * c2, sign * h * c3, sign * h * c4)


@njit(cache=True, inline='always')
def _poly(c, x):
    return c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * c[4])))


@njit(cache=True)
def _refine_root(c, level, lo, hi, flo):
    """Root of ``poly(c) - level`` in [lo, hi] given a sign change (Illinois regula falsi)."""
    fhi = _poly(c, hi) - level
    side = 0
    for _ in range(100):
        if hi - lo <= 1e-15:
            break
        x = (lo * fhi - hi * flo) / (fhi - flo)
        if not (lo < x < hi):
            x = 0.5 * (lo + hi)
        fx = _poly(c, x) - level
        if fx == 0.0:
            return x
        if (fx > 0.0) == (flo > 0.0):
            lo = x
            flo = fx
            if side == -1:
                fhi *= 0.5
            side = -1
        else:
            hi = x
            fhi = fx
            if side == 1:
                flo *= 0.5
            side = 1
    return hi


@njit(cache=True)
def _first_down(c, level, lo, hi):
    """First sigma in (lo, hi] where ``poly(c) - level`` falls from > 0 to <= 0, else -1.

    The quartic is sampled on 16 sub-intervals to bracket the first crossing, then refined by
    regula falsi. A start exactly on the level (theta = 0 right after an impact or an uplift) is
    not a crossing: the function must have been positive first. Returns -1 if it never was.
    """
    seen_pos = (_poly(c, lo) - level) > 0.0
    xprev = lo
    fprev = _poly(c, lo) - level
    for k in range(1, 17):
        x = lo + (hi - lo) * k / 16.0
        fx = _poly(c, x) - level
        if fx <= 0.0:
            if seen_pos and fprev > 0.0:
                return _refine_root(c, level, xprev, x, fprev)
        else:
            seen_pos = True
        xprev = x
        fprev = fx
    return -1.0


@njit(cache=True)
def _golden_max(c, sgn, lo, hi):
    """Location of the largest ``sgn * poly(c)`` on [lo, hi] (golden section; unimodal there)."""
    for _ in range(60):
        x1 = hi - 0.6180339887498949 * (hi - lo)
        x2 = lo + 0.6180339887498949 * (hi - lo)
        if sgn * _poly(c, x1) > sgn * _poly(c, x2):
            hi = x2
        else:
            lo = x1
    return 0.5 * (lo + hi)


@njit(cache=True)
def _first_exceed(c, thr):
    """First sigma in [0, 1] where ``|poly(c)|`` exceeds ``thr``: ``(sigma, sign of poly)``, else ``(-1, 0)``.

    The quartic is sampled at 17 points. A maximum of ``|poly|`` lies within 1/16 of a sample, so
    it exceeds that sample by at most ``max|poly''| / 512`` with ``max|poly''| <= 2|c2| + 6|c3| +
    12|c4|`` on [0, 1]: every sampled local maximum of ``|poly|`` (ends included) within that margin
    of ``thr`` is refined by golden section before it is dismissed, so no excursion above ``thr``
    between samples is missed. The crossing itself is refined by regula falsi.
    """
    margin = (2.0 * abs(c[2]) + 6.0 * abs(c[3]) + 12.0 * abs(c[4])) / 512.0
    f_prev = abs(_poly(c, 0.0))
    if f_prev > thr:
        return 0.0, (1.0 if _poly(c, 0.0) > 0.0 else -1.0)
    f_cur = abs(_poly(c, 1.0 / 16.0))
    for k in range(1, 17):
        x = k / 16.0
        if f_cur > thr:
            sg = 1.0 if _poly(c, x) > 0.0 else -1.0
            lo = (k - 1) / 16.0
            cs = (sg * c[0], sg * c[1], sg * c[2], sg * c[3], sg * c[4])
            return _refine_root(cs, thr, lo, x, sg * _poly(c, lo) - thr), sg
        f_next = abs(_poly(c, (k + 1) / 16.0)) if k < 16 else -1.0
        lo = (k - 1) / 16.0
        hi = min(1.0, (k + 1) / 16.0)
        # a sampled local maximum (an end counts: its outer neighbour is treated as lower)
        cand = f_cur >= f_prev and f_cur >= f_next and f_cur > thr - margin
        if k == 1 and f_prev >= f_cur and f_prev > thr - margin:
            cand = True
            hi = x
        if cand:
            sg = 1.0 if _poly(c, x) > 0.0 else -1.0
            if k == 1 and f_prev >= f_cur:
                sg = 1.0 if _poly(c, 0.0) > 0.0 else -1.0
            xm = _golden_max(c, sg, lo, hi)
            if sg * _poly(c, xm) > thr:
                cs = (sg * c[0], sg * c[1], sg * c[2], sg * c[3], sg * c[4])
                return _refine_root(cs, thr, lo, xm, sg * _poly(c, lo) - thr), sg
        f_prev = f_cur
        f_cur = f_next
    return -1.0, 0.0


@njit(cache=True)
def _state_at(W, h, sig, nst):
    """Dense-output state at fraction ``sig`` of the last step, written into ``W[W_TMP]``."""
    for i in range(nst):
        W[W_TMP, i] = _poly(_dense(W, h, i, 1.0), sig)


# ---------------------------------------------------------------------------------------------
# Excitation segments and the rigid-foundation uplift scan
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _pulse_segment(j, ekind, epar, t_begin):
    """Segment ``j`` of a pulse: 0 = [t_begin, ts] zero, 1 = the support [ts, te], 2 = zero tail."""
    if j == 0:
        return (float(SEG_LINEAR), 0.0, 0.0, t_begin), epar[E_TS]
    if j == 1:
        return (float(ekind), 0.0, 0.0, epar[E_TS]), epar[E_TE]
    return (float(SEG_LINEAR), 0.0, 0.0, epar[E_TE]), np.inf


@njit(cache=True)
def _rigid_uplift(seg, epar, thr, t, t_end):
    """First time in [t, t_end] at which |ag| exceeds ``thr`` (rigid foundation, stuck phase).

    Returns ``(t_uplift, s)`` with ``s = -sign(ag)`` (the corner the block pivots on), or
    ``(-1, 0)`` when the block stays stuck through ``t_end``. Linear segments are exact; pulse
    segments are scanned on a grid of T_p/512 with every sampled local maximum of |ag| near the
    threshold refined by golden-section search, then the crossing refined by bisection.
    """
    a0 = _ground(t, seg, epar)
    if abs(a0) > thr:
        return t, -1.0 if a0 > 0 else 1.0
    if int(seg[0]) == SEG_LINEAR:
        if seg[2] == 0.0:
            return -1.0, 0.0
        a1 = _ground(t_end, seg, epar)
        if a1 > thr:
            return t + (thr - a0) / (a1 - a0) * (t_end - t), -1.0
        if a1 < -thr:
            return t + (-thr - a0) / (a1 - a0) * (t_end - t), 1.0
        return -1.0, 0.0
    hg = epar[E_TP] / 512.0
    npts = max(1, int(math.ceil((t_end - t) / hg)))
    hg = (t_end - t) / npts
    # A maximum of |ag| lies within hg of a sample, so it exceeds that sample by at most
    # max|ag''| hg^2 / 2, and max|ag''| <= 1.5 |a_p| omega_p^2 for every pulse shape (sine and cosine:
    # 1; symmetric Ricker: 6/4; antisymmetric Ricker: 5.8/(3 beta) = 1.4). Every sampled local
    # maximum within that margin (or within 5% of the threshold) is refined.
    wp = 2.0 * math.pi / epar[E_TP]
    margin = max(0.05 * thr, 1.5 * abs(epar[E_AP]) * wp * wp * hg * hg)
    fm2 = abs(a0) - thr
    fm1 = fm2
    for k in range(1, npts + 1):
        tk = t + k * hg
        fk = abs(_ground(tk, seg, epar)) - thr
        found = False
        lo = tk - hg
        hi = tk
        if fk > 0.0:
            found = True
        elif k >= 2 and fm1 >= fm2 and fm1 >= fk and fm1 > -margin:
            # a sampled local maximum of |ag| close to the threshold: look between the samples
            xa = tk - 2.0 * hg
            xb = tk
            for _ in range(60):
                x1 = xb - 0.6180339887498949 * (xb - xa)
                x2 = xa + 0.6180339887498949 * (xb - xa)
                if abs(_ground(x1, seg, epar)) > abs(_ground(x2, seg, epar)):
                    xb = x2
                else:
                    xa = x1
            xm = 0.5 * (xa + xb)
            if abs(_ground(xm, seg, epar)) > thr:
                found = True
                lo = tk - 2.0 * hg
                hi = xm
        if found:
            sgn = 1.0 if _ground(hi, seg, epar) > 0.0 else -1.0
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if sgn * _ground(mid, seg, epar) > thr:
                    hi = mid
                else:
                    lo = mid
            return hi, -sgn
        fm2 = fm1
        fm1 = fk
    return -1.0, 0.0


# ---------------------------------------------------------------------------------------------
# Small helpers
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _hist_push(H, n, t, ag, W, row):
    if n >= H.shape[0]:
        H2 = np.empty((2 * H.shape[0], N_HIST))
        H2[:n] = H[:n]
        H = H2
    H[n, H_T] = t
    H[n, H_AG] = ag
    H[n, H_TH] = W[row, 0]
    H[n, H_THD] = W[row, 1]
    H[n, H_U] = W[row, 2]
    H[n, H_UD] = W[row, 3]
    return H, n + 1


@njit(cache=True)
def _u_extremum(W, hs, sig_end):
    """|u| at an extremum of u inside [0, sig_end] of the last step (u_dot changes sign), else -1."""
    c = _dense(W, hs, 3, 1.0 if W[W_Y, 3] > 0.0 else -1.0)
    sx = _first_down(c, 0.0, 0.0, sig_end)
    if sx < 0.0:
        return -1.0
    return abs(_poly(_dense(W, hs, 2, 1.0), sx))


@njit(cache=True)
def _count_uplift(out, t):
    out[O_N_UPLIFTS] += 1
    if out[O_UPLIFTED] == 0.0:
        out[O_UPLIFTED] = 1.0
        out[O_T_UPLIFT] = t


@njit(cache=True)
def _impulse_left(ekind, jtab, epar, dt, t):
    """An upper bound of ``int_t^{t_exc_end} |ag| dtau`` [m/s], the ground's remaining "impulse".

    ``jtab`` holds exact suffix integrals of ``|ag|``: for a record, from each sample to the end
    (of the unscaled samples; ``epar[E_AP]`` is the scale); for a pulse, of the unit pulse
    (``a_p = 1``, ``T_p = 1``) from each of ``n`` equally spaced points of its support. The value
    at the grid point at or before ``t`` bounds the integral from ``t``.
    """
    n = jtab.shape[0]
    if ekind == EXC_RECORD:
        x = t / dt - 1e-9
        j = 0 if x <= 0.0 else int(x)
        if j >= n:
            return 0.0
        return abs(epar[E_AP]) * jtab[j]
    ts = epar[E_TS]
    te = epar[E_TE]
    if t >= te:
        return 0.0
    x = (t - ts) / (te - ts) * (n - 1) - 1e-9
    k = 0 if x <= 0.0 else int(x)
    if k > n - 1:
        k = n - 1
    return abs(epar[E_AP]) * epar[E_TP] * jtab[k]


# ---------------------------------------------------------------------------------------------
# The simulation kernel
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def simulate_core(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                  want_history, early, out):
    """Integrate one scene. Fills ``out`` (see the ``O_*`` layout) and returns the history.

    End of the run (one rule for every mode)
    ----------------------------------------
    The run ends when the verdict is *proven* (or at overturning). Each proof below is a small
    theorem; the code checks exactly its assumptions. A history run goes on after the proof until
    exactly ``t_exc_end + tail`` to show the free motion; nothing after a proof can change the
    verdict, ``theta_max`` or ``n_impacts``, and nothing before it depends on the mode or on
    ``tail`` (the same steps are taken). A run that reaches
    ``t_exc_end + horizon`` unproven ends there with ``O_SETTLED = 0`` (e.g. an undamped base that
    keeps lifting the block): reported, never silently called safe.

    P1 (rigid foundation, ground still, block stuck). With ``ag = 0`` and theta = 0 the uplift
       condition ``|ag| > g tan(alpha)`` can never hold again.
    P2 (rigid foundation, ground still, rocking, ``|theta| < alpha``). Between impacts
       ``E = theta_dot^2/2 + p^2 cos(alpha - |theta|)`` is conserved (Eq 3 with ``ag = 0``); an impact
       keeps theta = 0 and multiplies theta_dot by ``|eta| <= 1``, so E never grows; a rest sets
       ``E = p^2 cos(alpha)``. The potential ``p^2 cos(alpha - |theta|)`` is largest, ``p^2``, at
       ``|theta| = alpha``. Hence if ``E < p^2`` while ``|theta| < alpha`` the block never reaches
       alpha, so never pi/2, and each later peak ``alpha - acos(E/p^2)`` is at most the next one,
       which is added to ``theta_max`` (so the peak is final too). If the block is heading for the
       pivot (``theta theta_dot < 0``) with ``|theta| < alpha``, the potential falls all the way to
       theta = 0, so the impact is certain and ``E`` after it, ``p^2 cos(alpha) + eta^2 (E - p^2
       cos(alpha))``, may be used. Past alpha (``|theta| >= alpha``) no such conclusion holds: the
       same energy means the block falls away from the barrier (issue 9), and the run goes on.
    P3 (isolated base, ground still, block stuck). The block moves with its base, a free damped
       oscillator ``u'' + 2 xi w u' + w^2 u = 0`` (any gamma < 1: the block rides on the base) whose
       energy ``(u'^2 + w^2 u^2)/2`` never grows for any ``xi >= 0``. The absolute base acceleration
       ``|a| = |w^2 u + 2 xi w u'| <= w sqrt(1 + 4 xi^2) sqrt(u'^2 + w^2 u^2)`` (Cauchy-Schwarz), so
       once this bound is below ``g tan(alpha)`` the block can never be lifted again.
       The peak base displacement is final only once ``sqrt(u'^2 + w^2 u^2)/w``, which bounds
       every later ``|u|``, is below it, or one base period later: the run follows the free base
       until then (2 states, a few steps).
    P4 (rigid foundation, ``early`` only, during the excitation, after the first uplift, block
       stuck or ``|theta| < alpha``). ``dE/dt = -p^2 (ag/g) cos(A) theta_dot`` and, while
       ``|theta| <= alpha``, ``theta_dot^2/2 <= E - p^2 cos(alpha) = X^2``, so
       ``dX/dt <= p^2 |ag| / (sqrt(2) g)`` (impacts and rests only lower X). Hence
       ``X(t') <= X(t) + p^2/(sqrt(2) g) int_t^t' |ag|``. If that bound with the whole remaining
       impulse (:func:`_impulse_left`) is below ``p sqrt(1 - cos(alpha))`` (``E < p^2``), the block
       cannot reach alpha before the ground stops (a first arrival at alpha needs ``E >= p^2``),
       and P2 holds from then on: it survives. ``theta_max`` is then only the peak so far
       (``O_PEAK_FINAL = 0``).
    P5 (rigid foundation, ``early`` only, after the first uplift, ``|theta| >= alpha``). Beyond
       alpha the potential is at least ``p^2 sin(alpha)`` (its value at pi/2), so with
       ``Z^2 = E - p^2 sin(alpha)`` the same argument gives ``Z(t') <= Z(t) + p^2/(sqrt(2) g)
       int_t^t' |ag|``. Coming back inside needs ``|theta| = alpha`` again, so ``E >= p^2``,
       ``Z >= p sqrt(1 - sin(alpha))``; if the bound with the whole remaining impulse stays below
       that, the block can never come back, and once the ground is still it falls (between alpha
       and pi/2 the potential falls outward; below the barrier a block moving inward turns back).
       With the ground already still, a block beyond alpha moving outward falls as well. The run
       ends as overturned with ``t_overturn`` unknown (NaN).

    Parameters
    ----------
    fkind : int
        Foundation kind (``FOUNDATION_*``).
    prm : tuple of N_PRM floats
        Block, foundation and tolerance constants (``P_*`` layout).
    ekind : int
        Excitation kind (``EXC_*``): ``acc`` [m/s^2] and ``dt`` [s] for a record (scaled by
        ``epar[E_AP]``), ``epar`` (tuple of 8 floats, ``E_*`` layout) for a pulse.
    t_begin, t_exc_end : float
        Start of the integration and end of the excitation [s].
    acc, jtab : float64 arrays
        The record's samples and the suffix integrals of ``|ag|`` (:func:`_impulse_left`).
    tail : float
        Free motion shown by a history run after the excitation [s] (see "End of the run").
    horizon : float
        Longest free motion followed after the excitation to prove the verdict [s].
    max_steps : int
        Hard cap on accepted + rejected steps (status ``STATUS_MAX_STEPS`` when reached).
    want_history : bool
        Store the state at every step end and event.
    early : bool
        Also stop during the excitation once survival is proven (P4); ``theta_max`` is then not
        final. Verdict-only sweeps use it; never together with ``want_history``.
    out : float64[N_OUT]
        Filled with the results.

    Returns
    -------
    H : float64[n, N_HIST]
        History rows ``t, ag, theta, theta_dot, u, u_dot`` (empty when not wanted).
    """
    isolated = fkind != FOUNDATION_RIGID
    nst = 4 if isolated else 2
    thr = prm[P_THR]
    alpha = prm[P_ALPHA]
    halfpi = 0.5 * math.pi
    p2 = prm[P_P2]
    w = prm[P_W]
    xi = prm[P_XI]
    bound_fac = w * math.sqrt(1.0 + 4.0 * xi * xi)  # P3: |a| <= w sqrt(1 + 4 xi^2) sqrt(u'^2 + w^2 u^2)
    cos_a = prm[P_COSA]
    c_imp = p2 / (math.sqrt(2.0) * prm[P_G])  # P4: dX/dt <= c_imp |ag|
    x_bar = math.sqrt(p2 * (1.0 - cos_a))  # P4: E < p^2  <=>  X < x_bar
    sin_a = prm[P_SINA]
    z_bar = math.sqrt(p2 * (1.0 - sin_a))  # P5: E < p^2  <=>  Z < z_bar
    peak_final = True

    W = np.zeros((N_W, 4))
    for k in range(N_OUT):
        out[k] = 0.0
    out[O_T_UPLIFT] = np.nan
    out[O_T_OVERTURN] = np.nan
    out[O_T_EXCEED] = np.nan
    out[O_T_THETA_MAX] = np.nan

    nrec = acc.shape[0]
    if want_history:
        H = np.empty((2 * nrec + 1024 if ekind == EXC_RECORD else 4096, N_HIST))
    else:
        H = np.empty((0, N_HIST))
    nh = 0

    t = t_begin
    t_show_end = t_exc_end + tail
    t_horizon = t_exc_end + max(horizon, tail)
    phase = PHASE_STUCK
    s = 0.0
    h = 0.0  # step-size proposal (0: choose one)
    steps = 0
    rejected = 0
    nrhs = 0
    status = STATUS_DONE
    settled = False
    fresh = True  # W[0] = f(t, y) must be (re)computed
    u_max = 0.0
    th_max = 0.0

    j = 0
    rscale = epar[E_AP]  # records: the factor the record is scaled by
    if ekind == EXC_RECORD:
        seg = (float(SEG_LINEAR), rscale * acc[0], rscale * (acc[1] - acc[0]) / dt, 0.0)
        seg_end = dt
    else:
        seg, seg_end = _pulse_segment(0, ekind, epar, t_begin)
    if want_history:
        H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)

    while True:
        # ----- move to the segment that contains t
        while t >= seg_end:
            j += 1
            if ekind == EXC_RECORD:
                if j < nrec - 1:
                    seg = (float(SEG_LINEAR), rscale * acc[j], rscale * (acc[j + 1] - acc[j]) / dt, j * dt)
                    seg_end = (j + 1) * dt
                    # a record is continuous across samples: the FSAL derivative stays valid
                else:
                    seg = (float(SEG_LINEAR), 0.0, 0.0, (nrec - 1) * dt)
                    seg_end = np.inf
                    fresh = True
            else:
                seg, seg_end = _pulse_segment(j, ekind, epar, t_begin)
                fresh = True
        t_stop = min(seg_end, t_horizon)
        if settled and t < t_show_end:
            t_stop = min(t_stop, t_show_end)  # a history run shows the free motion up to exactly here

        # ----- end of the run: is the verdict proven? (P1-P4 in the docstring)
        if not settled:
            if t >= t_exc_end:
                if phase == PHASE_STUCK:
                    if not isolated:
                        settled = True  # P1
                    elif bound_fac * math.sqrt(W[W_Y, 3] ** 2 + w * w * W[W_Y, 2] ** 2) < thr:
                        settled = True  # P3
                elif not isolated and abs(W[W_Y, 0]) < alpha:
                    th = W[W_Y, 0]
                    thd = W[W_Y, 1]
                    En = 0.5 * thd * thd + p2 * math.cos(alpha - abs(th))
                    if th * thd < 0.0:  # heading for the pivot: the impact is certain
                        c_a = p2 * cos_a
                        En = c_a + prm[P_ETA] ** 2 * (En - c_a)
                    if En < p2:  # P2
                        pk = alpha - math.acos(En / p2)
                        if pk > th_max:
                            th_max = pk
                            out[O_T_THETA_MAX] = np.nan
                        settled = True
            if not settled and early and not isolated and out[O_UPLIFTED] != 0.0:
                imp = c_imp * _impulse_left(ekind, jtab, epar, dt, t)
                if phase == PHASE_STUCK:
                    if imp < x_bar:
                        settled = True  # P4
                        peak_final = False
                else:
                    ath = abs(W[W_Y, 0])
                    En = 0.5 * W[W_Y, 1] ** 2 + p2 * math.cos(alpha - ath)
                    if ath < alpha:
                        if math.sqrt(max(0.0, En - p2 * cos_a)) + imp < x_bar:
                            settled = True  # P4
                            peak_final = False
                    elif (math.sqrt(max(0.0, En - p2 * sin_a)) + imp < z_bar
                          or (imp == 0.0 and s * W[W_Y, 1] >= 0.0)):
                        # P5: it falls; the time it lands is not computed
                        status = STATUS_OVERTURNED
                        th_max = halfpi
                        peak_final = False
                        out[O_T_SETTLED] = t
                        break
            if settled:
                out[O_T_SETTLED] = t
        if settled and (not want_history or t >= t_show_end):
            # P3 settles the verdict; the peak base displacement is final once the free base's
            # energy bound sqrt(u'^2 + w^2 u^2)/w cannot exceed it (or, undamped, after one more
            # period, in which the base reaches its amplitude)
            if not (isolated and phase == PHASE_STUCK
                    and math.sqrt(W[W_Y, 3] ** 2 + w * w * W[W_Y, 2] ** 2) > w * u_max * (1.0 + 1e-9)
                    and t < out[O_T_SETTLED] + 2.0 * math.pi / w and t < t_horizon):
                break
        if t >= t_horizon:
            break
        if steps + rejected >= max_steps:
            status = STATUS_MAX_STEPS
            break

        # ----- stuck on a rigid foundation: scan the ground motion, integrate nothing
        if phase == PHASE_STUCK and not isolated:
            tu, su = _rigid_uplift(seg, epar, thr, t, t_stop)
            if tu < 0.0:
                t = t_stop
            else:
                t = tu
                s = su
                phase = PHASE_ROCKING
                _count_uplift(out, t)
                fresh = True
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)
            continue

        # ----- stuck on an isolated base: already beyond the uplift threshold?
        i0 = 0
        if phase == PHASE_STUCK:
            a_now = _base_force(fkind, prm, W[W_Y, 2], W[W_Y, 3])
            if abs(a_now) > thr:
                s = -1.0 if a_now > 0.0 else 1.0
                phase = PHASE_ROCKING
                _count_uplift(out, t)
                fresh = True
                continue
            i0 = 2

        # ----- one Dormand-Prince step inside [t, t_stop]
        if h <= 0.0:
            h = 0.02 / math.sqrt(p2)
            if ekind != EXC_RECORD:
                h = min(h, epar[E_TP] / 50.0)
        if fresh:
            _rhs_into(fkind, phase, s, prm, seg, epar, t, W, W_Y, 0)
            nrhs += 1
            fresh = False
            if phase == PHASE_ROCKING and W[W_Y, 0] == 0.0:
                # just after an impact: the first step must not swallow a short flight that the
                # angular acceleration turns back (flight ~ 2 thd / |thdd|)
                vel = s * W[W_Y, 1]
                back = -s * W[0, 1]
                if vel > 0.0 and back > 0.0:
                    h = min(h, 0.5 * vel / back)
        last = False
        hs = h
        err = 2.0
        while steps + rejected < max_steps:
            hs = h
            last = hs >= t_stop - t
            if last:
                hs = t_stop - t
            err = _dp5_step(fkind, phase, s, prm, seg, epar, t, hs, W, i0, nst)
            nrhs += 6
            if err <= 1.0:
                fac = 5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)
                if not last or fac < 1.0:
                    h = hs * fac
                break
            rejected += 1
            h = hs * max(0.2, 0.9 * err ** -0.2)
        if err > 1.0:
            status = STATUS_MAX_STEPS
            break
        steps += 1
        t_new = t_stop if last else t + hs

        # ----- stuck on an isolated base: uplift when |a| crosses g tan(alpha)
        if phase == PHASE_STUCK:
            # a(sigma) is linear in the states, so a quartic in sigma like them; every step is
            # checked (no pre-filter on the step ends)
            cu = _dense(W, hs, 2, 1.0)
            cv = _dense(W, hs, 3, 1.0)
            ca = (-w * w * cu[0] - 2.0 * xi * w * cv[0], -w * w * cu[1] - 2.0 * xi * w * cv[1],
                  -w * w * cu[2] - 2.0 * xi * w * cv[2], -w * w * cu[3] - 2.0 * xi * w * cv[3],
                  -w * w * cu[4] - 2.0 * xi * w * cv[4])
            sig, sa = _first_exceed(ca, thr)
            su = -sa  # the block pivots on the corner s = -sign(a)
            if (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
                u_max = max(u_max, _u_extremum(W, hs, 1.0 if sig < 0.0 else sig))
            if sig >= 0.0:
                _state_at(W, hs, sig, 4)
                W[W_Y, 2] = W[W_TMP, 2]
                W[W_Y, 3] = W[W_TMP, 3]
                t = t + sig * hs
                s = su
                phase = PHASE_ROCKING
                _count_uplift(out, t)
                fresh = True
            else:
                t = t_new
                for i in range(2, 4):
                    W[W_Y, i] = W[W_YNEW, i]
                    W[0, i] = W[6, i]
            u_max = max(u_max, abs(W[W_Y, 2]))
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)
            continue

        # ----- rocking: impact (s theta falls to 0), peak, alpha, overturning (s theta = pi/2)
        sth1 = s * W[W_YNEW, 0]
        sd0 = s * W[W_Y, 1]
        sd1 = s * W[W_YNEW, 1]
        sig_end = 1.0
        impact = False
        failed = False
        if sth1 <= 0.0 or (sd0 < 0.0 and sd1 > 0.0):
            sig = _first_down(_dense(W, hs, 0, s), 0.0, 0.0, 1.0)
            if sig >= 0.0:
                impact = True
                sig_end = sig
            elif sth1 <= 0.0:
                failed = True  # never rose above theta = 0: the uplift did not take
        if not failed:
            if sd0 >= 0.0 and (sd1 <= 0.0 or impact):  # sd0 = 0 right after an uplift
                sp = _first_down(_dense(W, hs, 1, s), 0.0, 0.0, sig_end)
                if sp >= 0.0:
                    thp = _poly(_dense(W, hs, 0, s), sp)
                    if thp > th_max:
                        th_max = thp
                        out[O_T_THETA_MAX] = t + sp * hs
            if not impact and sth1 > th_max:
                th_max = sth1
                out[O_T_THETA_MAX] = t_new
            if math.isnan(out[O_T_EXCEED]) and th_max >= alpha:
                sa = _first_down(_dense(W, hs, 0, -s), -alpha, 0.0, sig_end)
                out[O_T_EXCEED] = t + (sa if sa >= 0.0 else sig_end) * hs
            if not impact and sth1 >= halfpi:
                so = _first_down(_dense(W, hs, 0, -s), -halfpi, 0.0, 1.0)
                if so < 0.0:
                    so = 1.0
                if isolated and (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
                    u_max = max(u_max, _u_extremum(W, hs, so))
                _state_at(W, hs, so, nst)
                for i in range(nst):
                    W[W_Y, i] = W[W_TMP, i]
                u_max = max(u_max, abs(W[W_Y, 2]))
                t = t + so * hs
                th_max = halfpi
                out[O_T_THETA_MAX] = t
                out[O_T_OVERTURN] = t
                status = STATUS_OVERTURNED
                if want_history:
                    H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)
                break
        if isolated and (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
            u_max = max(u_max, _u_extremum(W, hs, sig_end))

        if failed:
            # the block never left theta = 0: back to the stuck phase at the end of the step,
            # keeping the total horizontal momentum (u_dot + gamma h theta_dot per unit mass); the
            # uplift still counts (the uplift condition held; the rotation is below resolution)
            t = t_new
            if isolated:
                W[W_Y, 2] = W[W_YNEW, 2]
                W[W_Y, 3] = W[W_YNEW, 3] + prm[P_GAMMA] * prm[P_H] * W[W_YNEW, 1]
            W[W_Y, 0] = 0.0
            W[W_Y, 1] = 0.0
            phase = PHASE_STUCK
            s = 0.0
            fresh = True
            u_max = max(u_max, abs(W[W_Y, 2]))
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)
            continue

        if impact:
            _state_at(W, hs, sig_end, nst)
            for i in range(nst):
                W[W_Y, i] = W[W_TMP, i]
            t = t + sig_end * hs
            W[W_Y, 0] = 0.0
            thd1 = W[W_Y, 1]
            if want_history:  # the state just before the impact, then (below) just after
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)
            out[O_N_IMPACTS_ALL] += 1
            if t <= t_exc_end:
                out[O_N_IMPACTS] += 1
            # impact map (Eqs 14-19 with gamma = m/(m+m_b)): keeps the horizontal momentum of
            # block + base and the block's angular momentum about the new pivot
            thd2 = prm[P_ETA] * thd1
            if isolated:
                W[W_Y, 3] += prm[P_DU] * thd1
            s = -s
            # rest: the block could not lift off under the current base acceleration a, and the
            # rotation it could still reach against the restoring p^2 cos(alpha) (tan(alpha) - |a|/g),
            # thd^2 / (2 p^2 cos(alpha) (tan(alpha) - |a|/g)), is below rest_tol * alpha (a plastic
            # impact ends the train of impacts, momentum kept). With a = 0 this is the free-rocking
            # reach thd^2 / (2 p^2 sin(alpha)).
            if isolated:
                a_rest = _base_force(fkind, prm, W[W_Y, 2], W[W_Y, 3] + prm[P_GAMMA] * prm[P_H] * thd2)
            else:
                a_rest = _ground(t, seg, epar)
            c_rest = p2 * cos_a * (thr - abs(a_rest)) / prm[P_G]
            if c_rest > 0.0 and thd2 * thd2 < 2.0 * c_rest * prm[P_REST] * alpha:
                if isolated:
                    W[W_Y, 3] += prm[P_GAMMA] * prm[P_H] * thd2
                W[W_Y, 1] = 0.0
                phase = PHASE_STUCK
                s = 0.0
                out[O_N_RESTS] += 1
            else:
                W[W_Y, 1] = thd2
            u_max = max(u_max, abs(W[W_Y, 2]))
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)
            fresh = True
            continue

        # accepted step without events
        t = t_new
        for i in range(nst):
            W[W_Y, i] = W[W_YNEW, i]
            W[0, i] = W[6, i]
        if isolated:
            u_max = max(u_max, abs(W[W_Y, 2]))
        if want_history:
            H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), W, W_Y)

    out[O_STATUS] = status
    out[O_THETA_MAX] = th_max
    out[O_U_MAX] = u_max
    out[O_STEPS] = steps
    out[O_REJECTED] = rejected
    out[O_NRHS] = nrhs
    out[O_T_END] = t
    out[O_SETTLED] = 1.0 if (settled or status == STATUS_OVERTURNED) else 0.0
    out[O_PEAK_FINAL] = 1.0 if peak_final else 0.0
    out[O_THETA_END] = W[W_Y, 0]
    out[O_U_END] = W[W_Y, 2]
    return H[:nh]


@njit(cache=True, parallel=True)
def simulate_batch(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins, t_exc_ends,
                   tails, horizon, max_steps, early, outs):
    """Verdict-only runs of many scenes in parallel (one scene per ``prange`` iteration).

    Row ``i`` of each argument describes scene ``i``; records are slices
    ``acc_all[acc_off[i]:acc_off[i] + acc_len[i]]`` (scenes may share one; ``jtab_all`` is laid out
    alike). Results go to
    ``outs[i]`` (``O_*`` layout); nothing else is stored.
    """
    for i in prange(fkinds.shape[0]):
        q = prms[i]
        prm = (q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], q[10], q[11], q[12], q[13],
               q[14], q[15], q[16], q[17], q[18])
        e = epars[i]
        epar = (e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7])
        acc = acc_all[acc_off[i]:acc_off[i] + acc_len[i]]
        jtab = jtab_all[acc_off[i]:acc_off[i] + acc_len[i]]
        simulate_core(fkinds[i], prm, ekinds[i], epar, acc, jtab, dts[i], t_begins[i], t_exc_ends[i], tails[i],
                      horizon, max_steps, False, early, outs[i])
