"""Which contact pattern follows an event, for the slow reference of a column of drums
(:mod:`rockcli.reference.friction_drums`): every pattern the event allows is either tried (enumeration) or found by a
mixed-integer feasibility problem (``scipy.optimize.milp``, HiGHS) over the contact conditions; each pattern found is
then solved and checked exactly (:func:`margin`), and the rule below picks one.

**The conditions** (the existing reference's and the driver's, docs/physics-sliding.md): a face presses at both ends
of its overlap; a pivot that starts (angle and rate 0) presses and opens (``c psi'' >= 0``); a contact that sticks
stays inside Coulomb's cone (a pivot that pulls is not checked: no flight, counted); a slide that starts moves the way
it slides (``sl s'' >= 0``; at an impact every slide, on the rates after it); a sliding contact solved without
friction because it pulled must pull still. :func:`margin` is the smallest of them, each relative to the largest
force (``N``, ``T``) and the largest free rate of the pattern, as ``reference/friction.py``'s ``_margin``.

**The mixed-integer problem.** In the chart of the event (the interfaces with their angle and rate at 0 "closed",
the others open pivots on their corner) every contact force is an unknown: a closed interface's corner forces
``N_R, N_L >= 0`` at the ends of its overlap and its friction ``T``; an open pivot's ``N`` (either sign) and ``T``.
``M a = F + sum J^T lambda`` makes every relative acceleration (or, at an impact, every rate after it) affine in
them: the corner gaps ``g_R'', g_L''`` (exact at a closed interface, where every relative rate is 0), an open pivot's
gap ``g''`` and each slip ``s''``. Binaries per interface: ``z_R, z_L`` (the corner holds: ``g'' = 0``; else it is
free: ``N = 0``, ``g'' >= 0``; at least one holds: no flight), the slip mode (stick ``s'' = 0`` inside the cone,
slide ``+-``: ``T = -+mu N``, ``+-s'' >= 0``), and for an open pivot ``p_N`` (``N >= 0`` with Coulomb's friction, or
``N <= 0`` without: ``|T| <= mu max(N, 0)``); big-M links them. With all conditions relaxed by a slack ``1e-6`` (in
units of the problem's force scale and of each rate's scale) every pattern that meets them exactly is feasible;
feasible patterns are found one after the other (each excluded by a no-good cut) until none is left, and each is
then checked exactly. For up to three drums (``9^3`` patterns) the enumeration does the same by brute force;
``tests/test_drums_reference.py`` checks that both find the same patterns.

**The rule** where several patterns meet every condition (friction makes that possible, and at a threshold the
starting and the failing pattern both sit at margin 0), mirrored from the driver (``kernels/contact.py``,
``kernels/contact_lcp.py``) and the existing reference (``_choose``) so that the comparison is meaningful: the
pattern whose condition just failed (the current one) is left out, and taken only when no other meets the conditions
(a tangency); among the others the largest smallest margin wins. The candidates: the interfaces whose angle and rate
are at 0 may be a face or either pivot, those whose slip rate is 0 may stick or slide either way; for three drums or
more every closed face is released too (a joint that stays shut is then a result), and if nothing meets the
conditions the sticking pivots' slips as well. At an impact: first every contact sticking (the rocking model's law),
else every slip free; the impacting interface and every face choose their corners.
"""

from __future__ import annotations

import itertools
import math
import os

import numpy as np

#: relative slack of the exact checks (the driver's and the existing reference's CONTACT_TOL)
TOL = 1e-9
#: the mixed-integer problem's slack, in its own scales
MILP_EPS = 1e-6
#: the bounds of the forces, in units of the force scale
BOUND = 1e3
#: enumerate when the event allows at most this many patterns (else the mixed-integer problem)
ENUM_MAX = 81
#: stop looking for more feasible patterns after this many
MAX_FOUND = 64
#: HiGHS presolve (without it HiGHS 1.x in SciPy has crashed the process on some of these problems: scipy issue
#: 22188; one is kept in tests/data/milp_crash.npz)
PRESOLVE = True
#: where the mixed-integer problem finds nothing and the event allows at most this many patterns, they are tried
ENUM_CHECK = 729
#: a file to write each mixed-integer problem into before it is solved (to reproduce a crash of HiGHS)
_DUMP = os.environ.get("ROCKCLI_MILP_DUMP")


