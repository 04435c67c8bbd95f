"""How accurate, how fast, how robust: the solver measured against itself and against SciPy.

Two studies, both run by ``rockcli bench``:

* **Work-precision** (:func:`run_work_precision`). Named representative scenes
  (:data:`WP_SCENES`: rigid foundation, linear bearings, single and double concave sliding
  bearings; each under a pulse and under a real record when one is found). Every scene is solved
  by the kernel at a ladder of ``rtol`` (full-history runs, ``rockcli``; verdict-only runs as the
  sweeps use them, ``rockcli-verdict``) and by the SciPy reference (:mod:`rockcli.reference`) with
  ``RK45``, ``DOP853``, ``Radau``, ``LSODA`` and ``BDF`` at a ladder of ``rtol``. Each run is
  compared with a reference solution: the kernel at ``rtol = 1e-13``, verified by an independent
  solution (SciPy ``DOP853`` at ``1e-13``, steps aligned to a record's samples) on the same scene. Per run: the error in ``theta_max/alpha``, the error in the overturning time (or,
  for a survivor, the time the block comes to rest for good), whether the verdict agrees, steps,
  right-hand sides and the median wall time of repeats.
* **Stability** (:func:`run_stability`). Stiff and extreme scenes (:data:`STABILITY_SCENES`), each
  run at ``rtol = 1e-6`` and ``1e-10`` with a wall-time and a step budget, and judged by the checks
  below. Each check is a plain function of arrays, so a test can feed it a planted failure.

Checks (a scene passes when all apply and hold): :func:`check_finite` (no NaN/inf),
:func:`check_budget` (wall time and steps within budget: no hang), :func:`check_steps` (no
step-size collapse), :func:`check_tolerance` (same verdict at both tolerances, peak within
:data:`PEAK_TOL`), :func:`check_momentum` (the impact map keeps the horizontal momentum of block +
base and the angular momentum about the new pivot at every impact of the history),
:func:`check_energy` (on a rigid base, no energy created in free rocking after the excitation),
:func:`check_dissipation` (a hysteretic bearing never gives back more than it stored; needs the
Bouc-Wen history of the sliding-bearing kernels). A run that ends ``NOT PROVEN`` at the horizon
is a failure unless the scene states it as its expected behaviour (an undamped base that keeps
lifting the block). Each scene's conditioning is measured too (:func:`measure_conditioning`: the
answer on inputs moved by one ulp); an ill-conditioned scene (its answer is not determined by its
input at double precision) is reported as such, not failed: that is the physics, not the solver.

Scenes whose isolation spec does not parse yet (sliding bearings before their branch is merged)
are skipped with the note ``pending: sliding bearings not available``; scenes the solver refuses
(validation) are reported as ``refused: <reason>``.
"""

from __future__ import annotations

import math
import statistics
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from rockcli.conditioning import (ILL_PEAK, ILL_T_OVERTURN, ULP_DRAWS,  # noqa: F401 (re-exported)
                                  ill_conditioned, measure_conditioning, ulp_perturbed, widest)
from rockcli.errors import RockcliInputError
from rockcli.units import G

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

PENDING_SLIDING = "pending: sliding bearings not available"

KERNEL = "rockcli"
KERNEL_VERDICT = "rockcli-verdict"
#: The SciPy runs: each method with its steps aligned to a record's samples (as the kernel's), and
#: ``RK45-free``, RK45 whose steps only are at most one sample long and cross the record's kinks
#: (``max_step = dt``: how solve_ivp is usually called; run on records only).
SCIPY_METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF", "RK45-free")
FREE_SUFFIX = "-free"


# --------------------------------------------------------------------------------------------------
# Scenes
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Scene:
    """A named scene: block, isolation spec and excitation, as text (resolved by :func:`resolve_scene`).

    ``block``: a column preset (``bassae``) or ``R=<m>,alpha=<deg>`` or ``height=<m>,width=<m>``.
    ``excitation``: ``pulse:<spec>`` (``rockcli.pulses.parse_pulse_spec``, a_p in g) or
    ``record:<catalogue id or file>``.
    """

    name: str
    title: str
    block: str
    isolation: str
    excitation: str

    @property
    def sliding(self) -> bool:
        return self.isolation.split(":")[0].strip().lower() in ("scss", "dcss", "lrb")


class SceneUnavailable(Exception):
    """A scene that cannot run here: ``reason`` starts with ``pending:``, ``refused:`` or ``skipped:``."""

    def __init__(self, reason: str):
        super().__init__(reason)
        self.reason = reason


