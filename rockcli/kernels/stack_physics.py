"""The mechanics of a body on a free plinth for the stack driver (:mod:`rockcli.kernels.stack`), in closed form
(docs/physics-plinth.md): the equations of the pattern where both rock, the contact forces that end a pattern,
and the impact law with the choice of the pattern after an impact.

Numbering: block 1 the body (upper), block 2 the plinth. Masses per unit body mass. States of the pattern where
both rock (BP): ``psi, psi', theta2, theta2'`` (``psi = theta1 - theta2``, the body on the plinth). The parameter
tuple ``sp`` of the driver carries, at the indices of :mod:`rockcli.kernels.layout` that the Dormand-Prince step
reads (``P_RTOL``, the four state scales ``P_SC0..``, ``P_P2`` for a first step), those of pattern BP, and the
geometry at the indices ``S_*`` below (from ``N_PRM`` on). Velocities in impacts are the six maximal velocities
``(vx2, vy2, w2, vx1, vy1, w1)`` of the two centres of mass, angular rates clockwise.
"""

from __future__ import annotations

import math

from rockcli.kernels.ground import _ground
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import N_PRM

# the stack tuple ``sp``: the geometry (indices after the kernel's own parameters)
S_B1, S_H1, S_R1, S_A1, S_I1 = N_PRM + 0, N_PRM + 1, N_PRM + 2, N_PRM + 3, N_PRM + 4  # I: central, per unit mass
S_B2, S_H2, S_R2, S_A2, S_M2, S_I2 = N_PRM + 5, N_PRM + 6, N_PRM + 7, N_PRM + 8, N_PRM + 9, N_PRM + 10
S_G = N_PRM + 11
S_E = N_PRM + 12  # the coefficient of restitution, or -1: the plastic law
S_REST = N_PRM + 13  # rest_tol
S_A1REST, S_AAREST = N_PRM + 14, N_PRM + 15  # slenderness of what stands on the joint (alpha1), on the base
S_TOL = N_PRM + 16  # relative slack of the impact consistency tests
N_SP = N_PRM + 17


@kernel(inline='always')
def _rot(t, x, y):
    """The clockwise rotation by ``t`` of the body-frame vector ``(x, y)``."""
    c = math.cos(t)
    s = math.sin(t)
    return c * x + s * y, -s * x + c * y


@kernel(inline='always')
def _cw(rx, ry, fx, fy):
    """Clockwise moment of the force ``(fx, fy)`` at the arm ``(rx, ry)``."""
    return ry * fx - rx * fy


# ---------------------------------------------------------------------------------------------
# Both rocking: the 2x2 system of Lagrange's equations
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def bp_acc(s, k, sp, th2, psi, thd2, psid, ag):
    """``(psi'', theta2'')`` of pattern BP on the base corner ``s`` and the joint corner ``k`` (the note's
    ``M11 theta1'' + M12 theta2'' = Q1 - m1 D R1 sin(phi) theta2'^2`` and ``M12 theta1'' + M22 theta2'' = Q2 + m1 D
    R1 sin(phi) theta1'^2``, with ``theta1 = theta2 + psi``)."""
    b1 = sp[S_B1]
    b2 = sp[S_B2]
    h2 = sp[S_H2]
    R1 = sp[S_R1]
    R2 = sp[S_R2]
    m2 = sp[S_M2]
    g = sp[S_G]
    a1 = sp[S_A1]
    a2 = sp[S_A2]
    dx = s * b2 - k * b1
    dy = 2.0 * h2
    D = math.sqrt(dx * dx + dy * dy)
    dl = math.atan2(dx, dy)
    th1 = th2 + psi
    thd1 = thd2 + psid
    phi = th1 - k * a1 - th2 + dl
    sp_, cp = math.sin(phi), math.cos(phi)
    M11 = 4.0 / 3.0 * R1 * R1
    M22 = 4.0 / 3.0 * m2 * R2 * R2 + D * D
    M12 = D * R1 * cp
    A1 = k * a1 - th1
    A2 = s * a2 - th2
    Q1 = -R1 * (g * math.sin(A1) + ag * math.cos(A1))
    Q2 = -m2 * R2 * (g * math.sin(A2) + ag * math.cos(A2)) + D * (g * math.sin(th2 - dl) - ag * math.cos(th2 - dl))
    r1 = Q1 - D * R1 * sp_ * thd2 * thd2
    r2 = Q2 + D * R1 * sp_ * thd1 * thd1
    det = M11 * M22 - M12 * M12
    thdd1 = (M22 * r1 - M12 * r2) / det
    thdd2 = (M11 * r2 - M12 * r1) / det
    return thdd1 - thdd2, thdd2


