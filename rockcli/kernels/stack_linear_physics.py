"""The mechanics of a body on its plinth on an isolated base (docs/physics-plinth.md, "On linear bearings" and "On
sliding and lead-rubber bearings"), for :mod:`rockcli.kernels.stack_linear`: the right-hand side of every pattern and
the impacts with the base.

The bearings' force per unit moving mass is :func:`force`: the linear ``F(u, u')`` of :func:`bearing`, or a
hysteretic bearing's ``F(u)`` on the branch of its anchor (the single block's functions,
:func:`rockcli.kernels.bearings.hysteretic_force`). A bearing travels as ``bb = (fkind, prm, hy)``: its
:mod:`rockcli.kernels.layout` code, the single block's parameter vector (only the bearing's entries are read) and the
anchor of its Bouc-Wen elements (:mod:`rockcli.kernels.bearings`); on linear bearings only ``fkind`` is read.

States ``y = (psi, psi', theta2, theta2', u, u')``; a pattern is ``(s, k)``, the base and joint corners (0: a face).
Every pattern is the rigid foundation's with the base's absolute acceleration ``a_b`` for ``ag``, closed by the
horizontal momentum balance: R ``a_b = F``; B Eqs (10)-(11) of the body with ``gamma1 = gamma/(1 + m2)``; P those
of ``Stack.as_block()`` with ``gamma_e = gamma R_asm / R_e``; BP the note's 3x3 system. Contact forces are
:func:`rockcli.kernels.stack_physics.forces` with ``a_b`` for ``ag``.

Impacts are computed in maximal coordinates, the plinth's ``(x, y, theta)``, the body's, the base's ``x`` (the
order of :mod:`rockcli.reference.stack_mechanics`), as the constrained momentum balance (a small KKT system): the
plastic law (impulses at the constraints of the pattern after the impact only: the projection, in the kinetic
energy metric, onto the motions that pattern allows, the base's translation among them) or the energetic rule of a
restitution ``E``; the pattern after the impact is the one whose impulses press and whose new pivots open.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.bearings import hysteretic_force
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import FOUNDATION_LINEAR
from rockcli.kernels.stack_physics import (S_A1, S_A2, S_B1, S_B2, S_G, S_H1, S_H2, S_I1, S_I2, S_M2, S_R1, S_R2,
                                           _rot, bp_acc)

# the tuple ``lp`` of the bearings (per unit body mass)
L_P1SQ, L_PASQ, L_AASM, L_RE, L_ETA = 0, 1, 2, 3, 4  # p1^2, p_asm^2, alpha_asm, R_e of as_block(), eta_asm
L_G1, L_GE, L_MT, L_WB, L_XI, L_MB = 5, 6, 7, 8, 9, 10  # gamma1, gamma_e, moving mass M, omega_b, xi, base mass
L_RTOL, L_SC = 11, 12  # rtol, the six state scales (12..17)
L_THR1, L_THRA, L_PMAX, L_YC = 18, 19, 20, 21  # g tan(alpha1), g tan(alpha_asm), max(p1, p_asm), y_c
N_LP = 22


@kernel(inline='always')
def bearing(lp, u, ud):
    """The bearings' force per unit moving mass, ``F = -omega_b^2 u - 2 xi omega_b u'``."""
    w = lp[L_WB]
    return -w * w * u - 2.0 * lp[L_XI] * w * ud


@kernel(inline='always')
def force(lp, bb, u, ud):
    """The bearings' force per unit moving mass: linear (:func:`bearing`) or hysteretic (``bb``, the module notes)."""
    if bb[0] == FOUNDATION_LINEAR:
        return bearing(lp, u, ud)
    return hysteretic_force(bb[0], bb[1], u, bb[2])


@kernel(inline='always')
def on_base(th, thd, c, F, alpha, p2, gamma, R, g):
    """``(theta'', a_b)``: one block rocking on corner ``c`` of a base pushed by ``F`` (Eqs 10-11)."""
    A = alpha * c - th
    sA = math.sin(A)
    cA = math.cos(A)
    num = F - gamma * R * thd * thd * sA + gamma * R * p2 * cA * sA
    a_b = num / (1.0 - gamma * R * p2 * cA * cA / g)
    thdd = -p2 * (sA + cA * num / (g - gamma * R * p2 * cA * cA))
    return thdd, a_b


