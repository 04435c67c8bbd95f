"""The bearings' force on the base, per foundation family, and the Bouc-Wen element solved exactly.

Forces are per unit total mass ``m + m_b`` [m/s^2]; ``F`` is the force the bearings exert on the
base (it opposes ``u``): linear ``F = -w^2 u - 2 xi w u'`` (Eq 8); single concave sliding and
lead-rubber ``F = -w^2 u - Q z`` (Eqs 33, 36; ``Q = mu g`` or ``Q_LRB/(m + m_b)``); double concave
``F = -(k1 u1 + q1 z1) = -(k2 u2 + q2 z2)`` (two single concave surfaces in series, below).

The Bouc-Wen element, solved along the path of u (the stiff treatment)
------------------------------------------------------------------------
Eq (34) with ``A = 1`` and ``beta + gamma_bw = 1`` (so that ``|z| <= 1`` and ``Q`` is the strength):
``u_y z' = u' (1 - |z|^n (gamma_bw sgn(u' z) + beta))``. It is rate independent: z depends on the
path of u, not on time. While u moves one way, ``d = sign(u')``, the variable ``y = d z`` obeys
``dy/dx = g(y)`` with ``x = d (u - u_a)/u_y`` and

* ``g(y) = 1 - y^n`` for ``y >= 0`` (loading: ``|z|`` grows towards 1, the bearing slides),
* ``g(y) = 1 + c |y|^n`` for ``y < 0``, ``c = gamma_bw - beta >= 0`` (unloading: the elastic branch;
  ``c = 0``, the default, makes it exactly linear in u).

``g > 0``, so ``Phi(y) = int_0^y dy'/g(y')`` is strictly increasing and the exact solution is
``y = Phi^-1(Phi(y_a) + x)``; :func:`bw_phi` and :func:`bw_phi_inv` are its closed forms for n = 1
and n = 2 (``atanh``/``tanh`` on the loading side for n = 2). The driver stores the *branch
coordinate* ``xi_a = Phi(d z_a)`` at the start of every step (the anchor) and ends steps where u
reverses (``u' = 0``), so inside a step z is an analytic function of u and the Dormand-Prince
stages see a smooth, non-stiff right-hand side. The stiffness ``|dz'/dz| ~ n |u'|/u_y`` of Eq (34)
(4e3 to 1e5 1/s for u_y = 0.25 to 0.01 mm) never enters the integrator; what remains is the
physical elastic branch, ``Q/u_y`` per unit mass (period ~0.14 s at mu = 5 %, u_y = 0.25 mm), which
the error control resolves like any oscillation.

Double concave bearing: the articulated slider as a massless node
------------------------------------------------------------------
Two single concave surfaces in series (the paper's model of Figure 10): surface i has
``f_i = k_i u_i + q_i z_i``, ``k_i = g/R_i_eff``, ``q_i = mu_i g``, its own Bouc-Wen variable with yield
displacement ``u_y/2`` (so that the bearing as a whole yields at ``u_y``), and ``u = u1 + u2``. The
slider is massless: the two surface forces balance, ``f1(u1) = f2(u - u1)``. Each ``f_i`` increases
with ``u_i``, so for a given u the balance has exactly one root ``u1`` between ``u1_a`` and
``u1_a + (u - u_a)`` (:func:`dcss_split`, safeguarded Newton to round-off). A small slider mass would
instead add a contact oscillation of period ``2 pi sqrt(m_s u_y/(mu W))`` (microseconds): a stiff mode
with no bearing on the rocking. The states are u, u', z1, z2; ``u1`` follows from them.
"""

from __future__ import annotations

import math

from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (FOUNDATION_BILINEAR, FOUNDATION_DCSS, FOUNDATION_LINEAR, P_BWC, P_BWN, P_K1,
                                    P_K2, P_Q1, P_Q2, P_RTOL, P_SC0, P_UY1, P_UY2, P_W, P_XI)

_HALF_PI = 0.5 * math.pi


# ---------------------------------------------------------------------------------------------
# The Bouc-Wen branch in closed form
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def bw_slope(y, n, c):
    """``g(y) = dy/dx`` on the branch (``u_y dz/du`` in the direction of motion)."""
    if y >= 0.0:
        return 1.0 - (y * y if n == 2.0 else y)
    a = -y
    return 1.0 + c * (a * a if n == 2.0 else a)


