"""The mechanics of a column of drums with Coulomb friction for the slow reference (:mod:`rockcli.reference.friction_drums`),
from the separate bodies (maximal coordinates, Newton-Euler with constraint multipliers), never from the kernels'
relative-coordinate (Kane) equations.

Bodies and coordinates. Drum ``i`` (0 at the bottom) has its centre ``G_i = (x_i, y_i)`` and its angle ``theta_i``
(clockwise positive); on bearings one more coordinate, the base's ``u``. A vector fixed in a body turns as
``rot(theta)(x, y) = (x cos + y sin, -x sin + y cos)``; its rate per unit clockwise rate is ``perp(x, y) = (y, -x)``.
The support of drum 0 is the ground (or the base at ``(u, 0)``), which does not turn. ``M a = F + sum_k J_k^T
lambda_k``: ``M`` diagonal (masses, central inertias ``m (b^2 + h^2)/3``; the base's mass), ``F`` gravity and the
inertial force ``-m ag`` (the ground's frame) and the bearings' spring and damper.

One constraint for every contact force. Every contact is a point of one body on a line of the other: a material
point ``P_A = G_A + rot(theta_A) r_A`` of body ``A`` and a line of body ``B`` through ``P_B = G_B + rot(theta_B) r_B``
with the body-fixed direction ``d = rot(theta_B) d_0``; ``phi = (P_A - P_B) . d``. Differentiating,

    dphi/dx_A = d,   dphi/dtheta_A = perp(r_A) . d,   dphi/dx_B = -d,   dphi/dtheta_B = -perp(r_B) . d + w . perp(d),
    phi'' = J a + (-omega_A^2 r_A + omega_B^2 r_B) . d + 2 omega_B (v_PA - v_PB) . perp(d) - omega_B^2 w . d,

``w = P_A - P_B`` (``d' = omega_B perp(d)``, ``d'' = alpha_B perp(d) - omega_B^2 d``). The row ``J = grad phi`` is the
generalized force of a unit force along ``d`` on ``A`` at the contact (and its reaction on ``B``): where ``w`` lies
along the line, ``w . perp(d)`` is the arm of the reaction's moment about ``P_B``. So each multiplier is a contact
force, signed as below, and ``J a + bias`` is the exact second derivative of a function of the positions.

Interface ``j`` (drum ``j`` on the top of drum ``j - 1``, or on the support), ``T`` the centre of the top below, ``t``,
``n`` its tangent and upward normal, ``b``, ``h`` the half sizes of drum ``j``, ``b_L`` of the drum below (``inf`` on
the support and for a body on its plinth, where the plinth's own fall criterion holds instead), ``s`` the slip:

* **face** (``c = 0``): two normal constraints, the material points of drum ``j``'s base at the ends of the overlap
  ``e_R = min(b, b_L - s)``, ``e_L = max(-b, -b_L - s)`` against the top below (``phi = gap``, multipliers the corner
  forces ``N_R``, ``N_L``), and the slip ``s = (B - T) . t`` of its base's centre ``B`` (multiplier the friction
  ``T`` on drum ``j`` along ``t``). Any two points of the base give the same motion; these give the corner forces at
  the ends of the contact (docs/physics-drums.md).
* **pivot of kind A** (``c = +-1``, drum ``j``'s corner on the top below, ``c s + b <= b_L``): the corner ``C`` against
  the top: ``gap = (C - T) . n``, ``s = (C - T) . t - c b``.
* **pivot of kind B** (``c s + b > b_L``: the corner overhangs, the lower drum's top corner ``K`` bears on drum
  ``j``'s base line, through ``B`` with tangent ``t_U`` and normal ``n_U`` of drum ``j``): ``gap = (B - K) . n_U``
  (measured normal to the upper's base), ``s = c b_L - (K - B) . t_U`` (``K`` sits at ``e = c b_L - s`` along the
  base: the slip runs along the upper's base, and the friction acts along ``t_U``). At ``c s + b = b_L`` both kinds
  are the same point: positions are continuous across the switch.

**Flight** (``flight=True`` of the reference, :mod:`rockcli.reference.drum_flight`): interface ``j`` flying is coded in
a pattern as ``2 c`` (the chart of a pivot of kind A on corner ``c``) or ``3 c`` (of kind B), its slip entry 0; its
chart is that pivot's with the gap not held: ``q`` then carries one more coordinate per interface after the others,
the lift ``z_j = q[1 + 2 n + j]`` (the value of the chart's ``n`` row: kind A, the corner's height above the line of
the top below; kind B, the lower corner's depth below the drum's base line), and nothing acts at the interface.
Patterns without flying interfaces and ``q`` of length ``1 + 2 n`` are computed exactly as before.

A held normal constraint keeps its gap at 0 (no flight: a pivot's normal force may pull, counted); a sticking
contact holds its slip; a sliding one has ``T = -mu sl N`` (Coulomb: the normal column gets ``-mu sl`` times the
tangent row), and carries no friction where its ``N`` comes out negative (``|T| <= mu max(N, 0)``: solved again
without it, as the existing reference; and again while another sliding contact with friction is left pulling, where
the existing reference and the driver stop after one pass). At an impact the same rows at the velocity level:
``M (v+ - v-) = J^T Lambda``, ``J v+ = 0``. The relative coordinates (``u``, ``s_j``, ``psi_j = theta_j - theta_(j-1)``) are exact
functions of the positions, so their rates and accelerations are read from the same rows.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.io.units import G


def _rot(t, x, y):
    c, s = math.cos(t), math.sin(t)
    return x * c + y * s, -x * s + y * c


class DrumChain:
    """Blocks ``[(b, h, m), ...]`` bottom to top, friction ``mus`` per interface, ``base`` ``(m_b, k_b, c_b)`` or None
    (the rigid ground); ``blow`` per interface the half width of the top below (``inf``: no overlap, no kind B),
    ``edge`` the slip at which it fails by sliding off (``inf``: never)."""

    def __init__(self, blocks, mus, base=None, blow=None, edge=None):
        n = self.n = len(blocks)
        self.b = [float(x[0]) for x in blocks]
        self.h = [float(x[1]) for x in blocks]
        self.m = [float(x[2]) for x in blocks]
        self.I = [m * (b * b + h * h) / 3.0 for b, h, m in zip(self.b, self.h, self.m)]
        self.mu = [float(x) for x in mus]
        self.base = None if base is None else tuple(float(x) for x in base)
        self.nb = 0 if base is None else 1
        self.N = 3 * n + self.nb
        self.Mdiag = np.array([v for i in range(n) for v in (self.m[i], self.m[i], self.I[i])]
                              + ([self.base[0]] if self.nb else []))
        self.Minv = 1.0 / self.Mdiag
        self.blow = [math.inf] * n if blow is None else [float(x) for x in blow]
        self.edge = [math.inf] * n if edge is None else [float(x) for x in edge]
        # the slenderness of everything above interface j as one body, about the corner of its contact at rest
        self.alpha = []
        for j in range(n):
            mass = sum(self.m[j:])
            y0 = ym = 0.0
            for i in range(j, n):
                ym += self.m[i] * (y0 + self.h[i])
                y0 += 2.0 * self.h[i]
            self.alpha.append(math.atan2(min(self.b[j], self.blow[j]) * mass, ym))
        self.last_off = set()

    # ---- geometry ----------------------------------------------------------------------------------
    def kind_b(self, j, c, s):
        """True where interface ``j``'s pivot on corner ``c`` at slip ``s`` is of kind B (the corner overhangs)."""
        return c != 0.0 and c * s + self.b[j] > self.blow[j]

    def chart(self, j, c, s):
        """``(corner, kind B, flying)`` of interface ``j`` coded ``c`` at slip ``s`` (module notes on flight)."""
        if abs(c) >= 2.0:
            return math.copysign(1.0, c), abs(c) == 3.0, True
        return c, self.kind_b(j, c, s), False

    def ends(self, j, s):
        """``(e_R, e_L)``: the ends of the overlap from the centre of drum ``j``'s base."""
        b, bl = self.b[j], self.blow[j]
        return min(b, bl - s), max(-b, -bl - s)

    def maximal(self, pat, q, qd):
        """Positions and velocities (maximal) from the relative coordinates ``q = (u, s_0, psi_0, ...)`` and their
        rates in the chart of ``pat`` (a pivot turns about its point of contact, of kind A or B)."""
        n = self.n
        X = np.zeros(self.N)
        V = np.zeros(self.N)
        Tx, Ty, vTx, vTy = 0.0, 0.0, 0.0, 0.0
        if self.nb:
            X[-1], V[-1] = q[0], qd[0]
            Tx, vTx = q[0], qd[0]
        thL = omL = 0.0
        for j in range(n):
            c, kb, fly = self.chart(j, pat[2 * j], q[1 + 2 * j])
            s, ps = q[1 + 2 * j], q[2 + 2 * j]
            sd, psd = qd[1 + 2 * j], qd[2 + 2 * j]
            tx, ty = _rot(thL, 1.0, 0.0)
            th, om = thL + ps, omL + psd
            if kb:
                e = c * self.blow[j] - s
                d = c * self.blow[j]
                Px, Py = Tx + d * tx, Ty + d * ty
                vPx, vPy = vTx + omL * d * ty, vTy - omL * d * tx  # a material point of the drum below
                rx, ry = _rot(th, -e, self.h[j])
                ux, uy = _rot(th, 1.0, 0.0)
                vGx, vGy = vPx + om * ry + sd * ux, vPy - om * rx + sd * uy  # e' = -s'
                if fly:  # the base line lifted by z along the drum's own normal
                    z, zd = q[1 + 2 * n + j], qd[1 + 2 * n + j]
                    nx, ny = _rot(th, 0.0, 1.0)
                    rx, ry = _rot(th, -e, self.h[j] + z)
                    vGx, vGy = vPx + om * ry + sd * ux + zd * nx, vPy - om * rx + sd * uy + zd * ny
            else:
                d = s + c * self.b[j]
                Px, Py = Tx + d * tx, Ty + d * ty
                vPx, vPy = vTx + omL * d * ty + sd * tx, vTy - omL * d * tx + sd * ty
                if fly:  # the corner lifted by z along the normal of the top below
                    z, zd = q[1 + 2 * n + j], qd[1 + 2 * n + j]
                    nx, ny = _rot(thL, 0.0, 1.0)
                    Px, Py = Px + z * nx, Py + z * ny
                    vPx, vPy = vPx + omL * z * ny + zd * nx, vPy - omL * z * nx + zd * ny
                rx, ry = _rot(th, -c * self.b[j], self.h[j])
                vGx, vGy = vPx + om * ry, vPy - om * rx
            Gx, Gy = Px + rx, Py + ry
            X[3 * j:3 * j + 3] = Gx, Gy, th
            V[3 * j:3 * j + 3] = vGx, vGy, om
            ax, ay = _rot(th, 0.0, self.h[j])
            Tx, Ty = Gx + ax, Gy + ay
            vTx, vTy = vGx + om * ay, vGy - om * ax
            thL, omL = th, om
        return X, V

    # ---- constraints -------------------------------------------------------------------------------
    def _body(self, i, X, V):
        if i >= 0:
            return X[3 * i], X[3 * i + 1], X[3 * i + 2], V[3 * i], V[3 * i + 1], V[3 * i + 2]
        if self.nb:
            return X[-1], 0.0, 0.0, V[-1], 0.0, 0.0
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0

    def _pol(self, X, V, ia, ra, ib, rb, d0):
        """A point of body ``ia`` (arm ``ra`` in its frame) on the line of body ``ib`` through arm ``rb`` along
        ``d0`` (its frame): ``(phi, row, bias)``, ``phi'' = row . a + bias`` (module notes)."""
        gax, gay, tha, vax, vay, oma = self._body(ia, X, V)
        gbx, gby, thb, vbx, vby, omb = self._body(ib, X, V)
        rax, ray = _rot(tha, *ra)
        rbx, rby = _rot(thb, *rb)
        dx, dy = _rot(thb, *d0)
        pdx, pdy = dy, -dx  # perp(d)
        wx, wy = gax + rax - gbx - rbx, gay + ray - gby - rby
        vwx = vax + oma * ray - vbx - omb * rby
        vwy = vay - oma * rax - vby + omb * rbx
        row = np.zeros(self.N)
        if ia >= 0:
            row[3 * ia] += dx
            row[3 * ia + 1] += dy
            row[3 * ia + 2] += ray * dx - rax * dy
        elif self.nb:
            row[-1] += dx
        if ib >= 0:
            row[3 * ib] -= dx
            row[3 * ib + 1] -= dy
            row[3 * ib + 2] += -(rby * dx - rbx * dy) + wx * pdx + wy * pdy
        elif self.nb:
            row[-1] -= dx
        bias = (-oma * oma * (rax * dx + ray * dy) + omb * omb * (rbx * dx + rby * dy)
                + 2.0 * omb * (vwx * pdx + vwy * pdy) - omb * omb * (wx * dx + wy * dy))
        return wx * dx + wy * dy, row, bias

    def rows(self, j, c, s, X, V):
        """Interface ``j``'s constraints in the chart of corner ``c`` at slip ``s``: ``{name: (value, row,
        bias)}``, names ``nR``, ``nL`` (a face's corners) or ``n`` (a pivot), and ``t`` (the slip ``s``); each row
        the generalized force of a unit force on drum ``j`` (pressing, or along the slip)."""
        lo = j - 1
        top = (0.0, self.h[lo]) if lo >= 0 else (0.0, 0.0)
        h = self.h[j]
        out = {}
        c, kb, _ = self.chart(j, c, s)
        if c == 0.0:
            e_r, e_l = self.ends(j, s)
            out["nR"] = self._pol(X, V, j, (e_r, -h), lo, top, (0.0, 1.0))
            out["nL"] = self._pol(X, V, j, (e_l, -h), lo, top, (0.0, 1.0))
            out["t"] = self._pol(X, V, j, (0.0, -h), lo, top, (1.0, 0.0))
        elif not kb:
            cb = c * self.b[j]
            out["n"] = self._pol(X, V, j, (cb, -h), lo, top, (0.0, 1.0))
            v, r, bb = self._pol(X, V, j, (cb, -h), lo, top, (1.0, 0.0))
            out["t"] = (v - cb, r, bb)
        else:
            corner = (c * self.blow[j], self.h[lo])
            v, r, bb = self._pol(X, V, lo, corner, j, (0.0, -h), (0.0, 1.0))
            out["n"] = (-v, -r, -bb)
            v, r, bb = self._pol(X, V, lo, corner, j, (0.0, -h), (1.0, 0.0))
            out["t"] = (c * self.blow[j] - v, -r, -bb)
        return out

    def loads(self, X, V, ag):
        F = np.zeros(self.N)
        for i in range(self.n):
            F[3 * i] = -self.m[i] * ag
            F[3 * i + 1] = -self.m[i] * G
        if self.nb:
            mb, kb, cb = self.base
            F[-1] = -mb * ag - kb * X[-1] - cb * V[-1]
        return F

    # ---- a pattern's solution ----------------------------------------------------------------------
    def solve(self, pat, q, X, V, F, level="a", mu=None):
        """``(a, forces)``: the accelerations (``level="a"``, ``F`` the loads) or the velocity jump (``"v"``) of the
        pattern, and per interface ``(N, T, N_R, N_L)`` (forces or impulses on drum ``j``; ``N_R``, ``N_L`` a face's
        corners, NaN for a pivot). ``mu`` overrides the friction (the rest rules' frictionless projection). Raises
        ``numpy.linalg.LinAlgError`` when the pattern's system is singular."""
        mus = self.mu if mu is None else mu
        off = set()
        a, fr = self._solve(pat, q, X, V, F, level, off, mus)
        for _ in range(self.n):
            new = {j for j in range(self.n) if pat[2 * j + 1] != 0.0 and fr[j, 0] < 0.0 and mus[j] != 0.0
                   and j not in off}
            if not new:
                break
            off |= new
            a, fr = self._solve(pat, q, X, V, F, level, off, mus)
        self.last_off = off
        return a, fr

    def _solve(self, pat, q, X, V, F, level, off, mus):
        held, cols, names = [], [], []
        for j in range(self.n):
            c, sl = pat[2 * j], pat[2 * j + 1]
            if abs(c) >= 2.0:  # flying: nothing acts
                continue
            rw = self.rows(j, c, q[1 + 2 * j], X, V)
            tr = rw["t"][1]
            mu = 0.0 if j in off else mus[j]
            for name in (("nR", "nL") if c == 0.0 else ("n",)):
                _, r, bias = rw[name]
                held.append((r, bias))
                cols.append(r - mu * sl * tr if sl != 0.0 else r)
                names.append((j, name))
            if sl == 0.0:
                held.append((rw["t"][1], rw["t"][2]))
                cols.append(tr)
                names.append((j, "t"))
        J = np.array([r for r, _ in held]).reshape(len(held), self.N)
        C = np.array(cols).reshape(len(cols), self.N).T
        MiC = self.Minv[:, None] * C
        if level == "a":
            a0 = self.Minv * F
            rhs = -(J @ a0 + np.array([bb for _, bb in held]))
        else:
            a0 = np.zeros(self.N)
            rhs = -(J @ V)
        lam = np.linalg.solve(J @ MiC, rhs) if len(held) else np.zeros(0)
        a = a0 + MiC @ lam
        fr = np.full((self.n, 4), np.nan)
        fr[:, 0] = 0.0
        fr[:, 1] = 0.0
        for (j, name), v in zip(names, lam):
            if name == "t":
                fr[j, 1] = v
            else:
                fr[j, 0] += v
                if name == "nR":
                    fr[j, 2] = v
                elif name == "nL":
                    fr[j, 3] = v
        for j in range(self.n):
            sl = pat[2 * j + 1]
            if sl != 0.0:
                fr[j, 1] = -(0.0 if j in off else mus[j]) * sl * fr[j, 0]
        return a, fr

    def rates(self, pat, q, X, V, A, level="a"):
        """The relative coordinates' accelerations ``(u'', s_j'', psi_j'')`` from the maximal ``A`` (``level="a"``),
        or their rates from the maximal velocities ``A`` (``"v"``), in the chart of ``pat``."""
        out = np.zeros(len(q))
        if self.nb:
            out[0] = A[-1]
        for j in range(self.n):
            out[2 + 2 * j] = A[3 * j + 2] - (A[3 * (j - 1) + 2] if j > 0 else 0.0)
            rw = self.rows(j, pat[2 * j], q[1 + 2 * j], X, V)
            _, r, bias = rw["t"]
            out[1 + 2 * j] = float(r @ A) + (bias if level == "a" else 0.0)
            if abs(pat[2 * j]) >= 2.0:  # a flying interface's lift
                _, r, bias = rw["n"]
                out[1 + 2 * self.n + j] = float(r @ A) + (bias if level == "a" else 0.0)
        return out

    def kinetic(self, V):
        return 0.5 * float(np.dot(self.Mdiag, V * V))