@kernel
def bp_base(s, k, sp, lp, th2, psi, thd2, psid, F):
    """``(psi'', theta2'', a_b)`` of pattern BP on the bearings: the note's 3x3 system."""
    b1, b2, h2, R1, R2, m2, g = sp[S_B1], sp[S_B2], sp[S_H2], sp[S_R1], sp[S_R2], sp[S_M2], sp[S_G]
    a1, a2 = sp[S_A1], sp[S_A2]
    dx = s * b2 - k * b1
    dy = 2.0 * h2
    D = math.sqrt(dx * dx + dy * dy)
    dl = math.atan2(dx, dy)
    th1 = th2 + psi
    thd1 = thd2 + psid
    phi = th1 - k * a1 - th2 + dl
    sph = math.sin(phi)
    M11 = 4.0 / 3.0 * R1 * R1
    M22 = 4.0 / 3.0 * m2 * R2 * R2 + D * D
    M12 = D * R1 * math.cos(phi)
    c1 = R1 * math.cos(k * a1 - th1)
    c2 = m2 * R2 * math.cos(s * a2 - th2) + D * math.cos(th2 - dl)
    Mt = lp[L_MT]
    r1 = -R1 * g * math.sin(k * a1 - th1) - D * R1 * sph * thd2 * thd2
    r2 = -m2 * R2 * g * math.sin(s * a2 - th2) + D * g * math.sin(th2 - dl) + D * R1 * sph * thd1 * thd1
    r3 = Mt * F + R1 * math.sin(th1 - k * a1) * thd1 * thd1 + (m2 * R2 * math.sin(th2 - s * a2)
                                                               + D * math.sin(th2 - dl)) * thd2 * thd2
    # Cramer's rule on the symmetric positive definite 3x3
    d = M11 * (M22 * Mt - c2 * c2) - M12 * (M12 * Mt - c2 * c1) + c1 * (M12 * c2 - M22 * c1)
    x1 = (r1 * (M22 * Mt - c2 * c2) - M12 * (r2 * Mt - c2 * r3) + c1 * (r2 * c2 - M22 * r3)) / d
    x2 = (M11 * (r2 * Mt - c2 * r3) - r1 * (M12 * Mt - c2 * c1) + c1 * (M12 * r3 - r2 * c1)) / d
    x3 = (M11 * (M22 * r3 - r2 * c2) - M12 * (M12 * r3 - r2 * c1) + r1 * (M12 * c2 - M22 * c1)) / d
    return x1 - x2, x2, x3


@kernel
def accel(s, k, sp, lp, bb, y, ag):
    """``(psi'', theta2'', a_b)`` of the pattern ``(s, k)`` at the state ``y`` (``u'' = a_b - ag``)."""
    F = force(lp, bb, y[4], y[5])
    g = sp[S_G]
    if s == 0.0 and k == 0.0:
        return 0.0, 0.0, F
    if s == 0.0:
        pdd, ab = on_base(y[0], y[1], k, F, sp[S_A1], lp[L_P1SQ], lp[L_G1], sp[S_R1], g)
        return pdd, 0.0, ab
    if k == 0.0:
        tdd, ab = on_base(y[2], y[3], s, F, lp[L_AASM], lp[L_PASQ], lp[L_GE], lp[L_RE], g)
        return 0.0, tdd, ab
    return bp_base(s, k, sp, lp, y[2], y[0], y[3], y[1], F)


@kernel
def rhs(s, k, sp, lp, bb, y, ag, dy):
    pdd, tdd, ab = accel(s, k, sp, lp, bb, y, ag)
    dy[0] = y[1]
    dy[1] = pdd
    dy[2] = y[3]
    dy[3] = tdd
    dy[4] = y[5]
    dy[5] = ab - ag


