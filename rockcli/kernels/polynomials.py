"""Polynomials of the dense output: evaluation, first crossings and excursions (rigorous sampling).

Every event of a step (uplift, impact, peaks, |theta| = alpha, overturning, reversals of the
base) is located on the quartic dense output of the step, ``poly(c, sigma)`` with
``sigma = (t - t_step)/h`` in [0, 1], never on the step grid.
"""

from __future__ import annotations

from rockcli.kernels.jit import kernel


@kernel(inline='always')
def _poly(c, x):
    return c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * c[4])))


@kernel
def _refine_root(c, level, lo, hi, flo):
    """Root of ``poly(c) - level`` in [lo, hi] given a sign change (Illinois regula falsi)."""
    fhi = _poly(c, hi) - level
    side = 0
    for _ in range(100):
        if hi - lo <= 1e-15:
            break
        x = 0.5 * (lo + hi)
        if fhi != flo:  # (regula falsi values can underflow to equal: then bisect)
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


@kernel
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


@kernel
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


@kernel
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