@kernel(inline='always')
def _rhs_bp_into(fkind, phase, code, sp, seg, epar, hy, t, W, src, dst):
    """Right-hand side of pattern BP from row ``src`` into row ``dst`` (the signature of the other drivers'
    right-hand sides; ``code = 2 s + k`` carries the two corners)."""
    s = 1.0 if code > 0.0 else -1.0
    k = code - 2.0 * s
    ag = _ground(t, seg, epar)
    pdd, tdd = bp_acc(s, k, sp, W[src, 2], W[src, 0], W[src, 3], W[src, 1], ag)
    W[dst, 0] = W[src, 1]
    W[dst, 1] = pdd
    W[dst, 2] = W[src, 3]
    W[dst, 3] = tdd


# ---------------------------------------------------------------------------------------------
# Positions and the velocity fields of a pattern
# ---------------------------------------------------------------------------------------------
@kernel
def positions(s, k, sp, th2, psi):
    """``(O, G2, T, J, C1, G1)`` as 12 numbers: the base pivot (the base centre when ``s = 0``), the plinth's
    centre, the centre of its top, the joint pivot (``T`` when ``k = 0``), the body's base centre and centre."""
    b1, h1, b2, h2 = sp[S_B1], sp[S_H1], sp[S_B2], sp[S_H2]
    th1 = th2 + psi
    ox = s * b2
    oy = 0.0
    x, y = _rot(th2, -s * b2, h2)
    g2x, g2y = ox + x, oy + y
    x, y = _rot(th2, -s * b2, 2.0 * h2)
    tx, ty = ox + x, oy + y
    x, y = _rot(th2, k * b1, 0.0)
    jx, jy = tx + x, ty + y
    x, y = _rot(th1, -k * b1, 0.0)
    cx, cy = jx + x, jy + y
    x, y = _rot(th1, 0.0, h1)
    return ox, oy, g2x, g2y, tx, ty, jx, jy, cx, cy, cx + x, cy + y


@kernel
def fields(s, k, sp, th2, psi):
    """The velocity fields (6 maximal velocities each) of a unit rate of the base pivot (everything turning
    about ``O``, the body fixed on the plinth; zeros when ``s = 0``) and of the joint pivot (the body turning
    about ``J``; zeros when ``k = 0``)."""
    ox, oy, g2x, g2y, _, _, jx, jy, _, _, g1x, g1y = positions(s, k, sp, th2, psi)
    if s != 0.0:
        e2 = (g2y - oy, -(g2x - ox), 1.0, g1y - oy, -(g1x - ox), 1.0)
    else:
        e2 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    if k != 0.0:
        e1 = (0.0, 0.0, 0.0, g1y - jy, -(g1x - jx), 1.0)
    else:
        e1 = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    return e2, e1


@kernel(inline='always')
def _dot(sp, u, v):
    """The kinetic-energy inner product of two maximal velocity vectors (per unit body mass)."""
    m2 = sp[S_M2]
    return (m2 * (u[0] * v[0] + u[1] * v[1]) + m2 * sp[S_I2] * u[2] * v[2]
            + u[3] * v[3] + u[4] * v[4] + sp[S_I1] * u[5] * v[5])


@kernel(inline='always')
def _comb(a, u, b, v):
    return (a * u[0] + b * v[0], a * u[1] + b * v[1], a * u[2] + b * v[2], a * u[3] + b * v[3],
            a * u[4] + b * v[4], a * u[5] + b * v[5])


@kernel
def project(sp, e2, e1, V):
    """``(q2, q1)``: the rates of the orthogonal projection of ``V`` onto the span of the fields ``e2``, ``e1`` in
    the kinetic-energy metric (a zero field takes no part): the plastic impact into that pattern."""
    a = _dot(sp, e2, e2)
    b = _dot(sp, e2, e1)
    c = _dot(sp, e1, e1)
    r2 = _dot(sp, e2, V)
    r1 = _dot(sp, e1, V)
    if a > 0.0 and c > 0.0:
        det = a * c - b * b
        return (c * r2 - b * r1) / det, (a * r1 - b * r2) / det
    if a > 0.0:
        return r2 / a, 0.0
    if c > 0.0:
        return 0.0, r1 / c
    return 0.0, 0.0


# ---------------------------------------------------------------------------------------------
# Contact forces
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def _face(N, Mc, c):
    """The two corner forces ``(right, left)`` of a face carrying ``N`` and the clockwise couple ``Mc``."""
    return 0.5 * N - Mc / (2.0 * c), 0.5 * N + Mc / (2.0 * c)