KOBE = "record:kobe-1995-takarazuka-000"
WP_SCENES = (
    Scene("rigid-ricker", "Bassae, rigid, symmetric Ricker 0.5 g, 1.2 s", "bassae", "none",
          "pulse:ricker-sym:ap=0.5,Tp=1.2"),
    Scene("rigid-sine-overturn", "2 m x 0.5 m block, rigid, one-sine 0.29 g, 2 s (overturns, Figure 1)",
          "height=2,width=0.5", "none", "pulse:sine:ap=0.29,Tp=2"),
    Scene("rigid-kobe", "Bassae, rigid, Kobe Takarazuka 000", "bassae", "none", KOBE),
    Scene("linear-ricker", "Bassae, linear Tb = 2 s, xi = 0.1, symmetric Ricker 0.3 g, 1.2 s", "bassae",
          "linear:Tb=2,xi=0.1", "pulse:ricker-sym:ap=0.3,Tp=1.2"),
    Scene("linear-kobe", "Bassae, linear Tb = 2.5 s, xi = 0.1, Kobe Takarazuka 000", "bassae",
          "linear:Tb=2.5,xi=0.1", KOBE),
    Scene("scss-ricker", "Bassae, SCSS Tb = 3 s, mu = 0.1, symmetric Ricker 0.5 g, 1.2 s", "bassae",
          "scss:Tb=3,mu=0.1", "pulse:ricker-sym:ap=0.5,Tp=1.2"),
    Scene("scss-kobe", "Nemea, SCSS Tb = 3 s, mu = 0.1, Kobe Takarazuka 000", "nemea", "scss:Tb=3,mu=0.1", KOBE),
    Scene("dcss-ricker", "Bassae, DCSS R1 = R2 = 1.1 m, mu1 = 0.03, mu2 = 0.07, symmetric Ricker 0.5 g, 1.2 s",
          "bassae", "dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07", "pulse:ricker-sym:ap=0.5,Tp=1.2"),
    Scene("dcss-kobe", "Nemea, DCSS R1 = R2 = 1.1 m, mu1 = 0.03, mu2 = 0.07, Kobe Takarazuka 000", "nemea",
          "dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07", KOBE),
)


def _block(spec: str):
    from rockcli.models import build_block

    spec = spec.strip()
    if "=" not in spec:
        return build_block(preset=spec)
    from rockcli.inputs import parse_number, spec_items

    kv = {k.lower(): parse_number(v, f"block {spec!r}: {k}") for k, v, _ in spec_items(spec, f"block {spec!r}")}
    if "r" in kv:
        return build_block(R=kv["r"], alpha_deg=kv["alpha"])
    return build_block(height=kv["height"], width=kv["width"])


def parse_foundation(spec: str):
    """The foundation of an isolation spec; :class:`SceneUnavailable` ``pending`` for a sliding
    bearing the installed :mod:`rockcli.models` cannot parse yet."""
    from rockcli.models import parse_isolation_spec

    try:
        return parse_isolation_spec(spec)
    except RockcliInputError as exc:
        kind = spec.split(":")[0].strip().lower()
        if kind in ("scss", "dcss", "lrb") and "unknown isolation" in str(exc):
            raise SceneUnavailable(PENDING_SLIDING) from None
        raise SceneUnavailable(f"refused: {exc}") from None


def _excitation(spec: str):
    kind, _, rest = spec.partition(":")
    if kind == "pulse":
        from rockcli.pulses import parse_pulse_spec

        return parse_pulse_spec(rest)
    if kind == "record":
        from rockcli.records import read_record

        try:
            return read_record(rest)
        except RockcliInputError as exc:
            raise SceneUnavailable(f"skipped: record {rest} not found ({exc}); set ROCKCLI_RECORDS") from None
    raise ValueError(f"bad excitation {spec!r}")


def resolve_scene(scene: Scene):
    """``(block, foundation, excitation)`` of a scene, or :class:`SceneUnavailable`."""
    foundation = parse_foundation(scene.isolation)
    try:
        block = _block(scene.block)
    except RockcliInputError as exc:
        raise SceneUnavailable(f"refused: {exc}") from None
    return block, foundation, _excitation(scene.excitation)


def select_scenes(names, catalogue) -> list:
    """The scenes named (all when ``names`` is empty); an unknown name raises RockcliInputError."""
    by_name = {s.name: s for s in catalogue}
    if not names:
        return list(catalogue)
    out = []
    for n in names:
        if n not in by_name:
            raise RockcliInputError(f"unknown scene {n!r} (known: {', '.join(by_name)})")
        if by_name[n] not in out:
            out.append(by_name[n])
    return out


def excitation_end(excitation) -> float:
    """End of the ground motion [s] (a record's last sample; a pulse's support end)."""
    if hasattr(excitation, "acc"):
        return (np.asarray(excitation.acc).size - 1) * float(excitation.dt)
    return float(excitation.support()[1])


# --------------------------------------------------------------------------------------------------
# Small measurement helpers
# --------------------------------------------------------------------------------------------------
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


def history_rest_time(h) -> float:
    """Time [s] the block was last set at rest for good, from a kernel history (NaN if it never
    rests, or lifts off again). A rest is an impact (two rows at the same time, theta = 0) after
    which theta_dot is 0."""
    t, th, thd = np.asarray(h.t), np.asarray(h.theta), np.asarray(h.theta_dot)
    if t.size < 2:
        return math.nan
    same = (t[1:] == t[:-1]) & (th[1:] == 0.0) & (th[:-1] == 0.0) & (thd[1:] == 0.0) & (thd[:-1] != 0.0)
    idx = np.nonzero(same)[0]
    if idx.size == 0:
        return math.nan
    k = idx[-1] + 1
    if np.any(th[k:] != 0.0):
        return math.nan
    return float(t[k])


# --------------------------------------------------------------------------------------------------
# Work-precision
# --------------------------------------------------------------------------------------------------
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


