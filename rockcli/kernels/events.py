"""Events of a step and what happens at them: the impact map and the rest rule, uplift of a block on
a hysteretic base, reversals of the base, peaks, and the history rows.

Every event is located on the step's quartic dense output (:mod:`rockcli.kernels.polynomials`);
the state the run goes on from at an impact, an uplift or a reversal is the step retaken to it
(:func:`rockcli.kernels.dopri._restep_rows`), which is more accurate than the dense output.
"""

from __future__ import annotations

import numpy as np

from rockcli.kernels.bearings import base_force, element_states, u_at_force
from rockcli.kernels.dopri import _dense
from rockcli.kernels.ground import ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (FOUNDATION_BILINEAR, FOUNDATION_RIGID, H_AG, H_FB, H_KIND, H_T, H_TH, H_THD, H_U,
                                    H_UD, H_Z, H_Z2, HK_GRID, HK_PEAK, N_HIST, O_N_UPLIFTS, O_T_UPLIFT, O_UPLIFTED,
                                    P_COSA, P_DU, P_ETA, P_G, P_P2, P_REST, W_TMP, W_Y)
from rockcli.kernels.polynomials import _first_down, _first_exceed, _poly


# ---------------------------------------------------------------------------------------------
# Impact and rest
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def impact_map(prm, thd1):
    """Velocities just after an impact at theta = 0: ``(theta_dot+, jump of u_dot)``.

    Eqs (14)-(19) with ``gamma = m/(m + m_b)`` (reading note 3): the total horizontal momentum of
    block + base and the block's angular momentum about the new pivot are kept, which gives
    ``theta_dot+ = eta theta_dot-`` and ``u_dot+ = u_dot- + DU theta_dot-`` (``DU = 0`` on a rigid
    foundation). The Bouc-Wen variables of a hysteretic base do not jump: u does not.

    With a coefficient of restitution E (``--restitution``, :mod:`rockcli.models.impact`) ``eta`` is
    ``E`` on a rigid foundation and ``1 - 4 (1 - E)/(4 - 3 gamma cos^2 alpha)`` on an isolated base,
    and ``DU = gamma h (1 - eta)`` still keeps the horizontal momentum. Every ``0 <= eta <= 1`` with
    that ``DU`` changes the kinetic energy by ``gamma (2 R^2/3 - gamma h^2/2) (eta^2 - 1) theta_dot-^2
    <= 0`` (per unit total mass): impacts never add energy, which is what the end-of-run proofs use.
    """
    return prm[P_ETA] * thd1, prm[P_DU] * thd1


@kernel(inline='always')
def comes_to_rest(prm, a_rest, thd2, thr, alpha):
    """Rest rule after an impact: the block could not lift off under the current base acceleration
    ``a_rest``, and the rotation it could still reach against the restoring
    ``p^2 cos(alpha) (tan(alpha) - |a|/g)``, ``thd^2 / (2 p^2 cos(alpha) (tan(alpha) - |a|/g))``, is below
    ``rest_tol * alpha`` (a plastic impact ends the train of impacts, momentum kept). With a = 0
    this is the free-rocking reach ``thd^2 / (2 p^2 sin(alpha))``."""
    c_rest = prm[P_P2] * prm[P_COSA] * (thr - abs(a_rest)) / prm[P_G]
    return c_rest > 0.0 and thd2 * thd2 < 2.0 * c_rest * prm[P_REST] * alpha


# ---------------------------------------------------------------------------------------------
# Hysteretic base: reversals and uplift inside a step
# ---------------------------------------------------------------------------------------------
REV_NONE = 0  # u moved one way through the step
REV_AT = 1  # u reverses inside the step: the step ends there
REV_WRONG_START = 2  # u moved against the anchor's direction from the start: flip it, retake the step