@kernel
def bw_phi(y, n, c):
    """Branch coordinate ``Phi(y) = int_0^y dy'/g(y')`` (``y <= 1``; ``+inf`` at ``y = 1``)."""
    if y >= 0.0:
        if y >= 1.0:
            return math.inf
        if n == 2.0:
            return math.atanh(y)
        return -math.log1p(-y)
    a = -y
    if c == 0.0:
        return y
    if n == 2.0:
        rc = math.sqrt(c)
        return -math.atan(rc * a) / rc
    return -math.log1p(c * a) / c


@kernel(inline='always')
def bw_phi_inv(xi, n, c):
    """``y = Phi^-1(xi)``: the branch variable at coordinate ``xi``."""
    if xi >= 0.0:
        if n == 2.0:
            return math.tanh(xi)
        return -math.expm1(-xi)
    if c == 0.0:
        return xi
    if n == 2.0:
        rc = math.sqrt(c)
        # the unloading branch of n = 2 reaches y = -inf at xi = -pi/(2 sqrt c); a step never gets
        # there (|z| <= 1 on the path), the clamp only keeps a wild trial stage finite
        return -math.tan(min(-rc * xi, _HALF_PI - 1e-9)) / rc
    return -math.expm1(-c * xi) / c


@kernel(inline='always')
def bw_z(xi_a, d, du, uy, n, c):
    """``(z, dz/du)`` of an element anchored at branch coordinate ``xi_a``, moving in direction ``d``,
    after a displacement ``du`` across it (exact along a path that moves one way)."""
    y = bw_phi_inv(xi_a + d * du / uy, n, c)
    return d * y, bw_slope(y, n, c) / uy


# ---------------------------------------------------------------------------------------------
# Double concave: the slider position by force balance
# ---------------------------------------------------------------------------------------------
@kernel
def dcss_split(prm, hy, u):
    """Massless slider: ``(u1, z1, z2, dz1/du1, dz2/du2)`` at base displacement ``u``.

    Solves ``k1 u1 + q1 z1(u1) = k2 (u - u1) + q2 z2(u - u1)``; the left side increases and the
    right side decreases with ``u1``, so the root is unique and lies between ``u1_a`` and
    ``u1_a + (u - u_a)``. Newton from the anchor's tangent split, kept inside that bracket
    (bisection when a step leaves it), to round-off.
    """
    ua, d, xi1, u1a, xi2, split = hy
    k1 = prm[P_K1]
    k2 = prm[P_K2]
    q1 = prm[P_Q1]
    q2 = prm[P_Q2]
    uy1 = prm[P_UY1]
    uy2 = prm[P_UY2]
    n = prm[P_BWN]
    c = prm[P_BWC]
    u2a = ua - u1a
    du = u - ua
    lo = u1a if du >= 0.0 else u1a + du
    hi = u1a + du if du >= 0.0 else u1a
    x = u1a + split * du
    tol = 4.4e-16 * (abs(u1a) + abs(du) + uy1)
    z1 = 0.0
    z2 = 0.0
    s1 = 0.0
    s2 = 0.0
    for _ in range(80):
        z1, s1 = bw_z(xi1, d, x - u1a, uy1, n, c)
        z2, s2 = bw_z(xi2, d, (u - x) - u2a, uy2, n, c)
        phi = k1 * x + q1 * z1 - k2 * (u - x) - q2 * z2
        if phi > 0.0:
            hi = x
        elif phi < 0.0:
            lo = x
        else:
            break
        step = phi / (k1 + q1 * s1 + k2 + q2 * s2)
        xn = x - step
        if not (lo <= xn <= hi):
            xn = 0.5 * (lo + hi)
        if abs(xn - x) <= tol:
            break
        x = xn
    return x, z1, z2, s1, s2


