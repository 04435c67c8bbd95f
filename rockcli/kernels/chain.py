"""The mechanics of a chain of rigid blocks standing on each other, with Coulomb friction at every contact
(docs/physics-sliding.md): the equations of motion of any pattern of contacts, the contact forces, and the
same equations at the velocity level for impacts. Used by the friction driver (:mod:`rockcli.kernels.chain_run`)
for a single block (``n = 1``), a body on its plinth (``n = 2``) and, later, a column of drums.

Blocks ``i = 0 .. n-1`` bottom to top: half width ``b``, half height ``h``, mass ``m`` and central inertia ``I``.
Interface ``j`` lies under block ``j`` (interface 0 on the ground, or on an isolated base). Its relative
coordinates are the slip ``s_j`` of block ``j`` along the top of the block below (the centre of block ``j``'s base
from the centre of that top, along it) and the rotation ``psi_j`` of block ``j`` on it (clockwise positive: about
its right corner, rockcli's sign); the base, when isolated, has its displacement ``u`` relative to the ground.
The pattern of interface ``j`` is its corner ``c_j`` (0 a face, +1/-1 a pivot on the right/left corner) and its
slip ``sl_j`` (0 stuck, +1/-1 sliding forwards/backwards along the top below): ``psi_j`` is free where ``c_j !=
0`` and ``s_j`` where ``sl_j != 0``; the other coordinates keep their values (their rates are 0).

Kane's equations (the generalized forces of a coordinate, from its partial velocities) in the ground's frame,
where the ground's acceleration ``ag`` is the inertial force ``-m ag`` on every mass. For a free coordinate
``q_k``: ``sum_i [m_i (a_Gi + (ag, g)) . dv_Gi/dq_k' + I_i alpha_i domega_i/dq_k'] (+ the base's m_b (u'' + ag) + k_b
u + c_b u' for u) = Q_k``, where the contact forces do work only through a slip: ``Q_k`` is 0 but for a sliding
``s_j``, whose row is replaced by Coulomb's law ``T_j = -mu_j sl_j N_j`` with ``(N_j, T_j)`` the force the block
below (or the ground) exerts on everything above interface ``j``, ``F_j = sum_{i >= j} m_i (a_Gi + (ag, g))``,
in the frame of the surface below: ``F_j . (t_j + mu_j sl_j n_j) = 0``. The accelerations are affine in the free
``q''`` (propagated up the chain with the Coriolis and centripetal terms), so each pattern is one small linear
system. At an impact the same rows hold with ``a_Gi + (ag, g)`` replaced by the velocity jumps ``v_Gi+ - v_Gi-``
(the impulses, finite forces giving none): the plastic impact at the contacts of the pattern after it, with
Coulomb's law on its impulses where a contact slips.

Layout. ``cp`` (float array): the chain's parameters at the ``CP_*`` indices, then per block ``i`` the fields
``F_*`` at ``CP_BLK + NF_BLK i``. State ``y`` (columns of the work array): ``u, u'``, then per interface ``j``
``s_j, s_j', psi_j, psi_j'`` from column ``2 + 4 j``. ``pat`` (float array, ``2 n``): ``c_j, sl_j``.
The work tuple ``ws`` (:func:`workspace`) holds the chain's kinematics at one state.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.jit import hot, kernel

# the chain's parameters ``cp``
CP_N, CP_G, CP_RTOL, CP_REST, CP_E, CP_BASE, CP_MB, CP_KB, CP_CB, CP_TOL = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9
CP_P2MAX = 10  # the largest p^2 = 3 g / (4 R) of the blocks (a first step)
CP_HDT = 11  # spacing of the history's uniform grid [s], 0: none
CP_BLK = 16  # the blocks' fields from here
# a block's fields, and those of the interface under it
F_B, F_H, F_M, F_I, F_MU = 0, 1, 2, 3, 4  # half width, half height, mass, central inertia, friction under it
F_AREST = 5  # slenderness of everything above the interface as one body at rest (about a corner of the interface)
F_EDGE = 6  # the slip at which the block's base passes the edge of the top below: b_below - b (inf on the ground)
F_SC_S = 7  # the error scale of the slip s [m]
F_SC_PSI = 8  # the error scale of psi [rad]
F_P = 9  # sqrt(3 g / (4 R)) of the block [1/s]: the scale of the rates
F_BLOW = 10  # the half width of the top below (inf on the ground or the base): where the overlap of the faces ends
NF_BLK = 11

BASE_RIGID, BASE_LINEAR = 0.0, 1.0
#: a corner code ``c_j`` for the complementarity solve (kernels.contact_lcp): interface ``j`` closed (angle, rate, lift
#: and slip rate 0) with all three relative motions free, its slip, its rotation about the centre of its base and its
#: lift along the normal, each against its contact force (the face's corner forces and its friction)
RELEASED = 2.0
#: the same with the slip held (an impact whose contacts all stick: the rocking model's law)
RELEASED_STUCK = 3.0


def cp_size(n: int) -> int:
    return CP_BLK + NF_BLK * n


def n_states(n: int) -> int:
    return 2 + 4 * n


@kernel(inline='always')
def col_s(j):
    return 2 + 4 * j


@kernel(inline='always')
def col_psi(j):
    return 4 + 4 * j


@kernel(inline='always')
def col_lift(j):
    """The code of interface ``j``'s lift in a released pattern (no state column: the lift and its rate are 0)."""
    return -1 - j


