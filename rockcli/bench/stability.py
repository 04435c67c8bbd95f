"""The stability study: every stability scene at two tolerances, judged by the checks.

:func:`run_stability` runs each scene (untimed warm-up, then timed history runs at
:data:`STABILITY_RTOLS`), applies :func:`judge_run` (the checks of :mod:`rockcli.bench.checks`), the
tolerance check across the two runs, the expected verdict and the end-of-run proof, and measures the
scene's conditioning (:func:`rockcli.conditioning.measure_conditioning`).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

from rockcli.bench.checks import (Check, check_budget, check_dissipation, check_energy, check_finite, check_momentum,
                                  check_steps, check_tolerance)
from rockcli.bench.scenes import SceneUnavailable, excitation_end
from rockcli.bench.stability_scenes import StabilityScene
from rockcli.conditioning import ill_conditioned, measure_conditioning
from rockcli.errors import RockcliInputError
from rockcli.io.units import G

#: Tolerances of the stability study.
STABILITY_RTOLS = (1e-6, 1e-10)
#: Conditioning (:mod:`rockcli.conditioning`): each stability scene is run again (verdict-only, at the
#: tighter rtol) on ULP_DRAWS inputs moved by one ulp; a verdict that changes, or a peak (overturning
#: time) that moves by more than ILL_PEAK (ILL_T_OVERTURN), makes the scene ill-conditioned: its answer
#: is not determined by its input at double precision (measured and reported, not a solver failure).
ULP_SEED = 19800


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