def pattern_solution(ch, pat, q, qd, ag, level="a", V0=None):
    """``(X, V, A, forces, rates, off)`` of ``pat``: accelerations (``level="a"``) or, at an impact (``"v"``, ``V0``
    the maximal velocities before), the velocities after (``A`` then ``V+``) and impulses."""
    if level == "a":
        X, V = ch.maximal(pat, q, qd)
        A, fr = ch.solve(pat, q, X, V, ch.loads(X, V, ag))
        return X, V, A, fr, ch.rates(pat, q, X, V, A), set(ch.last_off)
    X, _ = ch.maximal(pat, q, qd)
    dv, fr = ch.solve(pat, q, X, V0, None, "v")
    Vp = V0 + dv
    return X, V0, Vp, fr, ch.rates(pat, q, X, V0, Vp, "v"), set(ch.last_off)


def free_of(ch, pat):
    out = [0] if ch.nb else []
    for j in range(ch.n):
        if pat[2 * j + 1] != 0.0 or abs(pat[2 * j]) >= 2.0:
            out.append(1 + 2 * j)
        if pat[2 * j] != 0.0:
            out.append(2 + 2 * j)
    out += [1 + 2 * ch.n + j for j in range(ch.n) if abs(pat[2 * j]) >= 2.0]  # flying: the lift
    return out


def margin(ch, pat, fr, rates, zero_psi, zero_s, level_v, off):
    """The smallest relative margin of the contact conditions (module notes) and the pivots that pull."""
    fs = max(1e-300, float(np.max(np.abs(fr[:, :2]))))
    vs = max([1e-300] + [abs(rates[i]) for i in free_of(ch, pat)])
    worst, pulls = math.inf, 0
    for j in range(ch.n):
        c, sl = pat[2 * j], pat[2 * j + 1]
        N, T = fr[j, 0], fr[j, 1]
        if c == 0.0:
            worst = min(worst, fr[j, 2] / fs, fr[j, 3] / fs)
        elif zero_psi[j]:
            worst = min(worst, N / fs, c * rates[2 + 2 * j] / vs)
        elif N < 0.0:
            pulls += 1
        if sl == 0.0:
            if N > 0.0 or c == 0.0 or zero_psi[j]:
                worst = min(worst, (ch.mu[j] * max(N, 0.0) - abs(T)) / fs)
        else:
            if j in off:
                worst = min(worst, -N / fs)
            if zero_s[j] or level_v:
                worst = min(worst, sl * rates[1 + 2 * j] / vs)
    return worst, pulls


def _options(pat, corner_free, slip_free):
    opts = []
    for j in range(len(corner_free)):
        opts.append((0.0, 1.0, -1.0) if corner_free[j] else (pat[2 * j],))
        opts.append((0.0, 1.0, -1.0) if slip_free[j] else (pat[2 * j + 1],))
    return opts


def _count(corner_free, slip_free):
    return 3 ** (sum(map(bool, corner_free)) + sum(map(bool, slip_free)))


