"""``simulate(block, foundation, excitation)``: one rocking scene, validated, on the compiled kernel.

The layer between the models and :mod:`rockcli.kernels`: it validates a scene, turns it into the
kernel's arrays, runs it (one scene, or many in parallel) and reads the result back. No numba here:
the kernels are imported on the first run. Read it in this order:

=================  =====================================================================================
``options``        the solver options' defaults and limits, :func:`default_rtol` (per foundation),
                   :func:`validate_options`; ``_kernel``, the lazy handle on :mod:`rockcli.kernels`
``response``       what a run returns: :class:`Response` and its :class:`History`, the verdict names,
                   :class:`JobError` and :class:`Verdicts` of the batch path, and ``_response`` (a
                   kernel's output row read into a :class:`Response`)
``excitation``     a record or a pulse as the kernel reads it (``_excitation_arrays``), with the table of
                   the ground impulse still to come (:func:`record_impulse_table`,
                   :func:`pulse_impulse_table`) that bounds the early stops; ``_excitation_arrays_cached``
                   keeps a record's arrays while its samples stay the same bit for bit
``parameters``     the parameter vector of a block on a foundation (``_parameters``), and
                   :func:`bearing_force_path`, the bearings alone under an imposed displacement
``work``           the work estimate (``_estimate_steps``, ``_check_work``): a scene that would need more
                   than a fifth of the step cap is refused up front
``single``         :func:`simulate`: one scene, with or without its history
``pool``           the process's pool of threads the batch kernels run on, :func:`run_tasks` (a list of
                   callables, longest first, on every core; one pool per process, kept between calls)
``batch``          :func:`simulate_many` and :func:`simulate_verdicts`: many verdict-only scenes on all
                   cores (``_run_many`` validates each distinct scene once and packs their arrays; a record's
                   arrays and a passed work estimate are kept between calls, exactly: see ``excitation``)
``stack``          :func:`simulate_stack`: a body on a free plinth (docs/physics-plinth.md),
                   :class:`StackResponse`
``stack_many``     the stack jobs of :func:`simulate_many` (on a pool of threads: the stack drivers release the
                   GIL), read back as a ``StackRun`` that answers to a :class:`Response`'s names
``friction``       the single block's friction demand of a rocking run from its history (docs/plinth.md)
``slide``          :func:`simulate_friction`: Coulomb friction as a model (docs/physics-sliding.md), one body or
                   a body on its plinth, on the ground or on linear bearings; :class:`SlideResponse`
``slide_many``     the :class:`Sliding` jobs of :func:`simulate_many`, read back as a ``SlideRun``; where nothing
                   slid, the rocking model's own run (bit for bit the answer without friction)
=================  =====================================================================================

Every public name (and the private helpers tests reach for) is importable from ``rockcli.solve``.
To replace a helper in a test, patch it in the module that calls it (e.g. ``rockcli.solve.single``).

Solver contract
---------------
* The block starts at rest on its base, base and ground at rest, at the start of the excitation
  (or, with ``theta0``/``theta_dot0``, rocking from that state: :mod:`rockcli.models.initial`).
* A record is piecewise linear between its samples, zero after its last sample. A pulse is
  evaluated analytically and is zero outside its support.
* Uplift when the absolute base acceleration ``a`` passes ``-g tan(alpha)`` (rocking on the
  right corner, theta > 0) or ``+g tan(alpha)`` (theta < 0).
* A vertical ground acceleration ``a_v`` (``vertical=``, rigid foundation only; a record on the horizontal
  record's time base or a pulse sampled at ``T_p/2000``, piecewise linear, zero after its end): gravity
  ``g + a_v`` in Eq (3), in the uplift threshold and in the rest rule; ``g + a_v <= 0`` anywhere is refused.
  A record may carry its vertical component (:func:`with_vertical`): then it runs under it wherever it goes.
  The excitation ends when both motions have ended.
* Impacts at theta = 0 keep the total horizontal momentum and the block's angular momentum about
  the new pivot: ``theta_dot+ = eta theta_dot-`` with ``eta = (k - 2)/(k + 4)``,
  ``k = (4 - 3 gamma) cot^2(alpha)`` (Housner's ``1 - 1.5 sin^2 alpha`` when gamma = 0). A given
  coefficient of restitution ``0 < E <= 1`` replaces it by ``E`` on a rigid foundation and by
  ``1 - 4 (1 - E)/(4 - 3 gamma cos^2 alpha)`` on an isolated base (horizontal momentum kept;
  derivation in :mod:`rockcli.models.impact`).
* Rest: after an impact, when the current base acceleration ``a`` could not lift the block
  (``|a| < g tan alpha``) and the rotation it could still reach against the restoring
  acceleration ``p^2 cos(alpha) (tan(alpha) - |a|/g)``, ``theta_dot^2 / (2 p^2 cos(alpha) (tan(alpha) -
  |a|/g))``, is below ``rest_tol * alpha``, the block is set at rest (a plastic impact that ends
  the train of ever smaller impacts, momentum kept) and moves with its base until the uplift
  condition holds again. ``rest_tol > 0``: without a rest rule the train of impacts never ends.
* Overturning: ``|theta|`` reaches ``pi/2`` (the block lies on its side). The first time
  ``|theta|`` exceeds ``alpha`` is reported separately: passing alpha is not final while the
  ground still moves.
* End of the run, the same in every mode: the run ends once the verdict is *proven*
  (overturned; after the excitation, a block at rest that the still ground, or the free base,
  can no longer lift; on a rigid foundation a block with ``|theta| < alpha`` whose energy is below
  the energy needed to reach alpha). The proofs are stated in
  :mod:`rockcli.kernels.rigid` and :mod:`rockcli.kernels.driver_end`. A history run then goes on to ``t_exc_end + tail`` to
  show the free motion. A run still unproven ``horizon`` seconds after the excitation ends there
  with ``settled = False`` and says so (e.g. an undamped base that keeps lifting the block).
  ``early=True`` (verdict-only sweeps) also stops during the excitation once survival is proven
  by the energy the rest of the ground motion can still supply, or overturning once the block,
  past alpha, can no longer be brought back; its ``theta_max`` is then only a lower bound and
  ``t_overturn_s`` may be NaN (``peak_final = False``). On an isolated base it stops once a block
  at rest on its base can never be lifted again (its peak stays final) and leaves the base's peak
  displacement NaN unless it is proven final.
"""

