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
from numba import njit

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
N_OUT = 19

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

# Dormand-Prince 5(4) tableau and dense output (Dormand & Prince 1980; Shampine 1986)
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
_A = np.array([
    [0.0, 0.0, 0.0, 0.0, 0.0],
    [1 / 5, 0.0, 0.0, 0.0, 0.0],
    [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
    [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
])
_B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
_E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
_P = np.array([
    [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
    [0.0, 0.0, 0.0, 0.0],
    [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
    [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
    [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
    [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
    [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
])


def tableau():
    """The Dormand-Prince arrays ``(C, A, B, E, P)``, passed to the kernel as arguments."""
    return _C, _A, _B, _E, _P


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
    """Ground acceleration inside the current segment. ``seg = [mode, a0, slope, ts]``."""
    mode = int(seg[0])
    if mode == SEG_LINEAR:
        return seg[1] + seg[2] * (t - seg[3])
    return pulse_acc(mode, epar, t)


# ---------------------------------------------------------------------------------------------
# Right-hand sides
# ---------------------------------------------------------------------------------------------
@njit(cache=True, inline='always')
def _base_force(fkind, prm, y):
    """Bearing force per unit total mass, ``-(k_b u + c_b u_dot)/(m + m_b)`` [m/s^2]."""
    w = prm[P_W]
    return -w * w * y[2] - 2.0 * prm[P_XI] * w * y[3]


@njit(cache=True, inline='always')
def _abs_base_acc(fkind, phase, s, prm, y):
    """Absolute acceleration of the base ``a = ug_ddot + u_ddot`` for an isolated base [m/s^2].

    Stuck: block and base move together, ``a = F``. Rocking: Eq (10) with the corrected
    denominator, ``a = (F - gamma R thd^2 sin A + gamma R p^2 sin A cos A)/(1 - gamma R p^2 cos^2 A / g)``.
    """
    F = _base_force(fkind, prm, y)
    if phase == PHASE_STUCK:
        return F
    A = s * prm[P_ALPHA] - y[0]
    sA = math.sin(A)
    cA = math.cos(A)
    gR = prm[P_GAMMA] * prm[P_R]
    return (F - gR * y[1] * y[1] * sA + gR * prm[P_P2] * sA * cA) / (1.0 - gR * prm[P_P2] * cA * cA / prm[P_G])


@njit(cache=True, inline='always')
def _rhs(fkind, phase, s, prm, seg, epar, t, y, dy, row):
    """Time derivatives of the active states. Returns the ground acceleration at ``t``."""
    ag = _ground(t, seg, epar)
    if fkind == FOUNDATION_RIGID:
        # Eq (3): theta_dd = -p^2 (sin A + ag/g cos A), A = s alpha - theta
        A = s * prm[P_ALPHA] - y[0]
        dy[row, 0] = y[1]
        dy[row, 1] = -prm[P_P2] * (math.sin(A) + ag / prm[P_G] * math.cos(A))
        return ag
    if phase == PHASE_STUCK:
        dy[row, 2] = y[3]
        dy[row, 3] = _base_force(fkind, prm, y) - ag
        return ag
    # rocking on an isolated base: Eqs (10)-(11) with notes 1-2 of the reading notes
    A = s * prm[P_ALPHA] - y[0]
    sA = math.sin(A)
    cA = math.cos(A)
    gR = prm[P_GAMMA] * prm[P_R]
    F = _base_force(fkind, prm, y)
    a = (F - gR * y[1] * y[1] * sA + gR * prm[P_P2] * sA * cA) / (1.0 - gR * prm[P_P2] * cA * cA / prm[P_G])
    dy[row, 0] = y[1]
    dy[row, 1] = -prm[P_P2] * (sA + a / prm[P_G] * cA)
    dy[row, 2] = y[3]
    dy[row, 3] = a - ag
    return ag


# ---------------------------------------------------------------------------------------------
# Dormand-Prince step and dense output
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _dp5_step(fkind, phase, s, prm, seg, epar, t, h, y, K, i0, i1, ynew, ytmp, C, A, B, E):
    """One Dormand-Prince step from ``(t, y)`` with ``K[0] = f(t, y)`` already set.

    Fills ``K[1:7]`` (``K[6] = f(t + h, ynew)``, first-same-as-last) and ``ynew``; returns the
    scaled RMS error norm over the active states ``i0:i1`` (accept when <= 1).
    """
    for st in range(1, 6):
        for i in range(i0, i1):
            acc = 0.0
            for j in range(st):
                acc += A[st, j] * K[j, i]
            ytmp[i] = y[i] + h * acc
        _rhs(fkind, phase, s, prm, seg, epar, t + C[st] * h, ytmp, K, st)
    for i in range(i0, i1):
        acc = 0.0
        for j in range(6):
            acc += B[j] * K[j, i]
        ynew[i] = y[i] + h * acc
    _rhs(fkind, phase, s, prm, seg, epar, t + h, ynew, K, 6)
    rtol = prm[P_RTOL]
    tot = 0.0
    for i in range(i0, i1):
        err = 0.0
        for j in range(7):
            err += E[j] * K[j, i]
        err *= h
        sc = max(abs(y[i]), abs(ynew[i]), prm[P_SC0 + i]) * rtol
        tot += (err / sc) ** 2
    return math.sqrt(tot / (i1 - i0))


@njit(cache=True)
def _dense_coeffs(y, K, h, i, P, c):
    """Coefficients ``c[0..4]`` of state ``i`` over the step as a polynomial in sigma = (t - t0)/h."""
    c[0] = y[i]
    for k in range(4):
        acc = 0.0
        for j in range(7):
            acc += K[j, i] * P[j, k]
        c[k + 1] = h * acc


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

    The polynomial is sampled on 16 sub-intervals to bracket the first crossing (so a start
    exactly on the level, e.g. theta = 0 right after an impact, is not taken for a crossing),
    then refined by regula falsi. Returns -1 if the function is never positive before it is <= 0.
    """
    n = 16
    seen_pos = (_poly(c, lo) - level) > 0.0
    xprev = lo
    fprev = _poly(c, lo) - level
    for k in range(1, n + 1):
        x = lo + (hi - lo) * k / n
        fx = _poly(c, x) - level
        if fx <= 0.0:
            if seen_pos and fprev > 0.0:
                return _refine_root(c, level, xprev, x, fprev)
        else:
            seen_pos = True
        xprev = x
        fprev = fx
    return -1.0


# ---------------------------------------------------------------------------------------------
# Small helpers
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _hist_push(H, n, t, ag, y):
    if n >= H.shape[0]:
        H2 = np.empty((2 * H.shape[0], N_HIST))
        H2[:n] = H[:n]
        H = H2
    H[n, H_T] = t
    H[n, H_AG] = ag
    H[n, H_TH] = y[0]
    H[n, H_THD] = y[1]
    H[n, H_U] = y[2]
    H[n, H_UD] = y[3]
    return H, n + 1


@njit(cache=True)
def _set_segment(j, ekind, epar, acc, dt, t_begin, seg):
    """Set ``seg`` for segment ``j`` and return its end time.

    Records: segment j < n-1 is the sample interval [j dt, (j+1) dt]; segment n-1 is the zero
    tail. Pulses: segment 0 is [t_begin, ts] (zero), 1 the support [ts, te], 2 the zero tail.
    """
    if ekind == EXC_RECORD:
        n = acc.shape[0]
        if j < n - 1:
            seg[0] = SEG_LINEAR
            seg[1] = acc[j]
            seg[2] = (acc[j + 1] - acc[j]) / dt
            seg[3] = j * dt
            return (j + 1) * dt
        seg[0] = SEG_LINEAR
        seg[1] = 0.0
        seg[2] = 0.0
        seg[3] = (n - 1) * dt
        return np.inf
    if j == 0:
        seg[0] = SEG_LINEAR
        seg[1] = 0.0
        seg[2] = 0.0
        seg[3] = t_begin
        return epar[E_TS]
    if j == 1:
        seg[0] = ekind
        seg[1] = 0.0
        seg[2] = 0.0
        seg[3] = epar[E_TS]
        return epar[E_TE]
    seg[0] = SEG_LINEAR
    seg[1] = 0.0
    seg[2] = 0.0
    seg[3] = epar[E_TE]
    return np.inf


@njit(cache=True)
def _rigid_uplift(seg, epar, thr, t, t_end):
    """First time in [t, t_end] at which |ag| exceeds ``thr`` (rigid foundation, stuck phase).

    Returns ``(t_uplift, s)`` with ``s = -sign(ag)`` (the corner the block pivots on), or
    ``(-1, 0)`` when the block stays stuck through ``t_end``. Linear segments are exact; pulse
    segments are scanned on a grid of T_p/512 with every sampled local maximum of |ag| refined by
    golden-section search, then the crossing refined by bisection.
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
        elif k >= 2 and fm1 >= fm2 and fm1 >= fk and fm1 > -0.05 * thr:
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
# The simulation kernel
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def _signed_coeffs(y, K, h, i, P, sign, c):
    _dense_coeffs(y, K, h, i, P, c)
    for k in range(5):
        c[k] *= sign


@njit(cache=True)
def _track_u_peak(y, ynew, K, hs, P, sig_end, valid_end, out, c):
    """Update the peak |u| over [0, sig_end] of the step (extremum where u_dot changes sign)."""
    if (y[3] > 0.0) != (ynew[3] > 0.0):
        _signed_coeffs(y, K, hs, 3, P, 1.0 if y[3] > 0.0 else -1.0, c)
        sx = _first_down(c, 0.0, 0.0, sig_end)
        if sx >= 0.0:
            _dense_coeffs(y, K, hs, 2, P, c)
            um = abs(_poly(c, sx))
            if um > out[O_U_MAX]:
                out[O_U_MAX] = um
    if valid_end and abs(ynew[2]) > out[O_U_MAX]:
        out[O_U_MAX] = abs(ynew[2])


@njit(cache=True)
def _start_rocking(t, out):
    out[O_N_UPLIFTS] += 1
    if out[O_UPLIFTED] == 0.0:
        out[O_UPLIFTED] = 1.0
        out[O_T_UPLIFT] = t


@njit(cache=True)
def simulate_core(fkind, prm, ekind, epar, acc, dt, t_begin, t_exc_end, tail, max_steps,
                  want_history, C, A, B, E, P, out):
    """Integrate one scene. Fills ``out`` (see the ``O_*`` layout) and returns the history.

    Parameters
    ----------
    fkind : int
        Foundation kind (``FOUNDATION_*``).
    prm : float64[N_PRM]
        Block, foundation and tolerance constants (``P_*`` layout).
    ekind : int
        Excitation kind (``EXC_*``); ``acc``/``dt`` for records, ``epar`` for pulses.
    t_begin, t_exc_end : float
        Start of the integration and end of the excitation [s].
    tail : float
        Free-motion time after the excitation [s]. A block still rocking then is followed until
        it rests or overturns, up to ``4 * tail``.
    max_steps : int
        Hard cap on accepted + rejected steps (status ``STATUS_MAX_STEPS`` when reached).
    want_history : bool
        Store the state at every step end and event. Without it, stop as soon as the verdict is
        settled (overturned, or no longer able to overturn once the ground is still).

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

    y = np.zeros(4)
    ynew = np.zeros(4)
    ytmp = np.zeros(4)
    K = np.zeros((7, 4))
    c0 = np.zeros(5)
    c1 = np.zeros(5)
    seg = np.zeros(4)

    for k in range(N_OUT):
        out[k] = 0.0
    out[O_T_UPLIFT] = np.nan
    out[O_T_OVERTURN] = np.nan
    out[O_T_EXCEED] = np.nan
    out[O_T_THETA_MAX] = np.nan

    if want_history:
        cap = 1024
        if ekind == EXC_RECORD:
            cap = 2 * acc.shape[0] + 1024
        H = np.empty((cap, N_HIST))
    else:
        H = np.empty((0, N_HIST))
    nh = 0

    t = t_begin
    t_min_end = t_exc_end + tail
    t_max_end = t_exc_end + 4.0 * tail
    phase = PHASE_STUCK
    s = 0.0
    h = 0.0  # step-size proposal (0: choose one)
    steps = 0
    rejected = 0
    nrhs = 0
    status = STATUS_DONE
    settled = False
    fresh = True  # K[0] = f(t, y) must be (re)computed

    j = 0
    seg_end = _set_segment(j, ekind, epar, acc, dt, t_begin, seg)
    if want_history:
        H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)

    while True:
        # ----- move to the segment that contains t
        while t >= seg_end:
            j += 1
            seg_end = _set_segment(j, ekind, epar, acc, dt, t_begin, seg)
            # a record is continuous across samples (the FSAL derivative stays valid); pulse
            # edges and the start of the tail may jump
            if ekind != EXC_RECORD or j >= acc.shape[0] - 1:
                fresh = True
        t_stop = min(seg_end, t_max_end)

        # ----- is the outcome settled once the ground is still?
        if t >= t_exc_end:
            if phase == PHASE_STUCK:
                if not isolated:
                    settled = True
                    break
                # the base oscillates freely: |F| <= omega (1 + 2 xi) sqrt(u_dot^2 + omega^2 u^2)
                bound = w * (1.0 + 2.0 * prm[P_XI]) * math.sqrt(y[3] * y[3] + w * w * y[2] * y[2])
                if bound < thr:
                    settled = True
                    if not want_history or t >= t_min_end:
                        break
                elif t >= t_min_end and want_history:
                    break
            elif not isolated and not want_history:
                # free rocking on a rigid base keeps E = thd^2/2 + p^2 cos(alpha - |theta|) between
                # impacts and loses energy at impacts: below p^2 it can never overturn.
                En = 0.5 * y[1] * y[1] + p2 * math.cos(alpha - abs(y[0]))
                if y[0] * y[1] < 0.0:  # heading for an impact first
                    c_a = p2 * math.cos(alpha)
                    En = c_a + prm[P_ETA] ** 2 * (En - c_a)
                if En < p2:
                    pk = alpha - math.acos(En / p2)
                    if pk > out[O_THETA_MAX]:
                        out[O_THETA_MAX] = pk
                        out[O_T_THETA_MAX] = np.nan
                    settled = True
                    break
        if t >= t_max_end:
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
                _start_rocking(t, out)
                fresh = True
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)
            continue

        # ----- stuck on an isolated base: already beyond the uplift threshold?
        if phase == PHASE_STUCK:
            a_now = _base_force(fkind, prm, y)
            if abs(a_now) > thr:
                s = -1.0 if a_now > 0.0 else 1.0
                phase = PHASE_ROCKING
                _start_rocking(t, out)
                fresh = True
                continue
            i0 = 2
        else:
            i0 = 0
        i1 = nst

        # ----- one Dormand-Prince step inside [t, t_stop]
        if fresh:
            _rhs(fkind, phase, s, prm, seg, epar, t, y, K, 0)
            nrhs += 1
            fresh = False
        if h <= 0.0:
            h = 0.02 / math.sqrt(p2)
            if ekind != EXC_RECORD:
                h = min(h, epar[E_TP] / 50.0)
        last = False
        while True:
            hs = h
            last = False
            if hs >= t_stop - t:
                hs = t_stop - t
                last = True
            err = _dp5_step(fkind, phase, s, prm, seg, epar, t, hs, y, K, i0, i1, ynew, ytmp, C, A, B, E)
            nrhs += 6
            if err <= 1.0:
                fac = 5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)
                if not last or fac < 1.0:
                    h = hs * fac
                break
            rejected += 1
            h = hs * max(0.2, 0.9 * err ** -0.2)
            if steps + rejected >= max_steps:
                break
        if err > 1.0:
            status = STATUS_MAX_STEPS
            break
        steps += 1
        t_new = t_stop if last else t + hs

        # ----- stuck on an isolated base: uplift when |a| crosses g tan(alpha)
        if phase == PHASE_STUCK:
            a_new = _base_force(fkind, prm, ynew)
            sig = -1.0
            su = 0.0
            if abs(a_new) > 0.9 * thr or abs(_base_force(fkind, prm, y)) > 0.9 * thr:
                # a(sigma) is linear in the states: a polynomial in sigma like them
                _dense_coeffs(y, K, hs, 2, P, c0)
                _dense_coeffs(y, K, hs, 3, P, c1)
                for k in range(5):
                    c0[k] = -w * w * c0[k] - 2.0 * prm[P_XI] * w * c1[k]
                    c1[k] = -c0[k]
                sig_up = _first_down(c1, -thr, 0.0, 1.0)  # a rises above +thr
                sig_dn = _first_down(c0, -thr, 0.0, 1.0)  # a falls below -thr
                if sig_up >= 0.0 and (sig_dn < 0.0 or sig_up <= sig_dn):
                    sig = sig_up
                    su = -1.0
                elif sig_dn >= 0.0:
                    sig = sig_dn
                    su = 1.0
            _track_u_peak(y, ynew, K, hs, P, 1.0 if sig < 0.0 else sig, sig < 0.0, out, c1)
            if sig >= 0.0:
                for i in range(2, 4):
                    _dense_coeffs(y, K, hs, i, P, c1)
                    ytmp[i] = _poly(c1, sig)
                y[2] = ytmp[2]
                y[3] = ytmp[3]
                t = t + sig * hs
                s = su
                phase = PHASE_ROCKING
                _start_rocking(t, out)
                fresh = True
            else:
                t = t_new
                for i in range(2, 4):
                    y[i] = ynew[i]
                    K[0, i] = K[6, i]
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)
            continue

        # ----- rocking: impact (s theta falls to 0), peak, alpha, overturning (s theta = pi/2)
        sth1 = s * ynew[0]
        sd0 = s * y[1]
        sd1 = s * ynew[1]
        sig_end = 1.0
        impact = False
        failed = False
        if sth1 <= 0.0 or (sd0 < 0.0 and sd1 > 0.0):
            _signed_coeffs(y, K, hs, 0, P, s, c0)
            sig = _first_down(c0, 0.0, 0.0, 1.0)
            if sig >= 0.0:
                impact = True
                sig_end = sig
            elif sth1 <= 0.0:
                failed = True  # never rose above theta = 0: the uplift did not take
        if not failed:
            if sd0 > 0.0 and (sd1 <= 0.0 or impact):
                _signed_coeffs(y, K, hs, 1, P, s, c1)
                sp = _first_down(c1, 0.0, 0.0, sig_end)
                if sp >= 0.0:
                    _signed_coeffs(y, K, hs, 0, P, s, c0)
                    thp = _poly(c0, sp)
                    if thp > out[O_THETA_MAX]:
                        out[O_THETA_MAX] = thp
                        out[O_T_THETA_MAX] = t + sp * hs
            if not impact and sth1 > out[O_THETA_MAX]:
                out[O_THETA_MAX] = sth1
                out[O_T_THETA_MAX] = t_new
            reach = sth1 if not impact else out[O_THETA_MAX]
            if math.isnan(out[O_T_EXCEED]) and reach >= alpha:
                _signed_coeffs(y, K, hs, 0, P, -s, c1)  # -s theta
                sa = _first_down(c1, -alpha, 0.0, sig_end)
                out[O_T_EXCEED] = t + (sa if sa >= 0.0 else sig_end) * hs
            if not impact and sth1 >= halfpi:
                _signed_coeffs(y, K, hs, 0, P, -s, c1)
                so = _first_down(c1, -halfpi, 0.0, 1.0)
                if so < 0.0:
                    so = 1.0
                if isolated:
                    _track_u_peak(y, ynew, K, hs, P, so, False, out, c0)
                for i in range(nst):
                    _dense_coeffs(y, K, hs, i, P, c1)
                    ytmp[i] = _poly(c1, so)
                for i in range(nst):
                    y[i] = ytmp[i]
                t = t + so * hs
                out[O_THETA_MAX] = halfpi
                out[O_T_THETA_MAX] = t
                out[O_T_OVERTURN] = t
                status = STATUS_OVERTURNED
                if want_history:
                    H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)
                break
        if isolated:
            _track_u_peak(y, ynew, K, hs, P, sig_end, not impact, out, c1)

        if failed:
            # the block never left theta = 0: back to the stuck phase at the end of the step,
            # keeping the total horizontal momentum (u_dot + gamma h theta_dot per unit mass)
            t = t_new
            if isolated:
                y[2] = ynew[2]
                y[3] = ynew[3] + prm[P_GAMMA] * prm[P_H] * ynew[1]
            y[0] = 0.0
            y[1] = 0.0
            phase = PHASE_STUCK
            s = 0.0
            fresh = True
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)
            continue

        if impact:
            for i in range(nst):
                _dense_coeffs(y, K, hs, i, P, c1)
                ytmp[i] = _poly(c1, sig_end)
            for i in range(nst):
                y[i] = ytmp[i]
            t = t + sig_end * hs
            y[0] = 0.0
            thd1 = y[1]
            out[O_N_IMPACTS_ALL] += 1
            if t <= t_exc_end:
                out[O_N_IMPACTS] += 1
            # impact map (Eqs 14-19 with gamma = m/(m+m_b)): keeps the horizontal momentum of
            # block + base and the block's angular momentum about the new pivot
            thd2 = prm[P_ETA] * thd1
            if isolated:
                y[3] = y[3] + prm[P_DU] * thd1
            s = -s
            # rest: the rotation still reachable by free rocking, thd^2/(2 p^2 sin alpha), is
            # below rest_tol * alpha (a plastic impact ends the motion, momentum kept)
            if thd2 * thd2 / (2.0 * p2 * prm[P_SINA]) < prm[P_REST] * alpha:
                if isolated:
                    y[3] = y[3] + prm[P_GAMMA] * prm[P_H] * thd2
                y[1] = 0.0
                phase = PHASE_STUCK
                s = 0.0
                out[O_N_RESTS] += 1
            else:
                y[1] = thd2
            if want_history:
                H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)
            fresh = True
            continue

        # accepted step without events
        t = t_new
        for i in range(nst):
            y[i] = ynew[i]
            K[0, i] = K[6, i]
        if want_history:
            H, nh = _hist_push(H, nh, t, _ground(t, seg, epar), y)

    if phase == PHASE_STUCK and isolated and not settled:
        settled = w * (1.0 + 2.0 * prm[P_XI]) * math.sqrt(y[3] * y[3] + w * w * y[2] * y[2]) < thr
    out[O_STATUS] = status
    out[O_STEPS] = steps
    out[O_REJECTED] = rejected
    out[O_NRHS] = nrhs
    out[O_T_END] = t
    out[O_SETTLED] = 1.0 if (settled or status == STATUS_OVERTURNED) else 0.0
    out[O_THETA_END] = y[0]
    out[O_U_END] = y[2]
    return H[:nh]
