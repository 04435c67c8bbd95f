"""Flight in the slow reference of a column of drums (``reference_drums(..., flight=True)``, docs/physics-drums.md,
"Flight (in the reference)").

An interface may be **flying**: nothing acts there, and the drums above it and below it move apart under gravity and
their other contacts. Its chart is that of the pivot it left (kind A or B, coded ``2 c`` or ``3 c`` in a pattern,
:mod:`rockcli.reference.drum_mechanics`) with the gap not held: one more coordinate, the lift ``z``, at ``q[1 + 2 n +
j]``. What flight changes in the contact law (:func:`choose`, :func:`impact`):

* **No pull.** Every pivot's normal force (at an impact, its impulse) must be ``>= 0``, like a face's corner forces:
  a pivot that pulls is no longer a hinge counted as a jump but a violated condition.
* **Lift-off.** A pivot whose normal force reaches 0 decreasing is an event (``lift``): its candidates are the
  patterns with that interface flying (a flying interface's condition: its gap's acceleration ``>= 0`` at zero gap;
  a face's, both corners'), else those where it stays shut; a face that opens has the flying option beside its
  pivots. Where no candidate meets every condition, the interfaces that the best one pulls get the flying option and
  the search is repeated, and then every shut interface (at most ``MAX_FLY``). Impacts the same, at the velocity
  level (the gap's rate after ``>= 0``).
* **Landing.** During flight the gap of each end of the drum's base over the top below is watched (:func:`end_gaps`:
  the drum's corner over the top where it lies over it, else the lower drum's corner under the drum's base, the overlap
  geometry of the pivots of kind A and B); the first to close is an impact by Moreau's plastic law with Coulomb's
  friction (:func:`impact`; the contacts at their surfaces take part, the other flying interfaces do not), on that
  corner (a pivot, of the kind that touched), or on a face when both ends touch at once.
* **Failures**: a flying interface's angle at ``pi/2`` (topple), its horizontal overlap gone (slid off).
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from rockcli.reference import drum_patterns as dp

#: interfaces given the flying option in one search, at most
MAX_FLY = 4


def flying(c) -> bool:
    return abs(c) >= 2.0


def fly_code(ch, pat, q, j):
    """The flying code of interface ``j`` leaving its current contact (a face: the chart of its right corner)."""
    c = pat[2 * j]
    if flying(c):
        return c
    c = 1.0 if c == 0.0 else c
    return c * (3.0 if ch.kind_b(j, c, q[1 + 2 * j]) else 2.0)


# ---- geometry -----------------------------------------------------------------------------------------------
def _frames(ch, j, X):
    lo = j - 1
    gx, gy, th = ch._body(j, X, X)[:3]
    if lo >= 0:
        lx, ly, thl = X[3 * lo], X[3 * lo + 1], X[3 * lo + 2]
        s_, c_ = math.sin(thl), math.cos(thl)
        Tx, Ty = lx + ch.h[lo] * s_, ly + ch.h[lo] * c_
    else:
        thl = 0.0
        Tx, Ty = (X[-1] if ch.nb else 0.0), 0.0
    t = (math.cos(thl), -math.sin(thl))
    n = (math.sin(thl), math.cos(thl))
    tu = (math.cos(th), -math.sin(th))
    nu = (math.sin(th), math.cos(th))
    B = (gx - ch.h[j] * nu[0], gy - ch.h[j] * nu[1])
    return (Tx, Ty), t, n, B, tu, nu


def end_gaps(ch, j, X):
    """``{c: (gap, kind B)}`` at both ends ``c = +-1`` of interface ``j``'s overlap: the drum's corner above the top
    below where it lies over it (kind A), else the lower drum's corner ``c b_L`` below the drum's base (kind B)."""
    T, t, n, B, tu, nu = _frames(ch, j, X)
    b, bl = ch.b[j], ch.blow[j]
    out = {}
    for c in (1.0, -1.0):
        C = (B[0] + c * b * tu[0], B[1] + c * b * tu[1])
        xc = (C[0] - T[0]) * t[0] + (C[1] - T[1]) * t[1]
        if c * xc <= bl:
            out[c] = ((C[0] - T[0]) * n[0] + (C[1] - T[1]) * n[1], False)
        else:
            K = (T[0] + c * bl * t[0], T[1] + c * bl * t[1])
            out[c] = ((B[0] - K[0]) * nu[0] + (B[1] - K[1]) * nu[1], True)
    return out


def overlap(ch, j, X):
    """The horizontal overlap (in the frame of the drum below) of drum ``j``'s base and the top below [m]."""
    T, t, n, B, tu, nu = _frames(ch, j, X)
    b, bl = ch.b[j], ch.blow[j]
    xs = [(B[0] + c * b * tu[0] - T[0]) * t[0] + (B[1] + c * b * tu[1] - T[1]) * t[1] for c in (1.0, -1.0)]
    return min(max(xs), bl) - max(min(xs), -bl)


