"""The linear isolated base carrying the standing block, in closed form (the piecewise-exact scheme).

While the block stands on its base (the stuck phase), the base on linear bearings is a damped
oscillator driven by the ground: ``u'' + 2 xi w u' + w^2 u = -ag`` (u relative to the ground, per
unit total mass), and the block lifts off when the absolute base acceleration
``a = -w^2 u - 2 xi w u'`` exceeds ``g tan(alpha)`` in magnitude. A record is piecewise linear between
its samples (``ag = a0 + b tau`` on a sample interval), so the state after a time ``tau`` is exact:

    x(tau) = P(tau) x(0) - a0 q1(tau) - b q2(tau),   x = (u, u'),

with ``P = exp(A tau)``, ``A = [[0, 1], [-w^2, -2 xi w]]``, ``q1 = int_0^tau exp(A r) e2 dr`` and
``q2 = int_0^tau exp(A r) e2 (tau - r) dr`` (Nigam & Jennings 1969, the scheme of response spectra;
:func:`coefficients` computes them once per time step, :func:`advance` applies them).

Stable for every supported base (``T_b`` 0.005 s to 1e6 s, ``xi`` 0 to 10): with ``sigma = xi w`` and
``mu^2 = sigma^2 - w^2``, ``P = exp(-sigma tau) (C I + tau S N)``, ``N = A + sigma I`` (``N^2 = mu^2 I``),
``C = cosh(mu tau)`` and ``S = sinh(mu tau)/(mu tau)`` as functions of ``z = mu^2 tau^2`` (cos/sin for
z < 0, a series near 0, exponentials folded with ``exp(-sigma tau)`` for z > 0, so that nothing
overflows); ``q1 = A^-1 (P - I) e2``, ``q2 = A^-1 (q1 - tau e2)``, replaced by their Taylor series
when ``(w + 2 sigma) tau <= 1.5`` (where ``A^-1`` would cancel: long periods).

Lift-off inside a step (:func:`first_exceed`). ``a = ag + a_h`` where ``a_h`` is itself a free
solution of the oscillator (``a`` of the particular solution for linear ground is ``ag``), so
``a(tau) = a0 + b tau + P11(tau) a_h(0) + P12(tau) a_h'(0)`` and ``a'' = a_h''``. The energy norm
``N(a_h) = sqrt(a_h'^2 + w^2 a_h^2)`` never grows (``d N^2/2 = -2 xi w a_h'^2 dtau``) and
``|a_h''| = |w^2 a_h + 2 xi w a_h'| <= w sqrt(1 + 4 xi^2) N(a_h)`` (Cauchy-Schwarz), so on any
sub-interval of length ``l`` ``|a|`` exceeds the larger of its end values by at most
``K l^2 / 8`` with ``K = w sqrt(1 + 4 xi^2) N(a_h)(0)`` (the error of linear interpolation). A step
whose ends satisfy ``max |a| + K h^2/8 <= thr`` has no lift-off (the cheap test, which nearly every
step passes); the others are bisected, left half first, dropping every piece the same bound clears,
down to pieces of ``h 2^-44``: the first piece whose right end exceeds ``thr`` holds the lift-off.
The result is exact up to rounding (a grazing excursion above ``thr`` by less than ``K (h 2^-44)^2/8``
is not an uplift).

:func:`stuck_peak` is the same exact solution over a whole record at one scale factor, from rest:
an upper bound of ``|a|`` at all times while the block stands (the margin search's lift-off factor,
:mod:`rockcli.assess.liftoff`). :func:`linear_base_table` is the same solution at unit scale with a
norm :func:`base_norm` that bounds the base's later accelerations (the early stop P9 of
:mod:`rockcli.kernels.driver_end`).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.jit import kernel

#: Below this ``|z| = |mu^2 tau^2|`` the functions C and S are summed as series (error < 1e-20).
Z_SERIES = 0.01
#: The Taylor series of q1 and q2 is used where ``(w + 2 xi w) tau`` is at most this (25 terms).
Q_SERIES = 1.5
#: Pieces of a step narrower than ``h * 2**-FIRST_EXCEED_LEVELS`` are not bisected further.
FIRST_EXCEED_LEVELS = 44


@kernel
def transition(w, xi, tau):
    """``P = exp(A tau)`` of the free base: ``(P11, P12, P21, P22)``."""
    sig = xi * w
    mu2 = (xi - 1.0) * (xi + 1.0) * w * w
    z = mu2 * tau * tau
    if z > Z_SERIES:  # overdamped: exp(-sigma tau) folded into the two exponentials
        mu = math.sqrt(mu2)
        slow = w * w / (sig + mu)  # sigma - mu, without cancellation
        ep = math.exp(-slow * tau)
        em = math.exp(-(sig + mu) * tau)
        p12 = (ep - em) / (2.0 * mu)
        p11 = (ep * (mu + sig) - em * slow) / (2.0 * mu)
        p22 = (em * (mu + sig) - ep * slow) / (2.0 * mu)
        return p11, p12, -w * w * p12, p22
    e = math.exp(-sig * tau)
    if z < -Z_SERIES:  # underdamped
        wd = math.sqrt(-mu2)
        c = e * math.cos(wd * tau)
        s = e * math.sin(wd * tau) / wd
    else:
        ch = 1.0 + z * (1.0 / 2.0 + z * (1.0 / 24.0 + z * (1.0 / 720.0 + z * (1.0 / 40320.0 + z / 3628800.0))))
        sh = 1.0 + z * (1.0 / 6.0 + z * (1.0 / 120.0 + z * (1.0 / 5040.0 + z * (1.0 / 362880.0 + z / 39916800.0))))
        c = e * ch
        s = e * tau * sh
    return c + sig * s, s, -w * w * s, c - sig * s


@kernel
def coefficients(w, xi, tau):
    """The exact step of length ``tau`` under ``ag = a0 + b t``: ``(P11, P12, P21, P22, q1u, q1v, q2u, q2v)``
    (:func:`advance`)."""
    p11, p12, p21, p22 = transition(w, xi, tau)
    sig = xi * w
    if (w + 2.0 * sig) * tau <= Q_SERIES:
        # q1 = tau sum (A tau)^k e2/(k+1)!, q2 = tau^2 sum (A tau)^k e2/(k+2)!
        x0 = 0.0
        x1 = 1.0
        f1 = 1.0  # 1/(k+1)!
        f2 = 0.5  # 1/(k+2)!
        s1u = 0.0
        s1v = 1.0
        s2u = 0.0
        s2v = 0.5
        for k in range(1, 26):
            x0, x1 = tau * x1, -w * w * tau * x0 - 2.0 * sig * tau * x1
            f1 /= k + 1.0
            f2 /= k + 2.0
            s1u += f1 * x0
            s1v += f1 * x1
            s2u += f2 * x0
            s2v += f2 * x1
        return p11, p12, p21, p22, tau * s1u, tau * s1v, tau * tau * s2u, tau * tau * s2v
    q1u = (1.0 - p22 - 2.0 * sig * p12) / (w * w)
    q1v = p12
    q2u = (tau - p12 - 2.0 * sig * q1u) / (w * w)
    return p11, p12, p21, p22, q1u, q1v, q2u, q1u


@kernel
def advance(c, u, v, a0, b):
    """The state ``(u, u')`` after the step ``c`` (:func:`coefficients`) from ``(u, v)`` under ``ag = a0 + b t``."""
    return (c[0] * u + c[1] * v - a0 * c[4] - b * c[6],
            c[2] * u + c[3] * v - a0 * c[5] - b * c[7])


@kernel
def base_acceleration(w, xi, u, v):
    """The absolute base acceleration ``a = -w^2 u - 2 xi w u'`` (the bearings' force per unit total mass)."""
    return -w * w * u - 2.0 * xi * w * v


@kernel
def free_part(w, xi, u, v, a0, b):
    """``(a(0), a_h(0), a_h'(0), K)`` at the start of a step from ``(u, v)`` under ``ag = a0 + b t``:
    the acceleration, its free part and the bound ``K`` of ``|a''|`` over the step (module notes)."""
    a = base_acceleration(w, xi, u, v)
    ah = a - a0
    ahd = -w * w * v - 2.0 * xi * w * ah - b  # a' = -w^2 u' - 2 xi w u'', u'' = a - ag
    k = w * math.sqrt(1.0 + 4.0 * xi * xi) * math.sqrt(ahd * ahd + w * w * ah * ah)
    return a, ah, ahd, k


@kernel
def acceleration_at(w, xi, ah, ahd, a0, b, tau):
    """``a(tau) = a0 + b tau + P11(tau) a_h(0) + P12(tau) a_h'(0)`` inside a step."""
    p11, p12, _, _ = transition(w, xi, tau)
    return a0 + b * tau + p11 * ah + p12 * ahd


@kernel
def step_clear(a_start, a_end, k, h, thr):
    """True when no ``|a| > thr`` can occur inside a step of length ``h`` with these end values (module notes)."""
    return max(abs(a_start), abs(a_end)) + 0.125 * k * h * h <= thr


@kernel
def first_exceed(w, xi, a_start, ah, ahd, k, a0, b, h, thr):
    """The first ``tau`` in ``(0, h]`` with ``|a(tau)| > thr`` and the sign of ``a`` there, or ``(-1, 0)``
    (``|a(0)| <= thr``; module notes: bisection with the bound ``K l^2/8`` on every piece)."""
    stack_t = np.empty(FIRST_EXCEED_LEVELS + 2)
    stack_a = np.empty(FIRST_EXCEED_LEVELS + 2)
    stack_t[0] = h
    stack_a[0] = acceleration_at(w, xi, ah, ahd, a0, b, h)
    top = 1
    lo = 0.0
    a_lo = a_start
    tiny = h * 2.0 ** -FIRST_EXCEED_LEVELS
    while top > 0:
        hi = stack_t[top - 1]
        a_hi = stack_a[top - 1]
        if max(abs(a_lo), abs(a_hi)) + 0.125 * k * (hi - lo) * (hi - lo) <= thr:
            lo = hi
            a_lo = a_hi
            top -= 1
            continue
        if hi - lo <= tiny or top >= FIRST_EXCEED_LEVELS + 2:
            if abs(a_hi) > thr:
                return hi, (1.0 if a_hi > 0.0 else -1.0)
            lo = hi
            a_lo = a_hi
            top -= 1
            continue
        mid = 0.5 * (lo + hi)
        stack_t[top] = mid
        stack_a[top] = acceleration_at(w, xi, ah, ahd, a0, b, mid)
        top += 1
    return -1.0, 0.0


@kernel
def velocity_zero(w, xi, u, v, a0, b, h):
    """The displacement at the reversal of the base inside a step over which ``u'`` changes sign:
    ``u(tau)`` where ``u'(tau) = 0``, by bisection (``u`` is flat there: 30 halvings leave an error of
    ``|u''| (h 2^-30)^2/2``)."""
    lo = 0.0
    hi = h
    v_lo = v
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        c = coefficients(w, xi, mid)
        _, vm = advance(c, u, v, a0, b)
        if (vm > 0.0) == (v_lo > 0.0) and vm != 0.0:
            lo = mid
            v_lo = vm
        else:
            hi = mid
    c = coefficients(w, xi, 0.5 * (lo + hi))
    um, _ = advance(c, u, v, a0, b)
    return um


@kernel
def p3_bound(w, xi, u, v):
    """P3's bound on every later ``|a|`` of the free base: ``w sqrt(1 + 4 xi^2) sqrt(u'^2 + w^2 u^2)``."""
    return w * math.sqrt(1.0 + 4.0 * xi * xi) * math.sqrt(v * v + w * w * u * u)


@kernel
def step_peak(w, xi, a_s, a_e, ah, ahd, k, a0, b, h, target):
    """``(U, L)``: an upper bound ``U`` of ``|a|`` over a step of length ``h`` and the largest ``|a|``
    evaluated, ``L``. Pieces whose bound ``max |a(ends)| + K l^2/8`` exceeds ``max(target, L)`` are
    halved (down to ``h 2^-30``), so ``U <= max(target, L)`` but for such slivers."""
    best = max(abs(a_s), abs(a_e))
    u = 0.0
    st_lo = np.empty(34)
    st_alo = np.empty(34)
    st_hi = np.empty(34)
    st_ahi = np.empty(34)
    st_lo[0] = 0.0
    st_alo[0] = a_s
    st_hi[0] = h
    st_ahi[0] = a_e
    top = 1
    tiny = h * 2.0 ** -30
    while top > 0:
        top -= 1
        lo = st_lo[top]
        hi = st_hi[top]
        alo = st_alo[top]
        ahi = st_ahi[top]
        ub = max(abs(alo), abs(ahi)) + 0.125 * k * (hi - lo) * (hi - lo)
        if ub <= max(target, best) or hi - lo <= tiny or top + 2 > 34:
            u = max(u, ub)
            continue
        mid = 0.5 * (lo + hi)
        am = acceleration_at(w, xi, ah, ahd, a0, b, mid)
        best = max(best, abs(am))
        st_lo[top] = lo
        st_alo[top] = alo
        st_hi[top] = mid
        st_ahi[top] = am
        st_lo[top + 1] = mid
        st_alo[top + 1] = am
        st_hi[top + 1] = hi
        st_ahi[top + 1] = ahi
        top += 2
    return u, best


@kernel
def _sweep(w, xi, acc, dt, scale, t_limit, slack, target):
    """One pass of :func:`stuck_peak`: ``(M, t_proof, L)`` with every step's bound refined down to
    ``target`` (:func:`step_peak`; ``target = inf``: the cheap bound, no refinement), ``L`` the largest
    ``|a|`` met at the steps' ends and inside them."""
    n = acc.shape[0]
    c = coefficients(w, xi, dt)
    u = 0.0
    v = 0.0
    m = 0.0
    low = 0.0
    t = 0.0
    j = 0
    while True:
        if j < n - 1:
            a0 = scale * acc[j]
            b = scale * (acc[j + 1] - acc[j]) / dt
        else:  # after the record: the ground still
            a0 = 0.0
            b = 0.0
            t = (n - 1) * dt + (j - (n - 1)) * dt
            p3 = p3_bound(w, xi, u, v)
            if p3 <= (1.0 + slack) * m:
                return max(m, p3), t, low
            if t > t_limit:
                return m, math.inf, low
        a_s, ah, ahd, k = free_part(w, xi, u, v, a0, b)
        u, v = advance(c, u, v, a0, b)
        a_e = base_acceleration(w, xi, u, v)
        ub = max(abs(a_s), abs(a_e)) + 0.125 * k * dt * dt
        low = max(low, abs(a_e))
        if ub > target and ub > m:
            ub, best = step_peak(w, xi, a_s, a_e, ah, ahd, k, a0, b, dt, target)
            low = max(low, best)
        m = max(m, ub)
        j += 1


@kernel
def stuck_peak(w, xi, acc, dt, scale, t_limit, slack, tol):
    """``(M, t_proof)``: a bound of ``|a|`` of the base carrying the standing block, from rest at t = 0,
    under ``scale * acc`` (piecewise linear, zero after the last sample), at all times.

    The base is advanced exactly from sample to sample (and on by ``dt`` after the record, the
    ground still); every step contributes ``max |a(ends)| + K dt^2/8`` (module notes), which
    bounds ``|a|`` inside it. After the record, from the first sample time ``t_proof`` at which P3's
    bound on every later ``|a|`` is at most ``(1 + slack)`` times the bound so far, ``M`` is the larger
    of the two: ``|a(t)| <= M`` for all ``t >= 0``, and P3's bound at every time from ``t_proof`` on is
    ``<= M``. When ``t_proof`` would exceed ``t_limit``: ``(M, inf)`` with ``M`` the bound up to there.

    Tight: a first pass finds the largest ``|a|`` at the samples, ``L``; the second refines the bound of
    every step that exceeds ``(1 + tol) L`` by halving it (:func:`step_peak`), so that
    ``M <= (1 + tol) sup |a|`` (and ``(1 + slack)`` where P3's bound sets it). The arithmetic is the
    kernel's own (``advance`` of :func:`coefficients`, each sample interval's ``a0`` and slope formed as
    :func:`rockcli.kernels.steps._advance_segment` forms them).
    """
    _, _, low = _sweep(w, xi, acc, dt, scale, t_limit, slack, math.inf)
    m, t_proof, _ = _sweep(w, xi, acc, dt, scale, t_limit, slack, (1.0 + tol) * low)
    return m, t_proof


# ---------------------------------------------------------------------------------------------
# A norm that the free base never increases, and the base's response to a whole record (the early stop P9
# of rockcli.kernels.driver_end)
# ---------------------------------------------------------------------------------------------
@kernel
def base_norm(xi):
    """``(c, k_a, k_u)`` of the norm ``S = sqrt(v^2 + 2 c v y + y^2)`` (``v = u'``, ``y = w u``) of a
    linear base ``u'' + 2 xi w u' + w^2 u = -ag`` (P9 in :mod:`rockcli.kernels.driver_end`).

    ``c = xi`` for ``xi <= 1/2``, ``xi/(1 + xi^2)`` above (P8's choice: ``0 <= c < 1`` and the free
    base's ``dS^2/dt = -w Q`` with ``Q >= 0``), so S never grows with the ground still and grows at
    most as fast as ``|ag|`` otherwise. The base's absolute acceleration and displacement are bounded
    by S: ``|w^2 u + 2 xi w u'| <= k_a w S``, ``|u| <= k_u S/w`` (the largest of a linear form over the
    ellipse ``S = 1``: ``k_a^2 = (4 xi^2 - 4 c xi + 1)/(1 - c^2)``, ``k_u^2 = 1/(1 - c^2)``).
    """
    c = xi if xi <= 0.5 else xi / (1.0 + xi * xi)
    k_a = math.sqrt((4.0 * xi * xi - 4.0 * c * xi + 1.0) / (1.0 - c * c))
    return c, k_a, 1.0 / math.sqrt(1.0 - c * c)


@kernel(inline='always')
def base_norm_of(c, w, u, v):
    """The norm ``S`` of :func:`base_norm` of the base state ``(u, v)`` [m/s]."""
    y = w * u
    return math.sqrt(max(v * v + 2.0 * c * v * y + y * y, 0.0))


@kernel
def linear_base_table(acc, dt, w, xi):
    """The linear base's response to a record of unit scale, from rest at t = 0 (the block riding on it
    throughout), one row per sample: ``u``, ``u'`` and the largest later value of its norm.

    Column 2 of row k bounds ``S`` (:func:`base_norm`) over every time from sample k on: the suffix
    maximum of ``S_j + dt (|a_j| + |a_j+1|)/2``, since inside a sample interval S grows by at most
    ``int |ag| <= dt (|a_j| + |a_j+1|)/2`` (|ag| of a linear piece is at most the chord of |a|), and
    after the last sample (the ground still) S never grows. The steps are exact (:func:`coefficients`, to
    rounding).
    """
    n = acc.shape[0]
    cf = coefficients(w, xi, dt)
    c = base_norm(xi)[0]
    tab = np.empty((n, 3))
    u = 0.0
    v = 0.0
    for k in range(n):
        tab[k, 0] = u
        tab[k, 1] = v
        S = base_norm_of(c, w, u, v)
        if k < n - 1:
            a0 = acc[k]
            slope = (acc[k + 1] - a0) / dt
            tab[k, 2] = S + 0.5 * dt * (abs(a0) + abs(acc[k + 1]))
            u, v = advance(cf, u, v, a0, slope)
        else:
            tab[k, 2] = S
    for k in range(n - 2, -1, -1):
        tab[k, 2] = max(tab[k, 2], tab[k + 1, 2])
    return tab