@kernel
def reversal_check(W, hs, d, tol):
    """Did u keep moving in direction ``d`` through the step? ``(code, sigma)``.

    The Bouc-Wen variables follow u exactly only while u moves one way, so a step must end where
    u reverses. ``REV_AT``: ``d u_dot`` falls to 0 after the base moved forward by more than ``tol``
    (the error tolerance of u): the step is cut at that sigma. ``REV_WRONG_START``: the base moved
    back by more than ``tol`` before moving forward (a start at ``u_dot = 0`` whose direction was
    guessed wrong). A back-and-forth within ``tol`` is accepted (the z error it makes is below the
    error the tolerance allows).
    """
    cv = _dense(W, hs, np.int64(3), d)
    cu = _dense(W, hs, np.int64(2), d)
    sr = _first_down(cv, 0.0, 0.0, 1.0)
    if sr >= 0.0 and _poly(cu, sr) - cu[0] > tol:
        return REV_AT, sr
    for k in range(1, 17):
        D = _poly(cu, k / 16.0) - cu[0]
        if D < -tol:
            return REV_WRONG_START, 0.0
        if D > tol:
            break
    return REV_NONE, 1.0


@kernel
def hysteretic_uplift(fkind, prm, hy, cu, sig_lim, thr):
    """First sigma in [0, sig_lim] at which a block stuck on a hysteretic base lifts: ``(sigma, s)``,
    else ``(-1, 0)``; ``s`` is the corner it pivots on.

    In the stuck phase the absolute base acceleration is the bearing force ``F(u)``, which on the
    step's branch is a strictly decreasing function of u alone (``dF/du = -w^2 - Q dz/du``, with
    ``dz/du > 0``; two elements in series likewise). Hence ``|F| > g tan(alpha)`` exactly when u
    leaves ``[u_lo, u_hi]``, the displacements at which ``F = +g tan(alpha)`` and ``-g tan(alpha)``
    (:func:`rockcli.kernels.bearings.u_at_force`), and the first exit of the quartic of u from that
    interval is found by :func:`rockcli.kernels.polynomials._first_exceed` (rigorous sampling).
    A quick test first: ``|u(sigma) - u(0)| <= sum |c_k| sig_lim^k`` and F decreasing bound the
    step's force range without solving anything.
    """
    L = sig_lim
    c = (cu[0], cu[1] * L, cu[2] * L * L, cu[3] * L * L * L, cu[4] * L * L * L * L)
    span = abs(c[1]) + abs(c[2]) + abs(c[3]) + abs(c[4])
    ua = hy[0]
    a = c[0] - span
    b = c[0] + span
    Fa = base_force(fkind, prm, a, 0.0, hy)  # the largest force the step can see
    Fb = base_force(fkind, prm, b, 0.0, hy)  # the smallest
    if Fa <= thr and Fb >= -thr:
        return -1.0, 0.0
    far = 2.0 * span + abs(ua) + 1.0
    u_lo = u_at_force(fkind, prm, hy, thr, a, c[0]) if Fa > thr else c[0] - far
    u_hi = u_at_force(fkind, prm, hy, -thr, c[0], b) if Fb < -thr else c[0] + far
    mid = 0.5 * (u_lo + u_hi)
    half = 0.5 * (u_hi - u_lo)
    cs = (c[0] - mid, c[1], c[2], c[3], c[4])
    sig, sg = _first_exceed(cs, half)
    if sig < 0.0:
        return -1.0, 0.0
    # u above u_hi: F < -g tan(alpha), the base accelerates to -x and the block pivots on its right
    # corner (s = +1); below u_lo the other way
    return sig * L, sg


# ---------------------------------------------------------------------------------------------
# Peaks, uplift bookkeeping, history rows
# ---------------------------------------------------------------------------------------------
@kernel
def _u_extremum(W, hs, sig_end):
    """|u| at an extremum of u inside [0, sig_end] of the last step (u_dot changes sign), else -1."""
    c = _dense(W, hs, np.int64(3), 1.0 if W[W_Y, 3] > 0.0 else -1.0)
    sx = _first_down(c, 0.0, 0.0, sig_end)
    if sx < 0.0:
        return -1.0
    return abs(_poly(_dense(W, hs, np.int64(2), 1.0), sx))


@kernel(inline='always')
def _count_uplift(out, t):
    out[O_N_UPLIFTS] += 1
    if out[O_UPLIFTED] == 0.0:
        out[O_UPLIFTED] = 1.0
        out[O_T_UPLIFT] = t