@kernel
def dcss_split_ratio(prm, z1, z2, d):
    """Share of a small increment of u taken by surface 1 moving in direction ``d``:
    ``K2/(K1 + K2)`` with the tangent stiffnesses ``K_i = k_i + q_i g(d z_i)/u_yi``."""
    n = prm[P_BWN]
    c = prm[P_BWC]
    K1 = prm[P_K1] + prm[P_Q1] * bw_slope(d * z1, n, c) / prm[P_UY1]
    K2 = prm[P_K2] + prm[P_Q2] * bw_slope(d * z2, n, c) / prm[P_UY2]
    return K2 / (K1 + K2)


# ---------------------------------------------------------------------------------------------
# Force of each family, its slope, the element states
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def base_force(fkind, prm, u, ud, hy):
    """Force of the bearings on the base per unit total mass, ``F`` [m/s^2] (see the module notes).

    The linear force is written out here (inlined into the right-hand side); the hysteretic ones
    are a call, which keeps the linear and rigid steps as lean as they were.
    """
    if fkind == FOUNDATION_LINEAR:
        w = prm[P_W]
        return -w * w * u - 2.0 * prm[P_XI] * w * ud
    return hysteretic_force(fkind, prm, u, hy)


@kernel
def hysteretic_force(fkind, prm, u, hy):
    """``F`` of a single Bouc-Wen element (``-w^2 u - Q z``) or of two in series (``-(k1 u1 + q1 z1)``)."""
    if fkind == FOUNDATION_BILINEAR:
        w = prm[P_W]
        z, _ = bw_z(hy[2], hy[1], u - hy[0], prm[P_UY1], prm[P_BWN], prm[P_BWC])
        return -w * w * u - prm[P_Q1] * z
    u1, z1, _, _, _ = dcss_split(prm, hy, u)
    return -(prm[P_K1] * u1 + prm[P_Q1] * z1)


@kernel
def force_slope(fkind, prm, hy, u):
    """``(F, dF/du)`` of a hysteretic bearing along the step's branch (velocity terms excluded)."""
    if fkind == FOUNDATION_BILINEAR:
        w = prm[P_W]
        z, dz = bw_z(hy[2], hy[1], u - hy[0], prm[P_UY1], prm[P_BWN], prm[P_BWC])
        return -w * w * u - prm[P_Q1] * z, -w * w - prm[P_Q1] * dz
    u1, z1, _, s1, s2 = dcss_split(prm, hy, u)
    K1 = prm[P_K1] + prm[P_Q1] * s1
    K2 = prm[P_K2] + prm[P_Q2] * s2
    return -(prm[P_K1] * u1 + prm[P_Q1] * z1), -K1 * K2 / (K1 + K2)


@kernel
def force_rate(fkind, prm, hy, u, ud, udd):
    """``(F, dF/dt)`` of the bearings at ``(u, u', u'')`` (on the step's branch for a hysteretic one)."""
    if fkind == FOUNDATION_LINEAR:
        w = prm[P_W]
        c = 2.0 * prm[P_XI] * w
        return -w * w * u - c * ud, -w * w * ud - c * udd
    F, dF = force_slope(fkind, prm, hy, u)
    return F, dF * ud


@kernel
def element_states(fkind, prm, hy, u):
    """``(z1, z2, u1)`` at ``u`` on the step's branch (``z2 = u1 = 0`` for a single element)."""
    if fkind == FOUNDATION_BILINEAR:
        z, _ = bw_z(hy[2], hy[1], u - hy[0], prm[P_UY1], prm[P_BWN], prm[P_BWC])
        return z, 0.0, 0.0
    u1, z1, z2, _, _ = dcss_split(prm, hy, u)
    return z1, z2, u1


@kernel
def tangent_stiffness(fkind, prm, z1, z2, d):
    """Tangent stiffness per unit total mass, ``-dF/du`` [1/s^2], for motion in direction ``d``
    from a state with element variables ``z1`` (``z2``)."""
    n = prm[P_BWN]
    c = prm[P_BWC]
    if fkind == FOUNDATION_BILINEAR:
        w = prm[P_W]
        return w * w + prm[P_Q1] * bw_slope(d * z1, n, c) / prm[P_UY1]
    K1 = prm[P_K1] + prm[P_Q1] * bw_slope(d * z1, n, c) / prm[P_UY1]
    K2 = prm[P_K2] + prm[P_Q2] * bw_slope(d * z2, n, c) / prm[P_UY2]
    return K1 * K2 / (K1 + K2)