# ---- the mixed-integer problem ----------------------------------------------------------------------------------
class _Milp:
    """The feasibility problem of one event (module notes): ``find()`` the next feasible pattern, ``cut(p)``."""

    def __init__(self, ch, pat, q, qd, ag, corner_free, slip_free, level, V0):
        self.ch, self.pat, self.level = ch, list(pat), level
        n = ch.n
        X, V = ch.maximal(pat, q, qd)
        Vb = V if V0 is None else V0
        # the force scale: the chain held in the event's chart (closed interfaces as sticking faces)
        hp = []
        for j in range(n):
            hp += [0.0 if corner_free[j] or pat[2 * j] == 0.0 else pat[2 * j], 0.0]
        try:
            if level == "a":
                _, fr = ch.solve(hp, q, X, V, ch.loads(X, V, ag))
            else:
                _, fr = ch.solve(hp, q, X, Vb, None, "v")
            f0 = float(np.max(np.abs(fr[:, :2])))
        except np.linalg.LinAlgError:
            f0 = 0.0
        if not f0 > 0.0:
            f0 = sum(ch.m) * (9.81 if level == "a" else max(1e-12, float(np.max(np.abs(Vb)))))
        self.f0 = f0
        # unknowns and the measured rows
        cols, meas, kinds = [], [], []  # kinds: per interface the indices of its unknowns and its measured rows
        for j in range(n):
            if abs(pat[2 * j]) >= 2.0 and not corner_free[j]:  # flying (the reference's flight): no unknowns
                kinds.append((None, [], []))
                continue
            closed = corner_free[j] or pat[2 * j] == 0.0
            rw = ch.rows(j, 0.0 if closed else pat[2 * j], q[1 + 2 * j], X, V)
            names = ("nR", "nL", "t") if closed else ("n", "t")
            k0, m0 = len(cols), len(meas)
            for nm in names:
                cols.append(rw[nm][1])
                meas.append(rw[nm])
            kinds.append((closed, list(range(k0, k0 + len(names))), list(range(m0, m0 + len(names)))))
        C = np.array(cols).T
        R = np.array([r for _, r, _ in meas])
        MiC = ch.Minv[:, None] * C
        if level == "a":
            q0 = R @ (ch.Minv * ch.loads(X, V, ag)) + np.array([b for _, _, b in meas])
        else:
            q0 = R @ Vb
        Gm = (R @ MiC) * f0
        sig = np.abs(q0) + np.sum(np.abs(Gm), axis=1)
        sig[sig == 0.0] = 1.0
        self.q0, self.Gm = q0 / sig, Gm / sig[:, None]
        self.kinds, self.nx = kinds, len(cols)
        self._build(corner_free, slip_free)

    def _build(self, corner_free, slip_free):
        ch, pat, n = self.ch, self.pat, self.ch.n
        nx = self.nx
        rows, lbs, ubs = [], [], []
        self.bins = []  # per interface: {"zR", "zL", "st", "sp", "sn", "pN"} -> variable index
        nvar = nx
        for j in range(n):
            b = {}
            closed = self.kinds[j][0]
            if closed is None:  # flying
                self.bins.append(b)
                continue
            if corner_free[j]:
                b["zR"], b["zL"] = nvar, nvar + 1
                nvar += 2
            if slip_free[j]:
                b["st"], b["sp"], b["sn"] = nvar, nvar + 1, nvar + 2
                nvar += 3
            if not closed:
                b["pN"] = nvar
                nvar += 1
            self.bins.append(b)
        iz = nvar
        nvar += 1
        self.nvar, self.iz = nvar, iz
        BX = BOUND
        BM = BOUND + 1.0

        def add(coef, lb, ub):
            r = np.zeros(nvar)
            for k, v in coef:
                r[k] += v
            rows.append(r)
            lbs.append(lb)
            ubs.append(ub)

        def meas_le(m, sign, extra, ub):
            """sign * m_hat + sum(extra) - z <= ub (m_hat affine in the unknowns)."""
            coef = [(k, sign * self.Gm[m, k]) for k in range(nx)] + extra + [(iz, -1.0)]
            add(coef, -np.inf, ub - sign * self.q0[m])

        lo = np.full(nvar, -BX)
        hi = np.full(nvar, BX)
        integ = np.zeros(nvar)
        for j in range(n):
            closed, ks, ms = self.kinds[j]
            if closed is None:  # flying
                continue
            bj = self.bins[j]
            mu = ch.mu[j]
            BT = BX * (1.0 + 3.0 * mu)
            for key, k in bj.items():
                lo[k], hi[k], integ[k] = 0.0, 1.0, 1.0
            if closed:
                kR, kL, kT = ks
                mR, mL, mT = ms
                lo[kR] = lo[kL] = 0.0
                N = [(kR, 1.0), (kL, 1.0)]
                if corner_free[j]:
                    zR, zL = bj["zR"], bj["zL"]
                    add([(kR, 1.0), (zR, -BX)], -np.inf, 0.0)
                    add([(kL, 1.0), (zL, -BX)], -np.inf, 0.0)
                    add([(zR, 1.0), (zL, 1.0)], 1.0, np.inf)
                    for m, z in ((mR, zR), (mL, zL)):
                        meas_le(m, -1.0, [], 0.0)
                        meas_le(m, 1.0, [(z, BM)], BM)
                else:  # a face kept
                    for m in (mR, mL):
                        meas_le(m, -1.0, [], 0.0)
                        meas_le(m, 1.0, [], 0.0)
                # the cone holds in every mode of a closed interface (a slide sits on its edge)
                add([(kT, 1.0)] + [(k, -mu * v) for k, v in N] + [(iz, -1.0)], -np.inf, 0.0)
                add([(kT, -1.0)] + [(k, -mu * v) for k, v in N] + [(iz, -1.0)], -np.inf, 0.0)
                pN = None
            else:
                kN, kT = ks
                mN, mT = ms
                N = [(kN, 1.0)]
                meas_le(mN, -1.0, [], 0.0)
                meas_le(mN, 1.0, [], 0.0)
                pN = bj["pN"]
                add([(kN, 1.0), (pN, -BX)], -BX, 0.0)  # N in [-BX (1 - pN), BX pN]
            hi[kT], lo[kT] = BT, -BT

            def stick(on):
                """``s'' = 0`` (when ``on`` holds: a list of binaries that are all 1) and the cone (a pivot: with p_N)."""
                big = [(k, BM) for k in on]
                meas_le(mT, 1.0, big, BM * len(on))
                meas_le(mT, -1.0, big, BM * len(on))
                if pN is not None:
                    for sg in (1.0, -1.0):
                        add([(kT, sg), (kN, -mu), (pN, BT)] + [(k, BT) for k in on] + [(iz, -1.0)], -np.inf,
                            BT * (1 + len(on)))

            def slide(sl, on, direction):
                """``T = -mu sl N`` (a pivot: with p_N, else ``T = 0``), and ``sl s'' >= 0`` if ``direction``."""
                big = [(k, BT) for k in on]
                extra = [] if pN is None else [(pN, BT)]
                nb_ = len(on) + (0 if pN is None else 1)
                for sg in (1.0, -1.0):
                    add([(kT, sg)] + [(k, sg * mu * sl * v) for k, v in N] + big + extra + [(iz, -1.0)], -np.inf,
                        BT * nb_)
                if pN is not None:
                    for sg in (1.0, -1.0):
                        add([(kT, sg), (pN, -BT)] + big + [(iz, -1.0)], -np.inf, BT * len(on))
                if direction:
                    meas_le(mT, -sl, [(k, BM) for k in on], BM * len(on))

            if slip_free[j]:
                st, sp, sn = bj["st"], bj["sp"], bj["sn"]
                add([(st, 1.0), (sp, 1.0), (sn, 1.0)], 1.0, 1.0)
                stick([st])
                slide(1.0, [sp], True)
                slide(-1.0, [sn], True)
            elif pat[2 * j + 1] == 0.0:
                stick([])
            else:
                slide(pat[2 * j + 1], [], self.level == "v")
        lo[iz], hi[iz] = 0.0, MILP_EPS
        self.A = np.array(rows)
        self.lb, self.ub = np.array(lbs), np.array(ubs)
        self.lo, self.hi, self.integ = lo, hi, integ
        self.cuts = []

    def _binaries_of(self, p):
        out = {}
        for j, bj in enumerate(self.bins):
            c, sl = p[2 * j], p[2 * j + 1]
            if "zR" in bj:
                out[bj["zR"]] = 1.0 if c in (0.0, 1.0) else 0.0
                out[bj["zL"]] = 1.0 if c in (0.0, -1.0) else 0.0
            if "st" in bj:
                out[bj["sp"]] = 1.0 if sl == 1.0 else 0.0
                out[bj["sn"]] = 1.0 if sl == -1.0 else 0.0
        return out

    def cut(self, p):
        r = np.zeros(self.nvar)
        rhs = 1.0
        for k, v in self._binaries_of(p).items():
            if v == 1.0:
                r[k] -= 1.0
                rhs -= 1.0
            else:
                r[k] += 1.0
        self.cuts.append((r, rhs))

    def find(self):
        """The next feasible pattern, or None."""
        from scipy.optimize import Bounds, LinearConstraint, milp

        A, lb, ub = self.A, self.lb, self.ub
        if self.cuts:
            A = np.vstack([A] + [r for r, _ in self.cuts])
            lb = np.concatenate([lb, [rhs for _, rhs in self.cuts]])
            ub = np.concatenate([ub, [np.inf] * len(self.cuts)])
        c = np.zeros(self.nvar)
        c[self.iz] = 1.0
        if _DUMP:  # the problem about to be solved (HiGHS has crashed the process on some: scipy issue 22188)
            np.savez(_DUMP, c=c, A=A, lb=lb, ub=ub, integ=self.integ, lo=self.lo, hi=self.hi)
        res = milp(c, constraints=LinearConstraint(A, lb, ub), integrality=self.integ,
                   bounds=Bounds(self.lo, self.hi), options={"presolve": PRESOLVE})
        if res.status != 0 or res.x is None:
            return None
        x = res.x
        p = list(self.pat)
        for j, bj in enumerate(self.bins):
            if "zR" in bj:
                zr, zl = x[bj["zR"]] > 0.5, x[bj["zL"]] > 0.5
                p[2 * j] = 0.0 if (zr and zl) else (1.0 if zr else -1.0)
            if "st" in bj:
                p[2 * j + 1] = 1.0 if x[bj["sp"]] > 0.5 else (-1.0 if x[bj["sn"]] > 0.5 else 0.0)
        return p