@kernel
def _hist_push(H, n, t, ag, W, row, z1, z2, fb, kind):
    """Append the row ``t, ag, theta, theta_dot, u, u_dot, z1, z2, bearing force, kind`` (grows ``H``;
    ``kind`` is one of the ``HK_*`` row kinds)."""
    if n >= H.shape[0]:
        H2 = np.empty((2 * H.shape[0], N_HIST))
        for i in range(n):  # an explicit copy: a slice assignment compiles numba's generic broadcasting
            for j in range(N_HIST):
                H2[i, j] = H[i, j]
        H = H2
    H[n, H_T] = t
    H[n, H_AG] = ag
    H[n, H_TH] = W[row, 0]
    H[n, H_THD] = W[row, 1]
    H[n, H_U] = W[row, 2]
    H[n, H_UD] = W[row, 3]
    H[n, H_Z] = z1
    H[n, H_Z2] = z2
    H[n, H_FB] = fb
    H[n, H_KIND] = kind
    return H, n + 1


@kernel
def _hist_peak(H, n, t, ag, W, row):
    """Append a peak row (``HK_PEAK``): the state ``W[row]`` at the turning point ``t`` of theta, with
    theta_dot = 0 exactly and no bearing variables (NaN)."""
    H, n = _hist_push(H, n, t, ag, W, row, np.nan, np.nan, np.nan, HK_PEAK)
    H[n - 1, H_THD] = 0.0
    return H, n



@kernel
def _hist_state(H, n, t, ag, fkind, prm, hy, W, row, kind):
    """Append the state ``W[row]`` at ``t`` with the bearings' z's and force for the anchor ``hy``
    (zeros on a rigid foundation)."""
    z1 = 0.0
    z2 = 0.0
    fb = 0.0
    if fkind != FOUNDATION_RIGID:
        u = W[row, 2]
        fb = -base_force(fkind, prm, u, W[row, 3], hy)
        if fkind >= FOUNDATION_BILINEAR:
            z1, z2, _ = element_states(fkind, prm, hy, u)
    return _hist_push(H, n, t, ag, W, row, z1, z2, fb, kind)


@kernel
def _hist_grid(H, n, kg, hdt, t0, hs, t_end, fkind, prm, hy, seg, epar, W, i0, nst):
    """Append the grid rows (``HK_GRID``) at the times ``kg hdt, (kg + 1) hdt, ... <= t_end`` of the
    last step (from ``t0``, length ``hs``; ``hs = 0``: the state ``W[W_Y]`` held, a block stuck on a
    rigid foundation): the step's dense output of the states ``i0 .. nst - 1`` (those below ``i0``, not
    integrated, held at ``W[W_Y]``: theta = theta_dot = 0 of a block stuck on its base), the ground
    acceleration of the excitation segment
    itself, the bearings' variables on the step's anchor ``hy`` (a step never crosses a reversal of
    the base, nor a segment end). Returns ``(H, n, kg)`` with ``kg`` the next grid index.

    Call it before the step's events move ``W[W_Y]`` (the dense output needs it); a step cut short
    by an event drops its grid rows past the event with :func:`_hist_grid_cut`."""
    while kg * hdt <= t_end:
        tg = kg * hdt
        sig = (tg - t0) / hs if hs > 0.0 else 0.0
        for i in range(i0):
            W[W_TMP, i] = W[W_Y, i]
        for i in range(i0, nst):
            W[W_TMP, i] = _poly(_dense(W, hs, i, 1.0), max(sig, 0.0))
        H, n = _hist_state(H, n, tg, ground_at(tg, seg, epar), fkind, prm, hy, W, W_TMP, HK_GRID)
        kg += 1
    return H, n, kg


@kernel
def _hist_grid_cut(H, n0, n, kg, t_cut):
    """Drop the grid rows appended from row ``n0`` on that lie after ``t_cut`` (the event that
    ended the step early), keeping the other rows in order: ``(n, kg)``."""
    m = n0
    for i in range(n0, n):
        if H[i, H_KIND] == HK_GRID and H[i, H_T] > t_cut:
            kg -= 1
            continue
        if m != i:
            for j in range(N_HIST):
                H[m, j] = H[i, j]
        m += 1
    return m, kg