@kernel(inline='always')
def fld(cp, i, f):
    """Field ``f`` of block ``i``."""
    return cp[CP_BLK + NF_BLK * i + f]


@kernel(inline='always')
def overlap_ends(cp, j, s):
    """``(e_R, e_L)``: the ends of interface ``j``'s contact from the centre of block ``j``'s base, at the slip ``s``:
    the block's corners ``+-b``, or the corner of the top below (half width ``b_below``) where the block's corner
    overhangs it."""
    b = fld(cp, j, F_B)
    bl = fld(cp, j, F_BLOW)
    e_r = b if s + b <= bl else bl - s
    e_l = -b if s - b >= -bl else -bl - s
    return e_r, e_l


@kernel
def workspace(n):
    """Preallocated arrays for :func:`kinematics` and the solves of a chain of ``n`` blocks: ``(free, AG, bG, AA,
    bA, G, vG, om, th, fr, M, r, x)``. ``free`` lists the free coordinates (as the state column of their
    position); per block ``AG`` (2 x nf) and ``bG`` the affine acceleration of its centre, ``AA``, ``bA`` of its
    angular acceleration, ``G`` and ``vG`` its centre and velocity, ``om`` and ``th`` its rate and angle; per
    interface ``fr`` the contact point and the frame of the surface below ``(Px, Py, tx, ty, nx, ny)``; ``M, r,
    x`` the linear system and its solution; ``mo`` per interface 1 where a sliding contact's friction is off (it
    pulls: :func:`solve_level`), ``fq`` scratch forces."""
    nf = 3 * n + 1  # at most: the base, and per interface its slip, rotation and (released) lift
    free = np.zeros(nf, dtype=np.int64)
    AG = np.zeros((n, 2, nf))
    bG = np.zeros((n, 2))
    AA = np.zeros((n, nf))
    bA = np.zeros(n)
    G = np.zeros((n, 2))
    vG = np.zeros((n, 2))
    om = np.zeros(n)
    th = np.zeros(n)
    fr = np.zeros((n, 6))
    M = np.zeros((nf, nf))
    r = np.zeros(nf)
    x = np.zeros(nf)
    mo = np.zeros(n)
    fq = np.zeros((n, 3))
    return free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq


@hot
def free_coordinates(cp, pat, free):
    """The free coordinates of the pattern (state columns of their positions, in the order u, then per interface
    s, psi); their number."""
    n = int(cp[CP_N])
    nf = 0
    if cp[CP_BASE] != BASE_RIGID:
        free[0] = 0
        nf = 1
    for j in range(n):
        if pat[2 * j + 1] != 0.0 or pat[2 * j] == RELEASED:
            free[nf] = col_s(j)
            nf += 1
        if pat[2 * j] != 0.0:
            free[nf] = col_psi(j)
            nf += 1
        if pat[2 * j] >= RELEASED:
            free[nf] = col_lift(j)
            nf += 1
    return nf


