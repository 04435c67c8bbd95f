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

from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (E_AP, E_BETA, E_T0, E_TE, E_TP, E_TS, EXC_COSINE, EXC_RECORD, EXC_RICKER_ANTI,
                                    EXC_RICKER_SYM, EXC_SINE, SEG_LINEAR)


@kernel(inline='always')
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


@kernel(inline='always')
def _ground(t, seg, epar):
    """Ground acceleration inside the current segment, ``seg = (mode, a0, slope, ts)``."""
    mode = int(seg[0])
    if mode == SEG_LINEAR:
        return seg[1] + seg[2] * (t - seg[3])
    return pulse_acc(mode, epar, t)


@kernel(inline='always')
def _vertical(t, seg):
    """Vertical ground acceleration [m/s^2] (upward positive) inside the current segment: linear on
    the piece ``seg[4:7] = (v0, slope, tv)`` of the vertical series (all zero without one, so that
    ``a_v = 0`` exactly)."""
    return seg[4] + seg[5] * (t - seg[6])


@kernel
def ground_at(t, seg, epar):
    """:func:`_ground` as a called function: for the places off the integrator's hot path (uplift
    scans, rest checks, history rows), where one compiled copy serves every call site."""
    return _ground(t, seg, epar)




@kernel
def _pulse_segment(j, ekind, epar, t_begin):
    """Segment ``j`` of a pulse: 0 = [t_begin, ts] zero, 1 = the support [ts, te], 2 = zero tail."""
    if j == 0:
        return (float(SEG_LINEAR), 0.0, 0.0, t_begin), epar[E_TS]
    if j == 1:
        return (float(ekind), 0.0, 0.0, epar[E_TS]), epar[E_TE]
    return (float(SEG_LINEAR), 0.0, 0.0, epar[E_TE]), np.inf


@kernel
def _pulse_turns(mode):
    """The times ``tau / T_p`` (from ``t0``) where a pulse's acceleration turns (``ag' = 0``) inside
    its support, ascending, padded with +inf: between two of them (or a turn and an end of the
    support) the acceleration is monotone.

    Symmetric Ricker: ``d/dr [(1 - 2 r) exp(-r)] = (2 r - 3) exp(-r)`` with ``r = (pi tau / T_p)^2``,
    so ``r = 3/2``, and ``tau = 0``. Antisymmetric Ricker: ``d/dx [(x^2 - 3) x exp(-x^2/2)] =
    -(x^4 - 6 x^2 + 3) exp(-x^2/2)``, so ``x^2 = 3 -+ sqrt 6`` with ``x = 2 pi tau / (sqrt 3 T_p)``.
    Sine: ``tau = T_p/4, 3 T_p/4``. Cosine: ``tau = T_p/2``.
    """
    inf = math.inf
    if mode == EXC_RICKER_SYM:
        c = math.sqrt(1.5) / math.pi
        return (-c, 0.0, c, inf)
    if mode == EXC_RICKER_ANTI:
        k = math.sqrt(3.0) / (2.0 * math.pi)
        a = math.sqrt(3.0 - math.sqrt(6.0)) * k
        b = math.sqrt(3.0 + math.sqrt(6.0)) * k
        return (-b, -a, a, b)
    if mode == EXC_SINE:
        return (0.25, 0.75, inf, inf)
    if mode == EXC_COSINE:
        return (0.5, inf, inf, inf)
    return (inf, inf, inf, inf)


@kernel(inline='always')
def _piece_end(turns, k, epar, lo, t_end):
    """End of the monotone piece of a pulse that starts at ``lo`` and ends at its turn ``k`` (0-3; 4: none
    left) or at ``t_end``, whichever comes first; ``-inf`` when the turn ``k`` lies at or before ``lo``."""
    if k < 4:
        tk = epar[E_T0] + turns[k] * epar[E_TP]
        if tk <= lo:
            return -math.inf
        if tk < t_end:
            return tk
    return t_end