# --------------------------------------------------------------------------------------------------
# Stability checks (plain functions of arrays: each can be fed a planted failure)
# --------------------------------------------------------------------------------------------------
#: Largest |change| in theta_max/alpha between rtol 1e-6 and 1e-10 that counts as "the same answer".
PEAK_TOL = 1e-3
#: Largest change in the overturning time [s] between the two tolerances.
T_OVERTURN_TOL = 1e-3
#: Relative tolerance on the momentum balances across an impact (exact algebra: rounding only).
MOMENTUM_TOL = 1e-9
#: Largest energy rise in free rocking, as a fraction of p^2, allowed per unit of rtol (integration error).
ENERGY_TOL_PER_RTOL = 100.0
#: A step shorter than this [s] is tiny; a run of COLLAPSE_RUN consecutive tiny steps is a collapse.
TINY_STEP = 1e-9
COLLAPSE_RUN = 50
#: Largest share of rejected steps.
MAX_REJECTED = 0.5
#: Tolerances of the stability study.
STABILITY_RTOLS = (1e-6, 1e-10)
#: Conditioning (:mod:`rockcli.conditioning`): each stability scene is run again (verdict-only, at the
#: tighter rtol) on ULP_DRAWS inputs moved by one ulp; a verdict that changes, or a peak (overturning
#: time) that moves by more than ILL_PEAK (ILL_T_OVERTURN), makes the scene ill-conditioned: its answer
#: is not determined by its input at double precision (measured and reported, not a solver failure).
ULP_SEED = 19800


@dataclass(frozen=True)
class Check:
    """One check: its name, whether it held, and a sentence with the measured value."""

    name: str
    ok: bool
    detail: str


def check_finite(**arrays) -> Check:
    """No NaN or inf in any of the named arrays or numbers."""
    bad = [k for k, v in arrays.items() if v is not None and not np.all(np.isfinite(np.asarray(v, dtype=float)))]
    return Check("finite", not bad, "no NaN/inf" if not bad else f"NaN or inf in {', '.join(bad)}")


def check_budget(wall_s: float, budget_s: float, status: int, steps: int, step_budget: int) -> Check:
    """Wall time within ``budget_s`` and the step cap not reached (status -1): no hang."""
    if status == -1 or steps >= step_budget:
        return Check("budget", False, f"step budget reached ({steps} of {step_budget} steps)")
    if not wall_s <= budget_s:
        return Check("budget", False, f"{wall_s:.2f} s, over the {budget_s:g} s budget")
    return Check("budget", True, f"{wall_s:.3f} s <= {budget_s:g} s, {steps} steps <= {step_budget}")


def check_steps(t, steps: int, rejected: int, *, tiny: float = TINY_STEP, run: int = COLLAPSE_RUN,
                max_rejected: float = MAX_REJECTED) -> Check:
    """No step-size collapse: no ``run`` consecutive steps shorter than ``tiny`` [s] in the history
    (events give two rows at one time: those zero-length pairs are not steps), and at most
    ``max_rejected`` of the steps rejected."""
    t = np.asarray(t, dtype=float)
    d = np.diff(t)
    d = d[d > 0]
    longest = 0
    if d.size:
        tinies = d < tiny
        # longest run of consecutive True
        if tinies.any():
            edges = np.diff(np.concatenate(([0], tinies.astype(np.int8), [0])))
            starts, ends = np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]
            longest = int(np.max(ends - starts))
    share = rejected / max(steps, 1)
    h_min = float(d.min()) if d.size else math.nan
    if longest >= run:
        return Check("steps", False, f"step size collapsed: {longest} consecutive steps shorter than {tiny:g} s")
    if share > max_rejected:
        return Check("steps", False, f"{100 * share:.0f}% of the steps rejected")
    return Check("steps", True, f"shortest step {h_min:.2g} s, {100 * share:.1f}% rejected")


def check_tolerance(verdict_a: str, verdict_b: str, peak_a: float, peak_b: float, t_ot_a: float = math.nan,
                    t_ot_b: float = math.nan, *, peak_tol: float = PEAK_TOL, t_tol: float = T_OVERTURN_TOL) -> Check:
    """The answer does not change with the tolerance: the same verdict, theta_max/alpha within
    ``peak_tol`` and (overturning) the overturning time within ``t_tol`` [s]."""
    if verdict_a != verdict_b:
        return Check("tolerance", False, f"verdict changes with rtol: {verdict_a} vs {verdict_b}")
    if verdict_a == "overturned":
        d = abs(t_ot_a - t_ot_b)
        if math.isnan(d) and not (math.isnan(t_ot_a) and math.isnan(t_ot_b)):
            return Check("tolerance", False, "overturning time missing at one tolerance")
        if not (d <= t_tol or (math.isnan(t_ot_a) and math.isnan(t_ot_b))):
            return Check("tolerance", False, f"overturning time changes by {d:.2g} s (> {t_tol:g} s)")
        return Check("tolerance", True, f"same verdict, overturning time within {d:.2g} s")
    d = abs(peak_a - peak_b)
    if not d <= peak_tol:
        return Check("tolerance", False, f"theta_max/alpha changes by {d:.2g} (> {peak_tol:g})")
    return Check("tolerance", True, f"same verdict, theta_max/alpha within {d:.2g}")