# ---- the conditions ---------------------------------------------------------------------------------------------
def margin(ch, prev, pat, sol, zero_psi, zero_s, level_v, shut=None):
    """The smallest relative margin of the contact conditions with flight (module notes; otherwise
    :func:`rockcli.reference.drum_patterns.margin`'s) and the interfaces that pull (a pivot's ``N < 0``, a face's
    corner force < 0). ``shut``: the interfaces with both ends at zero gap (a face, a pivot at angle 0)."""
    shut = zero_psi if shut is None else shut
    X, V, A, fr, rates, off = sol
    fs = max(1e-300, float(np.max(np.abs(fr[:, :2]))))
    vs = max([1e-300] + [abs(rates[i]) for i in dp.free_of(ch, pat)])
    worst, pulling = math.inf, []
    for j in range(ch.n):
        c, sl = pat[2 * j], pat[2 * j + 1]
        if flying(c):
            if not flying(prev[2 * j]):  # lifting off here: its gap (a face's two) must open
                if prev[2 * j] == 0.0 or shut[j]:
                    rw = ch.rows(j, 0.0, q_slip(ch, pat, X, j), X, V)
                    for nm in ("nR", "nL"):
                        _, r, bias = rw[nm]
                        worst = min(worst, (float(r @ A) + (0.0 if level_v else bias)) / vs)
                else:
                    worst = min(worst, rates[1 + 2 * ch.n + j] / vs)
            continue
        N, T = fr[j, 0], fr[j, 1]
        if c == 0.0:
            worst = min(worst, fr[j, 2] / fs, fr[j, 3] / fs)
            if min(fr[j, 2], fr[j, 3]) < -dp.TOL * fs:
                pulling.append(j)
        else:
            worst = min(worst, N / fs)
            if N < -dp.TOL * fs:
                pulling.append(j)
            if zero_psi[j]:
                worst = min(worst, c * rates[2 + 2 * j] / vs)
        if sl == 0.0:
            worst = min(worst, (ch.mu[j] * max(N, 0.0) - abs(T)) / fs)
        else:
            if j in off:
                worst = min(worst, -N / fs)
            if zero_s[j] or level_v:
                worst = min(worst, sl * rates[1 + 2 * j] / vs)
    return worst, pulling


def q_slip(ch, pat, X, j):
    """Interface ``j``'s slip in the chart of a face (the centre of its base along the top below)."""
    T, t, n, B, tu, nu = _frames(ch, j, X)
    return (B[0] - T[0]) * t[0] + (B[1] - T[1]) * t[1]


def best_of(ch, prev, cands, q, qd, ag, zero_psi, zero_s, level="a", V0=None, shut=None):
    best = (None, -math.inf, [], None)
    seen = set()
    for cand in cands:
        key = tuple(cand)
        if key in seen:
            continue
        seen.add(key)
        try:
            sol = dp.pattern_solution(ch, cand, q, qd, ag, level, V0)
        except np.linalg.LinAlgError:
            continue
        m, pulling = margin(ch, prev, cand, sol, zero_psi, zero_s, level == "v", shut)
        if m > best[1]:
            best = (list(cand), m, pulling, sol)
    return best