# ---------------------------------------------------------------------------------------------
# Impacts in maximal coordinates (plinth x, y, theta; body x, y, theta; base x)
# ---------------------------------------------------------------------------------------------
@kernel
def mass_diag(sp, lp):
    m2 = sp[S_M2]
    return np.array([m2, m2, m2 * sp[S_I2], 1.0, 1.0, sp[S_I1], lp[L_MB]])


@kernel
def _geometry(st0, st1, sp, q0, q1):
    """Centres ``G (2, 2)`` and pivots ``P (2, 2)`` (NaN at a face) with the base at 0 (only differences matter)."""
    b = (sp[S_B2], sp[S_B1])
    h = (sp[S_H2], sp[S_H1])
    st = (st0, st1)
    th = (q0, q0 + q1)
    G = np.zeros((2, 2))
    P = np.full((2, 2), np.nan)
    lx, ly = 0.0, 0.0
    for i in range(2):
        thl = th[i - 1] if i else 0.0
        c = b[1] if i else b[0]  # the contact's half width: the body is the narrower
        if st[i] == 0.0:
            bx, by = lx, ly
        else:
            dx, dy = _rot(thl, st[i] * c, 0.0)
            px, py = lx + dx, ly + dy
            P[i, 0] = px
            P[i, 1] = py
            dx, dy = _rot(th[i], -st[i] * c, 0.0)
            bx, by = px + dx, py + dy
        dx, dy = _rot(th[i], 0.0, h[i])
        G[i, 0] = bx + dx
        G[i, 1] = by + dy
        lx, ly = bx + 2.0 * dx, by + 2.0 * dy
    return G, P


@kernel
def velocities(st0, st1, sp, q0, q1, qd0, qd1, ud):
    """Maximal velocities from the pivots' rates ``qd`` (base pivot, joint pivot) and the base's ``u'``."""
    G, P = _geometry(st0, st1, sp, q0, q1)
    st = (st0, st1)
    qd = (qd0, qd1)
    v = np.zeros(7)
    v[0] = ud
    v[3] = ud
    v[6] = ud
    for i in range(2):
        for j in range(i + 1):
            if st[j] != 0.0 and qd[j] != 0.0:
                v[3 * i] += qd[j] * (G[i, 1] - P[j, 1])
                v[3 * i + 1] -= qd[j] * (G[i, 0] - P[j, 0])
                v[3 * i + 2] += qd[j]
    return v


@kernel
def _constraints(st0, st1, sp, q0, q1):
    b = (sp[S_B2], sp[S_B1])
    h = (sp[S_H2], sp[S_H1])
    st = (st0, st1)
    th = (q0, q0 + q1)
    nc = (2 if st0 != 0.0 else 3) + (2 if st1 != 0.0 else 3)
    J = np.zeros((nc, 7))
    r = 0
    for i in range(2):
        c = b[1] if i else b[0]
        rix, riy = _rot(th[i], st[i] * c, -h[i])
        pi = (riy, -rix)
        if i:
            rlx, rly = _rot(th[i - 1], st[i] * c, h[i - 1])
            pl = (rly, -rlx)
        for ax in range(2):
            J[r, 3 * i + ax] = 1.0
            J[r, 3 * i + 2] = pi[ax]
            if i:
                J[r, 3 * (i - 1) + ax] = -1.0
                J[r, 3 * (i - 1) + 2] = -pl[ax]
            elif ax == 0:
                J[r, 6] = -1.0
            r += 1
        if st[i] == 0.0:
            J[r, 3 * i + 2] = 1.0
            if i:
                J[r, 3 * (i - 1) + 2] = -1.0
            r += 1
    return J