from rockcli.solve.options import (DEFAULT_HORIZON, DEFAULT_MAX_STEPS, DEFAULT_REST_TOL, DEFAULT_RTOL,
                                   DEFAULT_RTOL_HYSTERETIC, DEFAULT_TAIL, FOUNDATION_TYPES, HORIZON_MAX, REST_TOL_MIN,
                                   TAIL_MAX, _kernel, _rtol, check_foundation, default_rtol, validate_options)
from rockcli.solve.response import (VERDICT_ERROR, VERDICT_NO_UPLIFT, VERDICT_OVERTURNED, VERDICT_ROCKED, History,
                                    JobError, Response, Verdicts, _response)
from rockcli.solve.excitation import (_PULSE_CODES, _PULSE_ZEROS, _UNIT_TABLES, N_IMPULSE_TABLE,
                                      PULSE_START_MAX_PERIODS, _excitation_arrays, attached_vertical,
                                      pulse_impulse_table, record_impulse_table, vertical_label, with_vertical)
from rockcli.solve.parameters import _parameters, bearing_force_path
from rockcli.solve.work import _check_work, _estimate_steps
from rockcli.solve.single import simulate
from rockcli.solve.batch import _run_many, _scene_arrays, _threads, simulate_many, simulate_verdicts
from rockcli.solve.stack import BlockPeak, StackHistory, StackResponse, friction_demand_single, simulate_stack

__all__ = ["DEFAULT_HORIZON", "DEFAULT_MAX_STEPS", "DEFAULT_REST_TOL", "DEFAULT_RTOL", "DEFAULT_RTOL_HYSTERETIC",
           "DEFAULT_TAIL", "FOUNDATION_TYPES", "HORIZON_MAX", "N_IMPULSE_TABLE", "PULSE_START_MAX_PERIODS",
           "REST_TOL_MIN", "TAIL_MAX",
           "VERDICT_ERROR", "VERDICT_NO_UPLIFT", "VERDICT_OVERTURNED", "VERDICT_ROCKED", "History", "JobError",
           "Response", "Verdicts", "attached_vertical", "bearing_force_path", "check_foundation", "default_rtol",
           "pulse_impulse_table",
           "record_impulse_table", "simulate", "simulate_many", "simulate_verdicts", "validate_options",
           "vertical_label", "with_vertical"]
__all__ += ["BlockPeak", "StackHistory", "StackResponse", "friction_demand_single", "simulate_stack"]
from rockcli.solve.slide import InterfacePeak, SlideResponse, simulate_friction  # noqa: E402
from rockcli.solve.slide_many import SlideRun, Sliding  # noqa: E402

__all__ += ["InterfacePeak", "SlideResponse", "SlideRun", "Sliding", "simulate_friction"]