def candidates(ch, pat, q, qd, ag, corner_free, slip_free, level="a", V0=None, method="auto", exclude=None):
    """The patterns the event allows that may meet every condition: all of them (enumeration), or those the
    mixed-integer problem finds feasible (``method``: ``"enum"``, ``"milp"`` or ``"auto"``: the enumeration when the
    event allows at most ``ENUM_MAX``, and where the problem finds none, every pattern if at most ``ENUM_CHECK``).
    ``exclude``: a pattern left out. Returns ``(patterns, how)``."""
    if method == "enum" or (method == "auto" and _count(corner_free, slip_free) <= ENUM_MAX):
        out = [list(c) for c in itertools.product(*_options(pat, corner_free, slip_free))]
        return [c for c in out if exclude is None or c != list(exclude)], "enum"
    mp = _Milp(ch, pat, q, qd, ag, corner_free, slip_free, level, V0)
    if exclude is not None:
        mp.cut(exclude)
    found = []
    for _ in range(MAX_FOUND):
        p = mp.find()
        if p is None:
            if method == "auto" and not found and _count(corner_free, slip_free) <= ENUM_CHECK:  # a second opinion
                out = [list(c) for c in itertools.product(*_options(pat, corner_free, slip_free))]
                return [c for c in out if exclude is None or c != list(exclude)], "milp-none-enum"
            return found, "milp"
        found.append(p)
        mp.cut(p)
    return found, "milp-capped"