def impact_rows(t, theta, theta_dot):
    """Indices k of the impacts in a history: rows k, k+1 at one time with theta = 0, theta_dot != 0 before."""
    t, th, thd = (np.asarray(a, dtype=float) for a in (t, theta, theta_dot))
    return np.nonzero((t[1:] == t[:-1]) & (th[1:] == 0.0) & (th[:-1] == 0.0) & (thd[:-1] != 0.0))[0]


def check_momentum(t, theta, theta_dot, u_dot, *, R: float, alpha: float, gamma: float, isolated: bool,
                   tol: float = MOMENTUM_TOL) -> Check:
    """Momentum across every impact of a history.

    Per unit block mass, the angular momentum about the new pivot, ``I_o theta_dot + h u_dot`` after
    against ``(I_o - 2 b^2) theta_dot + h u_dot`` before (``I_o = 4 R^2/3``; Eq 14), for every impact
    that is not a rest (a rest is plastic by design); on an isolated base also the total horizontal
    momentum per unit total mass ``u_dot + gamma h theta_dot`` (Eq 16), for every impact and rest.
    """
    th, thd, ud = (np.asarray(a, dtype=float) for a in (theta, theta_dot, u_dot))
    k = impact_rows(t, theta, theta_dot)
    if k.size == 0:
        return Check("momentum", True, "no impact")
    h, b = R * math.cos(alpha), R * math.sin(alpha)
    Io = 4.0 / 3.0 * R * R
    t1, t2 = thd[k], thd[k + 1]
    u1, u2 = (ud[k], ud[k + 1]) if isolated else (np.zeros(k.size), np.zeros(k.size))
    worst_ang = worst_lin = 0.0
    rest = t2 == 0.0
    ang = np.abs(Io * t2 + h * u2 - ((Io - 2 * b * b) * t1 + h * u1)) / (Io * np.abs(t1) + h * np.abs(u1))
    if (~rest).any():
        worst_ang = float(np.max(ang[~rest]))
    if isolated:
        lin = np.abs(u2 + gamma * h * t2 - (u1 + gamma * h * t1)) / (np.abs(u1) + gamma * h * np.abs(t1) + 1e-300)
        worst_lin = float(np.max(lin))
    ok = worst_ang <= tol and worst_lin <= tol
    what = f"{k.size} impacts ({int(rest.sum())} rests): angular momentum to {worst_ang:.1e}"
    if isolated:
        what += f", horizontal momentum to {worst_lin:.1e}"
    return Check("momentum", ok, (what if ok else "momentum not kept: " + what) + f" (tolerance {tol:g})")


def check_energy(t, theta, theta_dot, *, p: float, alpha: float, t_exc_end: float, rtol: float,
                 per_rtol: float = ENERGY_TOL_PER_RTOL) -> Check:
    """Rigid foundation, after the excitation: ``E = theta_dot^2/2 + p^2 cos(alpha - |theta|)`` never
    rises above its running minimum by more than ``per_rtol * rtol * p^2`` (free rocking conserves
    E between impacts; impacts and rests only lower it)."""
    t, th, thd = (np.asarray(a, dtype=float) for a in (t, theta, theta_dot))
    m = t >= t_exc_end
    if m.sum() < 2:
        return Check("energy", True, "no free motion in the history")
    E = 0.5 * thd[m] ** 2 + p * p * np.cos(alpha - np.abs(th[m]))
    rise = float(np.max(E - np.minimum.accumulate(E))) / (p * p)
    tol = per_rtol * rtol
    if not rise <= tol:  # NaN fails too
        return Check("energy", False, f"energy created in free rocking: rise {rise:.2e} p^2 (> {tol:.0e} p^2)")
    return Check("energy", True, f"largest rise {rise:.1e} p^2 (<= {tol:.0e} p^2)")


def check_dissipation(u, z, *, Q: float, u_y: float, tol: float = 1e-6) -> Check:
    """Hysteretic bearing: the energy it has dissipated, ``Q (int z du - u_y z^2/2)`` per unit total
    mass (work of the hysteretic force minus the energy stored in its elastic part), never falls
    below zero or below an earlier value by more than ``tol`` of ``Q max|u|`` (trapezoid rule
    on the history)."""
    u, z = np.asarray(u, dtype=float), np.asarray(z, dtype=float)
    if u.size < 2:
        return Check("dissipation", True, "no base motion")
    work = np.concatenate(([0.0], np.cumsum(0.5 * (z[1:] + z[:-1]) * np.diff(u))))
    D = Q * (work - 0.5 * u_y * z * z)
    scale = Q * max(float(np.max(np.abs(u))), u_y)
    drop = float(np.max(np.maximum.accumulate(D) - D)) / scale
    low = float(-min(0.0, np.min(D))) / scale
    if not (drop <= tol and low <= tol):  # NaN fails too
        return Check("dissipation", False, f"bearing energy created: dissipated energy falls by {max(drop, low):.1e} "
                                           f"of Q max|u|")
    return Check("dissipation", True, f"dissipated energy never falls (to {max(drop, low):.0e} of Q max|u|)")


# --------------------------------------------------------------------------------------------------
# Stability scenes
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StabilityScene:
    """A stiff or extreme scene: ``build()`` returns ``(block, foundation, excitation)`` (or raises
    :class:`SceneUnavailable` / RockcliInputError when refused)."""

    name: str
    title: str
    build: Callable
    expect: str | None = None  # the verdict physics demands, when it is known
    unproven_ok: bool = False  # NOT PROVEN at the horizon is the stated behaviour
    unproven_why: str = "an undamped base that keeps lifting the block"  # ... and why (the README's limit)
    wall_budget_s: float = 30.0
    step_budget: int = 5_000_000  # the solver's default step cap
    tail: float = 10.0