@kernel
def z_sensitivity(fkind, prm, hy):
    """Largest ``|dz_i/du|`` along the step [1/m]: ``g/u_y`` at the anchor, which is the largest on
    the step because g never grows while u moves one way (``c >= 0``). Used by the error norm of u."""
    n = prm[P_BWN]
    c = prm[P_BWC]
    g1 = bw_slope(bw_phi_inv(hy[2], n, c), n, c) / prm[P_UY1]
    if fkind == FOUNDATION_BILINEAR:
        return g1
    return max(g1, bw_slope(bw_phi_inv(hy[4], n, c), n, c) / prm[P_UY2])


#: Knee of a bearing's loop: a step moves each element's branch coordinate by at most KNEE_DX ...
KNEE_DX = 1.0
#: ... unless KNEE_C h A, the error a step can make on an unresolved knee of force A, is within tolerance.
KNEE_C = 0.1


@kernel(inline='always')
def _knee_h(q, uy, y, share, ud, udd, tol_v):
    """Step bound of one element (:func:`knee_step`)."""
    A = q * (1.0 - y)  # the force the element can still add on this branch
    if A <= 0.0 or share <= 0.0:
        return math.inf
    h_tol = tol_v / (KNEE_C * A)
    # the step in which share (|u'| h + |u''| h^2/2), the element's displacement, reaches KNEE_DX u_y
    b = share * abs(ud)
    a = 0.5 * share * abs(udd)
    cc = KNEE_DX * uy
    den = b + math.sqrt(b * b + 4.0 * a * cc)
    h_x = 2.0 * cc / den if den > 0.0 else math.inf
    return max(h_tol, h_x)


@kernel
def knee_step(fkind, prm, hy, ud, udd):
    """Largest step [s] from the anchor ``hy`` (base velocity ``ud``, acceleration ``udd``) that
    resolves the knees of the hysteretic elements ahead.

    Going from its elastic branch to sliding, an element's ``z`` closes on its limit exponentially
    in the branch coordinate ``x = d du_i/u_yi`` (``1 - y ~ exp(-2x)`` for n = 2), so its force
    ``q z`` has a knee of width ~``u_y`` in u. A step many widths long sees the knee only in its
    first stage: the step then errs by about ``b1 h A`` in u' (``b1 = 35/384``, ``A = q (1 - y)``
    the force still to come on the branch) while the embedded estimate sees only ``|e1| h A``
    (``e1 = -71/57600``), ~70 times less (measured on dcss-ricker at rtol 1e-8: actual local
    errors up to 10 times the tolerance with estimates below 1). Hence a step moves each element by
    at most ``KNEE_DX u_yi`` (``share`` of du: the DCSS split at the anchor), where the estimate
    is reliable again, unless ``KNEE_C h A`` is within the tolerance of u' (``tol_v``): a saturated
    element (``y ~ 1``) or a weak one does not limit the step.
    """
    n = prm[P_BWN]
    c = prm[P_BWC]
    tol_v = prm[P_RTOL] * max(abs(ud), prm[P_SC0 + 3])
    y1 = bw_phi_inv(hy[2], n, c)
    if fkind == FOUNDATION_BILINEAR:
        return _knee_h(prm[P_Q1], prm[P_UY1], y1, 1.0, ud, udd, tol_v)
    y2 = bw_phi_inv(hy[4], n, c)
    return min(_knee_h(prm[P_Q1], prm[P_UY1], y1, hy[5], ud, udd, tol_v),
               _knee_h(prm[P_Q2], prm[P_UY2], y2, 1.0 - hy[5], ud, udd, tol_v))


