"""The mechanics of a chain of rigid blocks with Coulomb friction, written for the slow reference
(:mod:`rockcli.reference.friction`) from the separate bodies' Newton-Euler equations with constraint multipliers,
never from the kernels' relative-coordinate (Kane) equations.

Maximal coordinates: each block ``i`` (0 at the bottom) its centre ``(x, y)`` and angle ``theta`` (clockwise
positive); on bearings one more, the base's displacement ``u``. Interface ``j`` (under block ``j``) in a pattern
``(c, sl)`` (corner: 0 face, +1/-1 pivot; slip: 0 stick, +1/-1 sliding that way) contributes the constraints, in
the frame of the surface below (its top centre ``T``, tangent ``t``, normal ``n``), on the point ``C`` of block
``j`` that touches (its corner ``c``, or its base's centre for a face), with ``d = C - T``:

* the normal gap ``phi_n = d . n = 0`` (always: no flight, a pulling pivot is counted, as in the rocking model);
* the slip ``phi_t = d . t - (s + c b) = 0`` while it sticks (``s`` its slip, frozen);
* the angle ``phi_a = theta_j - theta_(j-1) = 0`` on a face.

Each constraint's generalized force is that of its contact force pair (the normal force ``N`` and the tangential
``T`` at ``C``, the face's couple), so the multipliers are the contact forces. A sliding contact's tangential force
``T = -mu sl N`` is added to the normal one's column. ``M a = F + J^T lam``, ``J a = -(J' v)`` with ``J' v`` from
the second derivatives of the constraints written out below; at an impact ``M (v+ - v-) = J^T Lam``, ``J v+ = 0``.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.io.units import G


def _rot(t, v):
    c, s = math.cos(t), math.sin(t)
    return np.array([c * v[0] + s * v[1], -s * v[0] + c * v[1]])


def _perp(v):
    return np.array([v[1], -v[0]])


class FrictionChain:
    """Blocks ``[(b, h, m), ...]`` bottom to top, friction ``mus`` per interface, ``base`` ``(m_b, k_b, c_b)`` or
    None (the rigid ground)."""

    def __init__(self, blocks, mus, base=None):
        self.n = len(blocks)
        self.b = np.array([float(b) for b, _, _ in blocks])
        self.h = np.array([float(h) for _, h, _ in blocks])
        self.m = np.array([float(m) for _, _, m in blocks])
        self.I = self.m * (self.b ** 2 + self.h ** 2) / 3.0
        self.mu = np.array([float(x) for x in mus])
        self.base = None if base is None else tuple(float(x) for x in base)
        self.nb = 0 if base is None else 1
        self.N = 3 * self.n + self.nb
        self.Mdiag = np.concatenate([[m, m, i] for m, i in zip(self.m, self.I)] + ([[self.base[0]]] if self.nb else []))
        self.edge = np.array([math.inf] + [self.b[i - 1] - self.b[i] for i in range(1, self.n)])
        self.alpha = np.empty(self.n)
        for i in range(self.n):
            mass = self.m[i:].sum()
            ys = 2.0 * np.cumsum(self.h)[i:] - self.h[i:] - 2.0 * self.h[:i].sum()
            self.alpha[i] = math.atan2(self.b[i] * mass, float(np.dot(self.m[i:], ys)))

    # ---- relative coordinates -> maximal -------------------------------------------------------------
    def maximal(self, pat, q, qd):
        """Positions ``X`` and velocities ``V`` (maximal) from the relative coordinates ``q = (u, s_0, psi_0, ...)``
        and their rates, in the pattern's chart (a pivot turns about its corner)."""
        n = self.n
        X = np.zeros(self.N)
        V = np.zeros(self.N)
        u, ud = (q[0], qd[0]) if self.nb else (0.0, 0.0)
        if self.nb:
            X[-1], V[-1] = u, ud
        T = np.array([u, 0.0])
        vT = np.array([ud, 0.0])
        th, om = 0.0, 0.0
        for j in range(n):
            c = pat[2 * j]
            s, ps = q[1 + 2 * j], q[2 + 2 * j]
            sd, psd = qd[1 + 2 * j], qd[2 + 2 * j]
            t = _rot(th, (1.0, 0.0))
            d = s + c * self.b[j]
            P = T + d * t
            # the point of the surface that moves with the block below, plus the slip along it
            vP = vT + om * _perp(d * t) + sd * t
            thj = th + ps
            omj = om + psd
            rG = _rot(thj, (-c * self.b[j], self.h[j]))
            G_ = P + rG
            vG = vP + omj * _perp(rG)
            X[3 * j:3 * j + 3] = G_[0], G_[1], thj
            V[3 * j:3 * j + 3] = vG[0], vG[1], omj
            rT = _rot(thj, (0.0, self.h[j]))
            T = G_ + rT
            vT = vG + omj * _perp(rT)
            th, om = thj, omj
        return X, V

    # ---- the constraints ------------------------------------------------------------------------------
    def _points(self, j, c, X, V):
        """For interface ``j``: ``(C, vC, rho_C, T, vT, rho_T, th_L, om_L)``, the touching point of block ``j``
        (its arm from its centre) and the top centre of the surface below (its arm from the lower centre)."""
        G_ = X[3 * j:3 * j + 2]
        thU, omU = X[3 * j + 2], V[3 * j + 2]
        rhoC = _rot(thU, (c * self.b[j], -self.h[j]))
        C = G_ + rhoC
        vC = V[3 * j:3 * j + 2] + omU * _perp(rhoC)
        if j == 0:
            if self.nb:
                T = np.array([X[-1], 0.0])
                vT = np.array([V[-1], 0.0])
            else:
                T = np.zeros(2)
                vT = np.zeros(2)
            return C, vC, rhoC, T, vT, None, 0.0, 0.0
        GL = X[3 * (j - 1):3 * (j - 1) + 2]
        thL, omL = X[3 * (j - 1) + 2], V[3 * (j - 1) + 2]
        rhoT = _rot(thL, (0.0, self.h[j - 1]))
        return C, vC, rhoC, GL + rhoT, V[3 * (j - 1):3 * (j - 1) + 2] + omL * _perp(rhoT), rhoT, thL, omL

    def constraints(self, pat, X, V):
        """Rows ``J`` (k x N), the bias ``J' V`` (k), and the kind of each row: ``(j, 'n' | 't' | 'a')``."""
        rows, bias, kinds = [], [], []
        for j in range(self.n):
            c, sl = pat[2 * j], pat[2 * j + 1]
            C, vC, rhoC, T, vT, rhoT, thL, omL = self._points(j, c, X, V)
            t = _rot(thL, (1.0, 0.0))
            nn = _rot(thL, (0.0, 1.0))
            d = C - T
            dd = vC - vT
            omU = V[3 * j + 2]
            for kind, e, f in (("n", nn, t), ("t", t, nn)):
                if kind == "t" and sl != 0.0:
                    continue
                row = np.zeros(self.N)
                # d'' = aU + alphaU perp(rhoC) - omU^2 rhoC - (aL + alphaL perp(rhoT) - omL^2 rhoT) (or the base's)
                row[3 * j:3 * j + 2] += e
                row[3 * j + 2] += float(np.dot(_perp(rhoC), e))
                b = -omU ** 2 * float(np.dot(rhoC, e))
                if j > 0:
                    row[3 * (j - 1):3 * (j - 1) + 2] -= e
                    row[3 * (j - 1) + 2] -= float(np.dot(_perp(rhoT), e))
                    b += omL ** 2 * float(np.dot(rhoT, e))
                elif self.nb:
                    row[-1] -= e[0]
                if kind == "n":
                    # phi_n'' = d''.n + 2 omL d'.t + alphaL d.t - omL^2 d.n
                    if j > 0:
                        row[3 * (j - 1) + 2] += float(np.dot(d, t))
                    b += 2.0 * omL * float(np.dot(dd, t)) - omL ** 2 * float(np.dot(d, nn))
                else:
                    # phi_t'' = d''.t - 2 omL d'.n - alphaL d.n - omL^2 d.t
                    if j > 0:
                        row[3 * (j - 1) + 2] -= float(np.dot(d, nn))
                    b += -2.0 * omL * float(np.dot(dd, nn)) - omL ** 2 * float(np.dot(d, t))
                rows.append(row)
                bias.append(b)
                kinds.append((j, kind))
            if c == 0.0:
                row = np.zeros(self.N)
                row[3 * j + 2] = 1.0
                if j > 0:
                    row[3 * (j - 1) + 2] = -1.0
                rows.append(row)
                bias.append(0.0)
                kinds.append((j, "a"))
        return np.array(rows).reshape(len(rows), self.N), np.array(bias), kinds

    def tangent_row(self, j, c, X, V):
        """The row of ``phi_t`` of interface ``j`` (its generalized force direction; for a sliding contact's
        friction force) and the slip's acceleration bias."""
        pat = [0.0] * (2 * self.n)
        pat[2 * j] = c
        J, b, kinds = self.constraints(pat, X, V)
        i = kinds.index((j, "t"))
        return J[i], b[i]

    def loads(self, X, V, ag):
        """The applied generalized forces: gravity, the inertial force ``-m ag`` and the bearings'."""
        F = np.zeros(self.N)
        for i in range(self.n):
            F[3 * i] = -self.m[i] * ag
            F[3 * i + 1] = -self.m[i] * G
        if self.nb:
            mb, kb, cb = self.base
            F[-1] = -mb * ag - kb * X[-1] - cb * V[-1]
        return F

    def solve(self, pat, X, V, F, level="a"):
        """``(a, lam, kinds)``: accelerations (``level="a"``, ``F`` the loads) or velocity jumps (``"v"``, ``F`` =
        0 and the right-hand side ``-J V``) with the multipliers (forces or impulses) of the pattern's constraints,
        the sliding contacts' friction added to their normal columns. Coulomb's law is ``|T| <= mu max(N, 0)``: a
        sliding contact whose normal multiplier comes out negative (it pulls: a jump the model does not follow) is
        solved again without friction."""
        off = set()
        a, lam, kinds = self._solve(pat, X, V, F, level, off)
        pulling = {j for (j, kind), v in zip(kinds, lam) if kind == "n" and pat[2 * j + 1] != 0.0 and v < 0.0}
        if pulling:
            a, lam, kinds = self._solve(pat, X, V, F, level, pulling)
            self.last_off = pulling
        else:
            self.last_off = set()
        return a, lam, kinds

    def _solve(self, pat, X, V, F, level, off):
        J, bias, kinds = self.constraints(pat, X, V)
        k = J.shape[0]
        cols = J.T.copy()
        for i, (j, kind) in enumerate(kinds):
            sl = pat[2 * j + 1]
            if kind == "n" and sl != 0.0 and j not in off:
                Jt, _ = self.tangent_row(j, pat[2 * j], X, V)
                cols[:, i] += -self.mu[j] * sl * Jt
        A = np.zeros((self.N + k, self.N + k))
        A[:self.N, :self.N] = np.diag(self.Mdiag)
        A[:self.N, self.N:] = -cols
        A[self.N:, :self.N] = J
        rhs = np.zeros(self.N + k)
        if level == "a":
            rhs[:self.N] = F
            rhs[self.N:] = -bias
        else:
            rhs[self.N:] = -J @ V
        sol = np.linalg.solve(A, rhs)
        return sol[:self.N], sol[self.N:], kinds

    def relative_rates(self, pat, X, V, A):
        """``(u'', s_j'', psi_j'')`` (or their velocity counterparts with ``A`` the velocities) in the relative
        coordinates: ``psi_j'' = alpha_j - alpha_(j-1)``, ``s_j''`` the slip's acceleration ``phi_t''`` of the
        pattern's touching point."""
        out = np.zeros(1 + 2 * self.n)
        if self.nb:
            out[0] = A[-1]
        for j in range(self.n):
            out[2 + 2 * j] = A[3 * j + 2] - (A[3 * (j - 1) + 2] if j > 0 else 0.0)
            Jt, b = self.tangent_row(j, pat[2 * j], X, V)
            out[1 + 2 * j] = float(Jt @ A) + b
        return out

    def forces(self, pat, lam, kinds):
        """``(N, T, Mc)`` per interface from the multipliers (a slide's ``T = -mu sl N``)."""
        out = np.zeros((self.n, 3))
        for (j, kind), v in zip(kinds, lam):
            out[j, {"n": 0, "t": 1, "a": 2}[kind]] = v
        for j in range(self.n):
            if pat[2 * j + 1] != 0.0:
                mu = 0.0 if j in getattr(self, "last_off", ()) else self.mu[j]
                out[j, 1] = -mu * pat[2 * j + 1] * out[j, 0]
        return out

    def energy(self, X, V):
        T = 0.5 * float(np.dot(self.Mdiag, V * V))
        U = sum(self.m[i] * G * X[3 * i + 1] for i in range(self.n))
        if self.nb:
            U += 0.5 * self.base[1] * X[-1] ** 2
        return T, U