@kernel
def impact_into(st0, st1, sp, Md, q0, q1, vm, j, target, with_rate):
    """Velocities and per-interface impulses ``(N, T, P_right, P_left)`` (rows 0 base, 1 joint) just after an
    impact into the pattern ``(st0, st1)``; ``with_rate``: the relative rate of interface ``j`` prescribed."""
    J = _constraints(st0, st1, sp, q0, q1)
    nc = J.shape[0]
    nr = nc + (1 if with_rate else 0)
    n = 7 + nr
    A = np.zeros((n, n))
    rhs_ = np.zeros(n)
    for i in range(7):
        A[i, i] = Md[i]
        rhs_[i] = Md[i] * vm[i]
    for r in range(nc):
        for i in range(7):
            A[i, 7 + r] = -J[r, i]
            A[7 + r, i] = J[r, i]
    if with_rate:
        A[3 * j + 2, 7 + nc] = -1.0
        A[7 + nc, 3 * j + 2] = 1.0
        if j:
            A[2, 7 + nc] = 1.0
            A[7 + nc, 2] = -1.0
        rhs_[7 + nc] = target
    x = np.linalg.solve(A, rhs_)
    v = x[:7].copy()
    lam = x[7:7 + nc]
    imp = np.zeros((2, 4))
    st = (st0, st1)
    th = (q0, q0 + q1)
    r = 0
    for i in range(2):
        thl = th[i - 1] if i else 0.0
        nx, ny = _rot(thl, 0.0, 1.0)
        tx, ty = _rot(thl, 1.0, 0.0)
        N = lam[r] * nx + lam[r + 1] * ny
        T = lam[r] * tx + lam[r + 1] * ty
        imp[i, 0] = N
        imp[i, 1] = T
        if st[i] == 0.0:
            c = sp[S_B1] if i else sp[S_B2]
            Mc = lam[r + 2]
            imp[i, 2] = 0.5 * N - Mc / (2.0 * c)
            imp[i, 3] = 0.5 * N + Mc / (2.0 * c)
            r += 3
        else:
            imp[i, 2] = N if st[i] > 0.0 else 0.0
            imp[i, 3] = N if st[i] < 0.0 else 0.0
            r += 2
    return v, imp


@kernel(inline='always')
def rel_rates(v):
    return v[2], v[5] - v[2]


@kernel
def post_velocities(c0, c1, j, sp, Md, q0, q1, vm, E):
    """The plastic impact into ``(c0, c1)``, or with ``E >= 0`` the energetic rule of the note."""
    cj = c1 if j else c0
    if E < 0.0 or cj == 0.0:
        return impact_into(c0, c1, sp, Md, q0, q1, vm, j, 0.0, np.bool_(False))
    v0, _ = impact_into(0.0 if j == 0 else c0, 0.0 if j == 1 else c1, sp, Md, q0, q1, vm, j, 0.0, np.bool_(False))
    w, _ = impact_into(c0, c1, sp, Md, q0, q1, np.zeros(7), j, 1.0, np.bool_(True))
    a = 0.0
    bnorm = 0.0
    for i in range(7):
        a += Md[i] * (vm[i] - v0[i]) ** 2
        bnorm += Md[i] * w[i] * w[i]
    W = math.sqrt(max(0.0, a / bnorm))
    r = rel_rates(vm)
    rj = r[1] if j else r[0]
    return impact_into(c0, c1, sp, Md, q0, q1, vm, j, E * W * math.copysign(1.0, rj), np.bool_(True))