@kernel
def forces(s, k, sp, th2, psi, thd2, psid, thdd2, psidd, ag):
    """Contact forces of the pattern ``(s, k)`` (0: a face) at a state and its accelerations, per unit body mass:
    ``(NB, TB, PRB, PLB, NJ, TJ, PRJ, PLJ)``, normal and tangential force of the base and of the joint in the frame
    of the surface below, and the corner forces of a face (those of a pivot are its normal force on its corner)."""
    b1, b2, h2 = sp[S_B1], sp[S_B2], sp[S_H2]
    m2, g = sp[S_M2], sp[S_G]
    ox, oy, g2x, g2y, tx, ty, jx, jy, cx, cy, g1x, g1y = positions(s, k, sp, th2, psi)
    thd1 = thd2 + psid
    thdd1 = thdd2 + psidd
    # accelerations of the centres: a = sum of rate'' perp(r) - rate^2 r over the pivots turning them
    a2x = a2y = 0.0
    a1x = a1y = 0.0
    if s != 0.0:
        rx, ry = g2x - ox, g2y - oy
        a2x, a2y = thdd2 * ry - thd2 * thd2 * rx, -thdd2 * rx - thd2 * thd2 * ry
        rx, ry = jx - ox, jy - oy  # the joint point turns with the plinth
        a1x, a1y = thdd2 * ry - thd2 * thd2 * rx, -thdd2 * rx - thd2 * thd2 * ry
    rx, ry = g1x - jx, g1y - jy
    a1x += thdd1 * ry - thd1 * thd1 * rx
    a1y += -thdd1 * rx - thd1 * thd1 * ry
    fjx, fjy = a1x + ag, a1y + g  # the force on the body (m1 = 1)
    n2x, n2y = _rot(th2, 0.0, 1.0)
    t2x, t2y = _rot(th2, 1.0, 0.0)
    NJ = fjx * n2x + fjy * n2y
    TJ = fjx * t2x + fjy * t2y
    if k == 0.0:  # a face: its couple from the body's rotation about its centre
        Mc = sp[S_I1] * thdd1 - _cw(cx - g1x, cy - g1y, fjx, fjy)
        PRJ, PLJ = _face(NJ, Mc, b1)
        px, py = cx, cy
    else:
        PRJ = NJ if k > 0.0 else 0.0
        PLJ = NJ if k < 0.0 else 0.0
        Mc = 0.0
        px, py = jx, jy
    fbx, fby = fjx + m2 * (a2x + ag), fjy + m2 * (a2y + g)
    if s == 0.0:  # a face: the plinth's rotation about its centre (it is still: thdd2 = 0)
        McB = (m2 * sp[S_I2] * thdd2 - _cw(-g2x, -g2y, fbx, fby) - _cw(px - g2x, py - g2y, -fjx, -fjy) + Mc)
        PRB, PLB = _face(fby, McB, b2)
    else:
        PRB = fby if s > 0.0 else 0.0
        PLB = fby if s < 0.0 else 0.0
    return fby, fbx, PRB, PLB, NJ, TJ, PRJ, PLJ


@kernel(inline='always')
def forces_b(k, sp, psi, psid, psidd, ag):
    """:func:`forces` of pattern B (the body on its corner ``k``, the plinth still) in closed form:
    ``(NB, TB, PRB, PLB, NJ, TJ)``. ``F_J = R1 (psi'' cos A + psi'^2 sin A) + ag, R1 (psi'' sin A - psi'^2 cos A) +
    g`` with ``A = k alpha1 - psi``, and the base from the plinth's equilibrium (the note)."""
    R1, b1, b2, h2, m2, g = sp[S_R1], sp[S_B1], sp[S_B2], sp[S_H2], sp[S_M2], sp[S_G]
    A = k * sp[S_A1] - psi
    sA = math.sin(A)
    cA = math.cos(A)
    fx = R1 * (psidd * cA + psid * psid * sA) + ag
    fy = R1 * (psidd * sA - psid * psid * cA) + g
    NB = fy + m2 * g
    PLB = (fy * (b2 - k * b1) + m2 * g * b2 + 2.0 * h2 * fx + m2 * h2 * ag) / (2.0 * b2)
    return NB, fx + m2 * ag, NB - PLB, PLB, fy, fx


