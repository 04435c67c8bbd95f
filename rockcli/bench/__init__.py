"""How accurate, how fast, how robust: the solver measured against itself and against SciPy.

Two studies, both run by ``rockcli bench``:

* **Work-precision** (:func:`run_work_precision`). Named representative scenes
  (:data:`WP_SCENES`: rigid foundation, linear bearings, single and double concave sliding
  bearings; each under a pulse and under a real record when one is found). Every scene is solved
  by the kernel at a ladder of ``rtol`` (full-history runs, ``rockcli``; verdict-only runs as the
  sweeps use them, ``rockcli-verdict``) and by the SciPy reference (:mod:`rockcli.reference`) with
  ``RK45``, ``DOP853``, ``Radau``, ``LSODA`` and ``BDF`` at a ladder of ``rtol``. Each run is
  compared with a reference solution: the kernel at ``rtol = 1e-13``, verified by an independent
  solution (SciPy ``DOP853`` at ``1e-13``, steps aligned to a record's samples) on the same scene.
  Per run: the error in ``theta_max/alpha``, the error in the overturning time (or, for a survivor,
  the time the block comes to rest for good), whether the verdict agrees, steps, right-hand sides
  and the median wall time of repeats.
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

What is where, in reading order (every name is importable from ``rockcli.bench``):

* :mod:`~rockcli.bench.scenes`: the work-precision scenes as text (:class:`Scene`,
  :data:`WP_SCENES`), :func:`resolve_scene`, :func:`select_scenes`, :class:`SceneUnavailable`.
* :mod:`~rockcli.bench.history`: reading a kernel history: :func:`impact_rows`,
  :func:`history_rest_time`.
* :mod:`~rockcli.bench.work_precision`: the study's ladders and budgets, :class:`WPRun`,
  :class:`WPScene`, :func:`run_work_precision`, :func:`summarise`.
* :mod:`~rockcli.bench.checks`: :class:`Check` and the ``check_*`` functions with their limits.
* :mod:`~rockcli.bench.stability_scenes`: :class:`StabilityScene`, :data:`STABILITY_SCENES`,
  :func:`random_scenes`, :func:`band_limited_record`.
* :mod:`~rockcli.bench.stability`: :func:`judge_run`, :func:`run_stability`,
  :class:`StabilityResult`.

The printing, CSV and plots are in :mod:`rockcli.report.bench`, the command in ``rockcli.cli.bench``.
"""

from rockcli.bench.checks import (COLLAPSE_RUN, ENERGY_TOL_PER_RTOL, MAX_REJECTED, MOMENTUM_TOL, PEAK_TOL,
                                  T_OVERTURN_TOL, TINY_STEP, Check, check_budget, check_dissipation, check_energy,
                                  check_finite, check_momentum, check_steps, check_tolerance)
from rockcli.bench.history import history_rest_time, impact_rows
from rockcli.bench.scenes import (KOBE, PENDING_SLIDING, WP_SCENES, Scene, SceneUnavailable, excitation_end,
                                  parse_foundation, resolve_scene, select_scenes)
from rockcli.bench.stability import STABILITY_RTOLS, ULP_SEED, StabilityResult, judge_run, run_stability
from rockcli.bench.stability_scenes import (STABILITY_SCENES, StabilityScene,  # noqa: F401 (two private scenes: tests)
                                            _passes_alpha_at_end, _subnormal_uplift, band_limited_record, random_scenes)
from rockcli.bench.work_precision import (CHECK_METHOD, CHECK_RTOL, COMPARE_RTOL, FREE_SUFFIX, KERNEL, KERNEL_RTOLS,
                                          KERNEL_VERDICT, NOISE_DRAWS, NOISE_SEED, REFERENCE_RTOL, SCIPY_BUDGET_FULL_S,
                                          SCIPY_BUDGET_S, SCIPY_METHODS, SCIPY_RTOLS, SCIPY_RTOLS_FULL, WP_TAIL, WPRun,
                                          WPScene, WPSummary, median_time, run_work_precision, scene_default_rtol,
                                          summarise)
from rockcli.conditioning import (ILL_PEAK, ILL_T_OVERTURN, ULP_DRAWS, ill_conditioned, measure_conditioning,
                                  ulp_perturbed, widest)

__all__ = ["CHECK_METHOD", "CHECK_RTOL", "COLLAPSE_RUN", "COMPARE_RTOL", "ENERGY_TOL_PER_RTOL", "FREE_SUFFIX",
           "ILL_PEAK", "ILL_T_OVERTURN", "KERNEL", "KERNEL_RTOLS", "KERNEL_VERDICT", "KOBE", "MAX_REJECTED",
           "MOMENTUM_TOL", "NOISE_DRAWS", "NOISE_SEED", "PEAK_TOL", "PENDING_SLIDING", "REFERENCE_RTOL",
           "SCIPY_BUDGET_FULL_S", "SCIPY_BUDGET_S", "SCIPY_METHODS", "SCIPY_RTOLS", "SCIPY_RTOLS_FULL",
           "STABILITY_RTOLS", "STABILITY_SCENES", "TINY_STEP", "T_OVERTURN_TOL", "ULP_DRAWS", "ULP_SEED",
           "WP_SCENES", "WP_TAIL", "Check", "Scene", "SceneUnavailable", "StabilityResult", "StabilityScene",
           "WPRun", "WPScene", "WPSummary", "band_limited_record", "check_budget", "check_dissipation",
           "check_energy", "check_finite", "check_momentum", "check_steps", "check_tolerance",
           "excitation_end", "history_rest_time", "ill_conditioned", "impact_rows", "judge_run",
           "measure_conditioning", "median_time", "parse_foundation", "random_scenes", "resolve_scene",
           "run_stability", "run_work_precision", "scene_default_rtol", "select_scenes", "summarise",
           "ulp_perturbed", "widest"]