@hot
def kinematics(cp, pat, y, ws):
    """Positions, velocities and the affine accelerations of every block at the state ``y`` (a row of the work
    array) in the pattern ``pat``: fills ``ws``; returns the number of free coordinates."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    nf = free_coordinates(cp, pat, free)
    # the top of the support: the ground, or the base at u
    Tx = y[0] if cp[CP_BASE] != BASE_RIGID else 0.0
    Ty = 0.0
    vTx = y[1] if cp[CP_BASE] != BASE_RIGID else 0.0
    vTy = 0.0
    thL = 0.0
    omL = 0.0
    bAL = 0.0
    # the affine acceleration of the top of the support and of its angular acceleration: columns kept in the
    # rows of block -1, i.e. computed on the fly from the block below (the base's own is e_u)
    bTx = 0.0
    bTy = 0.0
    rTLx = 0.0  # the support's top from the centre of the block below (set from block 0 on)
    rTLy = 0.0
    for j in range(n):
        c = pat[2 * j]
        sl = pat[2 * j + 1]
        b = fld(cp, j, F_B)
        h = fld(cp, j, F_H)
        s = y[col_s(j)]
        sd = y[col_s(j) + 1]
        ps = y[col_psi(j)]
        psd = y[col_psi(j) + 1]
        tx = math.cos(thL)
        ty = -math.sin(thL)
        nx = -ty
        ny = tx
        thj = thL + ps
        omj = omL + psd
        cth = math.cos(thj)
        sth = math.sin(thj)
        # the pivot: the block's own corner on the top below (e = c b, "kind A"), or, where that corner overhangs the
        # top below (a drum slid past the edge of the one under it), the corner of the top below under the block's
        # base ("kind B": e = c b_below - s from the base's centre, the block's base sliding over that corner)
        if c >= RELEASED:
            c = 0.0
        kind_b = c != 0.0 and c * s + b > fld(cp, j, F_BLOW)
        if kind_b:
            e = c * fld(cp, j, F_BLOW) - s
            d = c * fld(cp, j, F_BLOW)
            Px = Tx + d * tx
            Py = Ty + d * ty
            vPx = vTx - omL * d * nx
            vPy = vTy - omL * d * ny
            bPx = bTx - bAL * d * nx - omL * omL * d * tx
            bPy = bTy - bAL * d * ny - omL * omL * d * ty
            # the slip runs along the block's own base: G gains s' t_U (and 2 omega s' perp(t_U) = -2 omega s' n_U)
            fr[j, 2] = cth
            fr[j, 3] = -sth
            fr[j, 4] = sth
            fr[j, 5] = cth
        else:
            e = c * b
            d = s + e
            Px = Tx + d * tx
            Py = Ty + d * ty
            vPx = vTx - omL * d * nx + sd * tx
            vPy = vTy - omL * d * ny + sd * ty
            # affine acceleration of P: a_T - alpha_L d n - 2 omega_L s' n - omega_L^2 d t + s'' t
            bPx = bTx - bAL * d * nx - 2.0 * omL * sd * nx - omL * omL * d * tx
            bPy = bTy - bAL * d * ny - 2.0 * omL * sd * ny - omL * omL * d * ty
            fr[j, 2] = tx
            fr[j, 3] = ty
            fr[j, 4] = nx
            fr[j, 5] = ny
        fr[j, 0] = Px
        fr[j, 1] = Py
        # r_G = rot(thj)(-e, h), r_T = rot(thj)(-e, 2 h); clockwise rotation (x cos + y sin, -x sin + y cos)
        rGx = -e * cth + h * sth
        rGy = e * sth + h * cth
        rTx = -e * cth + 2.0 * h * sth
        rTy = e * sth + 2.0 * h * cth
        G[j, 0] = Px + rGx
        G[j, 1] = Py + rGy
        th[j] = thj
        om[j] = omj
        # perp(r) = (r_y, -r_x): the velocity of r per unit clockwise rate
        vG[j, 0] = vPx + omj * rGy
        vG[j, 1] = vPy - omj * rGx
        bA[j] = bAL
        bG[j, 0] = bPx + bAL * rGy - omj * omj * rGx
        bG[j, 1] = bPy - bAL * rGx - omj * omj * rGy
        if kind_b:
            vG[j, 0] += sd * cth
            vG[j, 1] -= sd * sth
            bG[j, 0] -= 2.0 * omj * sd * sth
            bG[j, 1] -= 2.0 * omj * sd * cth
        for k in range(nf):
            col = free[k]
            # the support's top and its angular acceleration: the block below (or the base)
            if j == 0:
                aTx = 1.0 if col == 0 else 0.0
                aTy = 0.0
                aAL = 0.0
            else:
                aTx = AG[j - 1, 0, k] + AA[j - 1, k] * rTLy
                aTy = AG[j - 1, 1, k] - AA[j - 1, k] * rTLx
                aAL = AA[j - 1, k]
            aPx = aTx - aAL * d * nx
            aPy = aTy - aAL * d * ny
            if col == col_lift(j):
                aPx += nx
                aPy += ny
            elif col == col_s(j):
                if kind_b:
                    aPx += cth
                    aPy -= sth
                else:
                    aPx += tx
                    aPy += ty
            aA = aAL + (1.0 if col == col_psi(j) else 0.0)
            AA[j, k] = aA
            AG[j, 0, k] = aPx + aA * rGy
            AG[j, 1, k] = aPy - aA * rGx
        # the top of block j, the next support: T = P + r_T relative to block j's centre G: r_T - r_G
        Tx = Px + rTx
        Ty = Py + rTy
        vTx = vPx + omj * rTy
        vTy = vPy - omj * rTx
        if kind_b:
            vTx += sd * cth
            vTy -= sd * sth
        rTLx = rTx - rGx  # the top's centre from the centre of mass of block j
        rTLy = rTy - rGy
        bTx = bG[j, 0] + bAL * rTLy - omj * omj * rTLx
        bTy = bG[j, 1] - bAL * rTLx - omj * omj * rTLy
        thL = thj
        omL = omj
    return nf


@hot
def solve_small(M, r, x, nf):
    """``x[:nf] = M[:nf, :nf]^-1 r[:nf]`` by Gaussian elimination with partial pivoting (``M``, ``r`` are
    overwritten); False when the matrix is singular."""
    for k in range(nf):
        p = k
        big = abs(M[k, k])
        for i in range(k + 1, nf):
            if abs(M[i, k]) > big:
                big = abs(M[i, k])
                p = i
        if big == 0.0 or not math.isfinite(big):
            return False
        if p != k:
            for jj in range(nf):
                M[k, jj], M[p, jj] = M[p, jj], M[k, jj]
            r[k], r[p] = r[p], r[k]
        for i in range(k + 1, nf):
            f = M[i, k] / M[k, k]
            if f != 0.0:
                for jj in range(k, nf):
                    M[i, jj] -= f * M[k, jj]
                r[i] -= f * r[k]
    for k in range(nf - 1, -1, -1):
        acc = r[k]
        for jj in range(k + 1, nf):
            acc -= M[k, jj] * x[jj]
        x[k] = acc / M[k, k]
    return True


@hot
def assemble(cp, pat, y, ws, nf, ex, ey, level_v):
    """The linear system of the pattern for its free coordinates: Kane's rows (Coulomb's law in the rows of the
    sliding slips). ``level_v`` False: accelerations, the effective load of block ``i`` being ``b_G + (ex, ey)``
    with ``(ex, ey) = (ag, g)`` (and the base's own forces); True: an impact, the load being ``-v_G-`` (the
    velocities before, in ``ws``'s ``vG`` and ``om`` as given by the caller) and no base force."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    for k in range(nf):
        col = free[k]
        sliding_j = -1
        if col >= 2 and (col - 2) % 4 == 0:
            sliding_j = (col - 2) // 4
            if pat[2 * sliding_j + 1] == 0.0:  # free but not sliding: a released interface's Kane row
                sliding_j = -1
        if sliding_j >= 0:
            # Coulomb: F_j . (t + mu sl n) = 0, F_j = sum_{i >= j} m_i (a_Gi + (ag, g))
            j = sliding_j
            mu = fld(cp, j, F_MU) * (1.0 - mo[j])
            sl = pat[2 * j + 1]
            wx = fr[j, 2] + mu * sl * fr[j, 4]
            wy = fr[j, 3] + mu * sl * fr[j, 5]
            rr = 0.0
            for l in range(nf):
                M[k, l] = 0.0
            for i in range(j, n):
                m = fld(cp, i, F_M)
                for l in range(nf):
                    M[k, l] += m * (wx * AG[i, 0, l] + wy * AG[i, 1, l])
                if level_v:
                    rr += m * (wx * vG[i, 0] + wy * vG[i, 1])
                else:
                    rr -= m * (wx * (bG[i, 0] + ex) + wy * (bG[i, 1] + ey))
            r[k] = rr
            continue
        rr = 0.0
        for l in range(nf):
            M[k, l] = 0.0
        for i in range(n):
            m = fld(cp, i, F_M)
            I = fld(cp, i, F_I)
            px = AG[i, 0, k]
            py = AG[i, 1, k]
            pa = AA[i, k]
            if px == 0.0 and py == 0.0 and pa == 0.0:
                continue
            for l in range(nf):
                M[k, l] += m * (px * AG[i, 0, l] + py * AG[i, 1, l]) + I * pa * AA[i, l]
            if level_v:
                rr += m * (px * vG[i, 0] + py * vG[i, 1]) + I * pa * om[i]
            else:
                rr -= m * (px * (bG[i, 0] + ex) + py * (bG[i, 1] + ey)) + I * pa * bA[i]
        if col == 0:  # the base
            mb = cp[CP_MB]
            M[k, k] += mb
            if level_v:
                rr += mb * y[1]
            else:
                rr -= mb * ex + cp[CP_KB] * y[0] + cp[CP_CB] * y[1]
        r[k] = rr


@hot
def accelerations(cp, pat, y, ag, ws, ydot):
    """The pattern's right-hand side at the state ``y`` (a row): ``ydot`` (same layout; 0 for the coordinates the
    pattern holds). Returns False when the pattern's system is singular (then ``ydot`` holds no accelerations)."""
    if int(cp[CP_N]) == 1 and cp[CP_BASE] == BASE_RIGID:
        return accelerations_one(cp, pat, y, ag, ydot)
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    nf = kinematics(cp, pat, y, ws)
    ny = ydot.shape[0]
    for i in range(ny):
        ydot[i] = 0.0
    for k in range(nf):
        ydot[free[k]] = y[free[k] + 1]
    if nf == 0:
        return True
    ok = solve_level(cp, pat, y, ws, nf, ag, False)
    for k in range(nf):
        ydot[free[k] + 1] = x[k] if ok else 0.0
    return ok


@hot
def accelerations_one(cp, pat, y, ag, ydot):
    """:func:`accelerations` of one block on the rigid ground in closed form (the hot loop of a single body; the
    general solve gives the same numbers to rounding: tests/test_friction_model.py). With ``r = rot(psi)(-c b, h)``
    the centre from the pivot, Newton and Euler about the centre with the corner force ``(T, N)``:
    ``m (s'' + psi'' r_y - psi'^2 r_x + ag) = T``, ``m (g - psi'' r_x - psi'^2 r_y) = N``, ``I psi'' = N r_x - T r_y``;
    sticking, ``s'' = 0``; sliding, ``T = -mu sl N`` (``mu`` 0 where ``N`` would pull), so ``psi'' = m (g - psi'^2
    r_y) k / (I + m r_x k)``, ``k = r_x + mu sl r_y``."""
    for i in range(ydot.shape[0]):
        ydot[i] = 0.0
    c = pat[0]
    sl = pat[1]
    g = cp[CP_G]
    o = CP_BLK
    b, h, m, I, mu = cp[o + F_B], cp[o + F_H], cp[o + F_M], cp[o + F_I], cp[o + F_MU]
    sd = y[3]
    ps = y[4]
    psd = y[5]
    if c == 0.0:
        if sl != 0.0:  # a face sliding on the ground: N = m g
            ydot[2] = sd
            ydot[3] = -ag - mu * sl * g
        return True
    cs = math.cos(ps)
    sn = math.sin(ps)
    rx = -c * b * cs + h * sn
    ry = c * b * sn + h * cs
    ydot[4] = psd
    if sl == 0.0:  # Eq (3): I_O psi'' = m (g r_x - ag r_y) about the still corner
        ydot[5] = m * (g * rx - ag * ry) / (I + m * (rx * rx + ry * ry))
        return True
    k = rx + mu * sl * ry
    pdd = m * (g - psd * psd * ry) * k / (I + m * rx * k)
    N = m * (g - pdd * rx - psd * psd * ry)
    if N < 0.0:  # it pulls: no friction (solve_level's rule)
        k = rx
        pdd = m * (g - psd * psd * ry) * k / (I + m * rx * k)
        N = m * (g - pdd * rx - psd * psd * ry)
        T = 0.0
    else:
        T = -mu * sl * N
    ydot[2] = sd
    ydot[3] = T / m - ag - pdd * ry + psd * psd * rx
    ydot[5] = pdd
    return True


@hot
def forces_one(cp, pat, y, sdd, pdd, ag, out):
    """:func:`contact_forces` of one block on the rigid ground in closed form, for the accelerations ``s''``
    (``sdd``) and ``psi''`` (``pdd``) at the state ``y``: ``out[0] = (N, T, Mc)``, from the equations of
    :func:`accelerations_one` (a face: ``N = m g``, ``T = m (s'' + ag)``, ``Mc = T h`` about its centre). The
    general path gives the same numbers to rounding (tests/test_friction_model.py)."""
    c = pat[0]
    g = cp[CP_G]
    o = CP_BLK
    b, h, m = cp[o + F_B], cp[o + F_H], cp[o + F_M]
    if c == 0.0:
        T = m * (sdd + ag)
        out[0, 0] = m * g
        out[0, 1] = T
        out[0, 2] = T * h
        return
    ps = y[4]
    psd = y[5]
    cs = math.cos(ps)
    sn = math.sin(ps)
    rx = -c * b * cs + h * sn
    ry = c * b * sn + h * cs
    out[0, 0] = m * (g - pdd * rx - psd * psd * ry)
    out[0, 1] = m * (sdd + pdd * ry - psd * psd * rx + ag)
    out[0, 2] = 0.0


@hot
def solve_level(cp, pat, y, ws, nf, ag, level_v):
    """Assemble and solve the pattern's system (accelerations, or at an impact the rates after it: ``level_v``) into
    ``ws``'s ``x``, with Coulomb's law as ``|T| <= mu max(N, 0)``: a sliding contact whose normal force (impulse)
    comes out negative, a pull the model keeps as a contact that does not fly (a jump, counted by the driver), carries
    no friction (``mo[j] = 1``) and the system is solved again. Without that, the friction of a pulling contact would
    push along the slip and feed energy in. False when the system is singular."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    any_slide = False
    for j in range(n):
        mo[j] = 0.0
        if pat[2 * j + 1] != 0.0:
            any_slide = True
    assemble(cp, pat, y, ws, nf, ag, cp[CP_G], level_v)
    if not solve_small(M, r, x, nf):
        return False
    if not any_slide:
        return True
    if level_v:
        impulses(cp, pat, ws, nf, fq)
    else:
        contact_forces(cp, pat, ws, nf, ag, fq)
    again = False
    for j in range(n):
        if pat[2 * j + 1] != 0.0 and fq[j, 0] < 0.0:
            mo[j] = 1.0
            again = True
    if not again:
        return True
    assemble(cp, pat, y, ws, nf, ag, cp[CP_G], level_v)
    return solve_small(M, r, x, nf)


@hot
def contact_forces(cp, pat, ws, nf, ag, out):
    """The contact forces of every interface for the accelerations ``x[:nf]`` of the last solve (``ws`` at the same
    state): ``out[j] = (N, T, Mc)``, the force the block below exerts on everything above interface ``j`` in the frame
    of the surface below (normal, tangential) and its clockwise moment about the contact point (the face's centre:
    the couple that splits ``N`` between the two corners). With ``ag`` None-like (``math.nan``) the loads are the
    velocity jumps of an impact: the impulses."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    g = cp[CP_G]
    Fx = 0.0
    Fy = 0.0
    Mt = 0.0  # moment about the origin of the loads above, accumulated from the top (then shifted to P_j)
    for j in range(n - 1, -1, -1):
        m = fld(cp, j, F_M)
        I = fld(cp, j, F_I)
        ax = bG[j, 0]
        ay = bG[j, 1]
        al = bA[j]
        for k in range(nf):
            ax += AG[j, 0, k] * x[k]
            ay += AG[j, 1, k] * x[k]
            al += AA[j, k] * x[k]
        lx = m * (ax + ag)
        ly = m * (ay + g)
        Fx += lx
        Fy += ly
        # clockwise moment about the origin of the load (lx, ly) at G_j, plus the inertia couple:
        # sum m (a + (ag, g)) . perp(G - P) + I alpha = sum [l_x (G_y - P_y) - l_y (G_x - P_x)] + I alpha
        Mt += lx * G[j, 1] - ly * G[j, 0] + I * al
        Px = fr[j, 0]
        Py = fr[j, 1]
        out[j, 0] = Fx * fr[j, 4] + Fy * fr[j, 5]
        out[j, 1] = Fx * fr[j, 2] + Fy * fr[j, 3]
        out[j, 2] = Mt - Fx * Py + Fy * Px


@hot
def impulses(cp, pat, ws, nf, out):
    """The impulses of every interface for the velocities after an impact ``x[:nf]`` of the last velocity-level
    solve, the velocities before being ``ws``'s ``vG``, ``om`` (as :func:`contact_forces`, with the velocity jumps
    as loads): ``out[j] = (N, T, K)``."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    n = int(cp[CP_N])
    Fx = 0.0
    Fy = 0.0
    Mt = 0.0
    for j in range(n - 1, -1, -1):
        m = fld(cp, j, F_M)
        I = fld(cp, j, F_I)
        vx = -vG[j, 0]
        vy = -vG[j, 1]
        w = -om[j]
        for k in range(nf):
            vx += AG[j, 0, k] * x[k]
            vy += AG[j, 1, k] * x[k]
            w += AA[j, k] * x[k]
        lx = m * vx
        ly = m * vy
        Fx += lx
        Fy += ly
        Mt += lx * G[j, 1] - ly * G[j, 0] + I * w
        Px = fr[j, 0]
        Py = fr[j, 1]
        out[j, 0] = Fx * fr[j, 4] + Fy * fr[j, 5]
        out[j, 1] = Fx * fr[j, 2] + Fy * fr[j, 3]
        out[j, 2] = Mt - Fx * Py + Fy * Px


@kernel
def energy(cp, pat, y, ws):
    """``(kinetic, potential)`` energy of the chain and its base at the state ``y`` (potential: gravity from the
    ground's level and the bearings' spring)."""
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    kinematics(cp, pat, y, ws)
    n = int(cp[CP_N])
    g = cp[CP_G]
    T = 0.0
    V = 0.0
    for i in range(n):
        m = fld(cp, i, F_M)
        T += 0.5 * m * (vG[i, 0] ** 2 + vG[i, 1] ** 2) + 0.5 * fld(cp, i, F_I) * om[i] ** 2
        V += m * g * G[i, 1]
    if cp[CP_BASE] != BASE_RIGID:
        T += 0.5 * cp[CP_MB] * y[1] ** 2
        V += 0.5 * cp[CP_KB] * y[0] ** 2
    return T, V