@kernel(inline='always')
def forces_p(s, sp, th, thd, thdd, ag):
    """:func:`forces` of pattern P (the assembly on the plinth's corner ``s``) in closed form:
    ``(NB, TB, NJ, TJ, PRJ, PLJ)``; the joint's couple ``Mc = I1 theta'' + h1 T_J``."""
    b1, h1, b2, h2, m2, g = sp[S_B1], sp[S_H1], sp[S_B2], sp[S_H2], sp[S_M2], sp[S_G]
    c = math.cos(th)
    sn = math.sin(th)
    x, y = -s * b2 * c + (2.0 * h2 + h1) * sn, s * b2 * sn + (2.0 * h2 + h1) * c  # the body's centre from O
    fx = thdd * y - thd * thd * x + ag
    fy = -thdd * x - thd * thd * y + g
    NJ = fx * sn + fy * c
    TJ = fx * c - fy * sn
    Mc = sp[S_I1] * thdd + h1 * TJ
    x2, y2 = -s * b2 * c + h2 * sn, s * b2 * sn + h2 * c  # the plinth's centre from O
    NB = fy + m2 * (-thdd * x2 - thd * thd * y2 + g)
    TB = fx + m2 * (thdd * y2 - thd * thd * x2 + ag)
    return NB, TB, NJ, TJ, 0.5 * NJ - Mc / (2.0 * b1), 0.5 * NJ + Mc / (2.0 * b1)


# ---------------------------------------------------------------------------------------------
# Impacts
# ---------------------------------------------------------------------------------------------
@kernel
def _impulses(s, k, sp, th2, psi, V0, V1):
    """Impulses of the jump ``V0 -> V1`` into the pattern ``(s, k)``: ``(NB, TB, PRB, PLB, NJ, TJ, PRJ, PLJ)`` as in
    :func:`forces` (the momentum balances of the body, then of the plinth)."""
    b1, b2 = sp[S_B1], sp[S_B2]
    m2 = sp[S_M2]
    ox, oy, g2x, g2y, tx, ty, jx, jy, cx, cy, g1x, g1y = positions(s, k, sp, th2, psi)
    ljx, ljy = V1[3] - V0[3], V1[4] - V0[4]
    n2x, n2y = _rot(th2, 0.0, 1.0)
    t2x, t2y = _rot(th2, 1.0, 0.0)
    NJ = ljx * n2x + ljy * n2y
    TJ = ljx * t2x + ljy * t2y
    if k == 0.0:
        Mc = sp[S_I1] * (V1[5] - V0[5]) - _cw(cx - g1x, cy - g1y, ljx, ljy)
        PRJ, PLJ = _face(NJ, Mc, b1)
        px, py = cx, cy
    else:  # a pivot carries no couple, but for the restitution's at the impacting joint
        Mc = sp[S_I1] * (V1[5] - V0[5]) - _cw(jx - g1x, jy - g1y, ljx, ljy)
        PRJ = NJ if k > 0.0 else 0.0
        PLJ = NJ if k < 0.0 else 0.0
        px, py = jx, jy
    lbx, lby = ljx + m2 * (V1[0] - V0[0]), ljy + m2 * (V1[1] - V0[1])
    if s == 0.0:
        McB = (m2 * sp[S_I2] * (V1[2] - V0[2]) - _cw(-g2x, -g2y, lbx, lby) - _cw(px - g2x, py - g2y, -ljx, -ljy) + Mc)
        PRB, PLB = _face(lby, McB, b2)
    else:
        PRB = lby if s > 0.0 else 0.0
        PLB = lby if s < 0.0 else 0.0
    return lby, lbx, PRB, PLB, NJ, TJ, PRJ, PLJ


@kernel
def post_velocities(s, k, j, sp, th2, psi, V, E):
    """Velocities just after an impact at interface ``j`` (0 base, 1 joint) into the pattern ``(s, k)``: the
    plastic projection (``E < 0``), or with a restitution ``E >= 0`` the energetic rule (the motions that keep
    ``j`` stuck projected, the impacting pivot's own motion at ``E`` times the largest rate the energy allows)."""
    e2, e1 = fields(s, k, sp, th2, psi)
    pivot_j = s != 0.0 if j == 0 else k != 0.0
    if E < 0.0 or not pivot_j:
        q2, q1 = project(sp, e2, e1, V)
        return _comb(q2, e2, q1, e1)
    z = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    if j == 0:
        ej, e0 = e2, e1
    else:
        ej, e0 = e1, e2
    q0, _ = project(sp, e0, z, V)  # the plastic part: the pattern with j stuck
    P0 = _comb(q0, e0, 0.0, z)
    w0, _ = project(sp, e0, z, ej)
    w = _comb(1.0, ej, -w0, e0)  # the impacting pivot's own motion, orthogonal to those
    d = _comb(1.0, V, -1.0, P0)
    rate = V[2] if j == 0 else V[5] - V[2]
    W = math.sqrt(max(0.0, _dot(sp, d, d) / _dot(sp, w, w)))
    return _comb(1.0, P0, E * W * (1.0 if rate > 0.0 else -1.0), w)