@kernel
def knee_ratio(fkind, prm, hy, u, h, ud):
    """How far a step of size ``h`` from the anchor ``hy`` (base velocity ``ud``) to the
    displacement ``u`` moved the elements that are in a knee: the largest ``|dx_i|/KNEE_DX`` over
    the elements with ``KNEE_C h A_i`` above the tolerance of u' (0 when none is), see
    :func:`knee_step`. A step with a ratio above 1 is retaken shorter: the a priori bound of
    :func:`knee_step` uses the DCSS split at the anchor, and a surface's share of du grows as
    it yields (up to ~10 times within a step, measured on dcss-ricker)."""
    n = prm[P_BWN]
    c = prm[P_BWC]
    tol_v = prm[P_RTOL] * max(abs(ud), prm[P_SC0 + 3])
    ua = hy[0]
    if fkind == FOUNDATION_BILINEAR:
        if KNEE_C * h * prm[P_Q1] * (1.0 - bw_phi_inv(hy[2], n, c)) <= tol_v:
            return 0.0
        return abs(u - ua) / (KNEE_DX * prm[P_UY1])
    r = 0.0
    u1a = hy[3]
    if KNEE_C * h * prm[P_Q1] * (1.0 - bw_phi_inv(hy[2], n, c)) > tol_v:
        u1, _, _, _, _ = dcss_split(prm, hy, u)
        r = abs(u1 - u1a) / (KNEE_DX * prm[P_UY1])
    if KNEE_C * h * prm[P_Q2] * (1.0 - bw_phi_inv(hy[4], n, c)) > tol_v:
        u1, _, _, _, _ = dcss_split(prm, hy, u)
        r = max(r, abs((u - u1) - (ua - u1a)) / (KNEE_DX * prm[P_UY2]))
    return r


@kernel(inline='always')
def motion_direction(ud, d):
    """The direction of the base's motion for the next step: the sign of ``u'`` (``d``, the current one, if
    ``u'`` is 0), the ``d_new`` of :func:`reanchor`."""
    if ud > 0.0:
        return 1.0
    if ud < 0.0:
        return -1.0
    return d


@kernel
def reanchor(fkind, prm, hy, u, d_new):
    """The anchor at displacement ``u`` reached on the branch of ``hy``, for motion in ``d_new``.

    Same direction: the branch coordinate moves on by ``d du/u_y`` (no round trip through z, so
    a saturated ``z = 1`` keeps its coordinate). Reversal: ``xi = Phi(d_new z)`` on the new branch.
    """
    ua, d, xi1, u1a, xi2, split = hy
    n = prm[P_BWN]
    c = prm[P_BWC]
    if fkind == FOUNDATION_BILINEAR:
        x1 = xi1 + d * (u - ua) / prm[P_UY1]
        if d_new != d:
            x1 = bw_phi(-bw_phi_inv(x1, n, c), n, c)
        return (u, d_new, x1, 0.0, 0.0, 0.0)
    u1, z1, z2, _, _ = dcss_split(prm, hy, u)
    x1 = xi1 + d * (u1 - u1a) / prm[P_UY1]
    x2 = xi2 + d * ((u - u1) - (ua - u1a)) / prm[P_UY2]
    if d_new != d:
        x1 = bw_phi(-bw_phi_inv(x1, n, c), n, c)
        x2 = bw_phi(-bw_phi_inv(x2, n, c), n, c)
    return (u, d_new, x1, u1, x2, dcss_split_ratio(prm, z1, z2, d_new))


@kernel
def initial_anchor(fkind, prm):
    """Bearings at rest and centred: u = 0, z = 0, moving in +x (the first step corrects it)."""
    if fkind == FOUNDATION_DCSS:
        return (0.0, 1.0, 0.0, 0.0, 0.0, dcss_split_ratio(prm, 0.0, 0.0, 1.0))
    return (0.0, 1.0, 0.0, 0.0, 0.0, 0.0)


# ---------------------------------------------------------------------------------------------
# What the free base can still do (end of the run, rockcli.kernels.end_of_run)
# ---------------------------------------------------------------------------------------------
@kernel
def free_force_bound(fkind, prm, hy, u, ud):
    """Upper bound of ``|F|`` over the whole future of a free hysteretic base (ground still, block
    stuck): ``sqrt(F^2 + K ud^2)``, ``K`` the tangent stiffness in the direction of motion (P3s in
    :mod:`rockcli.kernels.driver_end`)."""
    F = base_force(fkind, prm, u, ud, hy)
    if ud == 0.0:
        return abs(F)
    z1, z2, _ = element_states(fkind, prm, hy, u)
    K = tangent_stiffness(fkind, prm, z1, z2, 1.0 if ud > 0.0 else -1.0)
    return math.sqrt(F * F + K * ud * ud)