@kernel
def _rigid_uplift(seg, epar, thr, t, t_end):
    """First time in [t, t_end] at which |ag| exceeds ``thr`` (rigid foundation, stuck phase).

    Returns ``(t_uplift, s)`` with ``s = -sign(ag)`` (the corner the block pivots on), or
    ``(-1, 0)`` when the block stays stuck through ``t_end``. Linear segments are exact. A pulse
    segment is cut at the pulse's turns (:func:`_pulse_turns`) into pieces on which ag is monotone:
    on a piece ``[a, b]`` with ``|ag(a)| <= thr`` every value lies between ``ag(a)`` and ``ag(b)``,
    so |ag| exceeds ``thr`` in it if and only if ``|ag(b)|`` does, and then ``ag = sign(ag(b)) thr``
    is crossed exactly once: found by bisection to the last bit.
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
    turns = _pulse_turns(int(seg[0]))
    lo = t
    for k in range(5):
        hi = _piece_end(turns, k, epar, lo, t_end)
        if hi < lo:  # the turn k lies at or before lo
            continue
        f_hi = ground_at(hi, seg, epar)
        if abs(f_hi) > thr:
            sgn = 1.0 if f_hi > 0.0 else -1.0
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                if sgn * ground_at(mid, seg, epar) > thr:
                    hi = mid
                else:
                    lo = mid
            return hi, -sgn
        if hi >= t_end:
            break
        lo = hi
    return -1.0, 0.0


#: sub-intervals per monotone piece of a pulse scanned for uplift under a vertical motion
N_UPLIFT_SCAN = 64


@kernel
def _uplift_excess(t, seg, epar, thr, g):
    """``(ag - thr_v, -ag - thr_v)`` at ``t``, ``thr_v = thr (1 + a_v/g) = (g + a_v) tan(alpha)``: the
    block lifts about the left corner when the first is positive, about the right one when the second is."""
    ag = ground_at(t, seg, epar)
    thr_v = thr * (1.0 + _vertical(t, seg) / g)
    return ag - thr_v, -ag - thr_v


@kernel
def _rigid_uplift_vertical(seg, epar, thr, g, t, t_end):
    """:func:`_rigid_uplift` under a vertical motion: the first time in [t, t_end] at which
    ``|ag| > (g + a_v) tan(alpha)`` (``thr = g tan(alpha)``); ``[t, t_end]`` lies inside one piece of
    the vertical series (a_v linear). A record segment is exact (both sides of the test are linear in
    t). A pulse segment is cut at the pulse's turns and each monotone piece into
    :data:`N_UPLIFT_SCAN` sub-intervals; the first sub-interval whose end exceeds is bisected to the
    last bit. The monotonicity argument of :func:`_rigid_uplift` does not survive a varying
    threshold, so an excursion above it that starts and ends inside one sub-interval (1/64 of a
    quarter period or less) can be missed: a grazing uplift, whose rocking would stay below the
    resolution of the run."""
    ep0, em0 = _uplift_excess(t, seg, epar, thr, g)
    if ep0 > 0.0:
        return t, -1.0
    if em0 > 0.0:
        return t, 1.0
    if int(seg[0]) == SEG_LINEAR:
        ep1, em1 = _uplift_excess(t_end, seg, epar, thr, g)
        tu = math.inf
        su = 0.0
        if ep1 > 0.0:
            tu = t + (-ep0) / (ep1 - ep0) * (t_end - t)
            su = -1.0
        if em1 > 0.0:
            tm = t + (-em0) / (em1 - em0) * (t_end - t)
            if tm < tu:
                tu = tm
                su = 1.0
        if su == 0.0:
            return -1.0, 0.0
        return min(max(tu, t), t_end), su
    turns = _pulse_turns(int(seg[0]))
    lo = t
    for k in range(5):
        hi = _piece_end(turns, k, epar, lo, t_end)
        if hi < lo:  # the turn k lies at or before lo
            continue
        a = lo
        for m in range(1, N_UPLIFT_SCAN + 1):
            b = hi if m == N_UPLIFT_SCAN else lo + (hi - lo) * m / N_UPLIFT_SCAN
            ep, em = _uplift_excess(b, seg, epar, thr, g)
            if ep > 0.0 or em > 0.0:
                sgn = 1.0 if ep > 0.0 else -1.0
                for _ in range(200):
                    mid = 0.5 * (a + b)
                    if mid <= a or mid >= b:
                        break
                    ep, em = _uplift_excess(mid, seg, epar, thr, g)
                    if (ep if sgn > 0.0 else em) > 0.0:
                        b = mid
                    else:
                        a = mid
                return b, -sgn
            a = b
        if hi >= t_end:
            break
        lo = hi
    return -1.0, 0.0


# ---------------------------------------------------------------------------------------------


@kernel(inline='always')
def _record_left(jtab, dt, t):
    """The suffix integral of a record's table at the sample at or before ``t`` (0 past its end)."""
    n = jtab.shape[0]
    x = t / dt - 1e-9
    j = 0 if x <= 0.0 else int(x)
    if j >= n:
        return 0.0
    return jtab[j]