@kernel
def _best_candidate(s, k, j, sp, th2, psi, V, E):
    """The most consistent pattern after the impact under the law ``E`` (< 0: plastic): ``(s', k', V+, margin)``."""
    zero_b = th2 == 0.0
    zero_j = psi == 0.0
    vscale = max(abs(V[2]), abs(V[5] - V[2])) + 1e-300
    best = -math.inf
    bs = s
    bk = k
    bV = V
    for ib in range(3):
        sb = (0.0, 1.0, -1.0)[ib]
        if j == 0 and E >= 0.0:
            if ib > 0:
                break
            sb = -s
        elif not zero_b:
            if ib > 0:
                break
            sb = s
        for ik in range(3):
            kb = (0.0, 1.0, -1.0)[ik]
            if j == 1 and E >= 0.0:
                if ik > 0:
                    break
                kb = -k
            elif not zero_j:
                if ik > 0:
                    break
                kb = k
            V1 = post_velocities(sb, kb, j, sp, th2, psi, V, E)
            NB, TB, PRB, PLB, NJ, TJ, PRJ, PLJ = _impulses(sb, kb, sp, th2, psi, V, V1)
            pscale = max(abs(NB), abs(NJ)) + 1e-300
            margin = math.inf
            if zero_b:
                if sb == 0.0:
                    margin = min(margin, min(PRB, PLB) / pscale)
                else:
                    margin = min(margin, sb * V1[2] / vscale)
                    if not (j == 0 and E >= 0.0):
                        margin = min(margin, max(PRB, PLB) / pscale)
            if zero_j:
                if kb == 0.0:
                    margin = min(margin, min(PRJ, PLJ) / pscale)
                else:
                    margin = min(margin, kb * (V1[5] - V1[2]) / vscale)
                    if not (j == 1 and E >= 0.0):
                        margin = min(margin, max(PRJ, PLJ) / pscale)
            if margin > best:
                best = margin
                bs = sb
                bk = kb
                bV = V1
    return bs, bk, bV, best


@kernel
def choose_after_impact(s, k, j, sp, th2, psi, V):
    """The pattern after an impact at ``j`` from the pattern ``(s, k)`` (its angle at ``j`` just back to 0):
    every candidate (an interface at angle 0 a face or either pivot, the other keeping its pivot; with a
    restitution the impacting one on its new corner) gets its velocities from :func:`post_velocities`, and the one
    whose impulses press and whose new pivots open (the largest smallest margin) is taken. With a restitution
    whose rebound no candidate can carry (its couple would lift a face, say), the plastic law is used instead.

    Returns ``(s', k', V+, margin, jump, dmd_base, dmd_joint, plastic)``: ``margin < 0`` when none is consistent,
    ``jump`` True when a kept pivot's impulse pulls, the impulsive friction demands ``|T|/N`` (0 without impulse),
    ``plastic`` True when a given restitution fell back to the plastic law."""
    E = sp[S_E]
    tol = sp[S_TOL]
    bs, bk, bV, best = _best_candidate(s, k, j, sp, th2, psi, V, E)
    plastic = False
    if E >= 0.0 and best < -tol:
        bs, bk, bV, best = _best_candidate(s, k, j, sp, th2, psi, V, -1.0)
        plastic = True
    zero_b = th2 == 0.0
    zero_j = psi == 0.0
    NB, TB, PRB, PLB, NJ, TJ, PRJ, PLJ = _impulses(bs, bk, sp, th2, psi, V, bV)
    pscale = max(abs(NB), abs(NJ)) + 1e-300
    jump = ((not zero_b) and max(PRB, PLB) < -tol * pscale) or ((not zero_j) and max(PRJ, PLJ) < -tol * pscale)
    dmd_b = abs(TB) / NB if NB > 0.0 else 0.0
    dmd_j = abs(TJ) / NJ if NJ > 0.0 else 0.0
    return bs, bk, bV, best, jump, dmd_b, dmd_j, plastic


@kernel
def max_velocities(s, k, sp, th2, psi, thd2, psid):
    """The six maximal velocities of the pattern ``(s, k)`` at the rates ``theta2'``, ``psi'``."""
    e2, e1 = fields(s, k, sp, th2, psi)
    return _comb(thd2, e2, psid, e1)
