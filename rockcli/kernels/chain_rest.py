"""The chain at rest on its linear bearings, in closed form (the friction driver's rest phase on a base under a
record): the base carrying everything on it is the damped oscillator of :mod:`rockcli.kernels.linear_base`, stepped
exactly over each sample interval, and the chain leaves rest where the base's absolute acceleration ``a = -w^2 u -
2 xi w u'`` leaves the band ``[lo, hi]`` in which every face presses and every contact sticks
(:func:`rockcli.kernels.chain_run.rest_band`, read with ``a`` for ``ag``).

The exit inside an interval (:func:`band_exceed`) is found as :func:`rockcli.kernels.linear_base.first_exceed` finds
the single block's lift-off, with the same bound: on a sub-interval of length ``l``, ``a`` passes the larger of its
end values by at most ``K l^2/8``; an interval whose ends satisfy ``max(a - hi, lo - a) + K h^2/8 <= 0`` has no exit,
the others are bisected down to ``h 2^-44``, left half first."""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.jit import kernel
from rockcli.kernels.linear_base import (FIRST_EXCEED_LEVELS, acceleration_at, advance, base_acceleration,
                                         coefficients, free_part, velocity_zero)


@kernel(inline='always')
def _out(a, lo, hi):
    """How far ``a`` lies outside ``[lo, hi]`` (negative inside)."""
    return max(a - hi, lo - a)


@kernel
def band_exceed(w, xi, a_start, ah, ahd, k, a0, b, h, lo, hi):
    """The first ``tau`` in ``(0, h]`` at which ``a`` leaves ``[lo, hi]``, or -1 (``a(0)`` inside)."""
    stack_t = np.empty(FIRST_EXCEED_LEVELS + 2)
    stack_a = np.empty(FIRST_EXCEED_LEVELS + 2)
    stack_t[0] = h
    stack_a[0] = acceleration_at(w, xi, ah, ahd, a0, b, h)
    top = 1
    lo_t = 0.0
    a_lo = a_start
    tiny = h * 2.0 ** -FIRST_EXCEED_LEVELS
    while top > 0:
        hi_t = stack_t[top - 1]
        a_hi = stack_a[top - 1]
        if max(_out(a_lo, lo, hi), _out(a_hi, lo, hi)) + 0.125 * k * (hi_t - lo_t) * (hi_t - lo_t) <= 0.0:
            lo_t = hi_t
            a_lo = a_hi
            top -= 1
            continue
        if hi_t - lo_t <= tiny or top >= FIRST_EXCEED_LEVELS + 2:
            if _out(a_hi, lo, hi) > 0.0:
                return hi_t
            lo_t = hi_t
            a_lo = a_hi
            top -= 1
            continue
        mid = 0.5 * (lo_t + hi_t)
        stack_t[top] = mid
        stack_a[top] = acceleration_at(w, xi, ah, ahd, a0, b, mid)
        top += 1
    return -1.0


@kernel
def rest_interval(w, xi, coef, dt, u, v, a0, b, h, lo, hi):
    """One interval of length ``h`` (``coef`` the exact step of length ``dt``, used when ``h == dt``) of the base at
    rest under ``ag = a0 + b tau``: ``(tau, u, v, u_peak)``, ``tau = h`` when the chain stays at rest through it, else
    the time it leaves (the state there); ``u_peak`` the largest ``|u|`` on the way (ends and reversals)."""
    a, ah, ahd, k = free_part(w, xi, u, v, a0, b)
    c = coef if h == dt else coefficients(w, xi, h)
    u1, v1 = advance(c, u, v, a0, b)
    a1 = base_acceleration(w, xi, u1, v1)
    tau = h
    if max(_out(a, lo, hi), _out(a1, lo, hi)) + 0.125 * k * h * h > 0.0:
        tx = band_exceed(w, xi, a, ah, ahd, k, a0, b, h, lo, hi)
        if tx >= 0.0:
            tau = tx
            u1, v1 = advance(coefficients(w, xi, tau), u, v, a0, b)
    peak = max(abs(u), abs(u1))
    if v * v1 < 0.0:  # a reversal of the base inside: its displacement there
        peak = max(peak, abs(velocity_zero(w, xi, u, v, a0, b, tau)))
    return tau, u1, v1, peak


@kernel
def quiet_until(acc, rscale, j, lo, hi, t_cap, dt):
    """Where a chain at rest on the rigid ground under a record, inside its rest band ``[lo, hi]`` through the
    end of segment ``j`` (from ``j dt`` to ``(j + 1) dt``, samples ``j`` and ``j + 1``), next needs a look: the
    index of the last segment the run may skip to (its start ``k dt``), every segment between lying inside the
    band at both its samples (the ground is linear on a segment, so inside throughout), the skip never passing
    ``t_cap`` (the end of the excitation or the horizon: the run's own checks happen there) nor the record's last
    segment. ``j + 1`` when nothing can be skipped. The same segments the run would otherwise take one at a time,
    and the same times: exact."""
    nrec = acc.shape[0]
    k = j + 1
    while k + 1 < nrec - 1 and (k + 1) * dt <= t_cap:
        a = rscale * acc[k + 1]
        if a > hi or a < lo:
            break
        k += 1
    return k