def best_of(ch, cands, q, qd, ag, zero_psi, zero_s, level="a", V0=None):
    """The candidate with the largest smallest margin: ``(pattern, margin, pulls, solution)`` (None: none solved)."""
    best = (None, -math.inf, 0, None)
    for cand in cands:
        try:
            sol = pattern_solution(ch, cand, q, qd, ag, level, V0)
        except np.linalg.LinAlgError:
            continue
        m, p = margin(ch, cand, sol[3], sol[4], zero_psi, zero_s, level == "v", sol[5])
        if m > best[1]:
            best = (list(cand), m, p, sol)
    return best


def choose(ch, pat, q, qd, ag, zero_psi, zero_s, method="auto", stats=None, force=False):
    """The pattern that continues the motion (no impact), by the rule of the module notes: ``(pattern, margin,
    pulls)``; the margin below ``-TOL`` when none met every condition (then ``pat`` is kept, or with ``force``, where
    keeping it has stalled the run at one instant, the other candidate of the largest margin, counted by the
    caller)."""
    n = ch.n
    zero_psi, zero_s = list(zero_psi), list(zero_s)
    if n >= 3:
        for j in range(n):
            if pat[2 * j] == 0.0:
                zero_psi[j] = True
                if pat[2 * j + 1] == 0.0:
                    zero_s[j] = True
    stages = [zero_s]
    if n >= 3 and any(pat[2 * j] != 0.0 and pat[2 * j + 1] == 0.0 and not zero_s[j] for j in range(n)):
        stages.append([zero_s[j] or (pat[2 * j] != 0.0 and pat[2 * j + 1] == 0.0) for j in range(n)])
    for zs in stages:
        cands, how = candidates(ch, pat, q, qd, ag, zero_psi, zs, "a", None, method, exclude=pat)
        if stats is not None:
            stats[how] = stats.get(how, 0) + 1
        best, m, pulls, _ = best_of(ch, cands, q, qd, ag, zero_psi, zs)
        if best is not None and m >= -TOL:
            return best, m, pulls
    if force:
        zs = stages[-1]
        if _count(zero_psi, zs) <= 3 ** 7:
            cands, _ = candidates(ch, pat, q, qd, ag, zero_psi, zs, "a", None, "enum", exclude=pat)
        else:
            mp = _Milp(ch, pat, q, qd, ag, zero_psi, zs, "a", None)
            mp.hi[mp.iz] = BOUND
            mp.cut(pat)
            p = mp.find()
            cands = [] if p is None else [p]
        best, m, pulls, _ = best_of(ch, cands, q, qd, ag, zero_psi, zs)
        if best is not None:
            return best, m, pulls
    sol = pattern_solution(ch, pat, q, qd, ag)
    m, pulls = margin(ch, pat, sol[3], sol[4], zero_psi, stages[-1], False, sol[5])
    return list(pat), m, pulls