@kernel
def _impulse_left(ekind, jtab, epar, dt, t):
    """An upper bound of ``int_t^{t_exc_end} |ag| dtau`` [m/s], the ground's remaining "impulse".

    ``jtab`` holds exact suffix integrals of ``|ag|``: for a record, from each sample to the end
    (of the unscaled samples; ``epar[E_AP]`` is the scale); for a pulse, of the unit pulse
    (``a_p = 1``, ``T_p = 1``) from each of ``n`` equally spaced points of its support. The value
    at the grid point at or before ``t`` bounds the integral from ``t``.
    """
    n = jtab.shape[0]
    if ekind == EXC_RECORD:
        return abs(epar[E_AP]) * _record_left(jtab, dt, t)
    ts = epar[E_TS]
    te = epar[E_TE]
    if t >= te:
        return 0.0
    x = (t - ts) / (te - ts) * (n - 1) - 1e-9
    k = 0 if x <= 0.0 else int(x)
    if k > n - 1:
        k = n - 1
    return abs(epar[E_AP]) * epar[E_TP] * jtab[k]


@kernel
def _vertical_left(vjtab, vdt, t):
    """An upper bound of ``int_t^{t_v_end} |a_v| dtau`` [m/s] of the vertical series (its table is
    :func:`rockcli.solve.record_impulse_table` of the scaled samples); 0 without one."""
    if vjtab.shape[0] == 0:
        return 0.0
    return _record_left(vjtab, vdt, t)


@kernel
def band_exit(seg, epar, a_lo, a_hi, t, t_end):
    """First time in [t, t_end] at which the ground acceleration leaves ``[a_lo, a_hi]`` (``a_lo < 0 < a_hi``: the
    band in which a stack at rest on the ground stays at rest; :func:`_rigid_uplift` is the symmetric case), else
    -1. Linear segments are exact; a pulse segment is cut at its turns into monotone pieces, on which the exit is
    bisected to the last bit (the argument of :func:`_rigid_uplift`). Returns ``(t, side)``: ``side`` +1 when it
    leaves above ``a_hi``, -1 below ``a_lo`` (``t = -1``, side 0: it stays inside)."""
    a0 = ground_at(t, seg, epar)
    if a0 > a_hi:
        return t, 1.0
    if a0 < a_lo:
        return t, -1.0
    if int(seg[0]) == SEG_LINEAR:
        if seg[2] == 0.0:
            return -1.0, 0.0
        a1 = ground_at(t_end, seg, epar)
        if a1 > a_hi:
            return t + (a_hi - a0) / (a1 - a0) * (t_end - t), 1.0
        if a1 < a_lo:
            return t + (a_lo - a0) / (a1 - a0) * (t_end - t), -1.0
        return -1.0, 0.0
    turns = _pulse_turns(int(seg[0]))
    lo = t
    for k in range(5):
        hi = _piece_end(turns, k, epar, lo, t_end)
        if hi < lo:
            continue
        f_hi = ground_at(hi, seg, epar)
        if f_hi > a_hi or f_hi < a_lo:
            up = f_hi > a_hi
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                fm = ground_at(mid, seg, epar)
                if (fm > a_hi) if up else (fm < a_lo):
                    hi = mid
                else:
                    lo = mid
            return hi, (1.0 if up else -1.0)
        if hi >= t_end:
            break
        lo = hi
    return -1.0, 0.0