@kernel
def _best(st0, st1, j, sp, Md, q0, q1, vm, E):
    r = rel_rates(vm)
    vscale = max(abs(r[0]), abs(r[1])) + 1e-300
    best_m = -np.inf
    bc0 = st0
    bc1 = st1
    bv = vm.copy()
    bimp = np.zeros((2, 4))
    zero0 = q0 == 0.0
    zero1 = q1 == 0.0
    for a in range(3):
        for b in range(3):
            # candidate options: the interfaces at angle 0 a face or either pivot; with E the impacting one on its
            # new corner; the others keep their pivot
            if j == 0 and E >= 0.0:
                if a > 0:
                    continue
                c0 = -st0
            elif zero0:
                c0 = (0.0, 1.0, -1.0)[a]
            else:
                if a > 0:
                    continue
                c0 = st0
            if j == 1 and E >= 0.0:
                if b > 0:
                    continue
                c1 = -st1
            elif zero1:
                c1 = (0.0, 1.0, -1.0)[b]
            else:
                if b > 0:
                    continue
                c1 = st1
            v, imp = post_velocities(c0, c1, j, sp, Md, q0, q1, vm, E)
            rr = rel_rates(v)
            pscale = max(abs(imp[0, 0]), abs(imp[1, 0])) + 1e-300
            margin = np.inf
            for i in range(2):
                if not (zero0 if i == 0 else zero1):
                    continue
                ci = c1 if i else c0
                if ci == 0.0:
                    margin = min(margin, min(imp[i, 2], imp[i, 3]) / pscale)
                else:
                    margin = min(margin, ci * (rr[1] if i else rr[0]) / vscale)
                    if not (i == j and E >= 0.0):
                        margin = min(margin, max(imp[i, 2], imp[i, 3]) / pscale)
            if margin > best_m:
                best_m = margin
                bc0 = c0
                bc1 = c1
                bv = v
                bimp = imp
    return bc0, bc1, bv, bimp, best_m


@kernel
def choose_post(st0, st1, j, sp, Md, q0, q1, vm, E, tol):
    """``(c0, c1, v+, impulses, margin, pulls, plastic)``: the pattern after an impact at ``j`` (as the
    reference's ``choose_post``: a restitution no candidate can carry gives way to the plastic law)."""
    c0, c1, v, imp, margin = _best(st0, st1, j, sp, Md, q0, q1, vm, E)
    plastic = False
    if E >= 0.0 and margin < -tol:
        c0, c1, v, imp, margin = _best(st0, st1, j, sp, Md, q0, q1, vm, -1.0)
        plastic = True
    pscale = max(abs(imp[0, 0]), abs(imp[1, 0]))
    pulls = 0
    if c0 != 0.0 and q0 != 0.0 and max(imp[0, 2], imp[0, 3]) < -tol * pscale:
        pulls += 1
    if c1 != 0.0 and q1 != 0.0 and max(imp[1, 2], imp[1, 3]) < -tol * pscale:
        pulls += 1
    return c0, c1, v, imp, margin, pulls, plastic


@kernel
def kinetic_relative(Md, v):
    """The blocks' kinetic energy relative to the base."""
    e = 0.0
    for i in range(6):
        w = v[i] - (v[6] if i % 3 == 0 else 0.0)
        e += Md[i] * w * w
    return 0.5 * e


@kernel
def rest_moments(sp, lp, a):
    """The restoring moments at rest of the joint (the body) and of the base (the assembly) under the support's
    acceleration ``a``, per unit body mass: ``m1 (g b1 - |a| h1)`` and ``(m1 + m2)(g b2 - |a| y_c)``."""
    g = sp[S_G]
    return (g * sp[S_B1] - abs(a) * sp[S_H1]), (1.0 + sp[S_M2]) * (g * sp[S_B2] - abs(a) * lp[L_YC])


@kernel
def restoring(j, s0, k0, sp, lp, q0, q1, qd0, qd1, a):
    """The smaller relative acceleration pulling interface ``j`` back (``min_sigma -sigma psi''_sigma`` with
    ``j`` pivoting at angle 0 on corner sigma, the rest of the stack ``(s0, k0)`` as it is) on a support moving
    with ``a`` (rigid-ground equations with ``ag = a``)."""
    g = sp[S_G]
    best = np.inf
    for sg in (1.0, -1.0):
        if j == 1:
            if s0 == 0.0:
                acc = -lp[L_P1SQ] * (math.sin(sg * sp[S_A1]) + a / g * math.cos(sg * sp[S_A1]))
            else:
                acc, _ = bp_acc(s0, sg, sp, q0, 0.0, qd0, 0.0, a)
        else:
            if k0 == 0.0:
                acc = -lp[L_PASQ] * (math.sin(sg * lp[L_AASM]) + a / g * math.cos(sg * lp[L_AASM]))
            else:
                _, acc = bp_acc(sg, k0, sp, 0.0, q1, 0.0, qd1, a)
        best = min(best, -sg * acc)
    return best