def impact(ch, pat, q, qd, j, method="auto", stats=None):
    """Moreau's plastic impact with Coulomb's law when interface ``j`` closes (its angle at 0 in ``q``): ``(pattern,
    margin, pulls, V-, V+, rates after, slipped)``: first every contact sticking, else every slip free (module
    notes); the impacting interface and every face choose their corners, open pivots keep theirs."""
    n = ch.n
    X, V0 = ch.maximal(pat, q, qd)
    zero_psi = [i == j or pat[2 * i] == 0.0 for i in range(n)]
    no_s = [False] * n
    best = (None, -math.inf, 0, None)
    slipped = False
    for stage in (0, 1):
        slipped = stage == 1
        base = [x if k % 2 == 0 or stage == 1 else 0.0 for k, x in enumerate(pat)]
        slip_free = [stage == 1] * n
        cands, how = candidates(ch, base, q, qd, 0.0, zero_psi, slip_free, "v", V0, method)
        if stats is not None:
            stats[how] = stats.get(how, 0) + 1
        best = best_of(ch, cands, q, qd, 0.0, zero_psi, no_s, "v", V0)
        if best[0] is not None and best[1] >= -TOL:
            break
    if best[0] is None or best[1] < -TOL:
        # nothing meets every condition: the best of every pattern the impact allows (enumerated when few, else
        # the pattern of least violation of the mixed-integer problem)
        if _count(zero_psi, [True] * n) <= 3 ** 7:
            cands, _ = candidates(ch, pat, q, qd, 0.0, zero_psi, [True] * n, "v", V0, "enum")
        else:
            mp = _Milp(ch, pat, q, qd, 0.0, zero_psi, [True] * n, "v", V0)
            mp.hi[mp.iz] = BOUND
            p = mp.find()
            cands = [] if p is None else [p]
        got = best_of(ch, cands, q, qd, 0.0, zero_psi, no_s, "v", V0)
        if got[0] is not None and got[1] > best[1]:
            best = got
        slipped = True
    if best[0] is None:  # nothing solved: the stick law into every face (a projection)
        cand = [x for i in range(n) for x in ((0.0 if zero_psi[i] else pat[2 * i]), 0.0)]
        sol = pattern_solution(ch, cand, q, qd, 0.0, "v", V0)
        best = (cand, -math.inf, 0, sol)
    cand, m, pulls, sol = best
    return cand, m, pulls, V0, sol[2], sol[4], slipped