def _pulse(shape, ap_g, tp, t0=None):
    from rockcli.pulses import make_pulse

    return make_pulse(shape, ap_g * G, tp) if t0 is None else make_pulse(shape, ap_g * G, tp, t0)


def _bassae():
    from rockcli.models import column

    return column("bassae")


def _record(acc, dt, name):
    from rockcli.records import Record

    return Record(np.asarray(acc, dtype=float), float(dt), name)


def band_limited_record(duration=100.0, dt=0.001, pga_g=0.4, f_lo=0.3, f_hi=8.0, seed=12):
    """A synthetic band-limited accelerogram: white noise filtered to ``[f_lo, f_hi]`` Hz (ideal FFT
    band-pass), a 5 s rise and a decay over the last third, scaled to ``pga_g``."""
    rng = np.random.default_rng(seed)
    n = int(round(duration / dt)) + 1
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, dt)
    spec[(f < f_lo) | (f > f_hi)] = 0.0
    acc = np.fft.irfft(spec, n)
    t = np.arange(n) * dt
    env = np.clip(t / 5.0, 0.0, 1.0) * np.clip((duration - t) / (duration / 3.0), 0.0, 1.0)
    acc *= env
    acc *= pga_g * G / np.max(np.abs(acc))
    return _record(acc, dt, f"band-limited-{duration:g}s-dt{dt:g}")


def _spike_record(g_level=10.0, dt=0.01, duration=10.0, at=2.0):
    acc = np.zeros(int(round(duration / dt)) + 1)
    acc[int(round(at / dt))] = g_level * G
    return _record(acc, dt, f"spike-{g_level:g}g")


def _sampled(pulse, dt, t_end):
    t = np.arange(0.0, t_end + 0.5 * dt, dt)
    return np.asarray(pulse.acceleration(t), dtype=float)


def _ends_mid_rocking():
    """A sampled Ricker cut while the block is in the air (half way up its first excursion)."""
    from rockcli.models import Rigid
    from rockcli.solve import simulate

    b, dt = _bassae(), 0.01
    pulse = _pulse("ricker-sym", 0.5, 1.2)
    full = _record(_sampled(pulse, dt, pulse.support()[1]), dt, "ricker")
    h = simulate(b, Rigid(), full, history=True, rtol=1e-12).history
    th = np.abs(h.theta)
    k_peak = int(np.argmax(th))
    k_cut = int(np.nonzero(th[:k_peak] >= 0.5 * th[k_peak])[0][0])
    n = int(h.t[k_cut] / dt)
    return b, Rigid(), _record(full.acc[: n + 1], dt, "ricker-cut-mid-rocking")


def _passes_alpha_at_end():
    """A sampled overturning Ricker whose last sample falls exactly when |theta| first reaches alpha:
    ``dt`` is adjusted (fixed point ``dt = t_alpha(dt)/n``) so that the crossing is a sample time."""
    from rockcli.models import Rigid
    from rockcli.solve import simulate

    b = _bassae()
    pulse = _pulse("ricker-sym", 0.8, 1.2)
    dt, n = 0.01, None
    for _ in range(30):
        full = _record(_sampled(pulse, dt, pulse.support()[1]), dt, "ricker")
        tx = simulate(b, Rigid(), full, rtol=1e-12).t_exceed_alpha_s
        if n is None:
            n = int(round(tx / dt))
        new = tx / n
        if abs(new - dt) <= 1e-16:
            break
        dt = new
    rec = _record(full.acc[: n + 1], dt, "ricker-ends-at-alpha")
    return b, Rigid(), rec


def _weak_chatter():
    """Bassae under a long weak harmonic motion just above its uplift threshold: many small uplifts,
    trains of impacts and rests."""
    from rockcli.models import Rigid

    b, dt = _bassae(), 0.005
    t = np.arange(0.0, 30.0 + dt / 2, dt)
    env = np.clip(t / 3.0, 0, 1) * np.clip((30.0 - t) / 3.0, 0, 1)
    acc = 1.05 * G * math.tan(b.alpha) * env * np.sin(2 * math.pi * 2.0 * t)
    return b, Rigid(), _record(acc, dt, "weak-2Hz")


def _subnormal_uplift():
    """A random extreme scene (``--random 5000 --seed 7``, number 3669), its numbers kept exactly."""
    from rockcli.models import Block, LinearIsolation
    from rockcli.pulses import make_pulse

    return (Block(4.185866746376747, 0.023977874382879526, "subnormal-uplift"),
            LinearIsolation(0.533663188523473, 0.5, 0.0), make_pulse("ricker-sym", 0.9275447215073718, 0.25285436453418914))


def _iso(spec):
    return parse_foundation(spec)


def _alpha_block(deg, R=1.0):
    from rockcli.models import Block

    return Block.from_degrees(R, deg, f"R{R:g}m-alpha{deg:g}deg")


def _ap_g_for(block, factor):
    return factor * math.tan(block.alpha)


