"""Minimum overturning acceleration (the paper's Figures 7, 8, 9 and 11).

Verdicts only: the search runs with ``early=True`` (each run stops as soon as its verdict is proven,
even during the pulse; the same verdicts).

Uplift threshold
----------------
On a rigid foundation the block uplifts when ``|ag|`` passes ``g tan(alpha)``; all four pulse shapes
peak at exactly ``|a_p|`` (the antisymmetric Ricker through its factor beta), so the no-uplift zone is
exactly ``y <= 1`` for each of them. On an isolated base, before uplift, block and base move together
as a linear oscillator, so the peak base acceleration is proportional to ``a_p``: uplift is monotone
in ``a_p`` and its threshold is found by bisection on the solver's uplift flag. Under a vertical pulse
(``rockcli spectrum min-overturning --vertical-pulse``) the threshold on a rigid foundation moves with
``g + a_v(t)``: still monotone in ``a_p`` (``g + a_v > 0``), found by the same bisection.

Minimum overturning acceleration
--------------------------------
Overturning is not monotone in ``a_p`` (safe islands lie above the minimum), so a bisection between
"safe" and "overturns" alone could land on the upper edge of an island. :func:`search_min_overturning`

1. scans ``y`` upwards from the uplift threshold ``y_u`` on the geometric grid ``y_u (1 + step)^k``
   (default step 1 %), all columns in parallel batches, each column up to its first overturning
   value ``F``;
2. scans again, on ``F / (1 + refine_band) (1 + refine)^k`` up to ``F`` (defaults: the 10 % below
   ``F`` in steps of 0.1 %), all columns in one batch;
3. bisects (geometrically) between the first overturning value scanned and the value below it
   (safe) to ``tol`` (default 0.1 %).

Result: ``ap_min`` overturns, ``ap_safe`` (within ``tol`` below) does not, and no value scanned
between the uplift threshold and ``ap_safe`` overturns.

The 100 g limit. No run of the search has a pulse beyond the 100 g rockcli runs (:data:`rockcli.pulses.A_P_MAX_G`,
the limit of ``--ap``, ``--scale`` and the record readers): a column's search stops at ``y_cap = min(ap_max,
100 / tan(alpha))`` (:func:`y_limit`), which is below the default ``ap_max = 20`` for alpha above 78.7 deg (squat
blocks, which need large pulses). Such a curve's ``ap_max`` is its cap, and it says so (``capped``); where nothing
overturns up to the cap the curve is empty, as above ``ap_max``. Below the cap the search is unchanged (the same
runs), so a curve that is not capped is the curve of before.

Why a second scan just below ``F`` (issue 28). The overturning boundary is ragged: below the band
where the first scan overturns lie windows a few tenths of a per cent wide or less, which a 1 % step
steps over, on the unsafe side (Figure 11: 4.578 reported where 4.49 already overturns). Measured
with a 0.1 % brute-force grid on the paper's Figures 7, 9 and 11 (``benchmarks/bench_min_windows.py``;
numbers in the README, "Minimum overturning search"): most such windows are a single 0.1 % value
wide, so the second scan steps at 0.1 % (the bisection tolerance); they lie within a few per cent
below ``F`` (one 8 % below), so it covers the 10 % below ``F``, at about half the runs of the first
scan rather than ten times them for a 0.1 % scan from ``y_u``. The peaks of the surviving runs next
to a window are no guide: they can be 0.01-0.3 alpha a few tenths of a per cent below one (the
response jumps where the block lifts off or the base sticks at one amplitude and not at the next),
so the second scan is placed by ``F`` alone. Stated resolution: a window narrower than ``refine``
can be missed anywhere, and one narrower than ``step`` that lies more than ``refine_band`` below
``F``, or in a column where the first scan finds nothing up to ``ap_max``; ``refine = 0`` gives the
first scan and bisection alone (the search before issue 28, the same runs).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.spectra.runner import Runner
from rockcli.spectra.scenes import REFERENCE_R, Family, Isolation, PulseChoice

#: Defaults of the minimum-overturning search: relative scan step, relative bisection tolerance,
#: and the largest a_p / (g tan alpha) tried.
DEFAULT_STEP = 0.01
DEFAULT_TOL = 1e-3
DEFAULT_AP_MAX = 20.0
#: Defaults of the refinement: relative step of the finer scan, and how far below the first overturning
#: value of the scan it reaches (relative).
DEFAULT_REFINE = 1e-3
DEFAULT_REFINE_BAND = 0.1


@dataclass(frozen=True)
class MinSearch:
    """Per column: uplift threshold, and the bracket of the smallest overturning amplitude.

    ``ap_min`` overturns, ``ap_safe`` (within ``tol`` below it) does not; both NaN when nothing
    overturns up to ``ap_max`` (``ap_uplift`` NaN too when the block does not even uplift). All in
    units of ``g tan(alpha)``. ``unproven``: runs still moving at the solver's horizon (counted safe).
    ``refined``: True where the second scan found an overturning value below the first scan's last
    safe value: a window the first scan stepped over (it and its bisection alone would have
    overstated the minimum).
    ``refine_runs``: the runs of the second scan (all columns). ``ap_cap``: per column the largest ``y`` searched,
    ``min(ap_max, y_limit(alpha))`` (the 100 g limit, see the module notes).
    """

    ap_uplift: np.ndarray
    ap_min: np.ndarray
    ap_safe: np.ndarray
    runs: int
    unproven: int = 0  # runs that reached the solver's horizon unproven (counted as safe)
    refined: Optional[np.ndarray] = None
    refine_runs: int = 0
    ap_cap: Optional[np.ndarray] = None


def y_limit(alpha: float) -> float:
    """The largest ``y = a_p / (g tan alpha)`` whose pulse stays within the 100 g rockcli runs
    (:data:`rockcli.pulses.A_P_MAX_G`) for a block of slenderness ``alpha`` [rad]: ``100 / tan(alpha)``, rounded
    down so that ``y tan(alpha)`` does not pass 100 (about 20 at alpha = 78.7 deg, 1 at 89.4 deg)."""
    from rockcli.pulses import A_P_MAX_G

    t = math.tan(alpha)
    y = A_P_MAX_G / t
    while y * t > A_P_MAX_G:
        y = math.nextafter(y, 0.0)
    return y


def describe_search(step: float, tol: float, refine: float, refine_band: float) -> str:
    """One line saying how the minimum was found (for the CSV and the figure notes)."""
    scan = f"scan in steps of {100 * step:.3g} % up from the uplift threshold"
    if refine > 0:
        scan += (f", rescanned in steps of {100 * refine:.3g} % over the {100 * refine_band:.3g} % below its first "
                 "overturning value")
    return f"{scan}, bisection to {100 * tol:.3g} %"


#: Floors of the search's settings. A relative bisection tolerance below TOL_MIN approaches the spacing of
#: double-precision numbers (2.2e-16 relative), where the midpoint equals an end and the bisection could not
#: end; a scan step below STEP_MIN (REFINE_MIN for the second scan) would take more than about 30,000
#: (10,000) runs per column from the uplift threshold to ap_max = 20 (over the 10 % band).
TOL_MIN = 1e-12
STEP_MIN = 1e-4
REFINE_MIN = 1e-5


def _check(step, tol, refine, refine_band, ap_max):
    if not (math.isfinite(step) and STEP_MIN <= step <= 0.5):
        raise RockcliInputError(f"scan step must lie in [{STEP_MIN:g}, 0.5] (relative; a finer scan takes more "
                                f"than ~30,000 runs per column), got {step!r}")
    if not (math.isfinite(tol) and TOL_MIN <= tol <= step):
        raise RockcliInputError(f"tolerance must lie in [{TOL_MIN:g}, step] (relative; double precision cannot "
                                f"bisect finer), got {tol!r}")
    if not (math.isfinite(refine) and (refine == 0 or REFINE_MIN <= refine < step)):
        raise RockcliInputError(f"refinement step must be 0 (no refinement) or lie in [{REFINE_MIN:g}, step) "
                                f"(relative), got {refine!r}")
    if not (math.isfinite(refine_band) and 0 < refine_band <= 10):
        raise RockcliInputError(f"refinement band must lie in (0, 10] (relative, below the first overturning "
                                f"scanned value), got {refine_band!r}")
    if not (math.isfinite(ap_max) and ap_max > 1):
        raise RockcliInputError(f"ap_max must be > 1 (in units of g tan alpha), got {ap_max!r}")


#: The most columns (curve x omega_p/p value) one search takes: about 150 runs each with the default settings
#: (100 to 1,000), so 100,000 columns are some 15 million runs, about half an hour on 2 cores.
MAX_COLUMNS = 100_000
#: The largest ``ap_max`` [g tan alpha]: a column that never overturns scans ``ln(ap_max / y_uplift) / ln(1 + step)``
#: values, at most 930 at the default step and 92,000 at the floor (1e-4); ``ap_max = 1e300`` would be 6.9 million.
#: Beyond 5,730 not even the most slender supported block (alpha = 1 deg) keeps its pulses within 100 g.
AP_MAX_MAX = 1e4


def _check_size(n: int, ap_max: float) -> None:
    """Before any run: at most :data:`MAX_COLUMNS` columns and ``ap_max`` at most :data:`AP_MAX_MAX`."""
    if n > MAX_COLUMNS:
        raise RockcliInputError(f"the search has {n:,} columns (curves x omega_p/p values); at most {MAX_COLUMNS:,} "
                                f"are searched at once (about 150 runs each): use fewer values or curves")
    if ap_max > AP_MAX_MAX:
        raise RockcliInputError(f"ap_max must be at most {AP_MAX_MAX:g} (in units of g tan alpha: a column that never "
                                f"overturns scans up to it, and beyond 5730 even a block of alpha = 1 deg needs pulses "
                                f"of more than 100 g), got {format_number(ap_max)}")


def search_min_overturning(families: Sequence[Family], fam, x, *, ap_max: float = DEFAULT_AP_MAX,
                           step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, refine: float = DEFAULT_REFINE,
                           refine_band: float = DEFAULT_REFINE_BAND, runner: Optional[Runner] = None,
                           progress=None) -> MinSearch:
    """Smallest ``y = a_p/(g tan alpha)`` that overturns, for columns ``(families[fam[i]], x[i])``.

    See the module notes: uplift threshold, geometric scan up from it with ratio ``1 + step`` to the
    first overturning value ``F``, a second scan with ratio ``1 + refine`` from ``F / (1 +
    refine_band)`` up to ``F`` (``refine = 0``: none), then geometric bisection to ``tol`` between
    the first overturning value scanned and the value below it. ``progress(n)`` is told when ``n``
    more columns are finished; a column is finished only when its whole search ends, so ``progress.runs(n)``, when
    the callable has that method (:func:`rockcli.progress.runs_counter`), is told as the runs finish.
    """
    _check(step, tol, refine, refine_band, ap_max)
    runner = runner or Runner()
    fam = np.asarray(fam, dtype=np.int64)
    x = np.asarray(x, dtype=float)
    n = len(x)
    _check_size(n, ap_max)
    from rockcli.progress import runs_counter

    told = {"progress": runs_counter(progress)} if runs_counter(progress) else {}  # the runs as they finish
    runs = 0
    unproven = 0
    limits = np.array([y_limit(f.alpha) for f in families])
    cap = np.minimum(ap_max, limits[fam]) if n else np.zeros(0)  # the 100 g limit (module notes)

    def run(idx, yv, early=True, uplift_only=False):
        nonlocal runs, unproven
        runs += len(idx)
        single = np.array([families[f].plinth is None for f in fam[idx]], bool)
        if uplift_only and not single.all():
            # only the uplift flags are read: the stack runs may stop once they lift (spectra.runner._run_stacks),
            # and are no verdicts to count
            out = runner(families, fam[idx], x[idx], yv, early=early, uplift_only=True, **told)
        else:
            out = runner(families, fam[idx], x[idx], yv, early=early, **told)
            single[:] = True
        unproven += int(np.count_nonzero((~out.settled & ~out.overturned)[single]))
        return out

    def tell(k):
        if progress and k:
            progress(int(k))

    y_u = _uplift_thresholds(families, fam, n, ap_max, run, getattr(runner, "vertical", None) is not None,
                             limits[fam] if n else np.zeros(0))
    active = np.flatnonzero(np.isfinite(y_u) & (y_u < cap))
    tell(n - active.size)
    scans = _scan(y_u, active, 1.0 + step, cap, run)
    # the last safe value of the first scan: an overturning value below it was stepped over by that scan
    first_safe = {i: (ys[-2] if over[-1] else ys[-1]) for i, (ys, over) in scans.items()}
    runs0 = runs
    if refine > 0:
        _refine(scans, 1.0 + refine, refine_band, run)
    refine_runs = runs - runs0

    # bisection between the last safe and the first overturning value scanned
    lo = np.full(n, np.nan)
    hi = np.full(n, np.nan)
    refined = np.zeros(n, bool)
    for i, (ys, over) in scans.items():
        hit = np.flatnonzero(over)
        if hit.size:
            j = int(hit[0])
            hi[i] = ys[j]
            lo[i] = ys[j - 1] if j > 0 else y_u[i]
            refined[i] = ys[j] < first_safe[i]
    act = np.flatnonzero(np.isfinite(hi))
    tell(len(scans) - act.size)  # nothing overturns up to ap_max
    act = act[hi[act] > lo[act] * (1.0 + tol)]
    tell(np.count_nonzero(np.isfinite(hi)) - act.size)
    while act.size:
        mid = np.sqrt(lo[act] * hi[act])
        o = run(act, mid).overturned
        hi[act[o]] = mid[o]
        lo[act[~o]] = mid[~o]
        keep = hi[act] > lo[act] * (1.0 + tol)
        tell(np.count_nonzero(~keep))
        act = act[keep]
    return MinSearch(ap_uplift=y_u, ap_min=hi, ap_safe=lo, runs=runs, unproven=unproven, refined=refined,
                     refine_runs=refine_runs, ap_cap=cap)


def _uplift_thresholds(families, fam, n, ap_max, run, vertical: bool = False, limits=None) -> np.ndarray:
    """Uplift threshold per column: exactly 1 on a rigid foundation (every shape peaks at |a_p|); on
    an isolated base the stuck motion is linear in a_p, so uplift is monotone: bisection (NaN when
    the block does not uplift up to 2 ap_max, or up to its 100 g limit ``limits`` when that is lower:
    the bracket then stops at the limit). Under a vertical pulse (rigid foundation) the block
    uplifts when ``y tan(alpha) |f(t)| > (1 + a_v(t)/g) tan(alpha)`` at some t, with ``g + a_v > 0``:
    monotone in y too, but not at y = 1: bisection on every column. A body on a plinth (``--on``): on linear
    bearings body, plinth and base move together before anything lifts, a linear oscillator, so the same
    bisection; on the rigid foundation the static threshold, checked (:func:`_stack_thresholds`)."""
    y_u = np.ones(n)
    iso_cols = np.array([i for i in range(n) if vertical or not families[fam[i]].isolation.rigid], dtype=np.int64)
    if not vertical:
        iso_cols = np.union1d(iso_cols, _stack_thresholds(families, fam, n, run, y_u)).astype(np.int64)
    if iso_cols.size:
        top = np.full(iso_cols.size, 2.0 * ap_max)
        if limits is not None:
            top = np.minimum(top, np.asarray(limits)[iso_cols])
        capped = top < 2.0 * ap_max  # the 100 g limit is below 2 ap_max: no run past it
        lo = np.zeros(iso_cols.size)
        hi = np.minimum(1.0, top)
        found = np.zeros(iso_cols.size, bool)
        pending = np.arange(iso_cols.size)
        while pending.size:  # bracket: double hi until the block uplifts
            up = run(iso_cols[pending], hi[pending], early=False, uplift_only=True).uplifted
            found[pending[up]] = True
            still = pending[~up]
            lo[still] = hi[still]
            more = np.where(capped[still], hi[still] < top[still], 2.0 * hi[still] <= top[still])
            hi[still] = np.where(capped[still], np.minimum(2.0 * hi[still], top[still]), 2.0 * hi[still])
            pending = still[more]
        ok = found
        act = np.flatnonzero(ok)
        while act.size:
            mid = 0.5 * (lo[act] + hi[act])
            up = run(iso_cols[act], mid, early=False, uplift_only=True).uplifted
            hi[act[up]] = mid[up]
            lo[act[~up]] = mid[~up]
            act = act[(hi[act] - lo[act]) > 1e-7 * hi[act]]
        y_u[iso_cols] = np.where(ok, lo, np.nan)
    return y_u


#: Relative gap above a plinth's static uplift threshold at which :func:`_stack_thresholds` checks that something
#: lifts: the resolution of the bisection of an isolated base's threshold (:func:`_uplift_thresholds`).
STACK_UPLIFT_GAP = 1e-7


def _stack_thresholds(families, fam, n, run, y_u) -> np.ndarray:
    """Uplift thresholds of the columns of a body on a plinth on the rigid foundation, written into ``y_u``; returns
    the columns left to the bisection of :func:`_uplift_thresholds`.

    Theorem (docs/physics-plinth.md, "From rest"): from rest, until something lifts the body and its plinth move with
    the ground, so the body lifts off the plinth when ``|a_g|`` passes ``g tan(alpha1)`` and the two lift off the
    ground together when it passes ``g tan(alpha_asm)``; every pulse peaks at exactly ``|a_p|``, so nothing lifts
    for ``y <= y_s = min(1, tan(alpha_asm)/tan(alpha1))`` and something lifts above it. Uplift is monotone in ``y``:
    the threshold is ``y_s``. Not assumed but checked, with two runs of the stack driver per column: nothing lifts
    at ``y_s`` (the scan's first value, counted safe, is a run that did not lift) and something lifts at ``y_s (1 +
    STACK_UPLIFT_GAP)`` (the threshold within the isolated base's bisection resolution). A column where either
    check fails (rounding at the threshold) goes to the bisection, as an isolated base's."""
    cols = np.array([i for i in range(n) if families[fam[i]].plinth is not None and families[fam[i]].isolation.rigid],
                    dtype=np.int64)
    if not cols.size:
        return cols
    from rockcli.io.units import G

    ys = np.empty(cols.size)
    for j, i in enumerate(cols):
        f = families[fam[i]]
        st = f.body
        ys[j] = min(1.0, st.assembly_uplift_acceleration / (G * math.tan(f.alpha)))
    below = run(cols, ys, early=False, uplift_only=True).uplifted
    above = run(cols, ys * (1.0 + STACK_UPLIFT_GAP), early=False, uplift_only=True).uplifted
    ok = ~below & above
    y_u[cols[ok]] = ys[ok]
    return cols[~ok]


def _scan(y_u, active, ratio, cap, run) -> dict:
    """The scan upwards from the threshold on ``y_u ratio^k`` (capped at each column's ``cap``), all columns in
    parallel rounds (4, 8, ... 64 values per column), each column up to its first overturning value.

    Returns ``{column: (y, overturned)}``, lists of the values scanned in increasing order, the
    uplift threshold first (safe). From here on only verdicts count: early runs (stopped once the
    verdict is proven; the same verdicts).
    """
    scans = {int(i): ([float(y_u[i])], [False]) for i in active}
    kdone = dict.fromkeys(scans, 0)
    width = dict.fromkeys(scans, 4)
    active = list(scans)
    while active:
        cols = np.concatenate([np.full(width[i], i) for i in active])
        ks = np.concatenate([np.arange(kdone[i] + 1, kdone[i] + 1 + width[i]) for i in active])
        yv = np.minimum(y_u[cols] * ratio ** ks, cap[cols])
        res = run(cols, yv)
        still = []
        pos = 0
        for i in active:
            w = width[i]
            o, yy = res.overturned[pos:pos + w], yv[pos:pos + w]
            pos += w
            hit = np.flatnonzero(o)
            stop = int(hit[0]) + 1 if hit.size else w
            ys, over = scans[i]
            ys += yy[:stop].tolist()
            over += o[:stop].tolist()
            if not hit.size and yy[-1] < cap[i]:
                kdone[i] += w
                width[i] = min(2 * w, 64)
                still.append(i)
        active = still
    return scans


def _refine(scans, ratio, band, run) -> None:
    """Scan on ``floor ratio^k`` from ``floor = max(y_u, F / (1 + band))`` up to each column's first
    overturning scanned value ``F``, all columns in one batch, and merge the values into ``scans`` (in
    order; only up to the new first overturning value). Columns where nothing overturned are left."""
    cols, yv = [], []
    for i, (ys, over) in scans.items():
        if over[-1]:
            floor = max(ys[0], ys[-1] / (1.0 + band))
            fine = floor * ratio ** np.arange(math.ceil(math.log(ys[-1] / floor) / math.log(ratio)) + 1)
            fine = fine[fine < ys[-1] * (1.0 - 1e-12)]
            cols.append(np.full(fine.size, i))
            yv.append(fine)
    if not cols:
        return
    cols = np.concatenate(cols)
    yv = np.concatenate(yv)
    res = run(cols, yv)
    for i in np.unique(cols):
        m = cols == i
        ys, over = scans[int(i)]
        y_all = np.concatenate([ys, yv[m]])
        o_all = np.concatenate([over, res.overturned[m]])
        order = np.argsort(y_all, kind="stable")
        y_all, o_all = y_all[order], o_all[order]
        stop = int(np.argmax(o_all)) + 1  # the coarse first overturning value is among them
        scans[int(i)] = (y_all[:stop].tolist(), o_all[:stop].tolist())


@dataclass(frozen=True)
class MinCurve:
    """Minimum overturning acceleration over ``wp_over_p`` for one configuration (units of g tan alpha).

    ``step``, ``tol``, ``refine`` and ``refine_band`` are the search's settings (:attr:`found_by` says
    them in words); ``refined`` is True where the minimum lies in a window the first scan stepped
    over (see :class:`MinSearch`). ``ap_max`` is the largest value searched: the one asked for, or, when
    ``capped``, the lower ``100 g / (g tan alpha)`` (:func:`y_limit`: no pulse past the 100 g rockcli runs).
    """

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
    refine: float = 0.0
    refine_band: float = DEFAULT_REFINE_BAND
    refined: Optional[np.ndarray] = None
    capped: bool = False
    #: the plinth the block stands on (:class:`rockcli.spectra.plinth.PlinthRatio`; None: alone)
    plinth: Optional[object] = None

    @property
    def found_by(self) -> str:
        return describe_search(self.step, self.tol, self.refine, self.refine_band)


def curves_of(search: MinSearch, keys, xs, *, ap_max, step, tol, refine, refine_band) -> list[MinCurve]:
    """The curves of ``search`` over columns laid out as ``keys x xs`` (``keys``: (alpha_deg, pulse, isolation[,
    plinth]))."""
    refined = search.refined if search.refined is not None else np.zeros(search.ap_min.size, bool)
    out = []
    for j, (a, pc, iso, *pl) in enumerate(keys):
        s = slice(j * xs.size, (j + 1) * xs.size)
        top = min(ap_max, y_limit(math.radians(a)))  # the search's cap (MinSearch.ap_cap) for this alpha
        out.append(MinCurve(float(a), pc, iso, xs, search.ap_min[s], search.ap_safe[s], search.ap_uplift[s],
                            top, step, tol, refine, refine_band, refined[s], capped=top < ap_max,
                            plinth=pl[0] if pl else None))
    return out


def capped_note(curves) -> str:
    """A sentence for the curves whose search stopped at the 100 g limit below ``ap_max`` (empty when none did)."""
    capped = {c.alpha_deg: c.ap_max for c in curves if c.capped}
    if not capped:
        return ""
    where = ", ".join(f"about {y:.4g} at alpha = {format_number(a, derived=True)} deg"
                      for a, y in sorted(capped.items()))
    return (f"Searched only up to a_p = 100 g, the largest pulse rockcli runs (recorded peaks reach about 4 g): "
            f"a_p/(g tan alpha) up to {where}; nothing overturning up to there is left empty.")


def min_overturning_curves(alphas_deg: Sequence[float], pulses: Sequence[PulseChoice],
                           isolations: Sequence[Isolation], wp_values, *, ap_max: float = DEFAULT_AP_MAX,
                           step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, refine: float = DEFAULT_REFINE,
                           refine_band: float = DEFAULT_REFINE_BAND, R: float = REFERENCE_R,
                           runner: Optional[Runner] = None, progress=None,
                           plinths: Sequence = (None,)) -> list[MinCurve]:
    """Minimum overturning curves for every ``alpha x pulse x isolation x plinth`` (nesting order), one search.
    Pulses and isolations may be spec strings; a wrong type is one sentence (:mod:`rockcli.spectra.arguments`).
    ``plinths``: None (the block alone) and/or :class:`rockcli.spectra.plinth.PlinthRatio` plinths it stands on."""
    from rockcli.spectra.arguments import as_alphas, as_isolations, as_plinths, as_pulses, as_values

    alphas_deg, pulses, isolations = as_alphas(alphas_deg), as_pulses(pulses), as_isolations(isolations)
    plinths = as_plinths(plinths)
    xs = as_values(wp_values, "wp_values", positive=True)
    keys = [(a, pc, iso, pl) for a in alphas_deg for pc in pulses for iso in isolations for pl in plinths]
    families = [Family(math.radians(a), pc.shape, iso, R, pl) for a, pc, iso, pl in keys]
    fam = np.repeat(np.arange(len(families)), xs.size)
    res = search_min_overturning(families, fam, np.tile(xs, len(families)), ap_max=ap_max, step=step, tol=tol,
                                 refine=refine, refine_band=refine_band, runner=runner, progress=progress)
    return curves_of(res, keys, xs, ap_max=ap_max, step=step, tol=tol, refine=refine, refine_band=refine_band)
