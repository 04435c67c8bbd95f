"""Ground motion inside the kernels: analytic pulses, the segments of the time axis, the
rigid-foundation uplift scan and the remaining ground impulse (early stop P4).

The time axis is cut into *segments* on which the ground acceleration is smooth: for a record,
each sample interval (the record is piecewise linear between samples); for an analytic pulse,
the pulse's support; after the excitation, a zero-acceleration tail. A step never crosses a
segment end, so the error estimate always sees a smooth right-hand side.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rockcli.kernels.layout import (E_AP, E_BETA, E_T0, E_TE, E_TP, E_TS, EXC_COSINE, EXC_RECORD, EXC_RICKER_ANTI,
                                    EXC_RICKER_SYM, EXC_SINE, SEG_LINEAR)


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


@njit(cache=True)
def ground_at(t, seg, epar):
    """:func:`_ground` as a called function: for the places off the integrator's hot path (uplift
    scans, rest checks, history rows), where one compiled copy serves every call site."""
    return _ground(t, seg, epar)




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
    a0 = ground_at(t, seg, epar)
    if abs(a0) > thr:
        return t, -1.0 if a0 > 0 else 1.0
    if int(seg[0]) == SEG_LINEAR:
        if seg[2] == 0.0:
            return -1.0, 0.0
        a1 = ground_at(t_end, seg, epar)
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
        fk = abs(_ground(tk, seg, epar)) - thr  # the hot loop: inlined
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
                if abs(ground_at(x1, seg, epar)) > abs(ground_at(x2, seg, epar)):
                    xb = x2
                else:
                    xa = x1
            xm = 0.5 * (xa + xb)
            if abs(ground_at(xm, seg, epar)) > thr:
                found = True
                lo = tk - 2.0 * hg
                hi = xm
        if found:
            sgn = 1.0 if ground_at(hi, seg, epar) > 0.0 else -1.0
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if sgn * ground_at(mid, seg, epar) > thr:
                    hi = mid
                else:
                    lo = mid
            return hi, -sgn
        fm2 = fm1
        fm1 = fk
    return -1.0, 0.0


# ---------------------------------------------------------------------------------------------


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
