"""Minimum overturning acceleration (the paper's Figures 7, 8, 9 and 11).

Verdicts only: the search runs with ``early=True`` (each run stops as soon as its verdict is proven,
even during the pulse; the same verdicts).

Uplift threshold
----------------
On a rigid foundation the block uplifts when ``|ag|`` passes ``g tan(alpha)``; all four pulse shapes
peak at exactly ``|a_p|`` (the antisymmetric Ricker through its factor beta), so the no-uplift zone is
exactly ``y <= 1`` for each of them. On an isolated base, before uplift, block and base move together
as a linear oscillator, so the peak base acceleration is proportional to ``a_p``: uplift is monotone
in ``a_p`` and its threshold is found by bisection on the solver's uplift flag.

Minimum overturning acceleration
--------------------------------
Overturning is not monotone in ``a_p`` (safe islands lie above the minimum), so a bisection between
"safe" and "overturns" alone could land on the upper edge of an island. :func:`search_min_overturning`
scans ``y`` upwards from the uplift threshold ``y_u`` on the geometric grid ``y_u (1 + step)^k``
(default step 1 %), all columns in parallel batches, stops each column at its first overturning grid
value and bisects (geometrically) between it and the grid value below (safe) to ``tol`` (default
0.1 %). Result: ``ap_min`` overturns, ``ap_safe`` (within ``tol`` below) does not, and no grid value
between the uplift threshold and ``ap_safe`` overturns. Stated resolution: an overturning window
narrower than one scan step (1 % of ``a_p``) can be missed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.spectra.runner import Runner
from rockcli.spectra.scenes import REFERENCE_R, Family, Isolation, PulseChoice

#: Defaults of the minimum-overturning search: relative scan step, relative bisection tolerance,
#: and the largest a_p / (g tan alpha) tried.
DEFAULT_STEP = 0.01
DEFAULT_TOL = 1e-3
DEFAULT_AP_MAX = 20.0


@dataclass(frozen=True)
class MinSearch:
    """Per column: uplift threshold, and the bracket of the smallest overturning amplitude.

    ``ap_min`` overturns, ``ap_safe`` (within ``tol`` below it) does not; both NaN when nothing
    overturns up to ``ap_max`` (``ap_uplift`` NaN too when the block does not even uplift). All in
    units of ``g tan(alpha)``. ``unproven``: runs still moving at the solver's horizon (counted safe).
    """

    ap_uplift: np.ndarray
    ap_min: np.ndarray
    ap_safe: np.ndarray
    runs: int
    unproven: int = 0  # runs that reached the solver's horizon unproven (counted as safe)


def search_min_overturning(families: Sequence[Family], fam, x, *, ap_max: float = DEFAULT_AP_MAX,
                           step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, runner: Optional[Runner] = None,
                           progress=None) -> MinSearch:
    """Smallest ``y = a_p/(g tan alpha)`` that overturns, for columns ``(families[fam[i]], x[i])``.

    See the module notes: uplift threshold, geometric scan up from it with ratio ``1 + step``, then
    geometric bisection to ``tol`` between the last safe and the first overturning scan value.
    ``progress(n)`` is told when ``n`` more columns are finished.
    """
    if not (math.isfinite(step) and 0 < step <= 0.5):
        raise RockcliInputError(f"scan step must lie in (0, 0.5] (relative), got {step!r}")
    if not (math.isfinite(tol) and 0 < tol <= step):
        raise RockcliInputError(f"tolerance must lie in (0, step], got {tol!r}")
    if not (math.isfinite(ap_max) and ap_max > 1):
        raise RockcliInputError(f"ap_max must be > 1 (in units of g tan alpha), got {ap_max!r}")
    runner = runner or Runner()
    fam = np.asarray(fam, dtype=np.int64)
    x = np.asarray(x, dtype=float)
    n = len(x)
    runs = 0

    unproven = 0

    def run(idx, yv, early=True):
        nonlocal runs, unproven
        runs += len(idx)
        out = runner(families, fam[idx], x[idx], yv, early=early)
        unproven += int(np.count_nonzero(~out.settled & ~out.overturned))
        return out

    # 1. uplift threshold: exactly 1 on a rigid foundation (every shape peaks at |a_p|); on an
    # isolated base the stuck motion is linear in a_p, so uplift is monotone: bisection.
    y_u = np.ones(n)
    iso_cols = np.array([i for i in range(n) if not families[fam[i]].isolation.rigid], dtype=np.int64)
    if iso_cols.size:
        lo = np.zeros(iso_cols.size)
        hi = np.ones(iso_cols.size)
        pending = np.arange(iso_cols.size)
        while pending.size:  # bracket: double hi until the block uplifts
            up = run(iso_cols[pending], hi[pending], early=False).uplifted
            lo[pending[~up]] = hi[pending[~up]]
            hi[pending[~up]] *= 2.0
            pending = pending[~up & (hi[pending] <= 2.0 * ap_max)]
        ok = hi <= 2.0 * ap_max
        act = np.flatnonzero(ok)
        while act.size:
            mid = 0.5 * (lo[act] + hi[act])
            up = run(iso_cols[act], mid, early=False).uplifted
            hi[act[up]] = mid[up]
            lo[act[~up]] = mid[~up]
            act = act[(hi[act] - lo[act]) > 1e-7 * hi[act]]
        y_u[iso_cols] = np.where(ok, lo, np.nan)

    # 2. scan upwards from the threshold on y_u (1 + step)^k; first overturning grid value. From here
    # on only verdicts count: early runs (stopped once the verdict is proven; the same verdicts).
    ratio = 1.0 + step
    ap_min = np.full(n, np.nan)
    ap_safe = np.full(n, np.nan)
    safe = y_u.copy()  # largest scanned value known safe (the threshold itself does not uplift)
    hi_ot = np.full(n, np.nan)
    kdone = np.zeros(n, np.int64)
    width = np.full(n, 4, np.int64)
    active = np.flatnonzero(np.isfinite(y_u) & (y_u < ap_max))
    if progress:
        progress(int(n - active.size))
    while active.size:
        cols, ks = [], []
        for i in active:
            k = np.arange(kdone[i] + 1, kdone[i] + 1 + width[i])
            cols.append(np.full(k.size, i))
            ks.append(k)
        cols = np.concatenate(cols)
        ks = np.concatenate(ks)
        yv = np.minimum(y_u[cols] * ratio ** ks, ap_max)
        res = run(cols, yv).overturned
        still = []
        pos = 0
        for i in active:
            w = int(width[i])
            o = res[pos:pos + w]
            yy = yv[pos:pos + w]
            pos += w
            hit = np.flatnonzero(o)
            if hit.size:
                j = int(hit[0])
                hi_ot[i] = yy[j]
                if j > 0:
                    safe[i] = yy[j - 1]
            elif yy[-1] >= ap_max:
                safe[i] = ap_max
                if progress:
                    progress(1)
            else:
                safe[i] = yy[-1]
                kdone[i] += w
                width[i] = min(2 * w, 64)
                still.append(i)
        active = np.array(still, dtype=np.int64)

    # 3. bisection between the last safe and the first overturning scan value
    act = np.flatnonzero(np.isfinite(hi_ot))
    lo = safe.copy()
    hi = hi_ot.copy()
    act = act[hi[act] > lo[act] * (1.0 + tol)]
    done0 = np.flatnonzero(np.isfinite(hi_ot) & ~np.isin(np.arange(n), act))
    if progress and done0.size:
        progress(int(done0.size))
    while act.size:
        mid = np.sqrt(lo[act] * hi[act])
        o = run(act, mid).overturned
        hi[act[o]] = mid[o]
        lo[act[~o]] = mid[~o]
        keep = hi[act] > lo[act] * (1.0 + tol)
        if progress and (~keep).any():
            progress(int((~keep).sum()))
        act = act[keep]
    found = np.isfinite(hi_ot)
    ap_min[found] = hi[found]
    ap_safe[found] = lo[found]
    return MinSearch(ap_uplift=y_u, ap_min=ap_min, ap_safe=ap_safe, runs=runs, unproven=unproven)


@dataclass(frozen=True)
class MinCurve:
    """Minimum overturning acceleration over ``wp_over_p`` for one configuration (units of g tan alpha)."""

    alpha_deg: float
    pulse: PulseChoice
    isolation: Isolation
    wp_over_p: np.ndarray
    ap_min: np.ndarray
    ap_safe: np.ndarray
    ap_uplift: np.ndarray
    ap_max: float
    step: float
    tol: float


def min_overturning_curves(alphas_deg: Sequence[float], pulses: Sequence[PulseChoice],
                           isolations: Sequence[Isolation], wp_values, *, ap_max: float = DEFAULT_AP_MAX,
                           step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, R: float = REFERENCE_R,
                           runner: Optional[Runner] = None, progress=None) -> list[MinCurve]:
    """Minimum overturning curves for every ``alpha x pulse x isolation`` (nesting order), one search."""
    xs = np.asarray(wp_values, dtype=float)
    keys = [(a, pc, iso) for a in alphas_deg for pc in pulses for iso in isolations]
    families = [Family(math.radians(a), pc.shape, iso, R) for a, pc, iso in keys]
    fam = np.repeat(np.arange(len(families)), xs.size)
    res = search_min_overturning(families, fam, np.tile(xs, len(families)), ap_max=ap_max, step=step, tol=tol,
                                 runner=runner, progress=progress)
    out = []
    for j, (a, pc, iso) in enumerate(keys):
        s = slice(j * xs.size, (j + 1) * xs.size)
        out.append(MinCurve(float(a), pc, iso, xs, res.ap_min[s], res.ap_safe[s], res.ap_uplift[s], ap_max, step,
                            tol))
    return out
