"""The mechanics of a stack of rigid rectangular blocks rocking on a rigid foundation, written for the slow
reference (:mod:`rockcli.reference.stack`) from the separate bodies, never from the kernels' closed forms.

Each block ``i`` (0 at the bottom) has half-width ``b``, half-height ``h``, mass ``m`` and central inertia
``m (b^2 + h^2)/3``, and three maximal coordinates: its centre of mass ``(x, y)`` and its angle ``theta``
(clockwise positive: theta > 0 is a rotation about the right corner, rockcli's sign). Interface ``i`` lies under
block ``i`` (interface 0 on the ground). Its state ``st[i]`` is 0 (a face: the two surfaces stuck together, three
constraints: the centres of the two surfaces coincide and the angles are equal) or ``+1``/``-1`` (a pivot on the
right/left corner of the contact, two constraints: the two corner points coincide; no sliding). The contact half
width is ``c = min(b_i, b_(i-1))`` (``b_0`` on the ground), the stack being centred.

The minimal coordinates are the relative angles ``psi[i] = theta_i - theta_(i-1)`` of the pivots (0 at faces).
Accelerations and contact forces come from Newton-Euler with Lagrange multipliers (the constrained system in
maximal coordinates, solved as one linear system, ``M a = F + J^T lam``, ``J a = -gamma``), impacts from the same
system at velocity level (``M v+ = M v- + J^T Lam``, ``J v+ = 0``): the impulses act at the constraints of the
motion after the impact only, which is the plastic (Housner-type) impact. Forces are read in the frame of the
lower surface: normal ``N``, tangential ``T``, and at a face the couple, split into the two corner forces
``P_right = N/2 - M/(2c)``, ``P_left = N/2 + M/(2c)`` (``M`` clockwise on the upper block about the face centre).

On linear bearings (``base = (m_b, k_b, c_b)``, per unit mass of the top block's units) the ground under interface
0 is an isolated base: one more maximal coordinate, its horizontal displacement ``u`` relative to the ground (its
height and angle are fixed), mass ``m_b``, under the bearing force ``-k_b u - c_b u'`` and the inertial force
``-m_b ag``. Interface 0's constraints tie the bottom block's contact points to the base's top (``x = u``). The
minimal coordinates are then the pivots' angles and ``u``; everything else (the KKT system, impacts, forces) is
unchanged: the impulses between the blocks and the base are internal, so an impact keeps the total horizontal
momentum (the base is free horizontally at the instant of an impact, the bearings' forces being finite). On
hysteretic bearings (sliding, lead-rubber) the bearings' force, which depends on their own states, is given to
:meth:`StackModel.accelerations` (``Fb``); nothing else changes.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.io.units import G


def _rot(t: float, x: float, y: float):
    """The clockwise rotation by ``t`` of the body-frame vector ``(x, y)``: its ground-frame components."""
    c, s = math.cos(t), math.sin(t)
    return c * x + s * y, -s * x + c * y


def _perp(v):
    """``d(rot(t) r)/dt`` per unit clockwise rate: ``(y, -x)``."""
    return v[1], -v[0]


class StackModel:
    """A stack of ``blocks`` ``[(b, h, m), ...]`` (half-width [m], half-height [m], mass), bottom to top."""

    def __init__(self, blocks, base=None):
        self.n = len(blocks)
        # the isolated base (m_b, k_b, c_b), or None: the rigid ground
        self.base = None if base is None else tuple(float(x) for x in base)
        self.nb = 0 if base is None else 1
        self.N = 3 * self.n + self.nb
        self.b = np.array([float(b) for b, _, _ in blocks])
        self.h = np.array([float(h) for _, h, _ in blocks])
        self.m = np.array([float(m) for _, _, m in blocks])
        self.I = self.m * (self.b ** 2 + self.h ** 2) / 3.0
        self.c = np.array([self.b[0]] + [min(self.b[i], self.b[i - 1]) for i in range(1, self.n)])
        self.Mdiag = np.concatenate([[m, m, i] for m, i in zip(self.m, self.I)] + ([[self.base[0]]] if self.nb else []))
        # the same blocks on the rigid ground (the rest rules ride on a given base acceleration)
        self.ground = self if base is None else StackModel(blocks)
        # the stack above each interface as one rigid body at rest: its slenderness about a corner
        self.alpha = np.empty(self.n)
        self.weight = np.empty(self.n)
        for i in range(self.n):
            y0 = 2.0 * self.h[:i].sum()
            ys = 2.0 * np.cumsum(self.h)[i:] - self.h[i:] - y0
            mass = self.m[i:].sum()
            self.alpha[i] = math.atan2(self.c[i] * mass, float(np.dot(self.m[i:], ys)))
            self.weight[i] = mass * G

    # ---- kinematics ---------------------------------------------------------------------------------
    def angles(self, q) -> np.ndarray:
        return np.cumsum(np.asarray(q, float))

    def positions(self, st, q, u=0.0):
        """``(theta (n,), G (n, 2) centres of mass, pivot points (n, 2); NaN at faces)``; ``u`` the base's
        displacement (on linear bearings)."""
        th = self.angles(q)
        G_ = np.empty((self.n, 2))
        piv = np.full((self.n, 2), np.nan)
        lx, ly = float(u), 0.0  # centre of the lower surface (the ground's or base's origin, then each block's top)
        for i in range(self.n):
            thl = th[i - 1] if i else 0.0
            if st[i] == 0:
                bx, by = lx, ly
            else:
                dx, dy = _rot(thl, st[i] * self.c[i], 0.0)
                px, py = lx + dx, ly + dy
                piv[i] = px, py
                dx, dy = _rot(th[i], -st[i] * self.c[i], 0.0)
                bx, by = px + dx, py + dy
            dx, dy = _rot(th[i], 0.0, self.h[i])
            G_[i] = bx + dx, by + dy
            lx, ly = bx + 2.0 * dx, by + 2.0 * dy
        return th, G_, piv

    def velocities(self, st, q, qd, ud=0.0) -> np.ndarray:
        """Maximal velocities ``(x', y', theta')`` of every block (and ``u'`` of the base, last) from the relative
        rates ``qd`` of the pivots and the base's rate ``ud``: each pivot turns everything above it about its
        point, the base carries everything."""
        _, G_, piv = self.positions(st, q)
        v = np.zeros(self.N)
        if self.nb:
            v[0:3 * self.n:3] = ud
            v[3 * self.n] = ud
        for i in range(self.n):
            for j in range(i + 1):
                if st[j] != 0 and qd[j] != 0.0:
                    v[3 * i] += qd[j] * (G_[i, 1] - piv[j, 1])
                    v[3 * i + 1] -= qd[j] * (G_[i, 0] - piv[j, 0])
                    v[3 * i + 2] += qd[j]
        return v

    def rel_rates(self, v) -> np.ndarray:
        """Relative angular velocities of the interfaces from maximal velocities."""
        w = v[2::3]
        return w - np.concatenate([[0.0], w[:-1]])

    # ---- constraints ----------------------------------------------------------------------------------
    def constraints(self, st, q, v=None):
        """``(J, gamma, rows)``: the constraint Jacobian on the maximal coordinates, the velocity-product term
        of ``J a`` (``J a + gamma = 0``; needs ``v``) and per interface the slice of its rows."""
        th = self.angles(q)
        w = None if v is None else v[2::3]
        nc = sum(2 if s else 3 for s in st)
        J, gam, rows = np.zeros((nc, self.N)), np.zeros(nc), []
        r = 0
        for i in range(self.n):
            r0 = r
            Ri = _rot(th[i], st[i] * self.c[i], -self.h[i])  # the contact point on block i, from its centre
            Pi = _perp(Ri)
            Rl = _rot(th[i - 1], st[i] * self.c[i], self.h[i - 1]) if i else None
            for ax in range(2):
                J[r, 3 * i + ax] = 1.0
                J[r, 3 * i + 2] = Pi[ax]
                if w is not None:
                    gam[r] = -w[i] ** 2 * Ri[ax]
                if i:
                    J[r, 3 * (i - 1) + ax] = -1.0
                    J[r, 3 * (i - 1) + 2] = -_perp(Rl)[ax]
                    if w is not None:
                        gam[r] += w[i - 1] ** 2 * Rl[ax]
                elif self.nb and ax == 0:  # the base's top point moves with the base (it neither rises nor turns)
                    J[r, 3 * self.n] = -1.0
                r += 1
            if st[i] == 0:
                J[r, 3 * i + 2] = 1.0
                if i:
                    J[r, 3 * (i - 1) + 2] = -1.0
                r += 1
            rows.append(slice(r0, r))
        return J, gam, rows

    def _kkt(self, J, rhs_top, rhs_bottom):
        n3, nc = self.N, J.shape[0]
        A = np.zeros((n3 + nc, n3 + nc))
        A[np.arange(n3), np.arange(n3)] = self.Mdiag
        A[:n3, n3:] = -J.T
        A[n3:, :n3] = J
        sol = np.linalg.solve(A, np.concatenate([rhs_top, rhs_bottom]))
        return sol[:n3], sol[n3:]

    def contact(self, st, q, lam, rows):
        """Per interface ``(N, T, P_right, P_left)`` from the multipliers (forces or impulses on the upper block)."""
        th = self.angles(q)
        out = []
        for i in range(self.n):
            thl = th[i - 1] if i else 0.0
            nrm, tan = _rot(thl, 0.0, 1.0), _rot(thl, 1.0, 0.0)
            lm = lam[rows[i]]
            N, T = float(lm[0] * nrm[0] + lm[1] * nrm[1]), float(lm[0] * tan[0] + lm[1] * tan[1])
            if st[i] == 0:
                Mcw = float(lm[2])
                out.append((N, T, N / 2 - Mcw / (2 * self.c[i]), N / 2 + Mcw / (2 * self.c[i])))
            else:
                out.append((N, T, N if st[i] > 0 else 0.0, N if st[i] < 0 else 0.0))
        return out

    # ---- dynamics ---------------------------------------------------------------------------------------
    def dynamics(self, st, q, qd, ag: float, g: float = G):
        """``(psi_dd (n,), contact forces per interface (N, T, P_right, P_left))`` under the ground acceleration
        ``ag`` (its inertial force ``-m ag`` on every block, in the ground's frame) and gravity ``g``; on linear
        bearings the base at rest (``u = u' = 0``): see :meth:`accelerations`."""
        return self.accelerations(st, q, qd, ag, g=g)[:2]

    def accelerations(self, st, q, qd, ag: float, u: float = 0.0, ud: float = 0.0, g: float = G, Fb=None):
        """``(psi_dd (n,), contact forces per interface, u_dd)``: :meth:`dynamics` with the base at ``u``,
        ``u'`` (its acceleration relative to the ground ``u_dd``; 0 on the rigid ground). ``Fb``, when given, is
        the bearings' force on the base (a hysteretic bearing's, which depends on its own states) in place of
        ``-k_b u - c_b u'``."""
        v = self.velocities(st, q, qd, ud)
        J, gam, rows = self.constraints(st, q, v)
        F = np.zeros(self.N)
        F[0:3 * self.n:3], F[1:3 * self.n:3] = -self.m * ag, -self.m * g
        if self.nb:
            mb, kb, cb = self.base
            F[3 * self.n] = -mb * ag - kb * u - cb * ud if Fb is None else -mb * ag + Fb
        a, lam = self._kkt(J, F, -gam)
        return self.rel_rates(a), self.contact(st, q, lam, rows), (float(a[3 * self.n]) if self.nb else 0.0)

    def impact(self, st, q, v_minus, rate=None):
        """Velocities just after an impact into the pattern ``st``: ``(v+, impulses per interface)``.

        The impulses act at the constraints of ``st`` only (plastic: every contact of ``st`` keeps its points
        together after the impact). ``rate = (j, target)`` also prescribes the relative rate of the pivot ``j``
        (the restitution rule of the note); the multiplier of that row is the impulsive couple there."""
        J, _, rows = self.constraints(st, q)
        b = np.zeros(J.shape[0])
        if rate is not None:
            j, target = rate
            row = np.zeros(self.N)
            row[3 * j + 2] = 1.0
            if j:
                row[3 * (j - 1) + 2] = -1.0
            J = np.vstack([J, row])
            b = np.append(b, target)
        v, lam = self._kkt(J, self.Mdiag * v_minus, b)
        return v, self.contact(st, q, lam[:sum(r.stop - r.start for r in rows)], rows)

    def kinetic(self, v) -> float:
        return 0.5 * float(np.sum(self.Mdiag * v * v))

    def kinetic_relative(self, v) -> float:
        """The blocks' kinetic energy relative to the base (the rocking energy; :meth:`kinetic` on rigid ground)."""
        if not self.nb:
            return self.kinetic(v)
        w = np.array(v[:3 * self.n], float)
        w[0::3] -= v[3 * self.n]
        return 0.5 * float(np.sum(self.Mdiag[:3 * self.n] * w * w))

    def base_velocity(self, v) -> float:
        return float(v[3 * self.n]) if self.nb else 0.0

    def momenta(self, st, q, v) -> np.ndarray:
        """The generalized momenta of the motion ``v`` along every pivot direction of ``st`` (each pivot turning
        everything above it): what a plastic impact into ``st`` keeps."""
        out = []
        for j in range(self.n):
            if st[j] != 0:
                e = np.zeros(self.n)
                e[j] = 1.0
                out.append(float(np.sum(self.Mdiag * v * self.velocities(st, q, e))))
        if self.nb:  # the base's direction: the total horizontal momentum
            out.append(float(np.sum(self.Mdiag * v * self.velocities(st, q, np.zeros(self.n), 1.0))))
        return np.array(out)