@kernel
def free_disp_bound(fkind, prm, hy, u, ud):
    """Upper bound of ``|u|`` over the future of a free hysteretic base: ``sqrt(2 E)/w`` with the
    non-increasing energy ``E = ud^2/2 + sum_i (k_i u_i^2 + q_i u_yi z_i^2)/2`` (``k = w^2`` for a
    single element; for two in series ``|u1 + u2|^2 <= (1/k1 + 1/k2)(k1 u1^2 + k2 u2^2)``)."""
    z1, z2, u1 = element_states(fkind, prm, hy, u)
    w = prm[P_W]
    if fkind == FOUNDATION_BILINEAR:
        E2 = ud * ud + w * w * u * u + prm[P_Q1] * prm[P_UY1] * z1 * z1
    else:
        u2 = u - u1
        E2 = (ud * ud + prm[P_K1] * u1 * u1 + prm[P_K2] * u2 * u2 + prm[P_Q1] * prm[P_UY1] * z1 * z1
              + prm[P_Q2] * prm[P_UY2] * z2 * z2)
    return math.sqrt(E2) / w


@kernel
def u_at_force(fkind, prm, hy, level, a, b):
    """The displacement in [a, b] at which the (decreasing) branch force equals ``level``, given
    ``F(a) >= level >= F(b)`` (safeguarded Newton, to round-off)."""
    x = 0.5 * (a + b)
    tol = 4.4e-16 * (abs(a) + abs(b)) + 1e-300
    for _ in range(200):
        f, fp = force_slope(fkind, prm, hy, x)
        f -= level
        if f > 0.0:
            a = x
        elif f < 0.0:
            b = x
        else:
            return x
        xn = x - f / fp
        if not (a <= xn <= b):
            xn = 0.5 * (a + b)
        if abs(xn - x) <= tol or b - a <= tol:
            return xn
        x = xn
    return x


# ---------------------------------------------------------------------------------------------
# Imposed displacement paths (hysteresis loops)
# ---------------------------------------------------------------------------------------------
@kernel
def force_along_path(fkind, prm, u_path, out):
    """Bearing under an imposed displacement path: ``out[k] = (F, z1, z2)`` at ``u_path[k]``.

    The path is taken as monotone between samples; the anchor moves only where it reverses (a
    sample that lies back against the direction of motion), exactly as in a run, so the loop is
    exact for a piecewise-monotone path whatever the spacing of the samples.
    """
    hy = initial_anchor(fkind, prm)
    for k in range(u_path.shape[0]):
        u = u_path[k]
        if k > 0:
            du = u - u_path[k - 1]
            if du != 0.0:
                d_new = 1.0 if du > 0.0 else -1.0
                if d_new != hy[1]:
                    hy = reanchor(fkind, prm, hy, u_path[k - 1], d_new)
        elif u != 0.0:
            hy = reanchor(fkind, prm, hy, 0.0, 1.0 if u > 0.0 else -1.0)
        z1, z2, _ = element_states(fkind, prm, hy, u)
        out[k, 0] = base_force(fkind, prm, u, 0.0, hy)
        out[k, 1] = z1
        out[k, 2] = z2


@kernel
def bearing_energy(fkind, prm, hy, u):
    """Energy stored in the bearings per unit total mass [J/kg]: ``w^2 u^2/2`` (linear), plus
    ``Q u_y z^2/2`` for a Bouc-Wen element (its elastic part: the rest of its work is dissipated when
    ``gamma_bw >= |beta|``); for two surfaces in series the sum over both."""
    w = prm[P_W]
    if fkind == FOUNDATION_LINEAR:
        return 0.5 * w * w * u * u
    z1, z2, u1 = element_states(fkind, prm, hy, u)
    if fkind == FOUNDATION_BILINEAR:
        return 0.5 * (w * w * u * u + prm[P_Q1] * prm[P_UY1] * z1 * z1)
    u2 = u - u1
    return 0.5 * (prm[P_K1] * u1 * u1 + prm[P_K2] * u2 * u2 + prm[P_Q1] * prm[P_UY1] * z1 * z1
                  + prm[P_Q2] * prm[P_UY2] * z2 * z2)