STABILITY_SCENES = (
    StabilityScene("alpha-1deg", "R = 1 m, alpha = 1 deg, rigid, symmetric Ricker 3 g tan(alpha), 0.5 s",
                   lambda: (_alpha_block(1.0), _iso("none"), _pulse("ricker-sym", _ap_g_for(_alpha_block(1.0), 3), 0.5))),
    StabilityScene("alpha-1deg-linear", "R = 1 m, alpha = 1 deg, linear Tb = 2 s, symmetric Ricker 3 g tan(alpha), 2 s",
                   lambda: (_alpha_block(1.0), _iso("linear:Tb=2,xi=0.1"),
                            _pulse("ricker-sym", _ap_g_for(_alpha_block(1.0), 3), 2.0))),
    StabilityScene("alpha-45deg", "R = 1 m, alpha = 45 deg, rigid, symmetric Ricker 3 g, 0.5 s",
                   lambda: (_alpha_block(45.0), _iso("none"), _pulse("ricker-sym", 3.0, 0.5))),
    StabilityScene("ap5g-Tp0.05", "Bassae, rigid, symmetric Ricker 5 g, 0.05 s",
                   lambda: (_bassae(), _iso("none"), _pulse("ricker-sym", 5.0, 0.05))),
    StabilityScene("ap5g-Tp0.05-linear", "Bassae, linear Tb = 2 s, symmetric Ricker 5 g, 0.05 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1"), _pulse("ricker-sym", 5.0, 0.05))),
    StabilityScene("ap5g-Tp10", "Bassae, rigid, symmetric Ricker 5 g, 10 s", lambda: (_bassae(), _iso("none"),
                   _pulse("ricker-sym", 5.0, 10.0))),
    StabilityScene("ap5g-Tp10-linear", "Bassae, linear Tb = 2 s, symmetric Ricker 5 g, 10 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1"), _pulse("ricker-sym", 5.0, 10.0))),
    StabilityScene("record-100s", "Bassae, rigid, 100 s band-limited record (0.3-8 Hz, 0.4 g) at dt = 0.001 s",
                   lambda: (_bassae(), _iso("none"), band_limited_record())),
    StabilityScene("record-100s-linear", "Bassae, linear Tb = 2.5 s, xi = 0.1, the same 100 s record at 0.5 g",
                   lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0.1"), band_limited_record(pga_g=0.5))),
    StabilityScene("chatter-pulse", "Bassae, rigid, symmetric Ricker 1.05 g tan(alpha), 0.5 s (chatters to rest)",
                   lambda: (_bassae(), _iso("none"), _pulse("ricker-sym", _ap_g_for(_bassae(), 1.05), 0.5))),
    StabilityScene("chatter-weak-record", "Bassae, rigid, 30 s of 2 Hz motion at 1.05 g tan(alpha)", _weak_chatter),
    StabilityScene("gamma-0", "Bassae, linear Tb = 2 s, xi = 0.1, gamma = 0, symmetric Ricker 0.3 g, 1.2 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1,gamma=0"), _pulse("ricker-sym", 0.3, 1.2))),
    StabilityScene("gamma-0.9", "Bassae, linear Tb = 2 s, xi = 0.1, gamma = 0.9, symmetric Ricker 0.3 g, 1.2 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1,gamma=0.9"), _pulse("ricker-sym", 0.3, 1.2))),
    StabilityScene("xi-0", "Bassae, linear Tb = 2.5 s, xi = 0 (undamped), symmetric Ricker 0.3 g, 1.2 s: the free "
                   "base keeps lifting the block", lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0"),
                                                            _pulse("ricker-sym", 0.3, 1.2)), unproven_ok=True),
    StabilityScene("xi-0.5", "Bassae, linear Tb = 2.5 s, xi = 0.5, symmetric Ricker 0.4 g, 1.2 s",
                   lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0.5"), _pulse("ricker-sym", 0.4, 1.2))),
    StabilityScene("spike-10g", "Bassae, rigid, 10 s record with a single 10 g sample (dt = 0.01 s)",
                   lambda: (_bassae(), _iso("none"), _spike_record())),
    StabilityScene("spike-10g-linear", "Bassae, linear Tb = 2.5 s, the same 10 g spike",
                   lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0.1"), _spike_record())),
    StabilityScene("ends-mid-rocking", "Bassae, rigid, sampled Ricker 0.5 g, 1.2 s cut while the block is in the air",
                   _ends_mid_rocking),
    StabilityScene("alpha-at-end", "Bassae, rigid, sampled Ricker 0.8 g, 1.2 s ending exactly as |theta| reaches "
                   "alpha", _passes_alpha_at_end, expect="overturned"),
    StabilityScene("alpha-45deg-gamma-0.9", "R = 2 m, alpha = 45 deg, linear Tb = 0.5 s, xi = 0.1, gamma = 0.9 (a squat "
                   "block on a light base: eta clamped to 0), antisymmetric Ricker 5 g, 0.25 s",
                   lambda: (_alpha_block(45.0, 2.0), _iso("linear:Tb=0.5,xi=0.1,gamma=0.9"),
                            _pulse("ricker-anti", 5.0, 0.25))),
    StabilityScene("slender-1.4deg-linear", "R = 17 m, alpha = 1.4 deg, linear Tb = 0.8 s, xi = 0.1, symmetric Ricker "
                   "0.7 g, 0.3 s (eta = 0.9991: the free rocking outlasts the horizon)",
                   lambda: (_alpha_block(1.4, 17.0), _iso("linear:Tb=0.8,xi=0.1"), _pulse("ricker-sym", 0.7, 0.3))),
    StabilityScene("subnormal-uplift", "R = 4.19 m, alpha = 1.37 deg, linear Tb = 0.534 s, xi = 0.5, gamma = 0, "
                   "symmetric Ricker 0.0946 g, 0.253 s (micro-uplifts: theta falls to subnormal numbers; found by "
                   "--random 5000 --seed 7)", _subnormal_uplift),
    StabilityScene("bouc-wen-uy-0.01mm", "Bassae, SCSS Tb = 3 s, mu = 0.05, u_y = 0.01 mm, symmetric Ricker 0.5 g, "
                   "1.2 s", lambda: (_bassae(), _iso("scss:Tb=3,mu=0.05,uy=0.00001"), _pulse("ricker-sym", 0.5, 1.2))),
    StabilityScene("slender-1.5deg-scss", "R = 2 m, alpha = 1.5 deg, SCSS Tb = 3 s, mu = 0.06, symmetric Ricker "
                   "0.157 g (6 g tan alpha), 0.5 s: rocks on a base at rest off centre",
                   lambda: (_alpha_block(1.5, 2.0), _iso("scss:Tb=3,mu=0.06"), _pulse("ricker-sym", 0.157, 0.5)),
                   unproven_ok=True, unproven_why="a very slender block rocking on a sliding base that rests off "
                                                  "centre (README, Sliding isolation: the limit)"),
)


def random_scenes(n: int, seed: int = 1) -> list:
    """``n`` random extreme pulse scenes (fixed ``seed``): alpha 1-45 deg, R 0.2-20 m (log-uniform),
    rigid (40 %) or linear bearings (T_b 0.3-6 s, xi in {0, 0.02, 0.1, 0.5, 1}, gamma in {0, 0.01, 0.3,
    0.9, 0.99}), any pulse shape, T_p 0.05-10 s, a_p 0.5-50 g tan(alpha) capped at 5 g. An undamped
    base (xi = 0) may end NOT PROVEN (stated)."""
    from rockcli.models import Block, LinearIsolation, Rigid

    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        alpha = math.radians(float(np.exp(rng.uniform(math.log(1), math.log(45)))))
        R = float(np.exp(rng.uniform(math.log(0.2), math.log(20))))
        if rng.random() < 0.4:
            f = Rigid()
        else:
            f = LinearIsolation(float(np.exp(rng.uniform(math.log(0.3), math.log(6)))),
                                float(rng.choice([0, 0.02, 0.1, 0.5, 1.0])), float(rng.choice([0, 0.01, 0.3, 0.9, 0.99])))
        shape = str(rng.choice(["ricker-sym", "ricker-anti", "sine", "cosine"]))
        tp = float(np.exp(rng.uniform(math.log(0.05), math.log(10))))
        ap_g = min(float(np.exp(rng.uniform(math.log(0.5), math.log(50)))) * math.tan(alpha), 5.0)
        blk = Block(R, alpha, f"random-{i}")
        title = (f"R = {R:.3g} m, alpha = {math.degrees(alpha):.3g} deg, {getattr(f, 'label', 'none')}, {shape} "
                 f"{ap_g:.3g} g, {tp:.3g} s")
        out.append(StabilityScene(f"random-{seed}-{i}", title,
                                  (lambda b=blk, f=f, e=(shape, ap_g, tp): (b, f, _pulse(*e))),
                                  unproven_ok=bool(getattr(f, "xi", 1.0) == 0.0)))
    return out


@dataclass
class StabilityResult:
    """Outcome of one stability scene: ``status`` pass / FAIL / stated / refused / pending / skipped."""

    scene: StabilityScene
    status: str = ""
    reason: str = ""
    checks: list = field(default_factory=list)
    runs: dict = field(default_factory=dict)  # rtol -> dict of measured values
    ulp_spread: float = math.nan  # largest change of theta_max/alpha (t_overturn [s] if overturned) over 1-ulp inputs
    ulp_verdicts: tuple = ()  # the verdicts on the 1-ulp inputs

    @property
    def passed(self) -> bool:
        return self.status in ("pass", "stated")

    @property
    def ill_conditioned(self) -> bool:
        """One ulp of the input changes the verdict, or moves the answer beyond the tolerance check's limits."""
        if not self.ulp_verdicts:
            return False
        return ill_conditioned(self.runs.get(STABILITY_RTOLS[-1], {}).get("verdict"), self.ulp_spread,
                               self.ulp_verdicts)


def _is_hysteretic(foundation) -> bool:
    return hasattr(foundation, "u_y")


def judge_run(block, foundation, exc, r, wall_s: float, rtol: float, scene: StabilityScene) -> list:
    """Every check of one history run ``r`` (a Response with history)."""
    from rockcli.models import Rigid

    h = r.history
    isolated = not isinstance(foundation, Rigid)
    arrays = dict(t=h.t, theta=h.theta, theta_dot=h.theta_dot, u=h.u, u_dot=h.u_dot,
                  peak=[r.theta_max_over_alpha], t_end=[r.t_end_s])
    checks = [check_finite(**arrays),
              check_budget(wall_s, scene.wall_budget_s, r.status, r.steps + r.rejected_steps, scene.step_budget),
              check_steps(h.t, r.steps, r.rejected_steps),
              check_momentum(h.t, h.theta, h.theta_dot, h.u_dot, R=block.R, alpha=block.alpha,
                             gamma=float(getattr(foundation, "gamma", 0.0)), isolated=isolated)]
    if not isolated:
        checks.append(check_energy(h.t, h.theta, h.theta_dot, p=block.p, alpha=block.alpha,
                                   t_exc_end=excitation_end(exc), rtol=rtol))
    if _is_hysteretic(foundation):
        z = getattr(h, "z", None)
        if z is None or hasattr(foundation, "R1_eff"):
            checks.append(Check("dissipation", True, "not checked (needs the Bouc-Wen history of a single-surface "
                                                     "bearing)"))
        else:
            Q = G * float(getattr(foundation, "strength_ratio", getattr(foundation, "mu", 0.0)))
            checks.append(check_dissipation(h.u, z, Q=Q, u_y=foundation.u_y))
    return checks


def run_stability(scenes, *, rtols=STABILITY_RTOLS, progress: Callable[[str], None] | None = None) -> list:
    """Run every stability scene at the two tolerances and judge it; one :class:`StabilityResult` each."""
    from rockcli.solve import simulate

    results = []
    warmed = set()
    for sc in scenes:
        res = StabilityResult(sc)
        results.append(res)
        if progress:
            progress(sc.name)
        try:
            block, foundation, exc = sc.build()
        except SceneUnavailable as why:
            res.status, res.reason = why.reason.split(":")[0], why.reason
            continue
        except RockcliInputError as exc_:
            res.status, res.reason = "refused", f"refused: {exc_}"
            continue
        responses = {}
        rt = rtols[0]
        try:
            # load (or compile) the kernels outside the timed runs: the budget is for the run
            key = (type(foundation).__name__, hasattr(exc, "acc"))
            if key not in warmed:  # the first timed run, once untimed
                simulate(block, foundation, exc, rtol=rt, history=True, tail=sc.tail, max_steps=sc.step_budget)
                warmed.add(key)
            for rt in rtols:
                t0 = time.perf_counter()
                r = simulate(block, foundation, exc, rtol=rt, history=True, tail=sc.tail, max_steps=sc.step_budget)
                wall = time.perf_counter() - t0
                responses[rt] = r
                checks = judge_run(block, foundation, exc, r, wall, rt, sc)
                res.checks += [Check(f"{c.name} @{rt:g}", c.ok, c.detail) for c in checks]
                res.runs[rt] = dict(verdict=r.verdict, theta_max_over_alpha=r.theta_max_over_alpha,
                                    t_overturn_s=r.t_overturn_s, settled=r.settled, steps=r.steps,
                                    rejected=r.rejected_steps, nfev=r.nfev, n_impacts=r.n_impacts_total,
                                    n_rests=r.n_rests, wall_s=wall, t_end_s=r.t_end_s, message=r.message)
        except RockcliInputError as exc_:
            res.status, res.reason = "refused", f"refused: {exc_}"
            continue
        except Exception as exc_:  # noqa: BLE001  (a crash is a result of the study, not of the bench)
            res.status = "FAIL"
            res.reason = f"crash at rtol {rt:g}: {type(exc_).__name__}: {exc_}"
            res.checks.append(Check(f"crash @{rt:g}", False, f"{type(exc_).__name__}: {exc_}"))
            continue
        try:
            res.ulp_spread, res.ulp_verdicts = measure_conditioning(block, foundation, exc, seed=ULP_SEED,
                                                                    rtol=rtols[-1], tail=sc.tail,
                                                                    max_steps=sc.step_budget)
        except RockcliInputError:  # a perturbed input refused (a pulse moved past a limit): not measured
            pass
        a, b = (responses[rt] for rt in rtols[:2])
        res.checks.append(check_tolerance(a.verdict, b.verdict, a.theta_max_over_alpha, b.theta_max_over_alpha,
                                          a.t_overturn_s, b.t_overturn_s))
        if sc.expect is not None:
            ok = all(r.verdict == sc.expect for r in responses.values())
            res.checks.append(Check("expected", ok, f"expected {sc.expect}, got "
                                                    f"{', '.join(r.verdict for r in responses.values())}"))
        unproven = [rt for rt, r in responses.items() if not r.settled]
        failed = [c for c in res.checks if not c.ok]
        if unproven and not sc.unproven_ok:
            r = responses[unproven[-1]]
            failed.append(Check("proven", False, f"NOT PROVEN at the horizon (rtol {', '.join(f'{x:g}' for x in unproven)}"
                                                 f"; t = {r.t_end_s:.1f} s, {r.n_impacts_total} impacts, "
                                                 f"{r.n_rests} rests)"))
        if failed:
            res.status = "FAIL"
            res.reason = "; ".join(f"{c.name}: {c.detail}" for c in failed)
        elif unproven:
            res.status = "stated"
            r = responses[rtols[-1]]
            res.reason = (f"NOT PROVEN at the horizon, as stated for {sc.unproven_why} "
                          f"(t_end {r.t_end_s:.0f} s, {r.n_uplifts} uplifts, {r.n_impacts_total} impacts); every check "
                          f"holds")
        else:
            res.status = "pass"
            res.reason = "every check holds"
    return results
