"""The work-precision study: the kernel and SciPy's methods against a reference solution, per scene.

:func:`run_work_precision` solves each scene of :data:`rockcli.bench.scenes.WP_SCENES` once at
:data:`REFERENCE_RTOL` (the reference solution), measures its rounding noise and verifies it with an
independent SciPy solution (:mod:`rockcli.reference`), then runs the kernel's rtol ladder (history
and verdict-only runs) and the SciPy ladders, one :class:`WPRun` each. :func:`summarise` compares
the kernel at its default tolerance with the comparator at :data:`COMPARE_RTOL`.
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from rockcli.bench.history import history_rest_time
from rockcli.bench.scenes import Scene, SceneUnavailable, excitation_end, parse_foundation, resolve_scene
from rockcli.conditioning import ulp_perturbed, widest

#: rtol ladder of the kernel (the defaults, 5e-9 and 2e-9 on sliding bearings, are in it).
KERNEL_RTOLS = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 5e-9, 2e-9, 1e-9, 1e-10, 1e-11, 1e-12)
#: rtol ladders of the SciPy methods for ``--full`` (implicit methods stop earlier: seconds per run).
SCIPY_RTOLS_FULL = {"RK45": (1e-4, 1e-6, 1e-8, 1e-10), "DOP853": (1e-4, 1e-6, 1e-8, 1e-10, 1e-12),
                    "Radau": (1e-4, 1e-6, 1e-8), "LSODA": (1e-4, 1e-6, 1e-8), "BDF": (1e-4, 1e-6, 1e-8),
                    "RK45-free": (1e-6, 1e-8, 1e-10)}
#: The default, shorter ladders (the whole study in a few minutes); 1e-8 is in every one.
SCIPY_RTOLS = {"RK45": (1e-6, 1e-8, 1e-10), "DOP853": (1e-8, 1e-12), "Radau": (1e-6, 1e-8), "LSODA": (1e-8,),
               "BDF": (1e-6,), "RK45-free": (1e-8,)}
#: Kernel rtol of the reference solution, and the independent SciPy solution that checks it (DOP853 with
#: aligned steps; on sliding bearings too: at this tolerance its steps are small enough for the Bouc-Wen
#: element, and it is 5 times faster than Radau at 1e-11, which agrees as well).
REFERENCE_RTOL = 1e-13
CHECK_METHOD = "DOP853"
CHECK_RTOL = 1e-13
#: The SciPy tolerance the summary compares the kernel at its default (rockcli.solve.default_rtol) with.
COMPARE_RTOL = 1e-8
#: The reference's rounding noise: it is recomputed this many times with its input moved by one ulp
#: (:func:`ulp_perturbed`), and the largest change is the scene's noise.
NOISE_DRAWS = 4
NOISE_SEED = 20121
#: Wall-time budget of one SciPy run [s] (default study; ``--full``): slower runs are reported as "over budget".
SCIPY_BUDGET_S = 20.0
SCIPY_BUDGET_FULL_S = 120.0
#: Free motion shown by history runs after the excitation [s], long enough to see a block rest.
WP_TAIL = 120.0


KERNEL = "rockcli"
KERNEL_VERDICT = "rockcli-verdict"
#: The SciPy runs: each method with its steps aligned to a record's samples (as the kernel's), and
#: ``RK45-free``, RK45 whose steps only are at most one sample long and cross the record's kinks
#: (``max_step = dt``: how solve_ivp is usually called; run on records only).
SCIPY_METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF", "RK45-free")
FREE_SUFFIX = "-free"



def median_time(fn: Callable[[], object], repeats: int = 5, min_time: float = 0.02) -> tuple[float, int]:
    """Median wall time of ``fn()`` [s] over ``repeats`` rounds (each of enough calls to last
    ``min_time``), and the number of calls timed. One warm-up call first."""
    t = time.perf_counter()
    fn()
    once = time.perf_counter() - t
    number = max(1, int(min_time / max(once, 1e-9)))
    times = []
    for _ in range(max(1, repeats)):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t) / number)
    return statistics.median(times), number * max(1, repeats)



@dataclass
class WPRun:
    """One run of one method at one tolerance (errors against the scene's reference solution)."""

    scene: str
    method: str
    rtol: float
    verdict: str = ""
    verdict_ok: bool | None = None
    theta_max_over_alpha: float = math.nan
    err_theta_max_over_alpha: float = math.nan
    event: str = ""
    t_event_s: float = math.nan
    err_t_event_s: float = math.nan
    steps: int | None = None
    nfev: int | None = None
    wall_s: float = math.nan
    calls: int = 0
    note: str = ""

    @property
    def error(self) -> float:
        """The plotted error: theta_max/alpha for a survivor, the overturning time [s] otherwise."""
        return self.err_t_event_s if self.event == "overturn" else self.err_theta_max_over_alpha


@dataclass
class WPScene:
    """A scene's reference solution, its verification, and every run."""

    scene: Scene
    available: bool = True
    note: str = ""
    ref_verdict: str = ""
    ref_theta_max_over_alpha: float = math.nan
    event: str = ""
    ref_t_event_s: float = math.nan
    check_method: str = ""
    check_rtol: float = math.nan
    check_d_theta: float = math.nan
    check_d_t_event_s: float = math.nan
    noise_theta: float = math.nan
    noise_t_event_s: float = math.nan
    order: float = math.nan
    tol_slope: float = math.nan
    runs: list = field(default_factory=list)

    @property
    def floor(self) -> float:
        """The reference's resolution in the plotted error: the larger of its disagreement with the
        check and its rounding noise (NaN when neither was measured). Errors below it cannot be ranked."""
        if self.event == "overturn":
            vals = (self.check_d_t_event_s, self.noise_t_event_s)
        else:
            vals = (self.check_d_theta, self.noise_theta)
        vals = [v for v in vals if math.isfinite(v)]
        return max(vals) if vals else math.nan

    @property
    def comparator(self) -> str:
        """The SciPy method the summary compares with: RK45, or Radau for sliding bearings."""
        return "Radau" if self.scene.sliding else "RK45"


def _kernel_history(block, foundation, exc, rtol, tail=WP_TAIL):
    from rockcli.solve import simulate

    return simulate(block, foundation, exc, rtol=rtol, history=True, tail=tail)


def _event_of(verdict: str) -> str:
    return "overturn" if verdict == "overturned" else "rest"


def _kernel_event_time(r, event: str) -> float:
    if event == "overturn":
        return r.t_overturn_s
    return history_rest_time(r.history) if r.history is not None else math.nan


def _measure_noise(ws: WPScene, block, foundation, exc):
    """Set ``ws.noise_*``: the largest change of the reference solution over :data:`NOISE_DRAWS` runs
    on :func:`ulp_perturbed` inputs. A verdict that flips leaves the noise unmeasured (NaN) and a note."""
    rng = np.random.default_rng(NOISE_SEED)
    d_theta = d_t = 0.0
    for _ in range(NOISE_DRAWS):
        r = _kernel_history(block, foundation, ulp_perturbed(exc, rng), REFERENCE_RTOL)
        if r.verdict != ws.ref_verdict:
            ws.note = f"one ulp of the input changes the reference's verdict to {r.verdict}"
            return
        d_theta = max(d_theta, abs(r.theta_max_over_alpha - ws.ref_theta_max_over_alpha))
        d_t = widest(d_t, abs(_kernel_event_time(r, ws.event) - ws.ref_t_event_s))  # NaN: no time of rest
    ws.noise_theta = d_theta
    ws.noise_t_event_s = d_t


def _fill_errors(run: WPRun, ws: WPScene):
    run.verdict_ok = run.verdict == ws.ref_verdict
    run.err_theta_max_over_alpha = abs(run.theta_max_over_alpha - ws.ref_theta_max_over_alpha)
    run.event = ws.event
    run.err_t_event_s = abs(run.t_event_s - ws.ref_t_event_s)


def _fit_slope(x, y) -> float:
    x, y = np.asarray(x, float), np.asarray(y, float)
    ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
    if ok.sum() < 3 or np.unique(x[ok]).size < 3:
        return math.nan
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


def run_work_precision(scenes, *, kernel_rtols=KERNEL_RTOLS, scipy_rtols=None, methods=SCIPY_METHODS,
                       repeats: int = 1, scipy_budget_s: float = SCIPY_BUDGET_S, check: bool = True,
                       progress: Callable[[str], None] | None = None) -> list:
    """Run the work-precision study on ``scenes``; returns one :class:`WPScene` per scene.

    Parameters
    ----------
    scenes : sequence of Scene
    kernel_rtols : sequence of float
        The kernel's ladder (each also run verdict-only, ``rockcli-verdict``).
    scipy_rtols : dict method -> sequence of float, optional
        SciPy ladders (default :data:`SCIPY_RTOLS`; a sequence applies to every method).
    methods : sequence of str
        SciPy methods to run (any of :data:`SCIPY_METHODS`; empty for the kernel only).
    repeats : int
        Timing repeats of a SciPy run (the median is kept; runs longer than 2 s are timed once).
        Kernel runs are timed over 5 rounds of enough calls to last 20 ms.
    check : bool
        Verify the reference solution with an independent SciPy solution.
    progress : callable, optional
        Called with a line of text as each scene starts.
    """
    from rockcli.reference import ReferenceFailure, ReferenceTimeout, reference_simulate

    if scipy_rtols is None:
        scipy_rtols = SCIPY_RTOLS
    elif not isinstance(scipy_rtols, dict):
        scipy_rtols = {m: tuple(scipy_rtols) for m in SCIPY_METHODS}
    out = []
    for scene in scenes:
        ws = WPScene(scene)
        out.append(ws)
        try:
            block, foundation, exc = resolve_scene(scene)
        except SceneUnavailable as why:
            ws.available, ws.note = False, why.reason
            if progress:
                progress(f"{scene.name}: {why.reason}")
            continue
        if progress:
            progress(f"{scene.name}: reference (kernel at rtol {REFERENCE_RTOL:g})")
        ref = _kernel_history(block, foundation, exc, REFERENCE_RTOL)
        ws.ref_verdict = ref.verdict
        ws.ref_theta_max_over_alpha = ref.theta_max_over_alpha
        ws.event = _event_of(ref.verdict)
        ws.ref_t_event_s = _kernel_event_time(ref, ws.event)
        if progress:
            progress(f"{scene.name}: the reference's rounding noise ({NOISE_DRAWS} inputs moved by one ulp)")
        _measure_noise(ws, block, foundation, exc)
        # history runs show the free motion until 5 s after the block rests (the SciPy reference stops
        # there), not a fixed long tail
        tail = WP_TAIL
        if ws.event == "rest" and math.isfinite(ws.ref_t_event_s):
            tail = max(0.0, ws.ref_t_event_s - excitation_end(exc)) + 5.0
        if check:
            cm = CHECK_METHOD
            ws.check_method, ws.check_rtol = cm, CHECK_RTOL
            if progress:
                progress(f"{scene.name}: verifying the reference ({cm} at rtol {ws.check_rtol:g})")
            try:
                chk = reference_simulate(block, foundation, exc, rtol=ws.check_rtol, atol=None, method=cm,
                                         align=True, deadline_s=600.0)
                ws.check_d_theta = abs(chk.theta_max / block.alpha - ws.ref_theta_max_over_alpha)
                t_chk = chk.t_overturn if ws.event == "overturn" else chk.t_rest
                ws.check_d_t_event_s = abs(t_chk - ws.ref_t_event_s)
                if chk.verdict != ws.ref_verdict:
                    ws.note = f"the check ({cm}) gives the verdict {chk.verdict}, the reference {ws.ref_verdict}"
            except (ReferenceTimeout, ReferenceFailure) as why:
                ws.note = f"reference not verified: {why}"
        # the kernel ladder
        from rockcli.solve import simulate

        for rt in kernel_rtols:
            r = _kernel_history(block, foundation, exc, rt, tail)
            run = WPRun(scene.name, KERNEL, rt, verdict=r.verdict, theta_max_over_alpha=r.theta_max_over_alpha,
                        t_event_s=_kernel_event_time(r, ws.event), steps=r.steps, nfev=r.nfev)
            run.wall_s, run.calls = median_time(lambda: _kernel_history(block, foundation, exc, rt, tail))
            _fill_errors(run, ws)
            ws.runs.append(run)
            v = simulate(block, foundation, exc, rtol=rt)
            run = WPRun(scene.name, KERNEL_VERDICT, rt, verdict=v.verdict, theta_max_over_alpha=v.theta_max_over_alpha,
                        t_event_s=v.t_overturn_s if ws.event == "overturn" else math.nan, steps=v.steps, nfev=v.nfev)
            run.wall_s, run.calls = median_time(lambda: simulate(block, foundation, exc, rtol=rt))
            _fill_errors(run, ws)
            ws.runs.append(run)
        # observed order from the verdict-only runs (they stop once the verdict is proven, so their
        # right-hand sides are those spent reaching the peak or the overturn), above the reference's noise
        kr = [x for x in ws.runs if x.method == KERNEL_VERDICT]
        floor = 10.0 * max(ws.floor if math.isfinite(ws.floor) else 0.0, 1e-13)
        good = [x for x in kr if x.error > floor]
        ws.tol_slope = _fit_slope([x.rtol for x in good], [x.error for x in good])
        if ws.tol_slope > 0.3:  # else the error does not follow rtol (steps capped by a record's samples)
            ws.order = -_fit_slope([x.nfev for x in good], [x.error for x in good])
        # the SciPy ladders
        for m in methods:
            free = m.endswith(FREE_SUFFIX)
            if free and not hasattr(exc, "acc"):
                continue  # a pulse has no sample intervals: the same runs as the aligned method
            for rt in scipy_rtols.get(m, scipy_rtols.get(m[:-len(FREE_SUFFIX)], ()) if free else ()):
                if progress:
                    progress(f"{scene.name}: {m} at rtol {rt:g}")
                run = WPRun(scene.name, m, rt)
                times = []
                try:
                    for i in range(max(1, repeats)):
                        res = reference_simulate(block, foundation, exc, rtol=rt, atol=None,
                                                 method=m[:-len(FREE_SUFFIX)] if free else m, align=not free,
                                                 deadline_s=scipy_budget_s)
                        times.append(res.wall_s)
                        if res.wall_s > 2.0:
                            break
                except ReferenceTimeout:
                    run.note = f"over budget ({scipy_budget_s:g} s)"
                except ReferenceFailure as why:
                    run.note = f"failed: {str(why).split(': ', 1)[-1]}"
                if times and not run.note:
                    run.verdict = res.verdict
                    run.theta_max_over_alpha = res.theta_max / block.alpha
                    run.t_event_s = res.t_overturn if ws.event == "overturn" else res.t_rest
                    run.steps, run.nfev = res.steps, res.nfev
                    run.wall_s, run.calls = statistics.median(times), len(times)
                    _fill_errors(run, ws)
                ws.runs.append(run)
    return out


@dataclass(frozen=True)
class WPSummary:
    """rockcli at its default tolerance (5e-9; 2e-9 on sliding bearings) against the comparator
    (RK45, or Radau for sliding bearings) at ``rtol = 1e-8``: errors, wall times and their ratio
    (kernel / SciPy).

    ``as_accurate``: rockcli's error is at most SciPy's, or at most the reference's resolution
    ``floor`` (:attr:`WPScene.floor`), below which no two errors can be ranked; ``at_floor`` says
    that the second case decided it (rockcli's error above SciPy's, both at the floor)."""

    scene: str
    comparator: str
    err_kernel: float
    err_scipy: float
    wall_kernel_s: float
    wall_verdict_s: float
    wall_scipy_s: float
    as_accurate: bool
    time_ratio: float
    verdicts_agree: bool
    err_free: float = math.nan
    wall_free_s: float = math.nan
    rtol_kernel: float = 5e-9
    floor: float = math.nan
    at_floor: bool = False


def scene_default_rtol(scene) -> float:
    """rockcli's default rtol for the scene's foundation (:func:`rockcli.solve.default_rtol`)."""
    from rockcli.solve import default_rtol

    return default_rtol(parse_foundation(scene.isolation))


def summarise(ws: WPScene) -> WPSummary | None:
    """The default-tolerance comparison of one scene (None when a run is missing)."""
    d = scene_default_rtol(ws.scene)
    k = next((r for r in ws.runs if r.method == KERNEL and r.rtol == d), None)
    kv = next((r for r in ws.runs if r.method == KERNEL_VERDICT and r.rtol == d), None)
    s = next((r for r in ws.runs if r.method == ws.comparator and r.rtol == COMPARE_RTOL and not r.note), None)
    if k is None or s is None:
        return None
    f = next((r for r in ws.runs if r.method == ws.comparator + FREE_SUFFIX and r.rtol == COMPARE_RTOL
              and not r.note), None)
    beats = k.error <= s.error
    at_floor = not beats and k.error <= ws.floor  # False when the floor is NaN
    return WPSummary(ws.scene.name, ws.comparator, k.error, s.error, k.wall_s, kv.wall_s if kv else math.nan,
                     s.wall_s, beats or at_floor, k.wall_s / s.wall_s, bool(k.verdict_ok and s.verdict_ok),
                     f.error if f else math.nan, f.wall_s if f else math.nan, d, ws.floor, at_floor)