def _search(ch, prev, q, qd, ag, stages, level, V0, method, stats, fly, exclude, fly_only=False):
    """The best pattern over ``stages`` (``(base pattern, corners free, slips free)``, tried in order), every subset of
    ``fly`` flying; where the best still fails, the interfaces it pulls get the flying option and the search is
    repeated. ``fly_only``: first the patterns with every one of ``fly`` flying."""
    n = ch.n
    fly = set(fly)
    best_all = (None, -math.inf, [], None)
    while True:
        subsets = [S for k in range(len(fly) + 1) for S in itertools.combinations(sorted(fly), k)]
        if fly_only:
            subsets = [tuple(sorted(fly))] + [S for S in subsets if len(S) < len(fly)]
        for S in subsets:
            for base, cf, sf in stages:
                shut = list(cf)
                p, cf, sf = list(base), list(cf), list(sf)
                for j in S:
                    p[2 * j], p[2 * j + 1] = fly_code(ch, prev, q, j), 0.0
                    cf[j] = sf[j] = False
                for j in range(n):
                    if flying(p[2 * j]):
                        cf[j] = sf[j] = False
                cands, how = dp.candidates(ch, p, q, qd, ag, cf, sf, level, V0, method, exclude=exclude)
                if stats is not None:
                    stats[how] = stats.get(how, 0) + 1
                got = best_of(ch, prev, cands, q, qd, ag, cf, sf, level, V0, shut)
                if got[0] is not None:
                    # the margins are those of the event's own corner and slip freedom
                    if got[1] > best_all[1]:
                        best_all = got
                    if got[1] >= -dp.TOL:
                        return got
            if fly_only and len(S) == len(fly) and best_all[1] >= -dp.TOL:
                return best_all
        shut = {j for j in range(n) if not flying(prev[2 * j])}
        new = (set(best_all[2]) & shut) - fly if best_all[0] is not None else set()
        if not new:  # nothing pulls, yet nothing meets the conditions: every shut interface may fly
            new = shut - fly
        if not new or len(fly) >= MAX_FLY:
            return best_all
        fly |= set(sorted(new)[:MAX_FLY - len(fly)])


def choose(ch, pat, q, qd, ag, zero_psi, zero_s, method="auto", stats=None, force=False, fly=(), fly_only=False):
    """:func:`rockcli.reference.drum_patterns.choose` with flight: ``(pattern, margin, pulling)``; ``fly`` the
    interfaces given the flying option from the start (the one that lifts off, a face that opens)."""
    n = ch.n
    zero_psi, zero_s = list(zero_psi), list(zero_s)
    if n >= 3:
        for j in range(n):
            if pat[2 * j] == 0.0:
                zero_psi[j] = True
                if pat[2 * j + 1] == 0.0:
                    zero_s[j] = True
    stages = [(pat, zero_psi, zero_s)]
    if n >= 3 and any(pat[2 * j] in (1.0, -1.0) and pat[2 * j + 1] == 0.0 and not zero_s[j] for j in range(n)):
        stages.append((pat, zero_psi, [zero_s[j] or (pat[2 * j] in (1.0, -1.0) and pat[2 * j + 1] == 0.0)
                                       for j in range(n)]))
    best, m, pulling, _ = _search(ch, pat, q, qd, ag, stages, "a", None, method, stats, fly, pat, fly_only)
    if best is not None and (m >= -dp.TOL or force):
        return best, m, pulling
    sol = dp.pattern_solution(ch, pat, q, qd, ag)
    m, pulling = margin(ch, pat, pat, sol, zero_psi, stages[-1][2], False)
    return list(pat), m, pulling


def impact(ch, pat, q, V0, zero_psi, method="auto", stats=None):
    """Moreau's plastic impact with Coulomb's law and flight: ``(pattern, margin, pulling, V+, rates after)``.
    ``pat``: the pattern entering the impact (the impacting interface on its pivot or, ``zero_psi``, free to choose its
    corners; every face chooses its corners; flying interfaces stay flying); first every contact sticking, else every
    slip free; interfaces that pull get the flying option (module notes)."""
    n = ch.n
    qd = np.zeros_like(q)
    stick = [x if k % 2 == 0 or flying(pat[k - 1]) else 0.0 for k, x in enumerate(pat)]
    stages = [(stick, zero_psi, [False] * n), (pat, zero_psi, [True] * n)]
    best, m, pulling, sol = _search(ch, pat, q, qd, 0.0, stages, "v", V0, method, stats, (), None)
    if best is None:  # nothing solved: every shut interface sticking on its faces (a projection)
        best = [x for i in range(n) for x in ((pat[2 * i] if flying(pat[2 * i]) else
                                                (0.0 if zero_psi[i] else pat[2 * i])), 0.0)]
        sol = dp.pattern_solution(ch, best, q, qd, 0.0, "v", V0)
        m, pulling = -math.inf, []
    return best, m, pulling, sol[2], sol[4]
